#include "liftremesh/measure/quality.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace liftremesh {

namespace {

// ---- per triangle -------------------------------------------------------------------------------

//! Histogram bin of kappa: [0, 0.1) -> 0, ..., [0.9, 1.0] -> 9 (kappa == 1 in the last bin).
int kappa_bin(double kappa) {
    if (!(kappa > 0.0)) return 0; // also NaN, from non-finite coordinates
    return std::min(9, static_cast<int>(kappa * 10.0));
}

void measure_triangles(const Mesh& mesh, MeshQuality& q) {
    const Eigen::Index nf = mesh.triangles.rows();
    q.triangles = static_cast<long>(nf);
    if (nf == 0) return;
    // Each triangle's figures in parallel, added up in the triangles' order: the same sums
    // whatever the threads.
    std::vector<double> kappas(static_cast<size_t>(nf)), angles(static_cast<size_t>(nf));
#pragma omp parallel for schedule(static)
    for (Eigen::Index f = 0; f < nf; ++f) {
        const Eigen::Vector3d a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
        kappas[f] = triangle_kappa(a, b, c); // Eq. 26
        angles[f] = triangle_min_angle_deg(a, b, c);
    }
    double kappa_sum = 0.0;
    q.kappa_min = std::numeric_limits<double>::infinity();
    q.min_angle_deg = 180.0;
    for (Eigen::Index f = 0; f < nf; ++f) {
        q.kappa_min = std::min(q.kappa_min, kappas[f]);
        kappa_sum += kappas[f];
        ++q.kappa_histogram[kappa_bin(kappas[f])];
        q.min_angle_deg = std::min(q.min_angle_deg, angles[f]);
    }
    q.kappa_mean = kappa_sum / static_cast<double>(nf);
}

// ---- per edge -----------------------------------------------------------------------------------

//! Angle in degrees between the normals of the two triangles on a manifold edge (their sides
//! s and t, see edge_uses). When the two triangles disagree in orientation one normal is
//! flipped, so that the measure is the dihedral deviation from flat whatever the orientation.
double normal_angle_deg(const Mesh& mesh, int32_t s, int32_t t) {
    const Eigen::Index fs = s / 3, ft = t / 3;
    const Eigen::Vector3d n1 = triangle_normal(corner(mesh, fs, 0), corner(mesh, fs, 1), corner(mesh, fs, 2));
    Eigen::Vector3d n2 = triangle_normal(corner(mesh, ft, 0), corner(mesh, ft, 1), corner(mesh, ft, 2));
    if (runs_forward(mesh.triangles, s) == runs_forward(mesh.triangles, t)) n2 = -n2;
    return std::atan2(n1.cross(n2).norm(), n1.dot(n2)) * 180.0 / M_PI;
}

//! Whether triangle f is at least `width` wide: its smallest altitude, twice its area over its
//! longest edge (for width 0, every triangle).
bool at_least_as_wide(const Mesh& mesh, Eigen::Index f, double width) {
    if (!(width > 0.0)) return true;
    const Eigen::Vector3d a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    return (b - a).cross(c - a).norm() >= width * longest;
}

//! Returns the number of distinct edges.
long measure_edges(const Mesh& mesh, const SharpEdgeCriterion& sharp, MeshQuality& q) {
    const EdgeUses edges = edge_uses(mesh.triangles);
    // The dihedral turn of each edge of two triangles, in parallel (two normals and an
    // arctangent an edge); the rest in the edges' order.
    std::vector<double> turns(static_cast<size_t>(edges.size()), 0.0);
#pragma omp parallel for schedule(static)
    for (long e = 0; e < edges.size(); ++e)
        if (edges.count(e) == 2) turns[e] = normal_angle_deg(mesh, edges.uses.begin(e)[0], edges.uses.begin(e)[1]);
    std::vector<std::pair<int, int>> boundary;
    for (long e = 0; e < edges.size(); ++e) {
        const long count = edges.count(e);
        const int32_t* use = edges.uses.begin(e);
        const double length = (mesh.points.row(edges.a[e]) - mesh.points.row(edges.b[e])).norm();
        q.edge_length_min = e == 0 ? length : std::min(q.edge_length_min, length);
        q.edge_length_max = std::max(q.edge_length_max, length);
        if (count == 1) boundary.emplace_back(edges.a[e], edges.b[e]);
        if (count >= 3) ++q.nonmanifold_edges;
        if (count == 2) {
            if (runs_forward(mesh.triangles, use[0]) == runs_forward(mesh.triangles, use[1])) q.oriented = false;
            const double turn = turns[e];
            if (turn > sharp.angle_deg && at_least_as_wide(mesh, use[0] / 3, sharp.min_width) &&
                at_least_as_wide(mesh, use[1] / 3, sharp.min_width))
                q.sharp_edge_length += length;
            if (turn > kFoldedTurnDeg) {
                ++q.folded_edges;
                q.folded_edge_length += length;
            }
        }
    }
    q.boundary_edges = static_cast<long>(boundary.size());
    // Boundary loops: the connected components of the boundary edges.
    std::vector<int> component;
    connected_components(static_cast<int>(mesh.points.rows()), boundary, component);
    std::vector<char> counted(mesh.points.rows(), 0);
    for (const auto& [a, b] : boundary)
        if (!counted[component[a]]) {
            counted[component[a]] = 1;
            ++q.boundary_loops;
        }
    return edges.size();
}

// ---- per vertex ---------------------------------------------------------------------------------

//! The vertices whose incident triangles fall into two or more fans, groups not connected
//! through edges at the vertex (e.g. two cones touching at their apex: vertex_fans, mesh.h),
//! into q.nonmanifold_vertices, and their fans beyond the first into q.extra_vertex_fans.
void measure_vertices(const Mesh& mesh, MeshQuality& q) {
    const Eigen::Index nv = mesh.points.rows();
    const CompressedRows incident = vertex_triangles(mesh);
    long nonmanifold = 0, extra = 0; // counts: the same sums in any order
#pragma omp parallel reduction(+ : nonmanifold, extra)
    {
        std::vector<std::array<int32_t, 3>> around;
        std::vector<int> fan;
#pragma omp for schedule(static)
        for (Eigen::Index v = 0; v < nv; ++v) {
            around.clear();
            for (const int32_t* f = incident.begin(v); f != incident.end(v); ++f)
                around.push_back({mesh.triangles(*f, 0), mesh.triangles(*f, 1), mesh.triangles(*f, 2)});
            const int fans = vertex_fans(static_cast<int32_t>(v), around, fan);
            if (fans > 1) {
                ++nonmanifold;
                extra += fans - 1;
            }
        }
    }
    q.nonmanifold_vertices += nonmanifold;
    q.extra_vertex_fans += extra;
}

// ---- sampling and distances -------------------------------------------------------------------

//! splitmix64 (Steele, Lea and Flood, 2014): a small, well-mixed 64-bit generator. Each
//! triangle draws from a stream of its own, so samples are drawn in parallel and are the same
//! for every thread count.
std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

//! Uniform double in [0, 1) from the top 53 bits.
double uniform01(std::uint64_t& state) { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; }

//! The referenced vertices of `mesh`, then about `samples` minus that many area-uniform random
//! points (none if the vertices already reach `samples`), stratified by triangle: each draws
//! its expected share, the fractional part at random. Vertices and triangles each come along a
//! Morton curve, so consecutive points are near each other (see distances_to).
std::vector<Eigen::Vector3d> sample_surface(const Mesh& mesh, long samples, std::uint64_t seed) {
    const Eigen::Index nf = mesh.triangles.rows();
    const std::vector<char> used = referenced_vertices(mesh);
    std::vector<Eigen::Vector3d> vertices;
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
        if (used[i]) vertices.push_back(mesh.points.row(i).transpose());
    std::vector<Eigen::Vector3d> points;
    points.reserve(static_cast<size_t>(std::max<long>(samples, static_cast<long>(vertices.size()))));
    if (!vertices.empty())
        for (long i : morton_order(vertices[0].data(), static_cast<long>(vertices.size()), 3)) points.push_back(vertices[i]);

    std::vector<double> area(static_cast<size_t>(nf));
    std::vector<Eigen::Vector3d> centroids(static_cast<size_t>(nf));
    double total = 0.0;
    for (Eigen::Index f = 0; f < nf; ++f) {
        const double a = triangle_area(corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2));
        area[f] = std::isfinite(a) ? a : 0.0;
        total += area[f];
        centroids[f] = (corner(mesh, f, 0) + corner(mesh, f, 1) + corner(mesh, f, 2)) / 3.0;
    }
    const long extra = samples - static_cast<long>(points.size());
    if (extra <= 0 || !(total > 0.0) || !std::isfinite(total) || nf == 0) return points;
    const std::vector<long> order = morton_order(centroids[0].data(), static_cast<long>(nf), 3);
    auto stream = [&](long f) { return seed * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(f) * 0xD1B54A32D192ED03ull; };
    std::vector<long> offset(static_cast<size_t>(nf) + 1, static_cast<long>(points.size()));
    for (Eigen::Index i = 0; i < nf; ++i) {
        const long f = order[i];
        std::uint64_t state = stream(f);
        const double expected = static_cast<double>(extra) * (area[f] / total);
        const double whole = std::floor(expected);
        offset[i + 1] = offset[i] + static_cast<long>(whole) + (uniform01(state) < expected - whole ? 1 : 0);
    }
    points.resize(static_cast<size_t>(offset[nf]));
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < nf; ++i) {
        const long f = order[i];
        std::uint64_t state = stream(f);
        uniform01(state); // the draw that rounded the count
        for (long s = offset[i]; s < offset[i + 1]; ++s) {
            // Uniform point in a triangle: (1 - sqrt r1) a + sqrt r1 (1 - r2) b + sqrt r1 r2 c.
            const double r1 = std::sqrt(uniform01(state)), r2 = uniform01(state);
            points[s] = (1.0 - r1) * corner(mesh, f, 0) + r1 * (1.0 - r2) * corner(mesh, f, 1) + r1 * r2 * corner(mesh, f, 2);
        }
    }
    return points;
}

