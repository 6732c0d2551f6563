#include "liftremesh/polish/hausdorff_refinement.h"

#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/editable_mesh.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

using Tri = EditableMesh::Tri;

// The splits that may follow a point's own to lift the triangles round it to the floor.
constexpr int kMendSplits = 3;
// A scan's creases can meet in thousands of junctions: the points farthest from a vertex are
// tried first, this many in all.
constexpr long kMaxPointsTried = 64;

// The input's referenced vertices, then points along each of its edges at most `spacing` apart.
std::vector<Eigen::Vector3d> edge_samples(const Mesh& input, double spacing) {
    const std::vector<char> used = referenced_vertices(input);
    std::vector<Eigen::Vector3d> samples;
    for (Eigen::Index i = 0; i < input.points.rows(); ++i)
        if (used[i]) samples.push_back(input.points.row(i).transpose());
    for (const EdgeCount& e : edge_counts(input.triangles)) {
        const Eigen::Vector3d a = input.points.row(e.a).transpose(), b = input.points.row(e.b).transpose();
        const double steps = std::ceil((b - a).norm() / spacing);
        if (!(steps < 1e6)) continue; // a non-finite or absurdly long edge: its end points will do
        for (int i = 1; i < static_cast<int>(steps); ++i) samples.push_back(a + (b - a) * (i / steps));
    }
    return samples;
}

// A sample farther than the tolerance from the mesh, and the triangle it is nearest to.
struct Witness {
    double distance;
    long sample;
    int32_t triangle;
    bool operator<(const Witness& o) const { return distance != o.distance ? distance > o.distance : sample < o.sample; }
};

class Refinement {
public:
    Refinement(const Mesh& mesh, const AabbTree& input, const HausdorffRefinementParams& params)
        : mesh_(mesh), input_(input), params_(params) {
        mesh_.keep_fans(); // each try's flips and splits are local: their neighbourhood from the fans
    }

    // Inserts the witnesses of the current mesh; returns how many, marking the triangles made.
    long insert(const std::vector<Eigen::Vector3d>& samples, long allowed) {
        const std::vector<Witness> witnesses = find_witnesses(samples);
        clear_near();
        made_.clear();
        if (witnesses.empty()) return 0;
        std::vector<int32_t> corners; // of the witnesses' triangles
        for (const Witness& w : witnesses)
            corners.insert(corners.end(), mesh_.tris[w.triangle].begin(), mesh_.tris[w.triangle].end());
        const auto uses = mesh_.edge_uses_near(corners);
        long inserted = 0;
        for (const Witness& w : witnesses) {
            if (inserted == allowed) break;
            if (near_[w.triangle]) continue; // changed this round: its witnesses are sampled again next round
            if (insert_at(w.triangle, samples[w.sample], uses, params_.kappa_floor)) ++inserted;
        }
        return inserted;
    }

