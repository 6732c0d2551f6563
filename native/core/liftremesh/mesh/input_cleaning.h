// The input's facets as a careless STL export leaves them, made into the surface they describe:
// welded, without degenerate or repeated facets, consistently oriented (the prepare stage).
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

//! What clean_input repaired (the report's input_* counts).
struct InputCleaning {
    long degenerate_removed = 0; //!< a repeated vertex after welding, or zero area (zero_area) where
                                 //!< no side is left open by the removal
    long duplicates_removed = 0; //!< repeats of a facet in either winding (a two-sided sheet's sides kept)
    long facets_turned = 0;      //!< turned to agree with their neighbours (orient_components)
};

//! Cleans a triangle soup the way FreeCAD's Mesh workbench repairs an STL ("remove duplicated
//! faces", "remove degenerated faces", "harmonize normals"), in this order:
//!  1. welds exactly equal vertices (weld_exact, mesh_io.h);
//!  2. drops facets with a repeated vertex;
//!  3. drops repeats of a facet (the same three vertices), in either winding: a facet listed
//!     again, or again the other way round, is one facet written twice. The first listed is
//!     kept; step 5 gives it the winding of its neighbours. The exception is a two-sided sheet:
//!     an open surface meshed on both sides, no volume between. Where the facets listed in both
//!     windings form patches (joined through shared sides) that no other facet touches and that
//!     have a free border (a side used by one facet of each winding only), both sides are kept;
//!     a reversed facet inside a surface, or a closed surface listed twice, is a duplicate;
//!  4. drops facets of zero area (zero_area, geometry.h) unless the removal would leave one of
//!     their sides with a single facet: a sliver closing a T-junction stays, a facet along the
//!     surface's sides, which only makes them non-manifold, goes;
//!  5. orients each component consistently (orient_components, orientation.h: the majority of
//!     area keeps its winding).
//! Vertices no longer used stay (remove_unreferenced_vertices drops them). Throws InvalidInput
//! if a triangle index is out of range.
InputCleaning clean_input(Mesh& mesh);

} // namespace liftremesh
