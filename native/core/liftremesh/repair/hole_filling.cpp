#include "liftremesh/repair/hole_filling.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace liftremesh {

namespace {

using Tri = std::array<int32_t, 3>;
using EdgeSet = std::unordered_set<uint64_t>;

// A boundary edge, directed the way the hole runs (the reverse of its one triangle), and that triangle.
struct HoleEdge {
    int32_t from, to;
    int tri;
};

// Edges used by exactly one triangle, directed from -> to where the triangle runs to -> from.
std::vector<HoleEdge> hole_edges(const Triangles& triangles) {
    const EdgeUses edges = edge_uses(triangles);
    std::vector<HoleEdge> out;
    for (long e = 0; e < edges.size(); ++e)
        if (edges.count(e) == 1) {
            const int32_t use = *edges.uses.begin(e), f = use / 3, j = use % 3;
            out.push_back({triangles(f, (j + 1) % 3), triangles(f, j), f}); // against the triangle's side
        }
    std::sort(out.begin(), out.end(),
              [](const HoleEdge& x, const HoleEdge& y) { return std::tie(x.from, x.to) < std::tie(y.from, y.to); });
    return out;
}

// Splits the directed hole edges into simple cycles. A walk follows unused edges; when it comes
// back to a vertex already on its path, the cycle from that vertex is cut off as one loop, so a
// boundary pinched at a vertex gives one simple loop per pass through it. On a balanced graph
// (every boundary vertex of an oriented manifold has as many hole edges in as out) the walk
// can only stop at its start; a walk stuck elsewhere (inconsistent orientation) is dropped.
// Every edge is used once: O(#edges).
// Each boundary edge's one triangle, by edge_key.
std::unordered_map<uint64_t, int> triangle_of_edge(const std::vector<HoleEdge>& edges) {
    std::unordered_map<uint64_t, int> out;
    for (const HoleEdge& e : edges) out[edge_key(e.from, e.to)] = e.tri;
    return out;
}

std::vector<std::vector<int32_t>> trace_loops(const std::vector<HoleEdge>& edges, Eigen::Index num_vertices) {
    const auto nv = static_cast<size_t>(num_vertices);
    std::vector<int> first(nv + 1, 0); // out-edges of v: order[first[v] .. first[v + 1])
    for (const HoleEdge& e : edges) ++first[e.from + 1];
    for (size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
    std::vector<int> order(edges.size()), cursor(first.begin(), first.end() - 1);
    for (size_t e = 0; e < edges.size(); ++e) order[cursor[edges[e].from]++] = static_cast<int>(e);
    std::copy(first.begin(), first.end() - 1, cursor.begin());

    std::vector<std::vector<int32_t>> loops;
    std::vector<int> pos(nv, -1); // position of a vertex on the current path
    std::vector<int32_t> path;
    for (const HoleEdge& start : edges) {
        int32_t v = start.from;
        if (cursor[v] == first[v + 1]) continue; // all its edges are used
        path.assign(1, v);
        pos[v] = 0;
        while (true) {
            if (cursor[v] == first[v + 1]) { // stuck: done if back at the start, else not a cycle
                for (int32_t x : path) pos[x] = -1;
                path.clear();
                break;
            }
            const int32_t w = edges[order[cursor[v]++]].to;
            if (pos[w] < 0) {
                pos[w] = static_cast<int>(path.size());
                path.push_back(w);
            } else {
                const auto k = static_cast<size_t>(pos[w]);
                loops.emplace_back(path.begin() + static_cast<std::ptrdiff_t>(k), path.end());
                for (size_t i = k + 1; i < path.size(); ++i) pos[path[i]] = -1;
                path.resize(k + 1);
            }
            v = w;
        }
    }
    return loops;
}

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Twice the signed area of (a, b, c): positive when counter-clockwise.
double orient2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return cross2(b - a, c - a);
}

// Whether the closed segments [a, b] and [c, d] meet (eps: tolerance on orient2).
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d, double eps) {
    const double o1 = orient2(a, b, c), o2 = orient2(a, b, d), o3 = orient2(c, d, a), o4 = orient2(c, d, b);
    auto sign = [eps](double x) { return x > eps ? 1 : (x < -eps ? -1 : 0); };
    const int s1 = sign(o1), s2 = sign(o2), s3 = sign(o3), s4 = sign(o4);
    if (s1 * s2 < 0 && s3 * s4 < 0) return true;
    // Touching or collinear: a point of one segment within the other's bounding box and on its line.
    auto on_segment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& x) {
        return x.x() >= std::min(p.x(), q.x()) && x.x() <= std::max(p.x(), q.x()) && x.y() >= std::min(p.y(), q.y()) &&
               x.y() <= std::max(p.y(), q.y());
    };
    return (s1 == 0 && on_segment(a, b, c)) || (s2 == 0 && on_segment(a, b, d)) || (s3 == 0 && on_segment(c, d, a)) ||
           (s4 == 0 && on_segment(c, d, b));
}

