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

//! How many triangles of `mesh`, other than those numbered `skip`, `a` and `b` cross (the same
//! triangle counted once for each of the two it crosses). A scan of every triangle behind a box
//! test: untangling runs only where crossings are, a few dozen quads on a mesh.
long crossings_of(const EditableMesh& mesh, const Tri& a, const Tri& b, const std::array<int, 2>& skip) {
    const std::array<Eigen::Vector3d, 3> pa = corners(mesh, a), pb = corners(mesh, b);
    Eigen::Vector3d lo = pa[0], hi = pa[0];
    for (const auto* p : {&pa, &pb})
        for (const Eigen::Vector3d& x : *p) {
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
        }
    long count = 0;
    for (size_t g = 0; g < mesh.tris.size(); ++g) {
        if (static_cast<int>(g) == skip[0] || static_cast<int>(g) == skip[1]) continue;
        const Tri& t = mesh.tris[g];
        const std::array<Eigen::Vector3d, 3> pt = corners(mesh, t);
        const Eigen::Vector3d tlo = pt[0].cwiseMin(pt[1]).cwiseMin(pt[2]), thi = pt[0].cwiseMax(pt[1]).cwiseMax(pt[2]);
        if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) continue;
        count += triangles_cross(a, pa, t, pt) ? 1 : 0;
        count += triangles_cross(b, pb, t, pt) ? 1 : 0;
    }
    return count;
}

} // namespace

UntangleStats untangle(Mesh& mesh, const AabbTree& input, std::vector<std::pair<int32_t, int32_t>> crossings,
                       const UntangleParams& params) {
    check_indices(mesh, "untangled mesh");
    if (!(params.tolerance > 0.0) || !std::isfinite(params.tolerance) || params.passes < 0)
        throw InvalidInput("untangle: the tolerance must be positive and finite, the passes not negative");
    UntangleStats stats;
    for (int pass = 0; pass < params.passes && !crossings.empty(); ++pass) {
        EditableMesh edit(mesh);
        std::vector<char> around(edit.tris.size(), 0), changed;
        for (const auto& [s, t] : crossings) around[static_cast<size_t>(s)] = around[static_cast<size_t>(t)] = 1;
        const auto accept = [&](const EditableMesh::Quad& q) {
            const Tri &t1 = edit.tris[q.t1], &t2 = edit.tris[q.t2];
            const auto [n1, n2] = EditableMesh::flipped(q);
            if (edit.normal(n1).isZero(0.0) || edit.normal(n2).isZero(0.0)) return false;
            const double worse_before = std::min(edit.kappa(t1), edit.kappa(t2));
            if (!(std::min(edit.kappa(n1), edit.kappa(n2)) >= std::min(worse_before, params.kappa_floor))) return false;
            if (!(crossings_of(edit, n1, n2, {q.t1, q.t2}) < crossings_of(edit, t1, t2, {q.t1, q.t2}))) return false;
            const double near_before = std::max(triangle_distance_from_input(edit, t1, input),
                                                triangle_distance_from_input(edit, t2, input));
            const double near_after = std::max(triangle_distance_from_input(edit, n1, input),
                                               triangle_distance_from_input(edit, n2, input));
            return near_after <= std::max(near_before, params.tolerance);
        };
        const long flips = edit.flip_pass_around(around, accept, changed);
        if (flips == 0) break;
        stats.flipped += flips;
        edit.write_to(mesh);
        crossings = self_intersecting_pairs(mesh, AabbTree(mesh));
    }
    stats.crossings = std::move(crossings);
    return stats;
}

} // namespace liftremesh
