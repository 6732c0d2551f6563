#include "liftremesh/patch_refinement.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace liftremesh {

namespace {

using Tri = std::array<int32_t, 3>;

constexpr double kCos30 = 0.86602540378443865; // largest turn of a triangle's normal allowed

// Where an edge is used by patch triangles: (triangle, j) with the edge running t[j] -> t[j+1].
struct Use {
    int tri, j;
};

class Patch {
public:
    Patch(const Mesh& mesh, Eigen::Index first) : first_added_(static_cast<int32_t>(mesh.points.rows())) {
        points_.reserve(static_cast<size_t>(mesh.points.rows()));
        for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) points_.push_back(mesh.points.row(i).transpose());
        for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
            const Tri t = {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
            if (f < first)
                for (int j = 0; j < 3; ++j) outside_.insert(edge_key(t[j], t[(j + 1) % 3]));
            else
                tris_.push_back(t);
        }
    }

    // Splits the edges two patch triangles share that are longer than 4/3 h, or longer than
    // h / 2 and opposite an angle above 120 degrees (a sliver's long side), longest first; a
    // triangle is split once a round. Returns whether any edge was split.
    bool split_long_edges(double h, long max_added) {
        std::vector<std::pair<double, uint64_t>> candidates;
        const auto uses = edge_uses();
        for (const auto& [key, use] : uses) {
            if (use.size() != 2) continue;
            const Tri& t = tris_[use[0].tri];
            const int32_t a = t[use[0].j], b = t[(use[0].j + 1) % 3];
            const double length = (points_[b] - points_[a]).norm();
            const bool obtuse = opposite_cos(use[0]) < -0.5 || opposite_cos(use[1]) < -0.5;
            if (length > 4.0 / 3.0 * h || (obtuse && length > 0.5 * h)) candidates.emplace_back(-length, key);
        }
        std::sort(candidates.begin(), candidates.end()); // longest first, then by key: deterministic
        std::vector<char> touched(tris_.size(), 0);
        bool any = false;
        for (const auto& [negative_length, key] : candidates) {
            const auto& use = uses.at(key);
            if (touched[use[0].tri] || touched[use[1].tri]) continue;
            if (added() >= max_added) break;
            const auto quad = quad_of(use);
            if (!quad) continue;
            const auto [t1, t2, a, b, c, d] = *quad;
            const auto m = static_cast<int32_t>(points_.size());
            points_.push_back(0.5 * (points_[a] + points_[b]));
            tris_[t1] = {a, m, c};
            tris_[t2] = {b, m, d};
            tris_.push_back({m, b, c});
            tris_.push_back({m, a, d});
            touched[t1] = touched[t2] = 1;
            touched.resize(tris_.size(), 1);
            any = true;
        }
        return any;
    }

    // Flips shared patch edges while a flip raises the smaller kappa of its two triangles.
    void flip_edges() {
        std::unordered_set<uint64_t> edges = outside_;
        for (const Tri& t : tris_)
            for (int j = 0; j < 3; ++j) edges.insert(edge_key(t[j], t[(j + 1) % 3]));
        for (int pass = 0; pass < 20; ++pass) {
            const auto uses = edge_uses();
            std::vector<uint64_t> keys;
            for (const auto& [key, use] : uses)
                if (use.size() == 2) keys.push_back(key);
            std::sort(keys.begin(), keys.end());
            std::vector<char> touched(tris_.size(), 0);
            bool any = false;
            for (uint64_t key : keys) {
                const auto& use = uses.at(key);
                if (touched[use[0].tri] || touched[use[1].tri]) continue;
                const auto quad = quad_of(use);
                if (!quad) continue;
                const auto [t1, t2, a, b, c, d] = *quad;
                if (c == d || edges.count(edge_key(c, d))) continue;
                // The quad a -> d -> b -> c: the new triangles keep its orientation.
                const Tri n1 = {a, d, c}, n2 = {d, b, c};
                const Eigen::Vector3d before1 = normal(tris_[t1]), before2 = normal(tris_[t2]);
                if (!turns_little(before1, before2)) continue; // not a near-planar quad: the flip would change the shape
                const Eigen::Vector3d mean = before1.normalized() + before2.normalized();
                if (!turns_little(mean, normal(n1)) || !turns_little(mean, normal(n2))) continue;
                if (std::min(kappa(n1), kappa(n2)) <= std::min(kappa(tris_[t1]), kappa(tris_[t2])) + 1e-9) continue;
                edges.erase(key);
                edges.insert(edge_key(c, d));
                tris_[t1] = n1;
                tris_[t2] = n2;
                touched[t1] = touched[t2] = 1;
                any = true;
            }
            if (!any) break;
        }
    }

