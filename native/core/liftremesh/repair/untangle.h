// Triangles of the output that pass through each other, untangled by edge flips, then by vertex
// moves: the repair's last step. Where the input has features smaller than the edge length (two
// parts of a solid closer together than an edge) the restricted Delaunay triangulation can fold
// there, and a fold that passes through its neighbours is what a tetrahedral mesher (TetGen,
// Netgen, Gmsh) refuses. So is a touch (self_intersection.h), where two sheets meeting along a
// line each put a vertex on it and one lies on the other's edge: counted as a crossing here.
// - Flips first, since they move no vertex: an edge of a crossing triangle is flipped when that
//   lowers the number of crossings of its two triangles with the rest of the mesh, the new
//   triangles are no farther from the input than the old ones (or within the tolerance), no
//   sliver is made and neither is folded onto its neighbour across the quad's rim
//   (flip_rules.h: flip_folds_rim): a crossing traded for a fold is no repair.
// - Then moves, for what the flips leave (a vertex pushed through the other side, which no flip
//   of its edges takes back): an inner vertex of a crossing triangle moves to whichever of
//   the points 0, 1/4, ..., 1 of the way to its neighbours' centroid, put on the input (closest
//   point), leaves its fan the fewest crossings (with the rest and among themselves), if fewer
//   than before, and then the best worst kappa; under the same rules as a flip, and no more of
//   its triangles facing against the input's triangle nearest to them than before, nor more
//   folded edges round its fan (no fold).
// - Both, first with no triangle made below the project's floor (kappa 0.3), then, for the
//   crossings left, down to the last resort's (0.2). With the lower floor alone, a flip that
//   undoes one crossing with a sliver can leave the crossings beside it to moves that no longer
//   undo them, where moves at the higher floor undo them all.
// - Last, for the crossings that neither undoes at either floor, tents taken out: an inner vertex
//   of a crossing triangle with three triangles round it, where a wall thinner than the edge
//   had a vertex of its far side joined to three of its near side's, is removed, the triangle
//   of its rim in their place, if that leaves fewer crossings under the rules of a move (and
//   the rim's triangle is not one of the mesh already). The apex lies on the input, on the
//   wrong side: no move onto the input takes it back.
// Nothing changes on a mesh without crossings; no vertex is added, only a tent's is removed, and
// no vertex on a border moves; topology and orientation are kept.
#pragma once

#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/reference.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace liftremesh {

struct UntangleParams {
    //! Distance from the input that a new triangle may reach when the old ones were nearer
    //! (the pipeline's: kInputTolerance, steps.h). Positive and finite.
    double tolerance = 0.0;
    //! Passes of flips around the triangles still crossing, each after a fresh count; then as
    //! many passes of moves; at each of the two floors.
    int passes = 4;
    //! A flip or move may not make a triangle of kappa (Eq. 26) below this, unless the worst
    //! one it changes was lower still: the last resort, for the crossings that edits keeping
    //! preferred_kappa_floor leave.
    double kappa_floor = kKappaFloorUntangle;
    //! The floor of the edits tried first (flips, then moves). A greedy flip down to kappa_floor
    //! can block the moves that would have undone the same crossing with good triangles.
    double preferred_kappa_floor = kKappaFloor;
};

struct UntangleStats {
    long flipped = 0; //!< edge flips
    long moved = 0;   //!< vertex moves
    long removed = 0; //!< vertices removed with the tent of three triangles round them
    std::vector<std::pair<int32_t, int32_t>> crossings; //!< what is left, as self_intersecting_pairs
    //! AabbTree(mesh) of the mesh as left.
    std::optional<AabbTree> tree;
};

//! Finds the pairs of triangles of `mesh` that cross (self_intersecting_pairs), then flips edges,
//! moves vertices and takes out tents of the crossing triangles as above, pass after pass while
//! crossings are left and a pass changes something. The crossings left and the tree of the mesh
//! as left come back in the stats, for the report.
//! \throw InvalidInput if the tolerance is not positive and finite, passes is negative, or an
//! index is out of range.
UntangleStats untangle(Mesh& mesh, const Reference& input, const UntangleParams& params);

} // namespace liftremesh
