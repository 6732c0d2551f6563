// Triangles of the output that pass through each other, untangled by edge flips: the repair's
// last step. Where the input has features smaller than the edge length (the peers' FreeCAD
// connector TSM_103: 0.108 mm between housings 0.381 mm apart, at edges of 0.1 to 0.26 mm) the
// restricted Delaunay triangulation can fold there, and a fold that passes through its
// neighbours is what a tetrahedral mesher (TetGen, Netgen, Gmsh) refuses. An edge of a crossing
// triangle is flipped when that lowers the number of crossings of its two triangles with the
// rest of the mesh, the new triangles are no farther from the input than the old ones (or
// within the tolerance) and no sliver is made. Nothing changes on a mesh without crossings; no
// vertex is added, moved or removed; topology and orientation are kept.
#pragma once

#include "liftremesh/aabb_tree.h"
#include "liftremesh/mesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace liftremesh {

struct UntangleParams {
    //! Distance from the input that a new triangle may reach when the old ones were nearer
    //! (the pipeline: the Hausdorff refinement's tolerance, 0.15 h). Positive and finite.
    double tolerance = 0.0;
    //! Passes of flips around the triangles still crossing, each after a fresh count.
    int passes = 4;
    //! A flip may not make a triangle of kappa (Eq. 26) below this, unless the old pair's worse
    //! one was lower still.
    double kappa_floor = 0.2;
};

struct UntangleStats {
    long flipped = 0; //!< edge flips
    std::vector<std::pair<int32_t, int32_t>> crossings; //!< what is left, as self_intersecting_pairs
};

//! Flips edges of the triangles in `crossings` (self_intersecting_pairs(mesh, ...)) as above,
//! pass after pass while crossings are left and a pass flips something. Throws InvalidInput if
//! the tolerance is not positive and finite, passes is negative, or an index is out of range.
UntangleStats untangle(Mesh& mesh, const AabbTree& input, std::vector<std::pair<int32_t, int32_t>> crossings,
                       const UntangleParams& params);

} // namespace liftremesh