// Whether the closed polygon q (no repeated point, no self-intersection, no spike folding an
// edge back on its predecessor) is simple. O(n^2).
bool is_simple(const std::vector<Eigen::Vector2d>& q, double eps) {
    const size_t n = q.size();
    for (size_t i = 0; i < n; ++i) {
        const auto& a = q[i];
        const auto& b = q[(i + 1) % n];
        const auto& c = q[(i + 2) % n];
        if ((b - a).squaredNorm() == 0.0) return false;
        // Adjacent edges may only share their common vertex: reject a fold-back.
        if (std::abs(orient2(a, b, c)) <= eps && (a - b).dot(c - b) > 0.0) return false;
        for (size_t j = i + 2; j < n; ++j) {
            if ((j + 1) % n == i) continue; // adjacent through the wrap-around
            if (segments_meet(a, b, q[j], q[(j + 1) % n], eps)) return false;
        }
    }
    return true;
}

// Doubly linked polygon being cut into ears.
struct Ring {
    std::vector<int> prev, next;
    int remaining;
    explicit Ring(int n) : prev(n), next(n), remaining(n) {
        for (int i = 0; i < n; ++i) {
            prev[i] = (i + n - 1) % n;
            next[i] = (i + 1) % n;
        }
    }
    void clip(int i) {
        next[prev[i]] = next[i];
        prev[next[i]] = prev[i];
        --remaining;
    }
};

// Everything a triangulation of one hole needs to read; local triangles index `loop`.
class HoleTriangulator {
public:
    //! `outer[i]`: the unit normal of the surface's triangle on the loop's edge i -> i + 1 (zero
    //! if none).
    HoleTriangulator(const Points& points, const std::vector<int32_t>& loop, const EdgeSet& existing,
                     std::vector<Eigen::Vector3d> outer)
        : loop_(loop), existing_(existing), outer_(std::move(outer)) {
        p_.reserve(loop.size());
        for (int32_t v : loop) p_.push_back(points.row(v).transpose());
    }

