#include "liftremesh/repair/untangle.h"

#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/editable_mesh.h"
#include "liftremesh/spatial/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace liftremesh {

namespace {

using Tri = EditableMesh::Tri;

//! The triangles of a pass: a tree of the mesh as the pass found it, and the triangles the
//! pass has changed since, flipped or moved (their boxes are no longer the tree's).
struct PassTriangles {
    const EditableMesh& mesh;
    const AabbTree& tree;
    std::vector<char> changed; // per triangle
    std::vector<int> changed_list;
    std::vector<char> gone; // per triangle: taken out of the mesh by the pass
    std::vector<int32_t> found; // scratch

    PassTriangles(const EditableMesh& m, const AabbTree& t)
        : mesh(m), tree(t), changed(m.tris.size(), 0), gone(m.tris.size(), 0) {}

    void mark_changed(int t) {
        if (!changed[static_cast<size_t>(t)]) changed_list.push_back(t);
        changed[static_cast<size_t>(t)] = 1;
    }

    //! How many times the triangles `tris` (corners as the mesh has them now) cross the others
    //! but those numbered in `skip`, and each other (a triangle crossing two of them counted
    //! twice): the others whose boxes meet theirs, as the tree finds them unless changed since,
    //! and as they are now for those changed since.
    long crossings_of(const std::vector<Tri>& tris, const std::vector<int>& skip) {
        std::vector<std::array<Eigen::Vector3d, 3>> at;
        Eigen::Vector3d lo = mesh.points[tris[0][0]], hi = lo;
        for (const Tri& t : tris) {
            at.push_back(mesh.corners(t));
            for (const Eigen::Vector3d& x : at.back()) {
                lo = lo.cwiseMin(x);
                hi = hi.cwiseMax(x);
            }
        }
        long count = crossings_among(mesh, tris);
        auto test = [&](int g) {
            if (gone[static_cast<size_t>(g)] || std::find(skip.begin(), skip.end(), g) != skip.end()) return;
            const Tri& t = mesh.tris[static_cast<size_t>(g)];
            const std::array<Eigen::Vector3d, 3> pt = mesh.corners(t);
            for (size_t i = 0; i < tris.size(); ++i) count += triangles_cross(tris[i], at[i], t, pt) ? 1 : 0;
        };
        found.clear();
        tree.triangles_meeting_box(lo, hi, found);
        for (int32_t g : found)
            if (!changed[static_cast<size_t>(g)]) test(g);
        for (int g : changed_list) {
            const std::array<Eigen::Vector3d, 3> pt = mesh.corners(mesh.tris[static_cast<size_t>(g)]);
            const Eigen::Vector3d tlo = pt[0].cwiseMin(pt[1]).cwiseMin(pt[2]);
            const Eigen::Vector3d thi = pt[0].cwiseMax(pt[1]).cwiseMax(pt[2]);
            if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) test(g);
        }
        return count;
    }
};

//! One pass of flips around the triangles of `crossings` (see untangle()), written into
//! `mesh`; the pass's copies of the mesh are gone when it returns. Returns the flips.
long untangle_pass(Mesh& mesh, const AabbTree& mesh_tree, const AabbTree& input,
                   const std::vector<std::pair<int32_t, int32_t>>& crossings, const UntangleParams& params) {
    EditableMesh edit(mesh);
    PassTriangles triangles(edit, mesh_tree);
    std::vector<char> around(edit.tris.size(), 0), changed;
    for (const auto& [s, t] : crossings) around[static_cast<size_t>(s)] = around[static_cast<size_t>(t)] = 1;
    const CompressedRows fans = edit.fans();
    const TrianglesOf triangles_of = fans_of(fans);
    const auto accept = [&](const EditableMesh::Quad& q) {
        const Tri &t1 = edit.tris[q.t1], &t2 = edit.tris[q.t2];
        const auto [n1, n2] = EditableMesh::flipped(q);
        if (edit.normal(n1).isZero(0.0) || edit.normal(n2).isZero(0.0)) return false;
        if (flip_folds_rim(edit, q, triangles_of)) return false; // a crossing traded for a fold
        const double worse_before = std::min(edit.kappa(t1), edit.kappa(t2));
        if (!(std::min(edit.kappa(n1), edit.kappa(n2)) >= std::min(worse_before, params.kappa_floor))) return false;
        if (!(triangles.crossings_of({n1, n2}, {q.t1, q.t2}) < triangles.crossings_of({t1, t2}, {q.t1, q.t2})))
            return false;
        const double near_before = std::max(triangle_distance_from_input(edit, t1, input),
                                            triangle_distance_from_input(edit, t2, input));
        const double near_after = std::max(triangle_distance_from_input(edit, n1, input),
                                           triangle_distance_from_input(edit, n2, input));
        if (!(near_after <= std::max(near_before, params.tolerance))) return false;
        triangles.mark_changed(q.t1); // flip_pass flips what it accepts
        triangles.mark_changed(q.t2);
        return true;
    };
    const long flips = edit.flip_pass_around(around, accept, changed);
    if (flips > 0) edit.write_to(mesh);
    return flips;
}

