// Closed pieces of the output that stand for no part of the input. Where a member is thinner
// than the cells, the restricted Delaunay triangulation of its sites may close a few triangles
// into a small bubble beside the surface, often facing inward (Section 2.2: "Problems may happen
// ... in regions where S is thin"); the manifold repair sees a valid closed manifold and keeps
// it. Such a bubble bounds no solid: TetGen and FEM refuse the surface, and a volume or mass
// property taken from it is wrong. The input says how many pieces there should be: each of its
// components (components.h) is one piece of the output, and its inward ones are the cavities of
// a hollowed solid. The output's pieces beyond
// those counts, smallest first, are strays when small; larger ones stay, and the report warns.
#pragma once

#include "liftremesh/mesh/components.h"
#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

//! Largest area of a stray piece, as a share of the input's smallest component (1%): a bubble
//! the triangulation closes spans a few cells, far less than any part of the input that was given
//! sites; a piece that broke off a thin member may be larger, and stays (the report warns).
constexpr double kStrayShare = 0.01;

struct StrayComponentParams {
    long pieces = 0;       //!< pieces the output may have: the input's components
    long inward = 0;       //!< closed pieces facing inward the output may have: the input's
    double max_area = 0.0; //!< a piece larger than this stays (input units); 0 removes nothing
};

//! The counts of `input` (the cleaned input's components) as the limits of
//! remove_stray_components, and kStrayShare of its smallest component's area.
StrayComponentParams stray_component_params(const MeshComponents& input);

struct StrayComponentStats {
    long removed = 0;        //!< pieces removed
    long inward_removed = 0; //!< of those, closed and facing inward
    long triangles_removed = 0;
};

//! Removes the stray pieces of `mesh` (components, as mesh_components() finds them), in two
//! passes, each removing only pieces of area at most params.max_area:
//!  1. the closed inward pieces beyond params.inward, keeping first those that are cavities of
//!     another piece, then the larger volume;
//!  2. the pieces beyond params.pieces, keeping the larger area.
//! The vertices the triangles left use stay, renumbered in order of first use (submesh). Leaves
//! the mesh as it was when nothing is stray. Throws InvalidInput if an index is out of range.
StrayComponentStats remove_stray_components(Mesh& mesh, const StrayComponentParams& params);

} // namespace liftremesh