//! Distance from each point to the tree's mesh; the loop is parallel, the result deterministic
//! (each distance is exact). Each query is warm-started by the previous answer of its thread,
//! which lies on the mesh near it when consecutive points are near each other (sample_surface).
std::vector<double> distances_to(const std::vector<Eigen::Vector3d>& points, const AabbTree& tree) {
    std::vector<double> d(points.size());
    const long n = static_cast<long>(points.size());
#pragma omp parallel
    {
        bool warm = false;
        Eigen::Vector3d previous;
#pragma omp for schedule(static)
        for (long i = 0; i < n; ++i) {
            const ClosestPoint c = warm ? tree.closest(points[i], previous) : tree.closest(points[i]);
            d[i] = std::sqrt(c.squared_distance);
            previous = c.point;
            warm = true;
        }
    }
    return d;
}

// The components' counts and the largest of them (MeshQuality::components ... component_list).
void measure_components(const Mesh& mesh, MeshQuality& q) {
    MeshComponents split = mesh_components(mesh);
    q.components = static_cast<long>(split.components.size());
    q.closed_components = split.closed();
    q.inward_components = split.inward();
    q.cavities = split.cavities();
    std::vector<MeshComponent>& list = split.components;
    const auto listed = list.begin() + std::min<std::ptrdiff_t>(kListedComponents, static_cast<std::ptrdiff_t>(list.size()));
    std::partial_sort(list.begin(), listed, list.end(),
                      [](const MeshComponent& a, const MeshComponent& b) { return a.area > b.area; });
    q.component_list.assign(list.begin(), listed);
}

} // namespace

