#include "liftremesh/edit/flip_rules.h"

#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/spatial/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace liftremesh {

namespace {

// The distance part of the rule: the new diagonal's midpoint no farther from the input than the
// old one's, or within half the tolerance.
bool keeps_surface(double before, double after, double tolerance) { return after <= std::max(0.5 * tolerance, before); }

// Seven points of the triangle, its centroid first, then its edges' midpoints and the points
// halfway from the centroid to its corners (the corners themselves are vertices of the output,
// put on the input).
std::array<Eigen::Vector3d, 7> probe_points(const EditableMesh& mesh, const EditableMesh::Tri& t) {
    const Eigen::Vector3d& a = mesh.points[t[0]];
    const Eigen::Vector3d& b = mesh.points[t[1]];
    const Eigen::Vector3d& c = mesh.points[t[2]];
    const Eigen::Vector3d g = (a + b + c) / 3.0;
    return {g, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), 0.5 * (g + a), 0.5 * (g + b), 0.5 * (g + c)};
}

// The largest of `d2` and the squared distances from the input of points[first, 7).
double farthest_squared(const std::array<Eigen::Vector3d, 7>& points, size_t first, double d2, const AabbTree& input) {
    for (size_t i = first; i < points.size(); ++i) d2 = std::max(d2, input.closest(points[i]).squared_distance);
    return d2;
}

// Within `tolerance` of the input (triangle_distance_from_input), its normal within 30 degrees of the
// input's triangle nearest to its centroid (whose query serves both).
bool lies_on_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input, double tolerance) {
    const std::array<Eigen::Vector3d, 7> points = probe_points(mesh, t);
    const ClosestPoint near = input.closest(points[0]);
    return near.triangle >= 0 && EditableMesh::turns_little(mesh.normal(t), input.triangle_normal(near.triangle)) &&
           std::sqrt(farthest_squared(points, 1, near.squared_distance, input)) <= tolerance;
}
} // namespace

bool faces_against_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input) {
    const ClosestPoint near = input.closest((mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]]) / 3.0);
    const Eigen::Vector3d n = mesh.normal(t);
    return near.triangle >= 0 && n.dot(input.triangle_normal(near.triangle)) < kCosCap * n.norm();
}

int folded_edges_among(const EditableMesh& mesh, const std::vector<int>& tris, const TrianglesOf& triangles_of) {
    return count_folded_edges(
        tris, [&mesh](int t) { return mesh.tris[t]; }, [&mesh](int t) { return mesh.normal(mesh.tris[t]); },
        [&triangles_of](int32_t v) {
            const auto [first, last] = triangles_of(v);
            return IndexRange{first, last};
        });
}

bool flip_folds_rim(const EditableMesh& mesh, const EditableMesh::Quad& q, const TrianglesOf& fans) {
    // The triangle other than the quad's on edge u-v, or -1.
    auto across = [&](int32_t u, int32_t v) {
        for (int32_t w : {u, v})
            for (auto [t, last] = fans(w); t != last; ++t) {
                if (*t == q.t1 || *t == q.t2) continue;
                const EditableMesh::Tri& x = mesh.tris[*t];
                if (std::find(x.begin(), x.end(), u) != x.end() && std::find(x.begin(), x.end(), v) != x.end()) return *t;
            }
        return -1;
    };
    const auto [n1, n2] = EditableMesh::flipped(q); // (a, d, c) and (d, b, c)
    // Each rim edge with its old triangle and its new one.
    const struct {
        int32_t u, v;
        int old_tri;
        const EditableMesh::Tri& made;
    } rim[4] = {{q.c, q.a, q.t1, n1}, {q.a, q.d, q.t2, n1}, {q.d, q.b, q.t2, n2}, {q.b, q.c, q.t1, n2}};
    for (const auto& e : rim) {
        const int t = across(e.u, e.v);
        if (t < 0) continue;
        const Eigen::Vector3d n = mesh.normal(mesh.tris[t]);
        if (folded(mesh.normal(e.made), n) && !folded(mesh.normal(mesh.tris[e.old_tri]), n)) return true;
    }
    return false;
}