//! The vertices of the triangles of `crossings` that are not on a border, each once, in index
//! order: the candidates of the moves and of the tents' removal.
std::vector<int32_t> inner_vertices_of(const EditableMesh& edit,
                                       const std::vector<std::pair<int32_t, int32_t>>& crossings) {
    const std::vector<char> on_border = edit.border_points();
    std::vector<int32_t> candidates;
    for (const auto& [s, t] : crossings)
        for (int32_t f : {s, t})
            for (int32_t v : edit.tris[static_cast<size_t>(f)])
                if (!on_border[static_cast<size_t>(v)]) candidates.push_back(v);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return candidates;
}

//! A vertex's fan as the move rules weigh it (see untangle()).
struct FanState {
    double worst_kappa = 2.0; // its worst triangle's kappa
    double farthest = 0.0;    // its farthest triangle's distance from the input
    int against = 0;          // its triangles facing against the input's triangle nearest to them
    bool degenerate = false;  // a triangle of zero area
};

FanState fan_state(const EditableMesh& mesh, const std::vector<Tri>& fan, const AabbTree& input) {
    FanState state;
    for (const Tri& t : fan) {
        const Eigen::Vector3d n = mesh.normal(t);
        state.degenerate = state.degenerate || n.isZero(0.0);
        state.worst_kappa = std::min(state.worst_kappa, mesh.kappa(t));
        const TriangleNearInput near = triangle_near_input(mesh, t, input);
        state.farthest = std::max(state.farthest, near.distance);
        state.against += near.nearest_to_centroid >= 0 && n.dot(input.triangle_normal(near.nearest_to_centroid)) < 0.0;
    }
    return state;
}

//! Whether the triangles an edit makes (`now`) may replace those it takes (`was`) under the move
//! rules (see untangle()), folds aside: none of zero area, no more facing against the input, the
//! worst no worse than both the old worst and the floor, and none farther from the input than the
//! old farthest and the tolerance.
bool keeps_move_rules(const FanState& was, const FanState& now, const UntangleParams& params) {
    return !now.degenerate && now.against <= was.against &&
           now.worst_kappa >= std::min(was.worst_kappa, params.kappa_floor) &&
           now.farthest <= std::max(was.farthest, params.tolerance);
}

