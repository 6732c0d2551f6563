#include "liftremesh/edit/edge_collapse.h"

#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <tuple>

namespace liftremesh {

namespace {

// How far from a poor triangle's longest edge, over its length, the input's point nearest the
// edge's middle may lie for the edge to run along the input (mend_poor_triangles): off a chord
// across a crease turning by 4.6 degrees, on a chord of a curved crease of radius 6 L.
constexpr double kAlongInput = 0.02;

// The most two triangles may turn at an edge that a split's flip takes away (Collapser::split):
// a flat face's, or a gently curved one's, where the flipped pair stays on the input as the old
// one did; a crease's edge stays.
constexpr double kFlatRimTurn = 15.0 * M_PI / 180.0;

struct Adjacency {
    std::vector<std::vector<int32_t>> triangles_of; // per vertex, live triangles using it
    std::vector<char> alive;                        // per triangle
};

Eigen::Vector3d position(const Mesh& m, int32_t v) { return m.points.row(v).transpose(); }

double kappa_of(const Mesh& m, const std::array<int32_t, 3>& t) {
    return triangle_kappa(position(m, t[0]), position(m, t[1]), position(m, t[2]));
}

// Unit normal of triangle f as the mesh has it now (zero if degenerate).
Eigen::Vector3d normal_of(const Mesh& m, int32_t f) {
    return triangle_normal(position(m, m.triangles(f, 0)), position(m, m.triangles(f, 1)), position(m, m.triangles(f, 2)));
}

// 2 pi minus the sum of the angles at v: zero on a flat or ruled (crease) surface, large at a corner.
double angle_defect(const Mesh& m, const Adjacency& adj, int32_t v) {
    double sum = 0.0;
    for (int32_t f : adj.triangles_of[v]) {
        const auto t = triangle_vertices(m, f);
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
        for (int32_t w : triangle_vertices(m, f))
            if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Whether merging `gone` into `kept` folds more edges shut (flip_rules.h) than gone's fan has:
// only the triangles of that fan move, so only their edges can fold. A triangle turned by less
// than 45 degrees still folds onto the one across a knife edge (the 151-degree edge of a
// thread's flank and end face, turned by 20 degrees more).
bool collapse_folds(const Mesh& m, const Adjacency& adj, int32_t kept, int32_t gone) {
    const std::vector<int32_t>& fan = adj.triangles_of[gone];
    auto uses = [&m](int32_t f, int32_t v) {
        const auto t = triangle_vertices(m, f);
        return std::find(t.begin(), t.end(), v) != t.end();
    };
    const int before = count_folded_edges(
        fan, [&m](int32_t f) { return triangle_vertices(m, f); }, [&m](int32_t f) { return normal_of(m, f); },
        [&adj](int32_t v) -> const std::vector<int32_t>& { return adj.triangles_of[v]; });
    std::vector<int32_t> moved;
    for (int32_t f : fan)
        if (!uses(f, kept)) moved.push_back(f);
    auto corners_after = [&](int32_t f) {
        auto t = triangle_vertices(m, f);
        for (auto& v : t)
            if (v == gone) v = kept;
        return t;
    };
    auto normal_after = [&](int32_t f) {
        const auto t = corners_after(f);
        return triangle_normal(position(m, t[0]), position(m, t[1]), position(m, t[2]));
    };
    // The two triangles on the edge are gone; kept has gone's others.
    auto triangles_after = [&](int32_t v) {
        std::vector<int32_t> out;
        for (int32_t w : {v, v == kept ? gone : -1})
            if (w >= 0)
                for (int32_t f : adj.triangles_of[w])
                    if (!uses(f, kept) || !uses(f, gone)) out.push_back(f);
        return out;
    };
    return count_folded_edges(moved, corners_after, normal_after, triangles_after) > before;
}

// Tries to merge `gone` into `kept` (kept's position stays). Returns the smallest kappa of the
// new fan, or -1 if the collapse is not allowed.
double try_collapse(const Mesh& m, const Adjacency& adj, int32_t kept, int32_t gone, double old_min) {
    const Eigen::Vector3d p = position(m, kept);
    double worst = 1.0;
    for (int32_t f : adj.triangles_of[gone]) {
        auto t = triangle_vertices(m, f);
        if (std::find(t.begin(), t.end(), kept) != t.end()) continue; // removed by the collapse
        const Eigen::Vector3d before = normal_of(m, f);
        for (auto& v : t)
            if (v == gone) v = kept;
        Eigen::Vector3d q[3];
        for (int j = 0; j < 3; ++j) q[j] = t[j] == kept ? p : position(m, t[j]);
        const Eigen::Vector3d after = triangle_normal(q[0], q[1], q[2]);
        if (after.dot(before) < std::cos(M_PI / 4)) return -1.0; // folds or turns too much
        worst = std::min(worst, triangle_kappa(q[0], q[1], q[2]));
    }
    for (int32_t f : adj.triangles_of[kept]) {
        const auto t = triangle_vertices(m, f);
        if (std::find(t.begin(), t.end(), gone) != t.end()) continue;
        worst = std::min(worst, kappa_of(m, t));
    }
    if (!(worst > old_min) || collapse_folds(m, adj, kept, gone)) return -1.0;
    return worst;
}

// The collapses of one mesh: its triangles' fans and boundary kept up to date, triangles
// marked dead, compacted by finish().
class Collapser {
public:
    explicit Collapser(Mesh& mesh) : mesh_(mesh) {
        const Eigen::Index nf = mesh.triangles.rows();
        // On an open surface, an interior edge between two boundary vertices must stay:
        // collapsing it joins the two boundaries at one vertex (the link condition with the
        // boundary's virtual vertex).
        on_boundary_.assign(static_cast<size_t>(mesh.points.rows()), 0);
        for (const EdgeCount& e : edge_counts(mesh.triangles))
            if (e.count == 1) on_boundary_[e.a] = on_boundary_[e.b] = 1;
        adj_.triangles_of.resize(mesh.points.rows());
        adj_.alive.assign(nf, 1);
        for (Eigen::Index f = 0; f < nf; ++f)
            for (int j = 0; j < 3; ++j) adj_.triangles_of[mesh.triangles(f, j)].push_back(static_cast<int32_t>(f));
    }

    //! Whether v may be collapsed away by the mending of poor triangles: not on the boundary,
    //! whose shape it would change, and every triangle around it turned from their mean normal
    //! by less than acos(min_cos).
    bool may_go(int32_t v, double min_cos) const {
        if (on_boundary_[v]) return false;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (int32_t f : adj_.triangles_of[v]) mean += normal_of(mesh_, f);
        if (!(mean.norm() > 0.0)) return false;
        mean.normalize();
        for (int32_t f : adj_.triangles_of[v])
            if (!(normal_of(mesh_, f).dot(mean) >= min_cos)) return false;
        return true;
    }

    //! Whether merging `gone` into `kept` keeps the surface as near to the input as it was: no
    //! triangle the collapse moves farther from the input than it was (the farthest of its
    //! centroid and edge midpoints, up to rounding), and gone's own position, a point of the
    //! input, no farther from them than the farthest of gone's fan was. A vertex off a flat fan
    //! may then go where that fan already cut across a feature finer than the triangles (a corner
    //! of a 0.1 mm terminal, a bevel standing for it): the collapse takes no more of it away.
    bool stays_near_input(int32_t kept, int32_t gone, const AabbTree& input) const {
        if (on_boundary_[gone]) return false;
        // Rounding aside: a millionth of the edge.
        const double tolerance = 1e-6 * (position(mesh_, kept) - position(mesh_, gone)).norm();
        auto farthest = [&](const Eigen::Vector3d (&q)[3]) {
            double d2 = 0.0;
            const Eigen::Vector3d samples[4] = {(q[0] + q[1] + q[2]) / 3.0, 0.5 * (q[0] + q[1]), 0.5 * (q[1] + q[2]),
                                                0.5 * (q[2] + q[0])};
            for (const Eigen::Vector3d& x : samples) d2 = std::max(d2, input.closest(x).squared_distance);
            return std::sqrt(d2);
        };
        double fan = 0.0, gone_to_after = std::numeric_limits<double>::infinity();
        const Eigen::Vector3d g = position(mesh_, gone);
        for (int32_t f : adj_.triangles_of[gone]) {
            const auto t = triangle_vertices(mesh_, f);
            Eigen::Vector3d q[3];
            for (int j = 0; j < 3; ++j) q[j] = position(mesh_, t[j]);
            const double before = farthest(q);
            fan = std::max(fan, before);
            if (std::find(t.begin(), t.end(), kept) != t.end()) continue; // removed by the collapse
            for (int j = 0; j < 3; ++j)
                if (t[j] == gone) q[j] = position(mesh_, kept);
            if (farthest(q) > before + tolerance) return false;
            gone_to_after = std::min(gone_to_after, (closest_point_on_triangle(g, q[0], q[1], q[2]) - g).norm());
        }
        return gone_to_after <= fan + tolerance;
    }

    //! Smallest kappa of the triangles around the given vertices.
    double worst_kappa_around(std::initializer_list<int32_t> vertices) const {
        double worst = 1.0;
        for (int32_t v : vertices)
            for (int32_t f : adj_.triangles_of[v]) worst = std::min(worst, kappa_of(mesh_, triangle_vertices(mesh_, f)));
        return worst;
    }

    //! The two live triangles of edge a-b, a -> b -> c and b -> a -> d (an oriented manifold
    //! edge), as {f1, f2, c, d}; none otherwise.
    std::optional<std::array<int32_t, 4>> quad(int32_t a, int32_t b) const {
        std::array<int32_t, 4> q{-1, -1, -1, -1};
        int found = 0;
        for (int32_t f : adj_.triangles_of[a]) {
            const auto t = triangle_vertices(mesh_, f);
            const int i = t[0] == a ? 0 : t[1] == a ? 1 : 2;
            if (t[(i + 1) % 3] == b) {
                q[0] = f;
                q[2] = t[(i + 2) % 3];
            } else if (t[(i + 2) % 3] == b) {
                q[1] = f;
                q[3] = t[(i + 1) % 3];
            } else {
                continue;
            }
            ++found;
        }
        if (found != 2 || q[0] < 0 || q[1] < 0) return std::nullopt;
        return q;
    }

    //! Smaller kappa of the two triangles of edge a-b (2 if it has not two).
    double worst_kappa_of_edge(int32_t a, int32_t b) const {
        const auto q = quad(a, b);
        if (!q) return 2.0;
        return std::min(kappa_of(mesh_, triangle_vertices(mesh_, (*q)[0])), kappa_of(mesh_, triangle_vertices(mesh_, (*q)[1])));
    }

    //! Whether triangle f is still there (not taken out by a collapse).
    bool alive(int32_t f) const { return adj_.alive[f] != 0; }

    //! Whether a and b are joined by an edge.
    bool joined(int32_t a, int32_t b) const {
        for (int32_t f : adj_.triangles_of[a]) {
            const auto t = triangle_vertices(mesh_, f);
            if (std::find(t.begin(), t.end(), b) != t.end()) return true;
        }
        return false;
    }

    //! Flips edge a-b of quad {f1, f2, c, d} (see quad()) to c-d: (a, d, c) and (d, b, c), the
    //! quad's orientation kept. Returns the two triangles as they were, for unflip().
    std::array<std::array<int32_t, 3>, 2> flip(int32_t a, int32_t b, const std::array<int32_t, 4>& q) {
        const auto [f1, f2, c, d] = q;
        const std::array<std::array<int32_t, 3>, 2> was = {triangle_vertices(mesh_, f1), triangle_vertices(mesh_, f2)};
        mesh_.triangles.row(f1) << a, d, c;
        mesh_.triangles.row(f2) << d, b, c;
        drop(a, f2);
        drop(b, f1);
        adj_.triangles_of[c].push_back(f2);
        adj_.triangles_of[d].push_back(f1);
        return was;
    }

    //! Undoes flip(a, b, q), which returned `was`.
    void unflip(int32_t a, int32_t b, const std::array<int32_t, 4>& q, const std::array<std::array<int32_t, 3>, 2>& was) {
        const auto [f1, f2, c, d] = q;
        for (int j = 0; j < 3; ++j) {
            mesh_.triangles(f1, j) = was[0][j];
            mesh_.triangles(f2, j) = was[1][j];
        }
        drop(c, f2);
        drop(d, f1);
        adj_.triangles_of[a].push_back(f2);
        adj_.triangles_of[b].push_back(f1);
    }

    //! Collapses edge a-b onto one of its end points if that keeps an oriented manifold with the
    //! same Euler characteristic (see collapse_short_edges) and the new fan's worst kappa is above
    //! `must_beat`; an end point whose `may_go` is false is the one kept. Returns whether it did.
    bool collapse(int32_t a, int32_t b, double must_beat, bool a_may_go = true, bool b_may_go = true) {
        // The edge must still exist with exactly two triangles, whose opposite vertices are the
        // only common neighbours of a and b (link condition: the collapse keeps a manifold).
        std::vector<int32_t> shared, opposite;
        for (int32_t f : adj_.triangles_of[a]) {
            const auto t = triangle_vertices(mesh_, f);
            if (std::find(t.begin(), t.end(), b) == t.end()) continue;
            shared.push_back(f);
            for (int32_t v : t)
                if (v != a && v != b) opposite.push_back(v);
        }
        if (shared.size() != 2 || opposite[0] == opposite[1]) return false;
        if (on_boundary_[a] && on_boundary_[b]) return false;
        const std::vector<int32_t> na = neighbours(mesh_, adj_, a), nb = neighbours(mesh_, adj_, b);
        std::vector<int32_t> common;
        std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
        std::sort(opposite.begin(), opposite.end());
        if (common != opposite) return false;
        if (na.size() + nb.size() <= 6) return false; // would leave a degenerate (tetrahedron-like) piece
        bool low_valence = false;                      // the opposite vertices lose an edge each
        for (int32_t v : opposite) low_valence = low_valence || adj_.triangles_of[v].size() <= 3;
        if (low_valence) return false;

        const double keep_a = b_may_go ? try_collapse(mesh_, adj_, a, b, must_beat) : -1.0;
        const double keep_b = a_may_go ? try_collapse(mesh_, adj_, b, a, must_beat) : -1.0;
        if (keep_a < 0.0 && keep_b < 0.0) return false;
        bool a_stays = keep_a >= 0.0;
        if (keep_a >= 0.0 && keep_b >= 0.0) a_stays = angle_defect(mesh_, adj_, a) >= angle_defect(mesh_, adj_, b);
        const int32_t kept = a_stays ? a : b, gone = a_stays ? b : a;

        for (int32_t f : shared) {
            adj_.alive[f] = 0;
            for (int32_t v : triangle_vertices(mesh_, f)) drop(v, f);
        }
        for (int32_t f : adj_.triangles_of[gone]) {
            for (int j = 0; j < 3; ++j)
                if (mesh_.triangles(f, j) == gone) mesh_.triangles(f, j) = kept;
            adj_.triangles_of[kept].push_back(f);
        }
        adj_.triangles_of[gone].clear();
        on_boundary_[kept] = on_boundary_[kept] || on_boundary_[gone];
        ++collapsed_;
        return true;
    }

    //! Splits the interior edge a-b at p into four triangles if none of them turns from the one it
    //! comes from by more than 45 degrees and their worst kappa is above `must_beat`; an edge
    //! whose two triangles turn by more only `along_input` (the caller found p on it: along a
    //! crease), and not folded shut. With `with_flips`, a new triangle at or under `must_beat`
    //! is taken if flipping its edge on the quad's rim lifts both triangles of that edge above
    //! it (rim_flip), and that flip is made too. Returns whether it split.
    bool split(int32_t a, int32_t b, const Eigen::Vector3d& p, double must_beat, bool along_input, bool with_flips = false) {
        const auto q = quad(a, b);
        if (!q) return false;
        const auto [f1, f2, c, d] = *q;
        // Not an edge across a crease or a fold, whose halves would stay one, unless the caller
        // found it along the input: a crease's edge, whose halves stay on its faces. Never an
        // edge folded shut (flip_rules.h: kCosFolded), whose halves would both be.
        const double turn = normal_of(mesh_, f1).dot(normal_of(mesh_, f2));
        if (c == d || !(turn >= std::cos(M_PI / 4) || (along_input && turn > kCosFolded))) return false;
        const std::array<std::pair<int32_t, std::array<int32_t, 3>>, 4> made = {
            {{f1, {a, -1, c}}, {f1, {-1, b, c}}, {f2, {b, -1, d}}, {f2, {-1, a, d}}}};
        std::vector<std::array<int32_t, 3>> flips; // rim edges x -> y of new triangles (m, x, y), and z
        for (const auto& [parent, t] : made) {
            Eigen::Vector3d x[3];
            for (int j = 0; j < 3; ++j) x[j] = t[j] < 0 ? p : position(mesh_, t[j]);
            const Eigen::Vector3d n = triangle_normal(x[0], x[1], x[2]), was = normal_of(mesh_, parent);
            if (!(n.dot(was) >= std::cos(M_PI / 4))) return false;
            // Nor folds (flip_rules.h: kCosFolded) onto the triangle across its edge of the
            // quad's rim, unless its parent was folded so already (and it is no more).
            const int k = t[0] < 0 ? 0 : t[1] < 0 ? 1 : 2;
            const int32_t u = t[(k + 1) % 3], v = t[(k + 2) % 3]; // the rim edge, u -> v
            const int32_t across = other_triangle(u, v, parent);
            if (folds_onto(across, n, was)) return false;
            if (triangle_kappa(x[0], x[1], x[2]) > must_beat) continue;
            const int32_t z = with_flips ? rim_flip(u, v, parent, across, p, {a, b, c, d}, must_beat) : -1;
            if (z < 0) return false;
            for (const auto& [x0, y0, z0] : flips)
                if (z0 == z) return false; // two flips would both join m to z
            flips.push_back({u, v, z});
        }
        const auto m = static_cast<int32_t>(mesh_.points.rows());
        mesh_.points.conservativeResize(m + 1, 3);
        mesh_.points.row(m) = p.transpose();
        const auto f3 = static_cast<int32_t>(mesh_.triangles.rows());
        mesh_.triangles.conservativeResize(f3 + 2, 3);
        adj_.alive.resize(f3 + 2, 1);
        adj_.triangles_of.emplace_back();
        on_boundary_.push_back(0);
        const std::array<int32_t, 4> rows = {f1, f3, f2, f3 + 1};
        drop(b, f1);
        drop(a, f2);
        for (int k = 0; k < 4; ++k) {
            std::array<int32_t, 3> t = made[k].second;
            for (int32_t& v : t)
                if (v < 0) v = m;
            mesh_.triangles.row(rows[k]) << t[0], t[1], t[2];
        }
        // Fans: m in all four; c and d in one new triangle each; a in f1 and f3 + 1; b in f3 and f2.
        adj_.triangles_of[m] = {f1, f3, f2, f3 + 1};
        adj_.triangles_of[c].push_back(f3);
        adj_.triangles_of[d].push_back(f3 + 1);
        adj_.triangles_of[a].push_back(f3 + 1);
        adj_.triangles_of[b].push_back(f3);
        ++split_;
        // The new triangle (m, x, y) and the one across x -> y become (x, z, m) and (z, y, m).
        for (const auto& [x, y, z] : flips)
            if (const auto rim = quad(x, y); rim && (*rim)[2] == m && (*rim)[3] == z) {
                flip(x, y, *rim);
                ++flipped_;
            }
        return true;
    }

    long splits() const { return split_; }
    long flips() const { return flipped_; }

    //! Removes the dead triangles and the vertices no triangle uses. Returns the collapses.
    long finish() {
        if (collapsed_ == 0) return 0;
        const Eigen::Index nf = mesh_.triangles.rows();
        Triangles kept_triangles(nf - 2 * collapsed_, 3);
        Eigen::Index row = 0;
        for (Eigen::Index f = 0; f < nf; ++f)
            if (adj_.alive[f]) kept_triangles.row(row++) = mesh_.triangles.row(f);
        mesh_.triangles = std::move(kept_triangles);
        renumbered_ = remove_unreferenced_vertices(mesh_);
        return collapsed_;
    }

    //! Vertex v's index after finish(), which renumbers the vertices if anything was collapsed.
    int32_t renumbered(int32_t v) const { return renumbered_.empty() ? v : renumbered_[v]; }

private:
    //! Whether a new triangle of unit normal n, on an edge of triangle g (none if g < 0), folds
    //! onto g (flip_rules.h: kCosFolded) where the triangle it replaces, of unit normal `was`,
    //! did not, or turns from g by more than that one did.
    bool folds_onto(int32_t g, const Eigen::Vector3d& n, const Eigen::Vector3d& was) const {
        if (g < 0) return false;
        const Eigen::Vector3d ng = normal_of(mesh_, g);
        return !(ng.dot(n) >= std::min(ng.dot(was), kCosFolded));
    }

    //! Whether the new triangle (m, x, y) of a split at p, whose rim edge x -> y its parent has,
    //! may be flipped with the triangle `across` on that edge (y -> x -> z) into (x, z, m) and
    //! (z, y, m): the edge no crease (parent and across within kFlatRimTurn), z none of the
    //! split's corners `quad` (whose edges to m the split makes), both new triangles turned
    //! from `across` by less than 45 degrees and above `must_beat`. Returns z, or -1 if not.
    int32_t rim_flip(int32_t x, int32_t y, int32_t parent, int32_t across, const Eigen::Vector3d& p,
                     const std::array<int32_t, 4>& quad, double must_beat) const {
        if (across < 0) return -1;
        const Eigen::Vector3d n_across = normal_of(mesh_, across);
        if (!(normal_of(mesh_, parent).dot(n_across) >= std::cos(kFlatRimTurn))) return -1;
        int32_t z = -1;
        for (int32_t v : triangle_vertices(mesh_, across))
            if (v != x && v != y) z = v;
        if (z < 0 || std::find(quad.begin(), quad.end(), z) != quad.end()) return -1;
        const Eigen::Vector3d px = position(mesh_, x), py = position(mesh_, y), pz = position(mesh_, z);
        // Each new triangle with its edge that was across's, and the triangle beyond that edge.
        const std::array<std::pair<std::array<Eigen::Vector3d, 3>, int32_t>, 2> made = {
            {{{px, pz, p}, other_triangle(x, z, across)}, {{pz, py, p}, other_triangle(z, y, across)}}};
        for (const auto& [t, beyond] : made) {
            const Eigen::Vector3d n = triangle_normal(t[0], t[1], t[2]);
            if (!(n.dot(n_across) >= std::cos(M_PI / 4)) || !(triangle_kappa(t[0], t[1], t[2]) > must_beat)) return -1;
            if (folds_onto(beyond, n, n_across)) return -1;
        }
        return z;
    }

    //! The live triangle other than f on edge u-v, or -1 if there is none.
    int32_t other_triangle(int32_t u, int32_t v, int32_t f) const {
        for (int32_t g : adj_.triangles_of[u]) {
            if (g == f) continue;
            const auto t = triangle_vertices(mesh_, g);
            if (std::find(t.begin(), t.end(), v) != t.end()) return g;
        }
        return -1;
    }

    void drop(int32_t v, int32_t f) {
        auto& list = adj_.triangles_of[v];
        list.erase(std::remove(list.begin(), list.end(), f), list.end());
    }

    Mesh& mesh_;
    Adjacency adj_;
    std::vector<char> on_boundary_;
    long collapsed_ = 0;
    long split_ = 0;
    std::vector<int32_t> renumbered_; // by finish(), old index to new
    long flipped_ = 0;
};

} // namespace

ShortEdgeStats collapse_short_edges(Mesh& mesh, const ShortEdgeParams& params) {
    if (mesh.triangles.rows() == 0) return {};
    std::vector<EdgeCount> edges = edge_counts(mesh.triangles);
    std::vector<double> lengths;
    lengths.reserve(edges.size());
    for (const EdgeCount& e : edges) lengths.push_back((position(mesh, e.a) - position(mesh, e.b)).norm());
    std::vector<double> sorted = lengths;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = params.ratio * sorted[sorted.size() / 2];

    std::vector<std::tuple<double, int32_t, int32_t>> candidates;
    for (size_t i = 0; i < edges.size(); ++i)
        if (edges[i].count == 2 && lengths[i] < limit) candidates.emplace_back(lengths[i], edges[i].a, edges[i].b);
    if (candidates.empty()) return {};
    std::sort(candidates.begin(), candidates.end());

    Collapser collapser(mesh);
    for (const auto& [length, a, b] : candidates) collapser.collapse(a, b, collapser.worst_kappa_around({a, b}));
    return {collapser.finish()};
}

PoorTriangleStats mend_poor_triangles(Mesh& mesh, const Reference& reference, const PoorTriangleParams& params) {
    if (!(params.kappa_below >= 0.0 && params.kappa_below <= 1.0) ||
        !(params.flat_angle_deg > 0.0 && params.flat_angle_deg < 90.0))
        throw InvalidInput("mend_poor_triangles: kappa_below must lie in [0, 1] and flat_angle_deg in (0, 90)");
    check_indices(mesh, "poor triangles' mesh");
    std::vector<std::pair<double, int32_t>> poor; // (kappa, triangle), worst first
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        if (const double k = kappa_of(mesh, triangle_vertices(mesh, static_cast<int32_t>(f))); k < params.kappa_below)
            poor.emplace_back(k, static_cast<int32_t>(f));
    if (poor.empty()) return {};
    std::sort(poor.begin(), poor.end());
    const double min_cos = std::cos(params.flat_angle_deg * M_PI / 180.0);
    Collapser collapser(mesh);
    // The longest edge of a triangle, a -> b as it runs, and its length.
    auto longest_edge = [&](const std::array<int32_t, 3>& tri) {
        int longest = 0;
        double length = -1.0;
        for (int j = 0; j < 3; ++j)
            if (const double l = (position(mesh, tri[j]) - position(mesh, tri[(j + 1) % 3])).norm(); l > length) {
                length = l;
                longest = j;
            }
        return std::make_tuple(tri[longest], tri[(longest + 1) % 3], length);
    };
    // Edge a-b split where its midpoint is nearest on the input; whether it was.
    auto split_at_middle = [&](int32_t a, int32_t b) {
        const Eigen::Vector3d pa = position(mesh, a), pb = position(mesh, b);
        const ClosestPoint p = reference.tree.closest(0.5 * (pa + pb));
        if (p.triangle < 0) return false;
        // The edge runs along the input (a crease's, if its triangles turn) when that point
        // lies on it: a chord across a crease turning by theta has its middle (L / 2)
        // sin(theta / 2) off the input, 0.19 L at 45 degrees; a chord of a curved crease of
        // radius R, L / (8 R).
        const double off_edge = (closest_point_on_segment(p.point, pa, pb) - p.point).norm();
        const bool along_input = off_edge <= kAlongInput * (pb - pa).norm();
        return collapser.split(a, b, p.point, collapser.worst_kappa_of_edge(a, b), along_input, true);
    };
    for (const auto& [kappa, f] : poor) {
        if (!collapser.alive(f)) continue; // taken out by an earlier collapse
        const auto t = triangle_vertices(mesh, f);
        if (kappa_of(mesh, t) != kappa) continue; // changed by an earlier split
        // A collapse of one of its edges, the end point that goes one `may_go(kept, gone)` allows,
        // the triangles round the edge ending above `floor` and above their worst now.
        auto collapse_an_edge = [&](auto may_go, double floor) {
            for (int j = 0; j < 3; ++j) {
                const int32_t a = t[j], b = t[(j + 1) % 3];
                const bool a_may_go = may_go(b, a), b_may_go = may_go(a, b);
                if ((a_may_go || b_may_go) &&
                    collapser.collapse(a, b, std::max(collapser.worst_kappa_around({a, b}), floor), a_may_go, b_may_go))
                    return true;
            }
            return false;
        };
        // Off a flat fan, a vertex may go where the surface stays as near to the input, if that
        // lifts every triangle round the edge to the floor: short of it, a split may do better.
        const bool mended =
            collapse_an_edge([&](int32_t, int32_t gone) { return collapser.may_go(gone, min_cos); }, 0.0) ||
            collapse_an_edge([&](int32_t kept, int32_t gone) { return collapser.stays_near_input(kept, gone, reference.tree); },
                             params.kappa_below);
        if (mended) continue;
        const auto [a, b, length] = longest_edge(t);
        if (split_at_middle(a, b)) continue;
        // Refused: the next step of Rivara's longest-edge propagation. The triangle across that
        // edge has a longer one (a crease's edge beside a strip narrower than it: the frame's
        // 0.6 mm of top face between a corner and its pin hole), split first; its split's rim
        // flip may then take the poor triangle's edge, joining its apex to the new vertex.
        if (const auto q = collapser.quad(a, b)) {
            const auto [u, v, across] = longest_edge(triangle_vertices(mesh, (*q)[1]));
            if (across > length) split_at_middle(u, v);
        }
    }
    PoorTriangleStats stats;
    stats.split = collapser.splits();
    stats.flipped = collapser.flips();
    const Eigen::Index before = mesh.points.rows(); // the splits' vertices: its last `split` rows
    stats.collapsed = collapser.finish();
    for (Eigen::Index v = before - stats.split; v < before; ++v)
        if (const int32_t now = collapser.renumbered(static_cast<int32_t>(v)); now >= 0) // never gone: guarded
            stats.added.push_back(now);
    return stats;
}

FoldedPairStats collapse_folded_pairs(Mesh& mesh, const Reference& reference, const FoldedPairParams& params) {
    const Mesh& input = reference.mesh;
    const AabbTree& input_tree = reference.tree;
    if (!(params.min_turn_deg > 90.0 && params.min_turn_deg < 180.0) || !(params.gap_ratio > 0.0 && params.gap_ratio < 1.0) ||
        !(params.kappa_floor >= 0.0 && params.kappa_floor <= 1.0) ||
        !(params.knife_turn_deg > 0.0 && params.knife_turn_deg < 180.0))
        throw InvalidInput("collapse_folded_pairs: min_turn_deg must lie in (90, 180), gap_ratio in (0, 1), "
                           "kappa_floor in [0, 1] and knife_turn_deg in (0, 180)");
    check_indices(mesh, "folded pairs' mesh");
    if (mesh.triangles.rows() == 0) return {};
    const double cos_turn = std::cos(params.min_turn_deg * M_PI / 180.0);
    // Whether triangle f faces against the input's triangle nearest to its centroid.
    auto faces_against_input = [&](int32_t f) {
        const Eigen::Vector3d centroid = (position(mesh, mesh.triangles(f, 0)) + position(mesh, mesh.triangles(f, 1)) +
                                          position(mesh, mesh.triangles(f, 2))) / 3.0;
        const ClosestPoint near = input_tree.closest(centroid);
        return near.triangle >= 0 && normal_of(mesh, f).dot(input_tree.triangle_normal(near.triangle)) < 0.0;
    };
    // Whether the quad {f1, f2, c, d} of edge a-b (Collapser::quad) is a pair folded shut.
    auto folded_shut = [&](int32_t a, int32_t b, const std::array<int32_t, 4>& q) {
        const auto [f1, f2, c, d] = q;
        const Eigen::Vector3d n1 = normal_of(mesh, f1), n2 = normal_of(mesh, f2);
        if (c == d || !(n1.dot(n2) < cos_turn * n1.norm() * n2.norm())) return false; // also for a zero normal
        const double gap = (position(mesh, c) - position(mesh, d)).norm();
        if (!(gap < params.gap_ratio * (position(mesh, a) - position(mesh, b)).norm())) return false;
        return faces_against_input(f1) || faces_against_input(f2); // else a knife edge's, on the input
    };

    // The candidates from one scan of the edges; the collapser, which the rest needs, only for
    // a mesh that has any (most have none).
    std::vector<std::pair<int32_t, int32_t>> candidates;
    const EdgeUses edges = edge_uses(mesh.triangles);
    for (long e = 0; e < edges.size(); ++e) {
        if (edges.count(e) != 2) continue;
        const int32_t* use = edges.uses.begin(e);
        if (runs_forward(mesh.triangles, use[0]) == runs_forward(mesh.triangles, use[1])) continue; // misoriented
        // The first use runs a -> b -> c, the second b -> a -> d.
        const int32_t f1 = use[0] / 3, j1 = use[0] % 3, f2 = use[1] / 3, j2 = use[1] % 3;
        const int32_t a = mesh.triangles(f1, j1), b = mesh.triangles(f1, (j1 + 1) % 3);
        if (folded_shut(a, b, {f1, f2, mesh.triangles(f1, (j1 + 2) % 3), mesh.triangles(f2, (j2 + 2) % 3)}))
            candidates.emplace_back(a, b);
    }
    if (candidates.empty()) return {};

    // A pair within its edge's length of a knife edge of the input, whose two faces there are
    // easily each other's nearest triangles, stands for it: kept. The creases sampled at the
    // longest such edge, or a thousandth of the input's size if that is longer (a bound on the
    // samples whatever the edges).
    double spacing = 0.0;
    for (const auto& [a, b] : candidates) spacing = std::max(spacing, (position(mesh, a) - position(mesh, b)).norm());
    if (input.points.rows() > 0)
        spacing = std::max(spacing, 1e-3 * (input.points.colwise().maxCoeff() - input.points.colwise().minCoeff()).norm());
    const AcuteCreases knives(input, params.knife_turn_deg, spacing);
    Collapser collapser(mesh);
    for (const auto& [a, b] : candidates) {
        const auto q = collapser.quad(a, b); // as the collapses before this one left it
        if (!q || !folded_shut(a, b, *q)) continue;
        const Eigen::Vector3d pa = position(mesh, a), pb = position(mesh, b);
        if (knives.closest(0.5 * (pa + pb), (pa - pb).norm())) continue;
        const auto [f1, f2, c, d] = *q;
        if (collapser.joined(c, d)) continue;
        const double must_beat = std::min(collapser.worst_kappa_around({a, b, c, d}), params.kappa_floor);
        const auto was = collapser.flip(a, b, *q);
        if (!collapser.collapse(c, d, must_beat)) collapser.unflip(a, b, *q, was);
    }
    return {collapser.finish()};
}

} // namespace liftremesh
