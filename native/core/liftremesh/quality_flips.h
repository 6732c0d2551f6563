// Edge flips for triangle quality, the last step of the repair. The restricted Delaunay
// triangulation of the optimised sites is Delaunay in the lifted space, not in the plane of the
// output, and the repair steps before this one edit it locally: on the shared CAD meshes a few
// flat quads come out split along their longer diagonal (gmsh_lever.stl, seed 3: a triangle of
// kappa 0.32 whose flip gives 0.67 and 0.73). Each such edge is flipped when
// - the quad is nearly planar and the worse kappa (Eq. 26) of its two triangles goes up
//   (EditableMesh::flip_improves_quality: a sharp edge, whose triangles turn by more than
//   30 degrees, is never flipped), and
// - the new diagonal's midpoint is no farther from the input than the old one's, or within half
//   the tolerance: the surface does not move away from the input.
// Flips only, so the vertices, the topology and the orientation are kept.
#pragma once

#include "liftremesh/aabb_tree.h"
#include "liftremesh/editable_mesh.h"

namespace liftremesh {

//! Whether flipping the quad's edge is a quality flip that keeps the surface on the input
//! (the two conditions above); `input` is the input's tree, `tolerance` > 0.
bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                                double tolerance);

//! Flips the edges of `mesh` that pass quality_flip_keeps_surface, in passes over all edges (in
//! edge order, one flip per triangle a pass) until one flips nothing or `passes` are done.
//! Returns the number of flips. Throws InvalidInput if tolerance is not positive and finite or
//! passes is negative.
long flip_for_quality(Mesh& mesh, const AabbTree& input, double tolerance, int passes = 8);

} // namespace liftremesh
