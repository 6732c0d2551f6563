// Filling holes of a surface mesh (Section 5.2.2): each boundary loop is projected onto its
// best-fit plane (principal component analysis) and triangulated by a constrained Delaunay
// triangulation of the loop.
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <functional>
#include <vector>

namespace liftremesh {

//! Boundary loops of an oriented manifold mesh. A boundary edge is an edge used by exactly one
//! triangle. Orientation convention: for every i, the edge loop[i] -> loop[(i + 1) % n] runs
//! OPPOSITE to the way its one triangle traverses it (that triangle runs loop[i+1] -> loop[i]).
//! Hence a new triangle (loop[i], loop[i+1], x) agrees with the surface's orientation, and the
//! loop is the boundary of the missing patch oriented like that patch: seen from the side the
//! surface normals point to (from outside a closed outward-oriented surface), it runs
//! counter-clockwise around the hole. Example: removing triangle (a, b, c) from a closed mesh
//! gives the loop (a, b, c), up to a rotation. Each loop is simple (no repeated vertex); where
//! the boundary passes a vertex twice (a "pinched" boundary) it is split there into simple
//! loops, each containing that vertex. Loops start at an arbitrary vertex. Boundary edges that
//! do not close up (only possible if the mesh is not consistently oriented) are left out.
//! O(#F log #F).
std::vector<std::vector<int32_t>> boundary_loops(const Mesh& mesh);

struct HoleFillingStats {
    long filled = 0; //!< holes (boundary loops) filled
};

//! Which holes to fill. The test is a predicate, not `const Reference& input` as the steps
//! after the repair take: the pipeline decides which holes are artefacts by the distance of a
//! loop's vertices to the input's boundary edges (in the unit ball), and Reference's tree is
//! over the input's triangles in the input's coordinates, so that expressing the test through
//! it would need another tree (over the unit-ball input's boundary) the pipeline does not
//! have at that point. The predicate keeps the choice with the caller.
struct HoleFillingParams {
    //! Fill the loop (boundary_loops()' convention, 3 or more vertices) when true; when empty,
    //! every loop is filled.
    std::function<bool(const std::vector<int32_t>&)> should_fill;
};

//! Removes the darts of the holes to be filled: a triangle two of whose edges are boundary
//! edges of one loop that `should_fill` accepts (every loop when it is empty), meeting at a
//! vertex no other triangle uses. That vertex's site kept one triangle of its fan through the
//! manifold repair, jutting into the hole: the loop then crosses itself round it and any fill
//! folds (RLF_7030's slots). The loop runs across the dart's third edge instead. Repeated
//! while some are found; the darts' vertices are left unused (remove_unreferenced_vertices).
//! Returns the triangles removed.
long remove_darts(Mesh& mesh, const HoleFillingParams& params);

//! Fills every boundary loop (as given by boundary_loops(), with its convention) for which
//! `params.should_fill(loop)` is true (all loops when it is empty; loops of fewer than 3
//! vertices are never offered). Section 5.2.2: a loop of 3 vertices gets its one triangle; a
//! longer one is projected onto its best-fit plane (PCA; normal = least-variance axis, oriented
//! like the triangles around the hole) and, if the projected polygon is simple, triangulated by
//! its constrained Delaunay triangulation (ear clipping, best kappa first, then Lawson flips of
//! the diagonals until locally Delaunay). Otherwise, if the edge rule below blocks every planar
//! ear, or if a triangle of that fill folds back onto the triangle across a loop edge (turned by
//! over 165 degrees: a hole across a knife edge projects simple yet folded over), it is
//! triangulated in 3D, taking the best-kappa triangles that face like the loop, and those that
//! fold back only as a last resort, as flat ones.
//! Rules: no vertex is added or moved; every new triangle follows the loop order, so it is
//! oriented like the surface; no new triangle creates an edge the mesh (or an earlier fill)
//! already has, and a loop that cannot be triangulated under that rule is left open; a 3-loop
//! that is already a triangle of the mesh (a lone triangle's boundary) is left open. A zero-area
//! triangle is made only by the 3D fallback when no other ear is valid (a collinear loop), so
//! that even such a loop closes. New triangles are appended after the existing ones, whose order is unchanged.
//! Returns the number of holes filled (HoleFillingStats::filled). The mesh should be an
//! oriented manifold (make_manifold) on entry and then stays one. O(n^2) per loop of n
//! vertices.
//! \throw InvalidInput if an index is out of range.
HoleFillingStats fill_holes(Mesh& mesh, const HoleFillingParams& params);

} // namespace liftremesh
