// Refining the patches that fill holes (after fill_holes, Section 5.2.2): a constrained
// Delaunay triangulation of a loop has no vertex inside, so a large hole gets long thin
// triangles, and three nearly collinear loop vertices a sliver. Vertices are added inside the
// patches, as an isotropic remesher would (split long edges, flip, smooth), until their
// triangles have about the size of the rest of the mesh.
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

struct PatchRefinementStats {
    long inserted = 0; //!< vertices added inside the patches
};

struct PatchRefinementParams {
    //! The first triangle of the patches (the triangle count before fill_holes appended them),
    //! in [0, #F].
    Eigen::Index first = 0;
    double spacing = 0.0; //!< the edge length h aimed at, > 0 and finite
    long max_added = 0;   //!< the most vertices added, >= 0
    int rounds = 6;       //!< the most rounds of split, flip and smooth
};

//! Refines the triangles of `mesh` from index `params.first` on (the patches fill_holes
//! appended), towards edge length h = `params.spacing`, in up to `params.rounds` rounds of:
//! - splitting at its midpoint every edge longer than 4/3 h that two patch triangles share,
//!   where they turn by at most 30 degrees (a midpoint across a fold lies off the surface);
//! - flipping every edge two patch triangles share where the flip raises the smaller kappa
//!   (Eq. 26) of the two, turns neither by more than 30 degrees and makes no edge the mesh has;
//! - moving each added vertex to the average of its neighbours (a move that would turn one of
//!   its triangles by more than 30 degrees is not made).
//! Vertices that existed before (the loops, the rest of the mesh) never move and triangles
//! before `params.first` are untouched; added vertices are appended. The mesh stays an oriented
//! manifold with the same Euler characteristic. At most `params.max_added` vertices are added
//! (splits stop there): huge patches mean the triangulation failed (too few vertices for thin
//! parts), and the vertex count should stay near what was asked. Returns the number of
//! vertices added (PatchRefinementStats::inserted).
//! \throw InvalidInput if `params.first` is out of range, the spacing is not positive and
//! finite, or a triangle's index is out of range.
PatchRefinementStats refine_patches(Mesh& mesh, const PatchRefinementParams& params);

} // namespace liftremesh