    // Section 5.2.2: projects the loop onto its best-fit plane (principal component analysis)
    // and, if the projection is a simple polygon, takes its constrained Delaunay triangulation
    // (ear clipping, then Lawson flips of the diagonals; if existing edges block every ear, the
    // exact planar triangulation avoiding them, then the flips). Otherwise the loop is
    // triangulated in 3D: exactly up to kMaxExact vertices, greedily beyond. `surround` is the
    // area-weighted normal of the triangles around the hole. Returns false (out untouched) if no
    // valid triangulation is found.
    bool triangulate(const Eigen::Vector3d& surround, std::vector<Tri>& out) {
        const int n = static_cast<int>(loop_.size());
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (const auto& x : p_) centroid += x;
        centroid /= n;
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const auto& x : p_) cov += (x - centroid) * (x - centroid).transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(cov);
        // Eigenvalues ascend: the normal is the direction of least spread.
        Eigen::Vector3d normal = pca.eigenvectors().col(0);
        if (normal.dot(surround) < 0.0) normal = -normal;
        const Eigen::Vector3d u = pca.eigenvectors().col(2);
        const Eigen::Vector3d v = normal.cross(u); // (u, v, normal) right-handed
        std::vector<Eigen::Vector2d> q(n);
        for (int i = 0; i < n; ++i) q[i] = {(p_[i] - centroid).dot(u), (p_[i] - centroid).dot(v)};
        double twice_area = 0.0;
        for (int i = 0; i < n; ++i) twice_area += cross2(q[i], q[(i + 1) % n]);
        // The loop is counter-clockwise about `normal` when the hole is smaller than the surface
        // around it; a hole wrapping past a hemisphere winds the other way. Either way the fill
        // follows the loop's own winding, which is what keeps it consistent with the surface.
        if (twice_area < 0.0)
            for (auto& x : q) x.y() = -x.y();
        double scale = 0.0;
        for (const auto& x : q) scale = std::max(scale, x.norm());
        const double eps = 1e-12 * scale * scale;
        std::vector<Tri> local;
        bool planar = std::abs(twice_area) > eps && is_simple(q, eps) &&
                      (ear_clip_2d(q, eps, local) || (n <= kMaxExact && exact_2d(q, eps, local)));
        if (planar) lawson_flips(q, eps, local);
        // A hole across a knife edge of the input may project simple yet folded over: a triangle
        // of its planar fill then folds back onto the surface across the loop. The 3D path
        // fills it instead.
        for (const Tri& t : local) planar = planar && !folds_back(t[0], t[1], t[2]);
        if (!planar) {
            local.clear();
            created_.clear();
            const bool done = n <= kMaxExact ? exact_3d(normal, local) : ear_clip_3d(normal, local);
            if (!done) return false;
        }
        for (const Tri& t : local) out.push_back({loop_[t[0]], loop_[t[1]], loop_[t[2]]});
        return true;
    }

