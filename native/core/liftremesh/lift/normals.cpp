#include "liftremesh/lift/normals.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {
// Triangles turned more than 120 degrees from the side averaged: the far side of a thin wall.
constexpr double kFacingMinDot = -0.5;
// How much more of a ball the triangles turned away from a vertex must fill for the vertex to
// be on a folded flap rather than on one side of a wall.
constexpr double kFoldedFlapRatio = 3.0;
// The most triangles a flap's search walks before it calls the side no flap.
constexpr size_t kMaxFlapTriangles = 4096;

// Whether vertex v lies on a flap folded back onto the surface: the triangles facing its own
// normal `own` (within 120 degrees) that it reaches across edges inside the ball of radius eta
// about it include an edge where the surface turns back, by more than 120 degrees. A wall's side
// meets its other side only across its rim, turning by less at each edge.
bool on_folded_flap(const Mesh& mesh, const CompressedRows& around, Eigen::Index v, const Eigen::Vector3d& own,
                    double eta) {
    const Eigen::Vector3d x = mesh.points.row(v).transpose();
    auto normal = [&](int32_t f) { return triangle_normal(corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)); };
    auto in_ball = [&](int32_t f) {
        return (closest_point_on_triangle(x, corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)) - x).norm() < eta;
    };
    std::unordered_set<int32_t> seen;
    std::vector<int32_t> queue;
    for (const int32_t* f = around.begin(v); f != around.end(v); ++f)
        if (normal(*f).dot(own) >= kFacingMinDot) {
            queue.push_back(*f);
            seen.insert(*f);
        }
    while (!queue.empty() && seen.size() < kMaxFlapTriangles) {
        const int32_t f = queue.back();
        queue.pop_back();
        const Eigen::Vector3d nf = normal(f);
        for (int j = 0; j < 3; ++j) {
            const int32_t a = mesh.triangles(f, j), b = mesh.triangles(f, j == 2 ? 0 : j + 1);
            for (const int32_t* g = around.begin(a); g != around.end(a); ++g) {
                if (*g == f || !std::binary_search(around.begin(b), around.end(b), *g)) continue; // not across (a, b)
                const Eigen::Vector3d ng = normal(*g);
                if (nf.dot(ng) < kFacingMinDot) return true; // the surface folds back here
                if (ng.dot(own) >= kFacingMinDot && !seen.count(*g) && in_ball(*g)) {
                    seen.insert(*g);
                    queue.push_back(*g);
                }
            }
        }
    }
    return false;
}
} // namespace

Points vertex_normals(const Mesh& mesh, double eta) { return vertex_normals(mesh, AabbTree(mesh), eta); }

Points vertex_normals(const Mesh& mesh, const AabbTree& tree, double eta) {
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    Points ring = Points::Zero(nv, 3); // one-ring, area-weighted: the fallback and the side test
    for (Eigen::Index f = 0; f < nf; ++f) {
        const auto a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
        const Eigen::Vector3d weighted = triangle_area(a, b, c) * triangle_normal(a, b, c);
        for (int j = 0; j < 3; ++j) ring.row(mesh.triangles(f, j)) += weighted.transpose();
    }
    // The triangles that meet each ball, from the AABB tree: a ball query on centroids needs a
    // radius grown by the longest triangle's reach, and on a fan of long slivers (a CAD disk)
    // finds most of them from every vertex. Inside the ball a triangle weighs its whole area,
    // and the tree adds whole subtrees inside it at once: only the triangles crossing the sphere
    // are clipped, so the cost goes with the ball's rim, not its area. The sums it adds up are
    // dropped on return: the caller's tree outlives them.
    const AabbTree::NormalSums sums_of = tree.normal_sums();
    // Vertices in Morton order: consecutive balls meet the same nodes, still in the cache.
    const std::vector<long> order = morton_order(mesh.points.data(), nv, 3);
    Points normals(nv, 3);
    // Vertices whose far side fills most of their ball, with that side's sum.
    std::vector<std::pair<Eigen::Index, Eigen::Vector3d>> flap_candidates;
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index i = 0; i < nv; ++i) {
        const Eigen::Index v = order[i];
        const Eigen::Vector3d x = mesh.points.row(v).transpose();
        const Eigen::Vector3d own = ring.row(v).transpose().normalized();
        // The far side of a thin wall left out, as seen from the vertex's own normal.
        const AabbTree::BallNormalSums sums = tree.area_weighted_normals_in_ball(sums_of, x, eta, {own, kFacingMinDot});
        // Unless it holds most of the ball: the vertex may be on a flap (below).
        if (sums.against.norm() > kFoldedFlapRatio * sums.facing.norm()) {
#pragma omp critical(folded_flaps)
            flap_candidates.emplace_back(v, sums.against);
        }
        const double len = sums.facing.norm();
        normals.row(v) = (len > 0.0 ? Eigen::Vector3d(sums.facing / len) : own).transpose();
    }
    // A vertex on a flap folded back onto the surface (a pleat, as hole fillers and scans leave)
    // takes the normal of the surface round it, the side that fills its ball: else the lifting
    // (Eq. 12) would set the flap apart from the surface, an island of sites of its own. Few
    // vertices, if any: the edges' triangles are listed for them alone.
    if (!flap_candidates.empty()) {
        std::sort(flap_candidates.begin(), flap_candidates.end(),
                  [](const auto& p, const auto& q) { return p.first < q.first; });
        const CompressedRows around = vertex_triangles(mesh);
        for (const auto& [v, surface] : flap_candidates) {
            const Eigen::Vector3d x = mesh.points.row(v).transpose();
            const Eigen::Vector3d own = ring.row(v).transpose().normalized();
            if (!on_folded_flap(mesh, around, v, own, eta)) continue;
            const Eigen::Vector3d sum = tree.area_weighted_normals_in_ball(sums_of, x, eta, {surface.normalized(), kFacingMinDot}).facing;
            if (sum.norm() > 0.0) normals.row(v) = sum.normalized().transpose();
        }
    }
    return normals;
}

