// Turning a restricted Delaunay triangulation into a clean surface: no degenerate or duplicate
// triangle, no non-manifold edge or vertex, consistent orientation, no unused vertex.
#pragma once

#include "liftremesh/mesh.h"

namespace liftremesh {

struct RepairStats {
    long degenerate_removed = 0;  //!< triangles with a repeated vertex or zero area
    long duplicates_removed = 0;  //!< same vertex set as an earlier triangle
    long nonmanifold_removed = 0; //!< removed to make edges and vertices manifold
    long flipped = 0;             //!< triangles reoriented to agree with their neighbours
};

//! Makes `mesh` an oriented 2-manifold (possibly with boundary) by removing as few triangles as
//! it can: where an edge has 3+ triangles, keeps the two best-shaped consistent ones; where a
//! vertex joins several fans, keeps the largest fan. Then orients each connected component
//! consistently (keeping the orientation of the majority of its triangles) and removes unused
//! vertices. Holes left behind are for fill_holes().
RepairStats make_manifold(Mesh& mesh);

} // namespace liftremesh