private:
    // Loops up to this size that ear clipping cannot finish, or that are not planar, are
    // triangulated exactly by an O(n^3) dynamic program; larger ones greedily in O(n^2).
    static constexpr int kMaxExact = 64;
    // A patch triangle turned by more than this from the surface's triangle across a loop edge
    // has folded back onto it: no knife edge of a CAD part is that sharp (15 degrees inside).
    static constexpr double kFoldBackDeg = 165.0;
    static inline const double kCosFoldBack = std::cos(kFoldBackDeg * M_PI / 180.0);

    // Whether the diagonal between loop positions a and c may be created.
    bool free_diagonal(int a, int c) const {
        const uint64_t key = edge_key(loop_[a], loop_[c]);
        return !existing_.count(key) && !created_.count(key);
    }

    double kappa(int a, int b, int c) const { return triangle_kappa(p_[a], p_[b], p_[c]); }

    // The ring vertex with the best non-negative ear score, or -1 if none is an ear.
    static int best_ear(const Ring& ring, int any, const std::vector<double>& score) {
        int best = -1;
        for (int i = any, k = 0; k < ring.remaining; i = ring.next[i], ++k)
            if (score[i] >= 0.0 && (best < 0 || score[i] > score[best])) best = i;
        return best;
    }

    // Takes the ear at `best` off the ring: records its triangle and its new diagonal, and
    // refreshes the scores of the two vertices beside it. Returns a vertex still on the ring.
    template <class Refresh>
    int take_ear(Ring& ring, int best, std::vector<Tri>& local, const Refresh& refresh) {
        const int a = ring.prev[best], c = ring.next[best];
        local.push_back({a, best, c});
        created_.insert(edge_key(loop_[a], loop_[c]));
        ring.clip(best);
        refresh(a);
        refresh(c);
        return a;
    }

    // Ear clipping of the simple counter-clockwise polygon q, each step taking the valid ear with
    // the best kappa (Eq. 26). Ear flags are refreshed beside the clipped vertex only: O(n^2).
    // A far vertex whose triangle held nothing but the clipped vertex keeps a stale "not an ear",
    // so when no ear is left every flag is refreshed, a bounded number of times.
    bool ear_clip_2d(const std::vector<Eigen::Vector2d>& q, double eps, std::vector<Tri>& local) {
        const int n = static_cast<int>(q.size());
        Ring ring(n);
        auto is_ear = [&](int i) {
            const int a = ring.prev[i], c = ring.next[i];
            if (orient2(q[a], q[i], q[c]) <= eps) return false;
            if (!free_diagonal(a, c)) return false;
            for (int j = ring.next[c]; j != a; j = ring.next[j])
                if (orient2(q[a], q[i], q[j]) >= -eps && orient2(q[i], q[c], q[j]) >= -eps &&
                    orient2(q[c], q[a], q[j]) >= -eps)
                    return false;
            return true;
        };
        std::vector<double> score(n);
        auto refresh = [&](int i) { score[i] = is_ear(i) ? kappa(ring.prev[i], i, ring.next[i]) : -1.0; };
        for (int i = 0; i < n; ++i) refresh(i);
        int any = 0, full_refreshes = 4;
        bool fresh = true; // every flag is up to date
        while (ring.remaining > 3) {
            const int best = best_ear(ring, any, score);
            if (best < 0 && !fresh && full_refreshes-- > 0) {
                for (int i = any, k = 0; k < ring.remaining; i = ring.next[i], ++k) refresh(i);
                fresh = true;
                continue;
            }
            if (best < 0) {
                created_.clear();
                return false;
            }
            any = take_ear(ring, best, local, refresh);
            fresh = false;
        }
        local.push_back({ring.prev[any], any, ring.next[any]});
        return true;
    }

    // Lawson flips of the diagonals of a triangulation of the polygon q until every diagonal is
    // locally Delaunay: the constrained Delaunay triangulation of the polygon [6]. A flip that
    // would create an edge the mesh already has is skipped.
    void lawson_flips(const std::vector<Eigen::Vector2d>& q, double eps, std::vector<Tri>& local) {
        const int n = static_cast<int>(q.size());
        auto is_side = [n](int a, int b) { return (a + 1) % n == b || (b + 1) % n == a; };
        auto key = [](int a, int b) { return edge_key(a, b); };
        std::unordered_map<uint64_t, std::array<int, 2>> owners; // local diagonal -> its two triangles
        for (size_t t = 0; t < local.size(); ++t)
            for (int j = 0; j < 3; ++j) {
                const int a = local[t][j], b = local[t][(j + 1) % 3];
                if (is_side(a, b)) continue;
                auto it = owners.find(key(a, b));
                if (it == owners.end())
                    owners.emplace(key(a, b), std::array<int, 2>{static_cast<int>(t), -1});
                else
                    it->second[1] = static_cast<int>(t);
            }
        std::vector<std::pair<int, int>> stack;
        for (const auto& [k, owner] : owners) stack.emplace_back(static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu));
        std::sort(stack.begin(), stack.end());
        double scale2 = 0.0; // squared size of the polygon: incircle values scale with its square
        for (const auto& x : q) scale2 = std::max(scale2, x.squaredNorm());
        const double eps_circle = 1e-12 * scale2 * scale2;
        // Lawson's algorithm flips each pair at most once, n(n-1)/2 in all; the bound guards rounding.
        long budget = static_cast<long>(n) * n + 16;
        while (!stack.empty() && budget-- > 0) {
            const auto [ea, eb] = stack.back();
            stack.pop_back();
            auto it = owners.find(key(ea, eb));
            if (it == owners.end() || it->second[1] < 0) continue;
            int t1 = it->second[0], t2 = it->second[1];
            // Name them so that t1 = (x, y, c) and t2 = (y, x, d).
            int x = -1, y = -1, c = -1, d = -1;
            for (int j = 0; j < 3; ++j)
                if ((local[t1][j] == ea || local[t1][j] == eb) &&
                    (local[t1][(j + 1) % 3] == ea || local[t1][(j + 1) % 3] == eb)) {
                    x = local[t1][j];
                    y = local[t1][(j + 1) % 3];
                    c = local[t1][(j + 2) % 3];
                }
            for (int j = 0; j < 3; ++j)
                if (local[t2][j] != x && local[t2][j] != y) d = local[t2][j];
            if (x < 0 || d < 0) continue;
            const Eigen::Vector2d &qx = q[x], &qy = q[y], &qc = q[c], &qd = q[d];
            if (!(incircle(qx, qy, qc, qd) > eps_circle)) continue;
            if (!(orient2(qx, qd, qc) > eps && orient2(qd, qy, qc) > eps)) continue; // flip must stay convex
            if (!free_diagonal(c, d)) continue;
            local[t1] = {x, d, c};
            local[t2] = {d, y, c};
            owners.erase(it);
            created_.erase(edge_key(loop_[x], loop_[y]));
            created_.insert(edge_key(loop_[c], loop_[d]));
            owners[key(c, d)] = {t1, t2};
            // Edge x-d moved from t2 to t1, edge y-c from t1 to t2.
            auto reassign = [&](int a, int b, int from, int to) {
                if (is_side(a, b)) return;
                auto& o = owners[key(a, b)];
                for (int& t : o)
                    if (t == from) t = to;
            };
            reassign(x, d, t2, t1);
            reassign(y, c, t1, t2);
            for (const auto& [a, b] : {std::pair<int, int>{x, d}, {d, y}, {y, c}, {c, x}})
                if (!is_side(a, b)) stack.emplace_back(a, b);
        }
    }

    // Positive when d lies inside the circumcircle of the counter-clockwise triangle (a, b, c).
    static double incircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                           const Eigen::Vector2d& d) {
        const Eigen::Vector2d ad = a - d, bd = b - d, cd = c - d;
        const double a2 = ad.squaredNorm(), b2 = bd.squaredNorm(), c2 = cd.squaredNorm();
        return ad.x() * (bd.y() * c2 - b2 * cd.y()) - ad.y() * (bd.x() * c2 - b2 * cd.x()) + a2 * cross2(bd, cd);
    }

    // The triangulation of the polygon 0..n-1 (loop order) that maximises its smallest triangle
    // score, by dynamic programming over the chords (i, j): best[i][j] is the best for the
    // sub-polygon i..j, closed by chord (i, j). `chord_ok(i, j)` says whether a chord may exist;
    // `score(i, k, j)` rates triangle (i, k, j), -infinity if invalid. O(n^3) time, O(n^2) memory,
    // no recursion. Returns false if every triangulation has an invalid chord or triangle.
    template <typename ChordOk, typename Score>
    static bool best_triangulation(int n, const ChordOk& chord_ok, const Score& score, std::vector<Tri>& local) {
        constexpr double kNone = -std::numeric_limits<double>::infinity();
        std::vector<double> best(static_cast<size_t>(n) * n, kNone);
        std::vector<int> split(static_cast<size_t>(n) * n, -1);
        auto at = [n](int i, int j) { return static_cast<size_t>(i) * n + j; };
        for (int i = 0; i + 1 < n; ++i) best[at(i, i + 1)] = std::numeric_limits<double>::infinity();
        for (int len = 2; len < n; ++len)
            for (int i = 0; i + len < n; ++i) {
                const int j = i + len;
                if (!(i == 0 && j == n - 1) && !chord_ok(i, j)) continue;
                for (int k = i + 1; k < j; ++k) {
                    const double v = std::min({best[at(i, k)], best[at(k, j)], score(i, k, j)});
                    if (v > best[at(i, j)]) {
                        best[at(i, j)] = v;
                        split[at(i, j)] = k;
                    }
                }
            }
        if (!(best[at(0, n - 1)] > kNone)) return false;
        std::vector<std::pair<int, int>> todo = {{0, n - 1}};
        while (!todo.empty()) {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j - i < 2) continue;
            const int k = split[at(i, j)];
            local.push_back({i, k, j});
            todo.emplace_back(i, k);
            todo.emplace_back(k, j);
        }
        return true;
    }

    // Whether (i, j) is a diagonal of the simple counter-clockwise polygon q: inside it at i
    // (O'Rourke's in-cone test) and crossing no edge not incident to i or j.
    static bool is_diagonal(const std::vector<Eigen::Vector2d>& q, int i, int j, double eps) {
        const int n = static_cast<int>(q.size());
        const auto &a = q[i], &b = q[j], &before = q[(i + n - 1) % n], &after = q[(i + 1) % n];
        const bool inside = orient2(a, after, before) >= 0.0 // convex at i
                                ? orient2(a, b, before) > eps && orient2(b, a, after) > eps
                                : !(orient2(a, b, after) >= -eps && orient2(b, a, before) >= -eps);
        if (!inside) return false;
        for (int m = 0; m < n; ++m) {
            const int m1 = (m + 1) % n;
            if (m == i || m == j || m1 == i || m1 == j) continue;
            if (segments_meet(a, b, q[m], q[m1], eps)) return false;
        }
        return true;
    }

    // Rescue when ear clipping of the planar polygon gets stuck on existing edges: the planar
    // triangulation with the best smallest kappa among those avoiding them.
    bool exact_2d(const std::vector<Eigen::Vector2d>& q, double eps, std::vector<Tri>& local) {
        local.clear();
        created_.clear();
        return best_triangulation(
            static_cast<int>(q.size()), [&](int i, int j) { return free_diagonal(i, j) && is_diagonal(q, i, j, eps); },
            [&](int i, int k, int j) {
                return orient2(q[i], q[k], q[j]) > eps ? kappa(i, k, j) : -std::numeric_limits<double>::infinity();
            },
            local);
    }

    // Normal that the loop's own winding gives (its vector area), or `fallback` if that vanishes.
    Eigen::Vector3d winding_normal(const Eigen::Vector3d& fallback) const {
        const int n = static_cast<int>(p_.size());
        Eigen::Vector3d reference = Eigen::Vector3d::Zero();
        for (int i = 0; i < n; ++i) reference += (p_[i] - p_[0]).cross(p_[(i + 1) % n] - p_[0]);
        return reference.norm() > 0.0 ? reference : fallback;
    }

    // Whether triangle (a, b, c), in loop order, folds back onto the surface across one of its
    // edges on the loop: turned by more than kFoldBackDeg from the triangle there.
    bool folds_back(int a, int b, int c) const {
        const Eigen::Vector3d cross = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
        return cross.norm() > 0.0 && folds_back(a, b, c, cross.normalized());
    }
    bool folds_back(int a, int b, int c, const Eigen::Vector3d& normal) const {
        const int n = static_cast<int>(p_.size());
        const int corner[3] = {a, b, c};
        for (int j = 0; j < 3; ++j) {
            const int from = corner[j], to = corner[(j + 1) % 3];
            if (to == (from + 1) % n && normal.dot(outer_[from]) < kCosFoldBack) return true;
        }
        return false;
    }

    // Score of triangle (a, b, c) for the 3D paths: kappa (Eq. 26) plus 2 if it is not flat and
    // faces like `reference`, plus 1 if it is not flat but faces away; flat ones, and those that
    // fold back onto the surface, score kappa alone.
    double score_3d(int a, int b, int c, const Eigen::Vector3d& reference) const {
        const Eigen::Vector3d cross = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
        const double longest2 =
            std::max({(p_[b] - p_[a]).squaredNorm(), (p_[c] - p_[b]).squaredNorm(), (p_[a] - p_[c]).squaredNorm()});
        int tier = 0;
        if (cross.norm() > 1e-12 * longest2 && !folds_back(a, b, c, cross.normalized()))
            tier = cross.dot(reference) > 0.0 ? 2 : 1;
        return tier + kappa(a, b, c);
    }

    // Non-planar loop of at most kMaxExact vertices: the triangulation whose worst triangle
    // (by score_3d) is best.
    bool exact_3d(const Eigen::Vector3d& pca_normal, std::vector<Tri>& local) {
        const Eigen::Vector3d reference = winding_normal(pca_normal);
        return best_triangulation(
            static_cast<int>(p_.size()), [&](int i, int j) { return free_diagonal(i, j); },
            [&](int i, int k, int j) { return score_3d(i, k, j, reference); }, local);
    }

    // Fallback for loops of more than kMaxExact vertices whose projection is not simple
    // (strongly non-planar, e.g. a saddle): repeatedly cut the ear with the best kappa, preferring ears that are not flat and that
    // face like the loop's vector area (the normal its own winding gives; the PCA normal when
    // that vanishes). Flat ears are used only when nothing else is left (a collinear loop), so
    // the hole still closes. O(n^2).
    bool ear_clip_3d(const Eigen::Vector3d& pca_normal, std::vector<Tri>& local) {
        const int n = static_cast<int>(loop_.size());
        created_.clear();
        const Eigen::Vector3d reference = winding_normal(pca_normal);
        Ring ring(n);
        std::vector<double> score(n);
        auto refresh = [&](int i) {
            const int a = ring.prev[i], c = ring.next[i];
            if (ring.remaining > 3 && !free_diagonal(a, c)) {
                score[i] = -1.0;
                return;
            }
            score[i] = score_3d(a, i, c, reference);
        };
        for (int i = 0; i < n; ++i) refresh(i);
        int any = 0;
        while (ring.remaining > 3) {
            const int best = best_ear(ring, any, score);
            if (best < 0) return false;
            any = take_ear(ring, best, local, refresh);
        }
        local.push_back({ring.prev[any], any, ring.next[any]});
        return true;
    }

    const std::vector<int32_t>& loop_;
    const EdgeSet& existing_;
    std::vector<Eigen::Vector3d> outer_; // per loop edge, the normal of the surface's triangle on it
    std::vector<Eigen::Vector3d> p_; // loop vertex positions
    EdgeSet created_;                // diagonals of the triangulation under construction
};

} // namespace