    // Moves each added vertex to the average of its neighbours, unless that turns one of its
    // triangles by more than 30 degrees or makes one degenerate.
    void smooth(int sweeps) {
        const auto added = static_cast<size_t>(static_cast<int32_t>(points_.size()) - first_added_);
        if (added == 0) return;
        std::vector<std::vector<int>> incident(added);
        std::vector<std::unordered_set<int32_t>> ring(added);
        for (size_t f = 0; f < tris_.size(); ++f)
            for (int j = 0; j < 3; ++j) {
                const int32_t v = tris_[f][j];
                if (v < first_added_) continue;
                incident[v - first_added_].push_back(static_cast<int>(f));
                ring[v - first_added_].insert(tris_[f][(j + 1) % 3]);
                ring[v - first_added_].insert(tris_[f][(j + 2) % 3]);
            }
        for (int sweep = 0; sweep < sweeps; ++sweep)
            for (size_t i = 0; i < added; ++i) {
                if (ring[i].empty()) continue;
                std::vector<int32_t> around(ring[i].begin(), ring[i].end());
                std::sort(around.begin(), around.end()); // a fixed summation order
                Eigen::Vector3d target = Eigen::Vector3d::Zero();
                for (int32_t w : around) target += points_[w];
                target /= static_cast<double>(around.size());
                const int32_t v = first_added_ + static_cast<int32_t>(i);
                std::vector<Eigen::Vector3d> before;
                for (int f : incident[i]) before.push_back(normal(tris_[f]));
                const Eigen::Vector3d old = points_[v];
                points_[v] = target;
                bool ok = true;
                for (size_t k = 0; k < before.size() && ok; ++k)
                    ok = turns_little(before[k], normal(tris_[incident[i][k]])) && kappa(tris_[incident[i][k]]) > 0.0;
                if (!ok) points_[v] = old;
            }
    }

    long added() const { return static_cast<long>(points_.size()) - first_added_; }

    void write_to(Mesh& mesh, Eigen::Index first) const {
        mesh.points.conservativeResize(static_cast<Eigen::Index>(points_.size()), 3);
        for (size_t i = static_cast<size_t>(first_added_); i < points_.size(); ++i)
            mesh.points.row(static_cast<Eigen::Index>(i)) = points_[i].transpose();
        mesh.triangles.conservativeResize(first + static_cast<Eigen::Index>(tris_.size()), 3);
        for (size_t k = 0; k < tris_.size(); ++k)
            for (int j = 0; j < 3; ++j) mesh.triangles(first + static_cast<Eigen::Index>(k), j) = tris_[k][j];
    }

private:
    // The two patch triangles of a shared edge, t1 running a -> b -> c and t2 b -> a -> d (the
    // quad a -> d -> b -> c); none if t2 does not run the edge the other way, as splitting and
    // flipping assume.
    struct Quad {
        int t1, t2;
        int32_t a, b, c, d;
    };
    std::optional<Quad> quad_of(const std::vector<Use>& use) const {
        const Tri &first = tris_[use[0].tri], &second = tris_[use[1].tri];
        const int32_t a = first[use[0].j], b = first[(use[0].j + 1) % 3], c = first[(use[0].j + 2) % 3];
        if (second[use[1].j] != b) return std::nullopt;
        return Quad{use[0].tri, use[1].tri, a, b, c, second[(use[1].j + 2) % 3]};
    }

    std::unordered_map<uint64_t, std::vector<Use>> edge_uses() const {
        std::unordered_map<uint64_t, std::vector<Use>> uses;
        for (size_t f = 0; f < tris_.size(); ++f)
            for (int j = 0; j < 3; ++j)
                uses[edge_key(tris_[f][j], tris_[f][(j + 1) % 3])].push_back({static_cast<int>(f), j});
        return uses;
    }
    // Cosine of the angle of the use's triangle opposite its edge.
    double opposite_cos(const Use& u) const {
        const Tri& t = tris_[u.tri];
        const Eigen::Vector3d c = points_[t[(u.j + 2) % 3]];
        const Eigen::Vector3d e1 = points_[t[u.j]] - c, e2 = points_[t[(u.j + 1) % 3]] - c;
        const double n = e1.norm() * e2.norm();
        return n > 0.0 ? e1.dot(e2) / n : 1.0;
    }
    Eigen::Vector3d normal(const Tri& t) const {
        return (points_[t[1]] - points_[t[0]]).cross(points_[t[2]] - points_[t[0]]);
    }
    double kappa(const Tri& t) const { return triangle_kappa(points_[t[0]], points_[t[1]], points_[t[2]]); }
    static bool turns_little(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
        const double n = u.norm() * v.norm();
        return n > 0.0 && u.dot(v) >= kCos30 * n;
    }

    std::vector<Eigen::Vector3d> points_;
    std::vector<Tri> tris_;
    std::unordered_set<uint64_t> outside_; // edges of the triangles before `first`
    int32_t first_added_;
};

} // namespace

long refine_patches(Mesh& mesh, Eigen::Index first, double h, long max_added, int rounds) {
    check_indices(mesh, "refine_patches");
    if (first < 0 || first > mesh.triangles.rows())
        throw InvalidInput("refine_patches: first patch triangle " + std::to_string(first) + " is out of range");
    if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInput("refine_patches: edge length must be positive and finite");
    if (first == mesh.triangles.rows()) return 0;
    Patch patch(mesh, first);
    for (int round = 0; round < rounds; ++round) {
        const bool split = patch.split_long_edges(h, max_added);
        patch.flip_edges();
        patch.smooth(3);
        if (!split) break;
    }
    patch.write_to(mesh, first);
    return patch.added();
}

} // namespace liftremesh
