// Thin walls kept apart on the lifted surface: the lifting scale of Eq. 12 raised, vertex by
// vertex, where the surface's far side is nearer than the sites' spacing.
//
// Two points on opposite sides of a wall of thickness t, with opposite normals, lie
// sqrt(t^2 + 4 nu^2) apart on the lifted surface. Where that is well under the sites' spacing h,
// a site's restricted Voronoi cell reaches across the wall and the restricted Delaunay
// triangulation joins the two sides: the paper's warning about thin regions (Section 2.2), on a
// thin-walled CAD part (gmsh_t13_data.stl, walls 2 units thick) the result's Euler characteristic went
// -2 -> -18, -52, -24 at 2000, 3000, 4000 vertices. Lifting each vertex by
//     nu_v = max(nu, 1/2 sqrt(h^2 - t_v^2))
// puts the two sides at least h apart, and changes nothing within a side (its normals do not
// turn across a flat wall), nor anywhere the far side is h away or more.
#pragma once

#include "liftremesh/aabb_tree.h"
#include "liftremesh/mesh.h"

namespace liftremesh {

//! Two faces are the sides of a wall when their normals are antiparallel within this many
//! degrees: a wall may taper by as much, a wedge of a larger interior angle is a knife edge.
constexpr double kWallTaperDeg = 25.0;

//! Per vertex of `mesh` (the mesh `tree` was built over), the distance to the far side of a
//! wall or of a narrow gap: the nearest triangle, not one of the vertex's own, whose normal is
//! antiparallel, within kWallTaperDeg, to that of one of the vertex's own triangles, and across
//! from the vertex (the way to its nearest point within kWallTaperDeg of its normal; a triangle
//! turned over in a face lies beside the vertex, not across); infinity if there is none nearer
//! than `reach`. Two faces meeting at a knife edge of a larger interior angle are
//! close only because they meet there: lifting them apart would keep the sites farther off the
//! edge (crease_snap.h), so they are no wall (on the shared hinge, a lip of 49 degrees). A
//! wall's rim, where the vertex has triangles of a side and of the rim's face, is still on
//! the wall. Parallel (OpenMP), the same for any thread count.
Eigen::VectorXd wall_thickness(const Mesh& mesh, const AabbTree& tree, double reach);

//! The thickness sqrt(spacing^2 - 4 nu^2) (0 if spacing <= 2 nu) from which nu alone keeps a
//! wall's sides a spacing apart: the reach wall_thickness() needs, no wall being thinner when it
//! is 0 (the bunny at 50k vertices: spacing 0.008, 2 nu 0.02).
double wall_reach(double nu, double spacing);

//! The lifting scale per vertex, max(nu, 1/2 sqrt(spacing^2 - t^2)) for thickness t (see
//! above), exactly nu from wall_reach(nu, spacing) on. All in unit-ball units; nu >= 0,
//! spacing > 0.
Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, double spacing);

} // namespace liftremesh