    // Inserts each of the `points` that `todo` lists and that has no vertex within `gap` nor
    // lies farther than the largest distance from the mesh (insert_input_points), farthest
    // from a vertex first, while `tries` lasts and fewer than `budget` vertices were added
    // (a try may add up to 1 + kMendSplits); returns the vertices added, adding the flips
    // made to `flipped`. Leaves in `todo` the points that an insertion before them came near
    // (its triangles as near as the point's closest or within the gap), for another call.
    long insert_points(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& floors, double gap,
                       std::vector<size_t>& todo, long& tries, long budget, long& flipped) {
        const AabbTree tree(mesh_.to_mesh());
        struct Wanted {
            double away;      // from the nearest corner of its closest triangle
            double distance;  // from that triangle
            size_t point;
            int32_t triangle; // its closest
        };
        std::vector<Wanted> wanted;
        std::vector<int32_t> met;
        for (const size_t i : todo) {
            met.clear();
            tree.triangles_within(points[i], gap, met);
            const bool on_vertex = std::any_of(met.begin(), met.end(), [&](int32_t t) {
                const Tri& x = mesh_.tris[t];
                return std::any_of(x.begin(), x.end(), [&](int32_t v) { return (mesh_.points[v] - points[i]).norm() <= gap; });
            });
            if (on_vertex) continue;
            const ClosestPoint c = tree.closest(points[i]);
            const double distance = std::sqrt(c.squared_distance);
            if (c.triangle < 0 || distance > params_.max_distance) continue; // a part the output lost
            double away = std::numeric_limits<double>::infinity();
            for (int32_t v : mesh_.tris[c.triangle]) away = std::min(away, (mesh_.points[v] - points[i]).norm());
            wanted.push_back({away, distance, i, c.triangle});
        }
        std::sort(wanted.begin(), wanted.end(),
                  [](const Wanted& a, const Wanted& b) { return a.away != b.away ? a.away > b.away : a.point < b.point; });
        const size_t vertices = mesh_.points.size();
        std::vector<char> changed(mesh_.tris.size(), 0); // since the tree was built
        std::vector<int32_t> made;                       // the same, listed
        // Whether an insertion before came near p: its closest triangle may be another now, or a
        // vertex within the gap.
        auto came_near = [&](const Eigen::Vector3d& p, int32_t t, double distance) {
            if (changed[t]) return true;
            const double reach2 = std::pow(std::max(distance, gap), 2);
            return std::any_of(made.begin(), made.end(), [&](int32_t f) {
                const Tri& x = mesh_.tris[f];
                return (closest_point_on_triangle(p, mesh_.points[x[0]], mesh_.points[x[1]], mesh_.points[x[2]]) - p)
                           .squaredNorm() <= reach2;
            });
        };
        todo.clear();
        for (const auto& [away, distance, i, t] : wanted) {
            if (came_near(points[i], t, distance)) {
                todo.push_back(i);
                continue;
            }
            if (tries == 0 || static_cast<long>(mesh_.points.size() - vertices) >= budget) break;
            --tries;
            clear_near();
            made_.clear();
            mesh_.begin_edits();
            long flips = 0;
            if (!insert_and_mend(t, points[i], floors.empty() ? params_.kappa_floor : floors[i], flips)) {
                mesh_.roll_back();
                continue;
            }
            mesh_.keep_edits();
            flipped += flips;
            changed.resize(mesh_.tris.size(), 0);
            for (const int f : near_list_) // the triangles made and changed by this try
                if (!std::exchange(changed[f], 1)) made.push_back(f);
        }
        return static_cast<long>(mesh_.points.size() - vertices);
    }

    // Flips edges of the triangles made this round, for distance or quality (see the header).
    // Crease flips keep `floor` (the refinement's, or the point's insert_points tries).
    long flip_near_insertions(double floor) {
        long flipped = 0;
        std::vector<int> changed;
        for (int pass = 0; pass < 5; ++pass) {
            fans_ = mesh_.fans_near(near_list_); // should_flip's quads all have a triangle there
            const long flips = mesh_.flip_pass_near(
                near_list_, [&](const EditableMesh::Quad& q) { return should_flip(q, floor); }, changed);
            for (const int t : changed) mark_near(t);
            flipped += flips;
            if (flips == 0) break;
        }
        return flipped;
    }

    void write_to(Mesh& mesh) const { mesh_.write_to(mesh, 0); }

private:
    // Flags triangle f as made or changed this round (near_, listed in near_list_).
    void mark_near(int f) {
        if (static_cast<size_t>(f) >= near_.size()) near_.resize(static_cast<size_t>(f) + 1, 0);
        if (!near_[f]) {
            near_[f] = 1;
            near_list_.push_back(f);
        }
    }
    // Clears the flags, near_ at least as long as the triangles.
    void clear_near() {
        for (const int f : near_list_) near_[f] = 0;
        near_list_.clear();
        if (near_.size() < mesh_.tris.size()) near_.resize(mesh_.tris.size(), 0);
    }

