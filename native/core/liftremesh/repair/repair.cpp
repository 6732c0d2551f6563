#include "liftremesh/repair/repair.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/orientation.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <tuple>
#include <unordered_set>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

using Tri = std::array<int32_t, 3>;

// The triangle soup being repaired: triangles are only ever removed (alive = false) or
// reoriented, never added, so every loop below runs a bounded number of times.
class Repairer {
public:
    Repairer(const Points& points, const Triangles& triangles) : points_(points) {
        tris_.reserve(static_cast<size_t>(triangles.rows()));
        for (Eigen::Index f = 0; f < triangles.rows(); ++f)
            tris_.push_back({triangles(f, 0), triangles(f, 1), triangles(f, 2)});
        alive_.assign(tris_.size(), 1);
        reversed_.assign(tris_.size(), 0);
    }

    // Triangles with a repeated index, or whose area is zero up to rounding (zero_area, geometry.h).
    long remove_degenerate() {
        long removed = 0;
        for (size_t f = 0; f < tris_.size(); ++f) {
            const Tri& t = tris_[f];
            if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || zero_area(p(t[0]), p(t[1]), p(t[2]))) {
                alive_[f] = 0;
                ++removed;
            }
        }
        return removed;
    }

    // Same vertex set as an earlier triangle, in either orientation: the first one is kept
    // (orientation is decided later, by the majority of the component).
    long remove_duplicates() {
        std::unordered_set<Tri, TriangleKeyHash> seen;
        seen.reserve(tris_.size());
        long removed = 0;
        for (size_t f = 0; f < tris_.size(); ++f) {
            if (!alive_[f]) continue;
            Tri key = tris_[f];
            std::sort(key.begin(), key.end());
            if (!seen.insert(key).second) {
                alive_[f] = 0;
                ++removed;
            }
        }
        return removed;
    }

    // Keeps at most two triangles on every edge. Removals only lower edge counts, so one pass
    // over the edges used by 3+ triangles settles every edge for good.
    long fix_nonmanifold_edges() {
        build_edge_index();
        long removed = 0;
        std::vector<int> live;
        for (long e = 0; e < edges_.size(); ++e) { // sorted edges: a deterministic order
            if (edges_.count(e) <= 2) continue;
            live_on(static_cast<int>(e), live);
            if (live.size() <= 2) continue;
            const int32_t a = edges_.a[e], b = edges_.b[e];
            const auto [keep1, keep2] = best_pair(live, a, b);
            for (int t : live)
                if (t != keep1 && t != keep2) {
                    alive_[t] = 0;
                    ++removed;
                }
        }
        return removed;
    }

    // Makes every vertex's triangles one edge-connected fan by keeping the largest fan. A
    // worklist revisits the vertices of removed triangles (a removal can split a neighbour's
    // fan); every removal is final, so the work is bounded by the number of triangles.
    long fix_nonmanifold_vertices() {
        std::vector<std::pair<int32_t, int32_t>> corners; // (vertex, live triangle)
        corners.reserve(3 * tris_.size());
        for (size_t f = 0; f < tris_.size(); ++f)
            if (alive_[f])
                for (int32_t v : tris_[f]) corners.emplace_back(v, static_cast<int32_t>(f));
        const CompressedRows vertex_tris = compress_rows(points_.rows(), corners);
        std::deque<int32_t> work;
        std::vector<char> queued(static_cast<size_t>(points_.rows()), 1);
        for (int32_t v = 0; v < static_cast<int32_t>(points_.rows()); ++v) work.push_back(v);
        long removed = 0;
        std::vector<int> live, fan;
        std::vector<Tri> around;                  // corners of the live triangles around v
        std::vector<std::pair<int, double>> fans; // per fan: (triangles, area)
        while (!work.empty()) {
            const int32_t v = work.front();
            work.pop_front();
            queued[v] = 0;
            live.clear();
            for (const int32_t* t = vertex_tris.begin(v); t != vertex_tris.end(v); ++t)
                if (alive_[*t]) live.push_back(*t);
            if (live.size() < 2) continue;
            around.clear();
            for (int t : live) around.push_back(tris_[t]);
            const int fan_count = vertex_fans(v, around, fan);
            if (fan_count < 2) continue;
            fans.assign(fan_count, {0, 0.0});
            for (size_t i = 0; i < live.size(); ++i) {
                fans[fan[i]].first += 1;
                fans[fan[i]].second += area(live[i]);
            }
            int best = 0; // most triangles, then most area, then first
            for (int r = 1; r < fan_count; ++r)
                if (fans[r] > fans[best]) best = r;
            for (size_t i = 0; i < live.size(); ++i) {
                if (fan[i] == best) continue;
                alive_[live[i]] = 0;
                ++removed;
                for (int32_t w : tris_[live[i]])
                    if (w != v && !queued[w]) {
                        queued[w] = 1;
                        work.push_back(w);
                    }
            }
        }
        return removed;
    }

    // Orients every connected component consistently (orient_components, orientation.h). On a
    // non-orientable component some edges stay inconsistent: remove_orientation_conflicts()
    // deals with them.
    void orient() {
        const std::vector<char> turned = orient_components(points_, tris_, alive_);
        for (size_t f = 0; f < tris_.size(); ++f) reversed_[f] ^= turned[f];
    }

    // After orient(), an edge whose two triangles still run the same way closes a non-orientable
    // loop (a Moebius band). Removes the worse-shaped (smaller kappa) triangle of each such edge,
    // cutting the band; the caller then fixes vertices and orients again.
    long remove_orientation_conflicts() {
        build_edge_index();
        long removed = 0;
        std::vector<int> live;
        for (long e = 0; e < edges_.size(); ++e) {
            live_on(static_cast<int>(e), live);
            if (live.size() != 2) continue;
            const int32_t a = edges_.a[e], b = edges_.b[e];
            if (traverses(tris_[live[0]], a, b) != traverses(tris_[live[1]], a, b)) continue;
            const int worse = kappa(live[0]) < kappa(live[1]) ? live[0] : live[1];
            alive_[worse] = 0;
            ++removed;
        }
        return removed;
    }

    // Surviving triangles whose orientation differs from the input's.
    long count_reversed() const {
        long n = 0;
        for (size_t f = 0; f < tris_.size(); ++f) n += alive_[f] && reversed_[f];
        return n;
    }

    // The surviving triangles in their original order.
    Triangles result() const {
        Triangles out(std::count(alive_.begin(), alive_.end(), 1), 3);
        Eigen::Index row = 0;
        for (size_t f = 0; f < tris_.size(); ++f)
            if (alive_[f]) {
                for (int j = 0; j < 3; ++j) out(row, j) = tris_[f][j];
                ++row;
            }
        return out;
    }