//! One pass of moves over the inner vertices of the triangles of `crossings`, in index order
//! (see untangle()), written into `mesh`. Returns the moves.
long move_pass(Mesh& mesh, const AabbTree& mesh_tree, const AabbTree& input,
               const std::vector<std::pair<int32_t, int32_t>>& crossings, const UntangleParams& params) {
    EditableMesh edit(mesh);
    PassTriangles triangles(edit, mesh_tree);
    const CompressedRows fans = edit.fans();
    const std::vector<int32_t> candidates = inner_vertices_of(edit, crossings);

    const TrianglesOf triangles_of = fans_of(fans);
    long moves = 0;
    std::vector<int> fan;
    std::vector<Tri> fan_tris;
    for (int32_t v : candidates) {
        fan.assign(fans.begin(v), fans.end(v));
        fan_tris.clear();
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // each neighbour of an inner vertex is in two of its triangles
        for (int f : fan) {
            fan_tris.push_back(edit.tris[static_cast<size_t>(f)]);
            for (int32_t w : fan_tris.back())
                if (w != v) centroid += edit.points[static_cast<size_t>(w)];
        }
        if (fan.size() < 3) continue;
        centroid /= static_cast<double>(2 * fan.size());
        const long before = triangles.crossings_of(fan_tris, fan);
        if (before == 0) continue;
        const FanState was = fan_state(edit, fan_tris, input);
        // The fan and the triangles round it, whose edges with the fan a move may fold.
        std::vector<int> region;
        for (int f : fan)
            for (int32_t w : edit.tris[static_cast<size_t>(f)]) region.insert(region.end(), fans.begin(w), fans.end(w));
        const int folded_before = folded_edges_among(edit, region, triangles_of);
        const Eigen::Vector3d p = edit.points[static_cast<size_t>(v)];
        Eigen::Vector3d chosen = p;
        long fewest = before;
        double best_kappa = -1.0;
        for (double s : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            edit.points[static_cast<size_t>(v)] = input.closest(p + s * (centroid - p)).point;
            const long after = triangles.crossings_of(fan_tris, fan);
            if (after > fewest) continue;
            const FanState now = fan_state(edit, fan_tris, input);
            if (!keeps_move_rules(was, now, params) || folded_edges_among(edit, region, triangles_of) > folded_before)
                continue;
            if (after < fewest || now.worst_kappa > best_kappa) {
                fewest = after;
                best_kappa = now.worst_kappa;
                chosen = edit.points[static_cast<size_t>(v)];
            }
        }
        edit.points[static_cast<size_t>(v)] = chosen;
        if (fewest < before) {
            ++moves;
            for (int f : fan) triangles.mark_changed(f);
        } else {
            edit.points[static_cast<size_t>(v)] = p;
        }
    }
    if (moves > 0) edit.write_to(mesh);
    return moves;
}

//! One pass over the inner vertices of the triangles of `crossings` with three triangles round
//! them, in index order (see untangle()): each such tent replaced by the triangle of its rim
//! where the rules of a move allow it, written into `mesh` with the vertices left unreferenced
//! removed. Returns the vertices removed.
long tent_pass(Mesh& mesh, const AabbTree& mesh_tree, const AabbTree& input,
               const std::vector<std::pair<int32_t, int32_t>>& crossings, const UntangleParams& params) {
    EditableMesh edit(mesh);
    PassTriangles triangles(edit, mesh_tree);
    const CompressedRows fans = edit.fans();
    long removed = 0;
    std::vector<int> fan, region;
    std::vector<Tri> fan_tris;
    // A vertex's triangles, those taken out already left out.
    auto present = [&](int32_t w) {
        std::vector<int> out;
        for (const int32_t* t = fans.begin(w); t != fans.end(w); ++t)
            if (!triangles.gone[static_cast<size_t>(*t)]) out.push_back(*t);
        return out;
    };
    // The apexes and rims of the tents taken out: the fans of the others are still `fans`.
    std::vector<char> touched(edit.points.size(), 0);
    for (int32_t v : inner_vertices_of(edit, crossings)) {
        if (touched[static_cast<size_t>(v)]) continue;
        fan = present(v);
        if (fan.size() != 3) continue;
        // Each triangle rotated to start at v runs v -> x -> y; the rim runs x -> y round it.
        std::array<int32_t, 3> from{}, to{};
        fan_tris.clear();
        for (size_t i = 0; i < 3; ++i) {
            const Tri& t = edit.tris[static_cast<size_t>(fan[i])];
            fan_tris.push_back(t);
            const int j = t[0] == v ? 0 : t[1] == v ? 1 : 2;
            from[i] = t[(j + 1) % 3];
            to[i] = t[(j + 2) % 3];
        }
        auto next = [&](int32_t x) {
            for (size_t i = 0; i < 3; ++i)
                if (from[i] == x) return to[i];
            return int32_t{-1};
        };
        const Tri rim{from[0], next(from[0]), next(next(from[0]))};
        if (rim[1] < 0 || rim[2] < 0 || next(rim[2]) != rim[0] || rim[1] == rim[0] || rim[2] == rim[0]) continue;
        if (std::any_of(rim.begin(), rim.end(), [&](int32_t w) { return touched[static_cast<size_t>(w)] != 0; }))
            continue;
        // The rim's triangle must not be one of the mesh already (a tetrahedron's last faces).
        bool exists = false;
        for (int f : present(rim[0])) {
            const Tri& t = edit.tris[static_cast<size_t>(f)];
            exists = exists || (std::find(t.begin(), t.end(), rim[1]) != t.end() &&
                                std::find(t.begin(), t.end(), rim[2]) != t.end());
        }
        if (exists) continue;
        const long before = triangles.crossings_of(fan_tris, fan);
        if (before == 0 || !(triangles.crossings_of({rim}, fan) < before)) continue;
        const FanState was = fan_state(edit, fan_tris, input), now = fan_state(edit, {rim}, input);
        if (!keeps_move_rules(was, now, params)) continue;
        // No more folded edges than the tent had: with the rim's triangle in the first one's place.
        const TrianglesOf triangles_of = [&](int32_t w) {
            region = present(w);
            return std::make_pair(region.data(), region.data() + region.size());
        };
        const int folded_before = folded_edges_among(edit, fan, triangles_of);
        edit.tris[static_cast<size_t>(fan[0])] = rim;
        triangles.gone[static_cast<size_t>(fan[1])] = triangles.gone[static_cast<size_t>(fan[2])] = 1;
        if (folded_edges_among(edit, {fan[0]}, triangles_of) > folded_before) {
            edit.tris[static_cast<size_t>(fan[0])] = fan_tris[0];
            triangles.gone[static_cast<size_t>(fan[1])] = triangles.gone[static_cast<size_t>(fan[2])] = 0;
            continue;
        }
        for (int f : fan) triangles.mark_changed(f);
        for (int32_t w : {v, rim[0], rim[1], rim[2]}) touched[static_cast<size_t>(w)] = 1;
        ++removed;
    }
    if (removed == 0) return 0;
    edit.write_to(mesh);
    drop_triangles(mesh, triangles.gone);
    remove_unreferenced_vertices(mesh);
    return removed;
}

} // namespace