    // The samples farther than the tolerance from the mesh, farthest first. A sample is near
    // the mesh if a triangle lies within the tolerance: the one found last round if it has not
    // changed since, else the one that proved its thread's previous sample near (consecutive
    // samples lie along the same edge), else one a search bounded by the tolerance finds. Only
    // the others, the witnesses, are searched for their closest triangle. Which triangle proves
    // a sample near may depend on the threads; whether it is near, its distance and its closest
    // triangle do not.
    std::vector<Witness> find_witnesses(const std::vector<Eigen::Vector3d>& samples) {
        const AabbTree tree(mesh_.to_mesh());
        const double tol2 = params_.tolerance * params_.tolerance;
        const long n = static_cast<long>(samples.size());
        proof_.resize(samples.size(), -1);
        const std::vector<char>& changed = near_; // last round's edits (no proof_ yet in the first)
        auto unchanged = [&](int32_t t) { return t >= 0 && !changed[t]; };
        auto within = [&](int32_t t, const Eigen::Vector3d& q) {
            const Tri& x = mesh_.tris[t];
            const Eigen::Vector3d& a = mesh_.points[x[0]];
            return (closest_point_on_triangle(q, a, mesh_.points[x[1]], mesh_.points[x[2]]) - q).squaredNorm() < tol2;
        };
        std::vector<ClosestPoint> far(samples.size(), ClosestPoint{Eigen::Vector3d::Zero(), 0.0, -1});
#pragma omp parallel
        {
            int32_t hint = -1;
#pragma omp for schedule(static)
            for (long i = 0; i < n; ++i) {
                if (unchanged(proof_[i])) continue;
                if (hint >= 0 && within(hint, samples[i])) {
                    proof_[i] = hint;
                    continue;
                }
                proof_[i] = tree.any_within(samples[i], params_.tolerance);
                if (proof_[i] >= 0)
                    hint = proof_[i];
                else
                    far[i] = tree.closest(samples[i]);
            }
        }
        std::vector<Witness> witnesses;
        for (long i = 0; i < n; ++i)
            if (far[i].triangle >= 0 && far[i].squared_distance <= params_.max_distance * params_.max_distance)
                witnesses.push_back({std::sqrt(far[i].squared_distance), i, far[i].triangle});
        std::sort(witnesses.begin(), witnesses.end()); // farthest first, then by sample: deterministic
        return witnesses;
    }

    // Splits triangle t at p, flips round the split, then while the worst triangle made is
    // under the floor, at most kMendSplits times, inserts the input's point nearest to the
    // middle of its longest edge into it (the best split of it or of an edge, as insert_at
    // chooses) and flips again. A point a quarter of an edge from a vertex
    // splits the triangle it falls in into a needle, whose long edges a flip does not always
    // shorten: split, they give the short triangles such a point needs. Whether every triangle
    // made reaches the floor; the caller restores the mesh if not.
    bool insert_and_mend(int32_t t, const Eigen::Vector3d& p, double floor, long& flips) {
        if (!split_now(t, p)) return false;
        flips += flip_near_insertions(floor);
        for (int k = 0;; ++k) {
            double worst = 2.0;
            int32_t worst_t = -1; // the first in triangle order of the worst
            for (const int f : near_list_)
                if (const double kappa = mesh_.kappa(mesh_.tris[f]); kappa < worst || (kappa == worst && f < worst_t)) {
                    worst = kappa;
                    worst_t = f;
                }
            if (worst >= floor) return true;
            if (k == kMendSplits) return false;
            const Tri w = mesh_.tris[worst_t];
            auto length2 = [&](int j) { return (mesh_.points[w[j]] - mesh_.points[w[(j + 1) % 3]]).squaredNorm(); };
            int longest = 0;
            for (int j = 1; j < 3; ++j)
                if (length2(j) > length2(longest)) longest = j;
            const ClosestPoint on = input_.closest(0.5 * (mesh_.points[w[longest]] + mesh_.points[w[(longest + 1) % 3]]));
            if (on.triangle < 0 || !split_now(worst_t, on.point)) return false;
            flips += flip_near_insertions(floor);
        }
    }

    // insert_at with the uses of t's edges as they are now, under no floor: insert_and_mend
    // judges the triangles after the flips.
    bool split_now(int32_t t, const Eigen::Vector3d& p) {
        const Tri x = mesh_.tris[t];
        return insert_at(t, p, mesh_.edge_uses_near({x[0], x[1], x[2]}), 0.0, true);
    }

