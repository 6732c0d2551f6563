// Vertex normals on geometric neighbourhoods (Section 5.2.1) and the normal lifting of the
// surface to R^6 (Eq. 12).
#pragma once

#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <vector>

namespace liftremesh {

//! #V by 3 unit vertex normals. Each vertex averages the normals of the triangles within
//! distance eta of it, weighted by the area of triangle and ball (radius eta) intersection
//! (Section 5.2.1), so triangles that touch the vertex only geometrically (across a gap or a
//! T-junction) count as much as connected ones. Triangles facing away from the vertex's own
//! one-ring normal by more than 120 degrees (the far side of a thin wall) are left out, unless
//! they fill three times as much of the ball as the others and the vertex's own side reaches,
//! across edges within the ball, an edge where the surface turns back by more than 120 degrees:
//! the vertex is then on a flap folded back onto the surface (a pleat), and the triangles
//! facing away from the flap are averaged.
//! A vertex with no triangle to average keeps its one-ring (area-weighted) normal.
Points vertex_normals(const Mesh& mesh, double eta);

//! The same with `tree`, built over mesh's triangles, as the caller keeps one: the normals of a
//! similar copy of the mesh (scaled by s, moved) are those of the mesh at radius eta / s, to
//! rounding, so a tree over the input serves its unit-ball copy.
Points vertex_normals(const Mesh& mesh, const AabbTree& tree, double eta);

//! Of `creases` (crease_edges() of `mesh`; `tree` over mesh's triangles), those that still turn
//! by more than `min_turn_deg` with each side's normal averaged over the ball of radius `eta`
//! about the edge's midpoint as in Section 5.2.1: the normals of the triangles the ball meets,
//! weighted by the area inside it, on the side of the plane bisecting the crease where its own
//! triangle lies. A CAD part's crease turns as much over the ball as across its edge; a scan's
//! noise turns fast from one facet to the next and little over a ball, and a facet's slip in a
//! smooth surface by about its own angle spread over the ball.
std::vector<CreaseEdge> creases_over_balls(const Mesh& mesh, const AabbTree& tree, const std::vector<CreaseEdge>& creases,
                                           double eta, double min_turn_deg);

//! #V by d lifted points x (+) nu n (Eq. 12): d = 6, or d = 3 (the plain surface) when nu == 0.
LiftedPoints lift(const Points& points, const Points& normals, double nu);

//! The same with a scale per vertex, x (+) nu_v n (#V values, thin_walls.h): always d = 6.
LiftedPoints lift(const Points& points, const Points& normals, const Eigen::VectorXd& nu);

} // namespace liftremesh