LiftedPoints lift(const Points& points, const Points& normals, double nu) {
    if (nu == 0.0) return points;
    LiftedPoints out(points.rows(), 6);
    out.leftCols(3) = points;
    out.rightCols(3) = nu * normals; // Eq. 12
    return out;
}

LiftedPoints lift(const Points& points, const Points& normals, const Eigen::VectorXd& nu) {
    LiftedPoints out(points.rows(), 6);
    out.leftCols(3) = points;
    out.rightCols(3) = normals.array().colwise() * nu.array(); // Eq. 12, nu per vertex
    return out;
}

std::vector<CreaseEdge> creases_over_balls(const Mesh& mesh, const AabbTree& tree, const std::vector<CreaseEdge>& creases,
                                           double eta, double min_turn_deg) {
    if (!(eta > 0.0) || !std::isfinite(eta)) throw InvalidInput("creases_over_balls: eta must be positive and finite");
    for (const CreaseEdge& e : creases)
        if (e.left < 0 || e.right < 0 || e.left >= mesh.triangles.rows() || e.right >= mesh.triangles.rows() ||
            e.a < 0 || e.b < 0 || e.a >= mesh.points.rows() || e.b >= mesh.points.rows())
            throw InvalidInput("creases_over_balls: a crease edge's vertex or triangle index is out of range");
    const double cos_turn = std::cos(min_turn_deg * M_PI / 180.0);
    auto corner = [&mesh](int32_t f, int j) { return Eigen::Vector3d(mesh.points.row(mesh.triangles(f, j)).transpose()); };
    auto centroid = [&](int32_t f) -> Eigen::Vector3d { return (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0; };
    std::vector<char> keep(creases.size(), 0);
#pragma omp parallel
    {
        std::vector<int32_t> met;
#pragma omp for schedule(dynamic, 64)
        for (long k = 0; k < static_cast<long>(creases.size()); ++k) {
            const CreaseEdge& e = creases[static_cast<size_t>(k)];
            const Eigen::Vector3d mid = 0.5 * (mesh.points.row(e.a) + mesh.points.row(e.b)).transpose();
            // The plane bisecting the crease: normal n_left - n_right, through its edge.
            const Eigen::Vector3d across = tree.triangle_normal(e.left) - tree.triangle_normal(e.right);
            const double left_side = (centroid(e.left) - mid).dot(across);
            Eigen::Vector3d sums[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
            met.clear();
            tree.triangles_within(mid, eta, met);
            for (int32_t f : met) {
                const double side = (centroid(f) - mid).dot(across);
                if (side == 0.0) continue;
                const double area = triangle_ball_intersection_area(mid, eta, corner(f, 0), corner(f, 1), corner(f, 2));
                sums[(side > 0.0) == (left_side > 0.0) ? 0 : 1] += area * tree.triangle_normal(f);
            }
            const double n0 = sums[0].norm(), n1 = sums[1].norm();
            keep[static_cast<size_t>(k)] = n0 > 0.0 && n1 > 0.0 && sums[0].dot(sums[1]) < cos_turn * n0 * n1;
        }
    }
    std::vector<CreaseEdge> out;
    for (size_t k = 0; k < creases.size(); ++k)
        if (keep[k]) out.push_back(creases[k]);
    return out;
}

} // namespace liftremesh
