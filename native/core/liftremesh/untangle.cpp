#include "liftremesh/untangle.h"

#include "liftremesh/editable_mesh.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/quality_polish.h"
#include "liftremesh/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace liftremesh {

namespace {

using Tri = EditableMesh::Tri;

std::array<Eigen::Vector3d, 3> corners(const EditableMesh& mesh, const Tri& t) {
    return {mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]};
}

//! The triangles of a pass: a tree of the mesh as the pass found it, and the triangles the
//! pass has flipped since (their boxes are no longer the tree's).
struct PassTriangles {
    const EditableMesh& mesh;
    AabbTree tree;
    std::vector<char> flipped; // per triangle
    std::vector<int> flipped_list;
    std::vector<int32_t> found; // scratch

    explicit PassTriangles(const EditableMesh& m) : mesh(m), tree(m.to_mesh()), flipped(m.tris.size(), 0) {}

    void mark_flipped(int t) {
        if (!flipped[static_cast<size_t>(t)]) flipped_list.push_back(t);
        flipped[static_cast<size_t>(t)] = 1;
    }

    //! How many triangles, other than those numbered `skip`, `a` and `b` cross (a triangle
    //! crossing both counted twice): those whose boxes meet the two's, as the tree finds them
    //! unless flipped since, and as they are now for those flipped since.
    long crossings_of(const Tri& a, const Tri& b, const std::array<int, 2>& skip) {
        const std::array<Eigen::Vector3d, 3> pa = corners(mesh, a), pb = corners(mesh, b);
        Eigen::Vector3d lo = pa[0], hi = pa[0];
        for (const auto* p : {&pa, &pb})
            for (const Eigen::Vector3d& x : *p) {
                lo = lo.cwiseMin(x);
                hi = hi.cwiseMax(x);
            }
        long count = 0;
        auto test = [&](int g) {
            if (g == skip[0] || g == skip[1]) return;
            const Tri& t = mesh.tris[static_cast<size_t>(g)];
            const std::array<Eigen::Vector3d, 3> pt = corners(mesh, t);
            count += triangles_cross(a, pa, t, pt) ? 1 : 0;
            count += triangles_cross(b, pb, t, pt) ? 1 : 0;
        };
        found.clear();
        tree.triangles_meeting_box(lo, hi, found);
        for (int32_t g : found)
            if (!flipped[static_cast<size_t>(g)]) test(g);
        for (int g : flipped_list) {
            const std::array<Eigen::Vector3d, 3> pt = corners(mesh, mesh.tris[static_cast<size_t>(g)]);
            const Eigen::Vector3d tlo = pt[0].cwiseMin(pt[1]).cwiseMin(pt[2]);
            const Eigen::Vector3d thi = pt[0].cwiseMax(pt[1]).cwiseMax(pt[2]);
            if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) test(g);
        }
        return count;
    }
};

//! One pass of flips around the triangles of `crossings` (see untangle()), written into
//! `mesh`; the pass's copies of the mesh are gone when it returns. Returns the flips.
long untangle_pass(Mesh& mesh, const AabbTree& input, const std::vector<std::pair<int32_t, int32_t>>& crossings,
                   const UntangleParams& params) {
    EditableMesh edit(mesh);
    PassTriangles triangles(edit);
    std::vector<char> around(edit.tris.size(), 0), changed;
    for (const auto& [s, t] : crossings) around[static_cast<size_t>(s)] = around[static_cast<size_t>(t)] = 1;
    const auto accept = [&](const EditableMesh::Quad& q) {
        const Tri &t1 = edit.tris[q.t1], &t2 = edit.tris[q.t2];
        const auto [n1, n2] = EditableMesh::flipped(q);
        if (edit.normal(n1).isZero(0.0) || edit.normal(n2).isZero(0.0)) return false;
        const double worse_before = std::min(edit.kappa(t1), edit.kappa(t2));
        if (!(std::min(edit.kappa(n1), edit.kappa(n2)) >= std::min(worse_before, params.kappa_floor))) return false;
        if (!(triangles.crossings_of(n1, n2, {q.t1, q.t2}) < triangles.crossings_of(t1, t2, {q.t1, q.t2})))
            return false;
        const double near_before = std::max(triangle_distance_from_input(edit, t1, input),
                                            triangle_distance_from_input(edit, t2, input));
        const double near_after = std::max(triangle_distance_from_input(edit, n1, input),
                                           triangle_distance_from_input(edit, n2, input));
        if (!(near_after <= std::max(near_before, params.tolerance))) return false;
        triangles.mark_flipped(q.t1); // flip_pass flips what it accepts
        triangles.mark_flipped(q.t2);
        return true;
    };
    const long flips = edit.flip_pass_around(around, accept, changed);
    if (flips > 0) edit.write_to(mesh);
    return flips;
}

} // namespace

UntangleStats untangle(Mesh& mesh, const AabbTree& input, std::vector<std::pair<int32_t, int32_t>> crossings,
                       const UntangleParams& params) {
    check_indices(mesh, "untangled mesh");
    if (!(params.tolerance > 0.0) || !std::isfinite(params.tolerance) || params.passes < 0)
        throw InvalidInput("untangle: the tolerance must be positive and finite, the passes not negative");
    UntangleStats stats;
    for (int pass = 0; pass < params.passes && !crossings.empty(); ++pass) {
        const long flips = untangle_pass(mesh, input, crossings, params);
        if (flips == 0) break;
        stats.flipped += flips;
        crossings = self_intersecting_pairs(mesh, AabbTree(mesh));
    }
    stats.crossings = std::move(crossings);
    return stats;
}

} // namespace liftremesh
