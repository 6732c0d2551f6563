#include "liftremesh/edge_collapse.h"

#include "liftremesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <tuple>

namespace liftremesh {

namespace {

struct Adjacency {
    std::vector<std::vector<int32_t>> triangles_of; // per vertex, live triangles using it
    std::vector<char> alive;                        // per triangle
};

Eigen::Vector3d position(const Mesh& m, int32_t v) { return m.points.row(v).transpose(); }

double kappa_of(const Mesh& m, const std::array<int32_t, 3>& t) {
    return triangle_kappa(position(m, t[0]), position(m, t[1]), position(m, t[2]));
}

std::array<int32_t, 3> corners(const Mesh& m, int32_t f) { return {m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)}; }

// 2 pi minus the sum of the angles at v: zero on a flat or ruled (crease) surface, large at a corner.
double angle_defect(const Mesh& m, const Adjacency& adj, int32_t v) {
    double sum = 0.0;
    for (int32_t f : adj.triangles_of[v]) {
        const auto t = corners(m, f);
        const int i = t[0] == v ? 0 : t[1] == v ? 1 : 2;
        const Eigen::Vector3d a = position(m, t[(i + 1) % 3]) - position(m, v);
        const Eigen::Vector3d b = position(m, t[(i + 2) % 3]) - position(m, v);
        sum += std::atan2(a.cross(b).norm(), a.dot(b));
    }
    return std::abs(2.0 * M_PI - sum);
}

std::vector<int32_t> neighbours(const Mesh& m, const Adjacency& adj, int32_t v) {
    std::vector<int32_t> out;
    for (int32_t f : adj.triangles_of[v])
        for (int32_t w : corners(m, f))
            if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Tries to merge `gone` into `kept` (kept's position stays). Returns the smallest kappa of the
// new fan, or -1 if the collapse is not allowed.
double try_collapse(const Mesh& m, const Adjacency& adj, int32_t kept, int32_t gone, double old_min) {
    const Eigen::Vector3d p = position(m, kept);
    double worst = 1.0;
    for (int32_t f : adj.triangles_of[gone]) {
        auto t = corners(m, f);
        if (std::find(t.begin(), t.end(), kept) != t.end()) continue; // removed by the collapse
        const Eigen::Vector3d before = triangle_normal(position(m, t[0]), position(m, t[1]), position(m, t[2]));
        for (auto& v : t)
            if (v == gone) v = kept;
        Eigen::Vector3d q[3];
        for (int j = 0; j < 3; ++j) q[j] = t[j] == kept ? p : position(m, t[j]);
        const Eigen::Vector3d after = triangle_normal(q[0], q[1], q[2]);
        if (after.dot(before) < std::cos(M_PI / 4)) return -1.0; // folds or turns too much
        worst = std::min(worst, triangle_kappa(q[0], q[1], q[2]));
    }
    for (int32_t f : adj.triangles_of[kept]) {
        const auto t = corners(m, f);
        if (std::find(t.begin(), t.end(), gone) != t.end()) continue;
        worst = std::min(worst, kappa_of(m, t));
    }
    return worst > old_min ? worst : -1.0;
}

} // namespace

long collapse_short_edges(Mesh& mesh, double ratio) {
    const Eigen::Index nf = mesh.triangles.rows();
    if (nf == 0) return 0;
    std::vector<EdgeCount> edges = edge_counts(mesh.triangles);
    std::vector<double> lengths;
    lengths.reserve(edges.size());
    for (const EdgeCount& e : edges) lengths.push_back((position(mesh, e.a) - position(mesh, e.b)).norm());
    std::vector<double> sorted = lengths;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = ratio * sorted[sorted.size() / 2];

    std::vector<std::tuple<double, int32_t, int32_t>> candidates;
    for (size_t i = 0; i < edges.size(); ++i)
        if (edges[i].count == 2 && lengths[i] < limit) candidates.emplace_back(lengths[i], edges[i].a, edges[i].b);
    if (candidates.empty()) return 0;
    std::sort(candidates.begin(), candidates.end());

    // On an open surface, an interior edge between two boundary vertices must stay: collapsing
    // it joins the two boundaries at one vertex (the link condition with the boundary's virtual
    // vertex).
    std::vector<char> on_boundary(static_cast<size_t>(mesh.points.rows()), 0);
    for (const EdgeCount& e : edges)
        if (e.count == 1) on_boundary[e.a] = on_boundary[e.b] = 1;

    Adjacency adj;
    adj.triangles_of.resize(mesh.points.rows());
    adj.alive.assign(nf, 1);
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int j = 0; j < 3; ++j) adj.triangles_of[mesh.triangles(f, j)].push_back(static_cast<int32_t>(f));

    long collapsed = 0;
    for (const auto& [length, a, b] : candidates) {
        // The edge must still exist with exactly two triangles, whose opposite vertices are the
        // only common neighbours of a and b (link condition: the collapse keeps a manifold).
        std::vector<int32_t> shared, opposite;
        for (int32_t f : adj.triangles_of[a]) {
            const auto t = corners(mesh, f);
            if (std::find(t.begin(), t.end(), b) == t.end()) continue;
            shared.push_back(f);
            for (int32_t v : t)
                if (v != a && v != b) opposite.push_back(v);
        }
        if (shared.size() != 2 || opposite[0] == opposite[1]) continue;
        if (on_boundary[a] && on_boundary[b]) continue;
        const std::vector<int32_t> na = neighbours(mesh, adj, a), nb = neighbours(mesh, adj, b);
        std::vector<int32_t> common;
        std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
        std::sort(opposite.begin(), opposite.end());
        if (common != opposite) continue;
        if (na.size() + nb.size() <= 6) continue; // would leave a degenerate (tetrahedron-like) piece
        bool low_valence = false;                  // the opposite vertices lose an edge each
        for (int32_t v : opposite) low_valence = low_valence || adj.triangles_of[v].size() <= 3;
        if (low_valence) continue;

        double old_min = 1.0;
        for (int32_t v : {a, b})
            for (int32_t f : adj.triangles_of[v]) old_min = std::min(old_min, kappa_of(mesh, corners(mesh, f)));
        const double keep_a = try_collapse(mesh, adj, a, b, old_min);
        const double keep_b = try_collapse(mesh, adj, b, a, old_min);
        if (keep_a < 0.0 && keep_b < 0.0) continue;
        bool a_stays = keep_a >= 0.0;
        if (keep_a >= 0.0 && keep_b >= 0.0) a_stays = angle_defect(mesh, adj, a) >= angle_defect(mesh, adj, b);
        const int32_t kept = a_stays ? a : b, gone = a_stays ? b : a;

        for (int32_t f : shared) {
            adj.alive[f] = 0;
            for (int32_t v : corners(mesh, f)) {
                auto& list = adj.triangles_of[v];
                list.erase(std::remove(list.begin(), list.end(), f), list.end());
            }
        }
        for (int32_t f : adj.triangles_of[gone]) {
            for (int j = 0; j < 3; ++j)
                if (mesh.triangles(f, j) == gone) mesh.triangles(f, j) = kept;
            adj.triangles_of[kept].push_back(f);
        }
        adj.triangles_of[gone].clear();
        on_boundary[kept] = on_boundary[kept] || on_boundary[gone];
        ++collapsed;
    }
    if (collapsed == 0) return 0;
    Triangles kept_triangles(nf - 2 * collapsed, 3);
    Eigen::Index row = 0;
    for (Eigen::Index f = 0; f < nf; ++f)
        if (adj.alive[f]) kept_triangles.row(row++) = mesh.triangles.row(f);
    mesh.triangles = std::move(kept_triangles);
    remove_unreferenced_vertices(mesh);
    return collapsed;
}

} // namespace liftremesh
