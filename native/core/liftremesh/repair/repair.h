// Turning a restricted Delaunay triangulation into a clean surface: no degenerate or duplicate
// triangle, no non-manifold edge or vertex, consistent orientation, no unused vertex.
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

struct RepairStats {
    long degenerate_removed = 0;  //!< triangles with a repeated vertex or zero area
    long duplicates_removed = 0;  //!< same vertex set as an earlier triangle
    long nonmanifold_removed = 0; //!< removed to make edges and vertices manifold
    long flipped = 0;             //!< triangles reoriented to agree with their neighbours
};

//! Makes `mesh` an oriented 2-manifold (possibly with boundary) by removing as few triangles as
//! it can, in this order:
//!  1. triangles with a repeated index or zero area (|cross| <= 1e-12 longest edge^2);
//!  2. duplicates (same vertex set as an earlier triangle, either orientation; the first stays);
//!  3. on every edge with 3+ triangles, keeps the pair ranked best by: runs the edge in opposite
//!     directions; then is attached to the rest of the surface across its other edges (so a
//!     fin loses to the surface it stands on); then the larger smaller kappa (Eq. 26);
//!  4. where a vertex joins several edge-connected fans, keeps the fan with the most triangles
//!     (then the most area), revisiting the vertices of removed triangles until stable;
//!  5. orients every connected component (through edges with two triangles) by breadth-first
//!     search, keeping the orientation of the larger area; a non-orientable component (Moebius
//!     band) is cut by removing the worse triangle of each edge still inconsistent, and steps
//!     4-5 repeat (each repetition removes triangles, so this ends);
//!  6. remove_unreferenced_vertices(), which renumbers the vertices in order of first use.
//! Holes left behind are for fill_holes(). Never throws on a bad triangle soup; throws
//! InvalidInput if an index is out of range. An input with no usable triangle gives an empty
//! mesh (0 points, 0 triangles): the caller decides whether that is a TopologyFailure.
//! It has no Params nor `const Reference& input`, unlike the other steps: it needs neither the
//! input nor a setting.
RepairStats make_manifold(Mesh& mesh);

} // namespace liftremesh
