// Filling holes of a surface mesh (Section 5.2.2): each boundary loop is projected onto its
// best-fit plane (principal component analysis) and triangulated by a constrained Delaunay
// triangulation of the loop.
#pragma once

#include "liftremesh/mesh.h"

#include <functional>
#include <vector>

namespace liftremesh {

//! Boundary loops of an oriented manifold mesh, each a cycle of vertex indices in the order
//! that the new triangles must follow to agree with the surface's orientation.
std::vector<std::vector<int32_t>> boundary_loops(const Mesh& mesh);

//! Fills every boundary loop for which `should_fill(loop)` is true (all loops when it is empty).
//! New triangles are oriented like the surface around the hole, create no edge the mesh already
//! has, and add no vertex. Returns the number of holes filled. The mesh must be an oriented
//! manifold (make_manifold) on entry and stays one.
long fill_holes(Mesh& mesh, const std::function<bool(const std::vector<int32_t>&)>& should_fill = {});

} // namespace liftremesh