long remove_darts(Mesh& mesh, const HoleFillingParams& params) {
    check_indices(mesh, "mesh with holes");
    long removed = 0;
    for (;;) {
        std::vector<int32_t> uses(static_cast<size_t>(mesh.points.rows()), 0);
        for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
            for (int j = 0; j < 3; ++j) ++uses[static_cast<size_t>(mesh.triangles(f, j))];
        const std::vector<HoleEdge> edges = hole_edges(mesh.triangles);
        const std::unordered_map<uint64_t, int> edge_triangle = triangle_of_edge(edges);
        std::vector<char> drop(static_cast<size_t>(mesh.triangles.rows()), 0);
        long found = 0;
        for (const auto& loop : trace_loops(edges, mesh.points.rows())) {
            if (loop.size() < 4 || (params.should_fill && !params.should_fill(loop))) continue;
            const size_t n = loop.size();
            for (size_t i = 0; i < n; ++i) {
                const int32_t prev = loop[(i + n - 1) % n], v = loop[i], next = loop[(i + 1) % n];
                if (uses[static_cast<size_t>(v)] != 1) continue;
                const auto in = edge_triangle.find(edge_key(prev, v)), out = edge_triangle.find(edge_key(v, next));
                if (in == edge_triangle.end() || out == edge_triangle.end() || in->second != out->second) continue;
                if (!drop[static_cast<size_t>(in->second)]) ++found;
                drop[static_cast<size_t>(in->second)] = 1;
            }
        }
        if (found == 0) return removed;
        drop_triangles(mesh, drop);
        removed += found;
    }
}