    // Splits triangle t at p, or one of its edges: an edge shared with a triangle unchanged this
    // round (or any, when `uses_current`: the uses were listed after the last change), both split
    // in two, or a boundary edge (t split in two, p joining the boundary). Of the splits that
    // turn no triangle over, the one whose worst triangle is best, if that is at least `floor`.
    bool insert_at(int32_t t, const Eigen::Vector3d& p, const std::unordered_map<uint64_t, EditableMesh::Uses>& uses,
                   double floor, bool uses_current = false) {
        struct Split {
            std::vector<std::pair<int, Tri>> replace; // triangle index, what it becomes
            std::vector<Tri> append;
        };
        const Tri tri = mesh_.tris[t];
        const auto m = static_cast<int32_t>(mesh_.points.size());
        std::vector<Split> splits;
        splits.push_back({{{t, {tri[0], tri[1], m}}}, {{tri[1], tri[2], m}, {tri[2], tri[0], m}}});
        for (int j = 0; j < 3; ++j) {
            const int32_t a = tri[j], b = tri[(j + 1) % 3], c = tri[(j + 2) % 3];
            const auto found = uses.find(edge_key(a, b));
            if (found == uses.end()) continue;
            if (found->second.size() == 1) {
                splits.push_back({{{t, {a, m, c}}}, {{m, b, c}}});
                continue;
            }
            const auto quad = mesh_.quad_of(found->second);
            if (!quad || (!uses_current && (near_[quad->t1] || near_[quad->t2]))) continue;
            const int other = quad->t1 == t ? quad->t2 : quad->t1;
            const int32_t d = quad->t1 == t ? quad->d : quad->c; // opposite the edge in the other triangle
            splits.push_back({{{t, {a, m, c}}, {other, {b, m, d}}}, {{m, b, c}, {m, a, d}}});
        }
        // The triangle across edge u-v from the split's, or -1: as `uses` lists it, unless that
        // use is stale, when it is one made or changed since (made_).
        auto across = [&](int32_t u, int32_t v, const Split& split) {
            auto fits = [&](int x) {
                const Tri& w = mesh_.tris[x];
                return std::none_of(split.replace.begin(), split.replace.end(), [x](const auto& r) { return r.first == x; }) &&
                       std::find(w.begin(), w.end(), u) != w.end() && std::find(w.begin(), w.end(), v) != w.end();
            };
            if (const auto found = uses.find(edge_key(u, v)); found != uses.end())
                for (int i = 0; i < std::min(found->second.count, 2); ++i)
                    if (fits(found->second[i].tri)) return found->second[i].tri;
            for (const int x : made_)
                if (fits(x)) return x;
            return -1;
        };
        mesh_.points.push_back(p); // so that normal() and kappa() see it; removed if nothing is split
        double best = -1.0;
        const Split* chosen = nullptr;
        for (const Split& split : splits) {
            // Each new triangle keeps the side of the one it comes from: the replaced one, or
            // for an appended one the triangle it shares the new point's edge with; nor does it
            // fold onto the triangle across its outer edge where that one did not (flip_rules.h:
            // a point on the input off the triangle's plane, beside a knife edge).
            double worst = 2.0;
            bool ok = true;
            auto check = [&](const Tri& made, int parent) {
                const Eigen::Vector3d n = mesh_.normal(made), was = mesh_.normal(mesh_.tris[parent]);
                ok = ok && n.dot(was) > 0.0 && !faces_against_input(mesh_, made, input_);
                const int k = made[0] == m ? 0 : made[1] == m ? 1 : 2;
                if (const int x = across(made[(k + 1) % 3], made[(k + 2) % 3], split); ok && x >= 0) {
                    const Eigen::Vector3d beyond = mesh_.normal(mesh_.tris[x]);
                    ok = !folded(n, beyond) || folded(was, beyond);
                }
                worst = std::min(worst, mesh_.kappa(made));
            };
            for (const auto& [f, made] : split.replace) check(made, f);
            for (size_t k = 0; k < split.append.size(); ++k)
                check(split.append[k], split.replace[std::min(k, split.replace.size() - 1)].first);
            if (ok && worst > best) {
                best = worst;
                chosen = &split;
            }
        }
        if (!chosen || !(best >= floor)) {
            mesh_.points.pop_back();
            return false;
        }
        for (const auto& [f, made] : chosen->replace) {
            mesh_.set_tri(f, made);
            mark_near(f);
            made_.push_back(f);
        }
        for (const Tri& made : chosen->append) {
            const int f = mesh_.add_tri(made);
            mark_near(f);
            made_.push_back(f);
        }
        return true;
    }