UntangleStats untangle(Mesh& mesh, const Reference& reference, const UntangleParams& params) {
    const AabbTree& input = reference.tree;
    check_indices(mesh, "untangled mesh");
    if (!(params.tolerance > 0.0) || !std::isfinite(params.tolerance) || params.passes < 0)
        throw InvalidInput("untangle: the tolerance must be positive and finite, the passes not negative");
    UntangleStats stats;
    // One tree of the mesh at a time: the one each pass finds it with, made again after each pass
    // that changed it (the pass's copies gone by then), for the next pass and the crossings left.
    stats.tree.emplace(mesh);
    std::vector<std::pair<int32_t, int32_t>> crossings = self_intersecting_pairs(mesh, *stats.tree);
    auto tree = [&]() -> const AabbTree& {
        if (!stats.tree) stats.tree.emplace(mesh);
        return *stats.tree;
    };
    auto recount = [&]() {
        stats.tree.reset();
        crossings = self_intersecting_pairs(mesh, tree());
    };
    // Passes of one kind of edit at the floor of `at`, while crossings are left and a pass makes one.
    UntangleParams at = params; // the passes' floor: the preferred one, then the last resort's
    auto run_passes = [&](auto pass_of, long& made) {
        for (int pass = 0; pass < params.passes && !crossings.empty(); ++pass) {
            const long edits = pass_of(mesh, tree(), input, crossings, at);
            if (edits == 0) break;
            made += edits;
            recount();
        }
    };
    const double preferred = std::max(params.preferred_kappa_floor, params.kappa_floor);
    const std::vector<double> floors = preferred > params.kappa_floor ? std::vector<double>{preferred, params.kappa_floor}
                                                                     : std::vector<double>{params.kappa_floor};
    // Edits that keep the preferred floor first, then, for the crossings they leave, those down
    // to the last resort's; at each floor flips first, since they move no vertex, then moves for
    // what they leave.
    for (const double kappa_floor : floors) {
        at.kappa_floor = kappa_floor;
        run_passes(untangle_pass, stats.flipped);
        run_passes(move_pass, stats.moved);
    }
    // Last, for the crossings that no flip or move undoes, the tents of three triangles round a
    // vertex taken out, at the same floors.
    for (const double kappa_floor : floors) {
        at.kappa_floor = kappa_floor;
        run_passes(tent_pass, stats.removed);
    }
    stats.crossings = std::move(crossings);
    tree();
    return stats;
}

} // namespace liftremesh