MeshQuality measure_quality(const Mesh& mesh, const SharpEdgeCriterion& sharp) {
    check_indices(mesh, "measured mesh");
    MeshQuality q;
    const std::vector<char> used = referenced_vertices(mesh);
    q.vertices = static_cast<long>(std::count(used.begin(), used.end(), 1));
    measure_triangles(mesh, q);
    const long edges = measure_edges(mesh, sharp, q);
    measure_vertices(mesh, q);
    // euler_characteristic(mesh), from the counts at hand instead of a second sort of the edges.
    q.euler_characteristic = static_cast<int>(q.vertices - edges + q.triangles);
    measure_components(mesh, q);
    return q;
}

DistanceStats hausdorff_distance(const Mesh& a, const Mesh& b, int samples, std::uint64_t seed) {
    check_mesh(a, "first"); // before the tree is built
    return hausdorff_distance(a, AabbTree(a), b, samples, seed);
}

DistanceStats hausdorff_distance(const Mesh& a, const AabbTree& a_tree, const Mesh& b, int samples, std::uint64_t seed) {
    check_mesh(b, "second"); // before the tree is built
    return hausdorff_distance(a, a_tree, b, AabbTree(b), samples, seed);
}

DistanceStats hausdorff_distance(const Mesh& a, const AabbTree& a_tree, const Mesh& b, const AabbTree& b_tree,
                                 int samples, std::uint64_t seed) {
    check_mesh(a, "first");
    check_mesh(b, "second");
    const std::vector<Eigen::Vector3d> on_a = sample_surface(a, samples, 2 * seed);
    const std::vector<Eigen::Vector3d> on_b = sample_surface(b, samples, 2 * seed + 1);
    const std::vector<double> a_to_b = distances_to(on_a, b_tree);
    const std::vector<double> b_to_a = distances_to(on_b, a_tree);

    DistanceStats stats;
    stats.a_to_b = *std::max_element(a_to_b.begin(), a_to_b.end());
    stats.b_to_a = *std::max_element(b_to_a.begin(), b_to_a.end());
    stats.hausdorff = std::max(stats.a_to_b, stats.b_to_a);
    const double sum =
        std::accumulate(a_to_b.begin(), a_to_b.end(), 0.0) + std::accumulate(b_to_a.begin(), b_to_a.end(), 0.0);
    stats.mean = sum / static_cast<double>(a_to_b.size() + b_to_a.size());
    return stats;
}

} // namespace liftremesh