long crossings_among(const EditableMesh& mesh, const std::vector<EditableMesh::Tri>& tris) {
    std::vector<std::array<Eigen::Vector3d, 3>> at;
    for (const EditableMesh::Tri& t : tris) at.push_back(mesh.corners(t));
    long count = 0;
    for (size_t i = 0; i < tris.size(); ++i)
        for (size_t j = i + 1; j < tris.size(); ++j) count += triangles_cross(tris[i], at[i], tris[j], at[j]) ? 1 : 0;
    return count;
}

long crossings_among(const EditableMesh& mesh, std::vector<int> tris) {
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
    std::vector<EditableMesh::Tri> as_now;
    for (int t : tris) as_now.push_back(mesh.tris[t]);
    return crossings_among(mesh, as_now);
}

bool flip_crosses_fans(const EditableMesh& mesh, const EditableMesh::Quad& q, const TrianglesOf& fans) {
    std::vector<int32_t> around;
    for (int32_t w : {q.a, q.b, q.c, q.d}) {
        const auto [first, last] = fans(w);
        around.insert(around.end(), first, last);
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    auto crossings = [&](const EditableMesh::Tri& u, const EditableMesh::Tri& v) {
        const std::array<Eigen::Vector3d, 3> at_u = mesh.corners(u), at_v = mesh.corners(v);
        long count = 0;
        for (int32_t g : around) {
            if (g == q.t1 || g == q.t2) continue;
            const EditableMesh::Tri& t = mesh.tris[g];
            const std::array<Eigen::Vector3d, 3> at_t = mesh.corners(t);
            count += (triangles_cross(u, at_u, t, at_t) ? 1 : 0) + (triangles_cross(v, at_v, t, at_t) ? 1 : 0);
        }
        return count;
    };
    const auto [n1, n2] = EditableMesh::flipped(q);
    return crossings(n1, n2) > crossings(mesh.tris[q.t1], mesh.tris[q.t2]);
}

DiagonalDistances diagonal_distances(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input) {
    const std::vector<Eigen::Vector3d>& x = mesh.points;
    auto distance = [&](const Eigen::Vector3d& p) { return std::sqrt(input.closest(p).squared_distance); };
    return {distance(0.5 * (x[quad.a] + x[quad.b])), distance(0.5 * (x[quad.c] + x[quad.d]))};
}

double triangle_distance_from_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input) {
    return std::sqrt(farthest_squared(probe_points(mesh, t), 0, 0.0, input));
}

TriangleNearInput triangle_near_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input) {
    const std::array<Eigen::Vector3d, 7> points = probe_points(mesh, t);
    const ClosestPoint near = input.closest(points[0]);
    return {std::sqrt(farthest_squared(points, 1, near.squared_distance, input)), near.triangle};
}

bool fold_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                          double tolerance) {
    const EditableMesh::Tri& t1 = mesh.tris[quad.t1];
    const EditableMesh::Tri& t2 = mesh.tris[quad.t2];
    if (!(mesh.normal(t1).dot(mesh.normal(t2)) < 0.0)) return false; // turns by 90 degrees at most
    // Folded shut, one of them off the input's faces: the two lie on each other, however near
    // the input, and a mesher refuses the pair whatever the shape of the new triangles.
    const bool shut = folded(mesh.normal(t1), mesh.normal(t2)) &&
                      !(lies_on_input(mesh, t1, input, tolerance) && lies_on_input(mesh, t2, input, tolerance));
    if (!shut &&
        !(std::max(triangle_distance_from_input(mesh, t1, input), triangle_distance_from_input(mesh, t2, input)) > tolerance))
        return false; // near the input: a crease of it, followed, or a fold too small to matter
    const auto [n1, n2] = EditableMesh::flipped(quad);
    const double worse_before = std::min(mesh.kappa(t1), mesh.kappa(t2));
    const double floor = shut ? 0.0 : std::min(worse_before, kKappaFloor);
    if (!(std::min(mesh.kappa(n1), mesh.kappa(n2)) >= floor)) return false;
    return lies_on_input(mesh, n1, input, tolerance) && lies_on_input(mesh, n2, input, tolerance);
}

