// The input as the steps after the triangulation see it: the input mesh and the tree over its
// triangles, built once and shared by every step that compares the surface with the input.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/aabb_tree.h"

namespace liftremesh {

//! The input mesh (#V x 3 points, #F x 3 triangles) and AabbTree(mesh), in the coordinates of
//! the surface a step edits. It holds references: both must outlive it.
//! \pre `tree` was built over `mesh`, and neither has changed since.
struct Reference {
    const Mesh& mesh;
    const AabbTree& tree;
};

} // namespace liftremesh