    bool should_flip(const EditableMesh::Quad& q, double floor) const {
        if (flip_folds_rim(mesh_, q, std::cref(fans_))) return false;
        const auto [before, after] = diagonal_distances(mesh_, q, input_);
        // The edge that cuts across a crease: the other diagonal lies on the input.
        const bool fits = before > params_.tolerance && after < 0.5 * before
                              ? crease_flip_fits(mesh_, q, before, after, params_.tolerance, floor)
                              : quality_flip_keeps_surface(mesh_, q, before, after, params_.tolerance);
        return fits && !flip_crosses_fans(mesh_, q, std::cref(fans_));
    }

    EditableMesh mesh_;
    const AabbTree& input_;
    const HausdorffRefinementParams& params_;
    std::vector<char> near_;      // per triangle: made or changed this round
    std::vector<int> near_list_;  // the same, listed
    std::vector<int> made_;       // the triangles insert_at made or changed since near_ was cleared
    EditableMesh::FanSnapshot fans_; // per point near near_, its triangles at the start of the flip pass
    std::vector<int32_t> proof_;  // per sample: a triangle within the tolerance last round, or -1
};

} // namespace

HausdorffRefinementStats refine_towards_input(Mesh& mesh, const Reference& reference,
                                              const HausdorffRefinementParams& params) {
    const Mesh& input = reference.mesh;
    check_indices(mesh, "refined mesh");
    check_indices(input, "input mesh");
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(params.tolerance) || !positive(params.sample_spacing) || !(params.max_distance > 0.0) ||
        !(params.kappa_floor >= 0.0) || params.rounds < 0 || params.max_inserted < 0)
        throw InvalidInput("refine_towards_input: tolerance, sample spacing and largest distance must be positive "
                           "(the first two finite), the kappa floor, rounds and most insertions not negative");
    HausdorffRefinementStats stats;
    if (mesh.triangles.rows() == 0 || input.triangles.rows() == 0) return stats;
    const std::vector<Eigen::Vector3d> samples = edge_samples(input, params.sample_spacing);
    Refinement refinement(mesh, reference.tree, params);
    for (int round = 0; round < params.rounds && stats.inserted < params.max_inserted; ++round) {
        const long inserted = refinement.insert(samples, params.max_inserted - stats.inserted);
        if (inserted == 0) break;
        stats.inserted += inserted;
        stats.flipped += refinement.flip_near_insertions(params.kappa_floor);
    }
    refinement.write_to(mesh);
    return stats;
}

HausdorffRefinementStats insert_input_points(Mesh& mesh, const Reference& reference,
                                             const std::vector<Eigen::Vector3d>& points, double gap,
                                             const HausdorffRefinementParams& params, const std::vector<double>& floors) {
    check_indices(mesh, "refined mesh");
    check_indices(reference.mesh, "input mesh");
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!(gap >= 0.0) || !std::isfinite(gap) || !(params.kappa_floor >= 0.0) || !positive(params.tolerance) ||
        !(params.max_distance > 0.0) || params.max_inserted < 0)
        throw InvalidInput("insert_input_points: the gap must be finite and not negative, the tolerance positive and "
                           "finite, the largest distance positive, the kappa floor and most insertions not negative");
    if (!floors.empty() && floors.size() != points.size())
        throw InvalidInput("insert_input_points: " + std::to_string(floors.size()) + " floors for " +
                           std::to_string(points.size()) + " points");
    if (std::any_of(floors.begin(), floors.end(), [](double f) { return !(f >= 0.0); }))
        throw InvalidInput("insert_input_points: a point's kappa floor is negative or not a number");
    HausdorffRefinementStats stats;
    if (mesh.triangles.rows() == 0 || points.empty()) return stats;
    Refinement refinement(mesh, reference.tree, params);
    // Again for the points an insertion came near, against the mesh as it is then: a point is
    // left for another call only after an insertion, which takes a try, so the calls end.
    std::vector<size_t> todo(points.size());
    std::iota(todo.begin(), todo.end(), size_t{0});
    long tries = kMaxPointsTried;
    while (!todo.empty() && tries > 0 && stats.inserted < params.max_inserted)
        stats.inserted +=
            refinement.insert_points(points, floors, gap, todo, tries, params.max_inserted - stats.inserted, stats.flipped);
    if (stats.inserted > 0) refinement.write_to(mesh);
    return stats;
}

} // namespace liftremesh