bool cap_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                         double tolerance) {
    const std::vector<Eigen::Vector3d>& x = mesh.points;
    // The cosine of the angle at `apex` of the triangle it makes with the quad's edge a-b.
    auto cos_at = [&](int32_t apex) {
        const Eigen::Vector3d u = x[quad.a] - x[apex], v = x[quad.b] - x[apex];
        return u.dot(v) / (u.norm() * v.norm());
    };
    if ((cos_at(quad.c) <= kCosCap) == (cos_at(quad.d) <= kCosCap)) return false; // one cap on the edge, not two
    const EditableMesh::Tri& t1 = mesh.tris[quad.t1];
    const EditableMesh::Tri& t2 = mesh.tris[quad.t2];
    const auto [n1, n2] = EditableMesh::flipped(quad);
    if (!(std::min(mesh.kappa(n1), mesh.kappa(n2)) > std::min(mesh.kappa(t1), mesh.kappa(t2)))) return false;
    // A cap turned over onto the triangle across its long edge (by more than 90 degrees) is a
    // fold laid flat, its apex on the wrong side of that edge: three vertices along a crease
    // bending towards a face a step lower, narrower than the edge length, which has no row of
    // its own. Either way the surface crosses that step; flipped, it no longer doubles back, so
    // the new triangles may lie twice as far from the input.
    const bool turned_over = mesh.normal(t1).dot(mesh.normal(t2)) < 0.0;
    const double reach = turned_over ? 2.0 * tolerance : tolerance;
    return lies_on_input(mesh, n1, input, reach) && lies_on_input(mesh, n2, input, reach);
}

bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                                double tolerance) {
    if (!mesh.flip_improves_quality(quad)) return false; // first: it spares the two distance queries
    const auto [before, after] = diagonal_distances(mesh, quad, input);
    return keeps_surface(before, after, tolerance);
}

bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, double before, double after,
                                double tolerance) {
    return mesh.flip_improves_quality(quad) && keeps_surface(before, after, tolerance);
}

bool crease_flip_fits(const EditableMesh& mesh, const EditableMesh::Quad& q, double before, double after,
                      double tolerance, double kappa_floor) {
    if (!(before > tolerance && after < 0.5 * before)) return false;
    const auto [n1, n2] = EditableMesh::flipped(q);
    const Eigen::Vector3d mean = mesh.normal(mesh.tris[q.t1]).normalized() + mesh.normal(mesh.tris[q.t2]).normalized();
    if (!(mean.squaredNorm() > 0.0)) return false; // a degenerate triangle (NaN) or opposite ones
    if (mesh.normal(n1).dot(mean) <= 0.0 || mesh.normal(n2).dot(mean) <= 0.0) return false; // a fold
    const double worst_before = std::min(mesh.kappa(mesh.tris[q.t1]), mesh.kappa(mesh.tris[q.t2]));
    return std::min(mesh.kappa(n1), mesh.kappa(n2)) >= std::min(kappa_floor, worst_before);
}

bool chord_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, double before, double after,
                           const AabbTree& input, double tolerance) {
    if (!crease_flip_fits(mesh, quad, before, after, 0.5 * tolerance, kKappaFloorChord)) return false;
    const auto [n1, n2] = EditableMesh::flipped(quad);
    return lies_on_input(mesh, n1, input, tolerance) && lies_on_input(mesh, n2, input, tolerance);
}

} // namespace liftremesh
