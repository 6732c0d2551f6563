// Refining the patches that fill holes (after fill_holes, Section 5.2.2): a constrained
// Delaunay triangulation of a loop has no vertex inside, so a large hole gets long thin
// triangles, and three nearly collinear loop vertices a sliver. Vertices are added inside the
// patches, as an isotropic remesher would (split long edges, flip, smooth), until their
// triangles have about the size of the rest of the mesh.
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

//! Refines the triangles of `mesh` from index `first` on (the patches fill_holes appended),
//! towards edge length `h`, in up to `rounds` rounds of:
//! - splitting at its midpoint every edge longer than 4/3 h that two patch triangles share;
//! - flipping every edge two patch triangles share where the flip raises the smaller kappa
//!   (Eq. 26) of the two, turns neither by more than 30 degrees and makes no edge the mesh has;
//! - moving each added vertex to the average of its neighbours (a move that would turn one of
//!   its triangles by more than 30 degrees is not made).
//! Vertices that existed before (the loops, the rest of the mesh) never move and triangles
//! before `first` are untouched; added vertices are appended. The mesh stays an oriented
//! manifold with the same Euler characteristic. At most `max_added` vertices are added (splits
//! stop there): huge patches mean the triangulation failed (too few vertices for thin parts),
//! and the vertex count should stay near what was asked. Returns the number of vertices added.
//! Throws InvalidInput if `first` is out of range, h is not positive or an index is.
long refine_patches(Mesh& mesh, Eigen::Index first, double h, long max_added, int rounds = 6);

} // namespace liftremesh
