// A local size field: the edge length the output should have at each point of the input,
// smaller where the part is thin or bends tightly, graded, bounded; turned into the CVT's
// density (a restricted Voronoi cell's diameter goes as density^(-1/4) on a surface), which
// multiplies the curvature density rho_p^delta of Eq. 25.
//
// Why a size field besides rho^delta: a uniform spacing h merges or breaks what is thinner than
// h (Section 2.2: "problems may happen ... in regions where S is thin"), and rho^delta, which sees
// the normals turn, refines a tight bend only by rho^(-delta/4), a factor 0.76 at most with the
// defaults. The field asks for
//   - h <= t where the part is t thick (the distance across to the far side of a wall or slot,
//     thin_walls.h): two vertices across the wall's rim, and the cells of its two sides apart;
//   - h <= theta_max R where the surface bends with radius R (where both the input's facets,
//     triangle_bend, and the eta-ball normals' turn of Eqs. 22-23 see it: the facets are not
//     fooled by a crease, the eta normals not by a scan's noise): no edge turns the normal by
//     more than theta_max; a small part has both;
//   - h(x) <= h(y) + (g - 1) |x - y| for gradation g: neighbouring edges differ by a factor
//     g at most (as Gmsh's and MMG's gradation);
//   - smallest <= h <= largest.
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

//! The largest turn of the normal along one edge, in radians, that the curvature term allows
//! (h <= kSizeTurn R): eight edges round a full circle, the coarsest that keeps a hole round.
constexpr double kSizeTurn = M_PI / 4.0;

struct SizeFieldParams {
    double largest = 0.0;   //!< the size where nothing asks for less (> 0, mesh units)
    double smallest = 0.0;  //!< no size below this (> 0, <= largest)
    double gradation = 1.3; //!< neighbouring edges differ by at most this factor (>= 1)
};

//! Per triangle, the curvature 1 / R its edges show: over its edges shared with one other
//! triangle whose normal turns by less than `max_turn_deg` (more is a crease, which the feature
//! term keeps, not a bend to refine), the largest turn over the mean of the two triangles' widths
//! across the edge (their altitudes on it); 0 where there is none. A CAD tessellation's facets
//! of a cylinder of radius R, each a chord c wide turning by phi = c / R from the next: 1 / R,
//! however long the facets are.
Eigen::VectorXd triangle_bend(const Mesh& mesh, double max_turn_deg);

//! The field per vertex of a mesh and why it is below `largest` there.
struct SizeField {
    Eigen::VectorXd size;        //!< #V sizes, in [smallest, largest]
    double wall_area = 0.0;      //!< the area whose size a wall thinner than `largest` set, before grading
    double curvature_area = 0.0; //!< the area whose size a bend tighter than largest / kSizeTurn set
    double graded_area = 0.0;    //!< the area below `largest` in the end (grading included)
};

//! The size field at the vertices of `mesh`: from `thickness` (#V, thin_walls.h; infinity where
//! no wall is near) and `turn` (#F, triangle_bend's curvature, in the mesh's inverse units), each vertex taking its triangles' fastest turn, then graded
//! over the straight distance between vertices (a wall's two sides, or two patches a gap
//! parts, are graded together), then bounded. Areas are a third of each triangle's per vertex.
//! Throws InvalidInput unless 0 < smallest <= largest are finite and gradation >= 1.
SizeField size_field(const Mesh& mesh, const Eigen::VectorXd& thickness, const Eigen::VectorXd& turn,
                     const SizeFieldParams& params);

//! h(x) = min over y of (h(y) + (g - 1) |x - y|), over the points' straight distances: the
//! largest field below `size` whose slope is at most g - 1 (g = gradation > 1; g = 1 leaves
//! `size`). Sizes at `largest` and above are no source: only cones under it are walked.
Eigen::VectorXd graded(const Points& points, const Eigen::VectorXd& size, double gradation, double largest);

//! Per triangle, the mean over it of (reference / h)^2 for h interpolated linearly from its
//! vertices' sizes: the share of the sites it needs against a triangle of size `reference`.
Eigen::VectorXd site_density(const Mesh& mesh, const Eigen::VectorXd& size, double reference);

//! The CVT weights of Eq. 25 with the field: rho_p^delta times site_density^2, since a cell of
//! a surface CVT has an area going as density^(-1/2).
Eigen::VectorXd sized_weights(const Eigen::VectorXd& density_weights, const Eigen::VectorXd& site_density);

//! The vertex count an isotropic mesh following the field has: the sum over triangles of
//! |T| site_density / (sqrt(3)/2 reference^2).
double sized_vertex_count(const Mesh& mesh, const Eigen::VectorXd& site_density, double reference);

} // namespace liftremesh