private:
    Eigen::Vector3d p(int32_t i) const { return points_.row(i).transpose(); }

    double area(int t) const { return triangle_area(p(tris_[t][0]), p(tris_[t][1]), p(tris_[t][2])); }

    double kappa(int t) const { return triangle_kappa(p(tris_[t][0]), p(tris_[t][1]), p(tris_[t][2])); }

    // Sorted edge -> triangle incidence of the live triangles (edge_uses, mesh.h), and each
    // edge's key for find_edge().
    void build_edge_index() {
        static_assert(sizeof(Tri) == 3 * sizeof(int32_t), "triangles stored as consecutive corners");
        edges_ = edge_uses(tris_.empty() ? nullptr : tris_[0].data(), static_cast<long>(tris_.size()), alive_);
        keys_.resize(static_cast<size_t>(edges_.size()));
        for (long e = 0; e < edges_.size(); ++e) keys_[e] = edge_key(edges_.a[e], edges_.b[e]);
    }

    // Index of the edge with this key in the last build_edge_index(), or -1.
    int find_edge(uint64_t key) const {
        const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
        return it != keys_.end() && *it == key ? static_cast<int>(it - keys_.begin()) : -1;
    }

    // The still-live triangles of edge e (none when e < 0).
    void live_on(int e, std::vector<int>& live) const {
        live.clear();
        if (e < 0) return;
        for (const int32_t* use = edges_.uses.begin(e); use != edges_.uses.end(e); ++use)
            if (alive_[*use / 3]) live.push_back(*use / 3);
    }

    // Number of t's edges other than {a, b} that another live triangle shares: a fin hanging on
    // the edge scores 0, a triangle of the surrounding surface 2.
    int support(int t, int32_t a, int32_t b) const {
        int s = 0;
        std::vector<int> live;
        for (int j = 0; j < 3; ++j) {
            const int32_t u = tris_[t][j], w = tris_[t][(j + 1) % 3];
            if (edge_key(u, w) == edge_key(a, b)) continue;
            live_on(find_edge(edge_key(u, w)), live);
            if (live.size() >= 2) ++s;
        }
        return s;
    }

    // The two triangles of `live` (all on edge {a, b}) to keep, ranked by: consistent
    // orientation across the edge; then how well both are attached to the rest of the surface
    // (support); then the larger smaller kappa (Eq. 26); then the earlier pair.
    std::pair<int, int> best_pair(const std::vector<int>& live, int32_t a, int32_t b) const {
        std::vector<int> sup(live.size());
        std::vector<double> kap(live.size());
        std::vector<char> ab(live.size());
        for (size_t i = 0; i < live.size(); ++i) {
            sup[i] = support(live[i], a, b);
            kap[i] = kappa(live[i]);
            ab[i] = traverses(tris_[live[i]], a, b);
        }
        std::tuple<int, int, double> best{-1, -1, -1.0};
        std::pair<int, int> keep{live[0], live[1]};
        for (size_t i = 0; i < live.size(); ++i)
            for (size_t j = i + 1; j < live.size(); ++j) {
                const std::tuple<int, int, double> score{ab[i] != ab[j] ? 1 : 0, sup[i] + sup[j],
                                                         std::min(kap[i], kap[j])};
                if (score > best) {
                    best = score;
                    keep = {live[i], live[j]};
                }
            }
        return keep;
    }

    const Points& points_;
    std::vector<Tri> tris_;
    std::vector<char> alive_;
    std::vector<char> reversed_; // reoriented an odd number of times
    EdgeUses edges_;             // see build_edge_index()
    std::vector<uint64_t> keys_; // edge_key of each of edges_, sorted
};

} // namespace

RepairStats make_manifold(Mesh& mesh) {
    check_indices(mesh, "make_manifold");
    RepairStats stats;
    Repairer repair(mesh.points, mesh.triangles);
    stats.degenerate_removed = repair.remove_degenerate();
    stats.duplicates_removed = repair.remove_duplicates();
    // Edge removals never create a non-manifold edge, the vertex worklist runs to a fixed point,
    // and every further pass is caused by (and removes) an orientation conflict, so the loop
    // ends after at most #F passes; in practice one or two.
    while (true) {
        stats.nonmanifold_removed += repair.fix_nonmanifold_edges() + repair.fix_nonmanifold_vertices();
        repair.orient();
        const long conflicts = repair.remove_orientation_conflicts();
        stats.nonmanifold_removed += conflicts;
        if (conflicts == 0) break;
    }
    stats.flipped = repair.count_reversed();
    mesh.triangles = repair.result();
    remove_unreferenced_vertices(mesh);
    return stats;
}

} // namespace liftremesh