std::vector<std::vector<int32_t>> boundary_loops(const Mesh& mesh) {
    return trace_loops(hole_edges(mesh.triangles), mesh.points.rows());
}

HoleFillingStats fill_holes(Mesh& mesh, const HoleFillingParams& params) {
    const auto& should_fill = params.should_fill;
    check_indices(mesh, "fill_holes");
    const auto nv = mesh.points.rows();
    const std::vector<HoleEdge> edges = hole_edges(mesh.triangles);
    const auto loops = trace_loops(edges, nv);
    if (loops.empty()) return {};

    const std::unordered_map<uint64_t, int> edge_triangle = triangle_of_edge(edges);
    EdgeSet existing;
    existing.reserve(static_cast<size_t>(3 * mesh.triangles.rows() / 2 + 1));
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) existing.insert(edge_key(mesh.triangles(f, j), mesh.triangles(f, (j + 1) % 3)));
    auto point = [&](int32_t i) -> Eigen::Vector3d { return mesh.points.row(i).transpose(); };

    std::vector<Tri> added;
    long filled = 0;
    for (const auto& loop : loops) {
        if (loop.size() < 3) continue;
        if (should_fill && !should_fill(loop)) continue;
        // Area-weighted normal of the triangles along the hole (cross products are 2 area * normal).
        Eigen::Vector3d surround = Eigen::Vector3d::Zero();
        std::vector<Eigen::Vector3d> outer(loop.size(), Eigen::Vector3d::Zero());
        for (size_t i = 0; i < loop.size(); ++i) {
            const auto it = edge_triangle.find(edge_key(loop[i], loop[(i + 1) % loop.size()]));
            if (it == edge_triangle.end()) continue;
            const auto f = static_cast<Eigen::Index>(it->second);
            const Eigen::Vector3d a = point(mesh.triangles(f, 0)), b = point(mesh.triangles(f, 1)),
                                  c = point(mesh.triangles(f, 2));
            surround += (b - a).cross(c - a);
            outer[i] = triangle_normal(a, b, c);
        }
        std::vector<Tri> fill;
        if (loop.size() == 3) {
            // The one triangle, unless the surface already has it (a lone triangle's own boundary).
            const auto it = edge_triangle.find(edge_key(loop[0], loop[1]));
            bool present = false;
            if (it != edge_triangle.end())
                for (int j = 0; j < 3; ++j)
                    present = present || mesh.triangles(it->second, j) == loop[2];
            if (present) continue;
            fill.push_back({loop[0], loop[1], loop[2]});
        } else {
            HoleTriangulator triangulator(mesh.points, loop, existing, std::move(outer));
            if (!triangulator.triangulate(surround, fill)) continue;
        }
        for (const Tri& t : fill)
            for (int j = 0; j < 3; ++j) existing.insert(edge_key(t[j], t[(j + 1) % 3]));
        added.insert(added.end(), fill.begin(), fill.end());
        ++filled;
    }
    if (!added.empty()) {
        const Eigen::Index old = mesh.triangles.rows();
        mesh.triangles.conservativeResize(old + static_cast<Eigen::Index>(added.size()), 3);
        for (size_t k = 0; k < added.size(); ++k)
            for (int j = 0; j < 3; ++j) mesh.triangles(old + static_cast<Eigen::Index>(k), j) = added[k][j];
    }
    return {filled};
}

} // namespace liftremesh
