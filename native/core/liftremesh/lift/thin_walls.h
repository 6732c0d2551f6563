// Thin walls kept apart on the lifted surface: the lifting scale of Eq. 12 raised, vertex by
// vertex, where the surface's far side is nearer than the sites' spacing.
//
// Two points on opposite sides of a wall of thickness t, with opposite normals, lie
// sqrt(t^2 + 4 nu^2) apart on the lifted surface. Where that is well under the sites' spacing h,
// a site's restricted Voronoi cell reaches across the wall and the restricted Delaunay
// triangulation joins the two sides with handles through the wall (a wrong Euler
// characteristic): the paper's warning about thin regions (Section 2.2). Lifting each vertex by
//     nu_v = max(nu, 1/2 sqrt(h^2 - t_v^2))
// puts the two sides at least h apart, and changes nothing within a side (its normals do not
// turn across a flat wall), nor anywhere the far side is h away or more.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <array>
#include <vector>

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
//! edge (crease_snap.h), so they are no wall. A wall's rim, where the vertex has triangles of a
//! side and of the rim's face, is still on the wall. Parallel (OpenMP), the same for any thread
//! count.
Eigen::VectorXd wall_thickness(const Mesh& mesh, const AabbTree& tree, double reach);

//! Where a wall's far side is nearer than `reach` only across the inside of a large triangle,
//! none of whose vertices lies across from it (a CAD tessellation's few large triangles on
//! the two sides of a slot narrower than the spacing, their corners offset from each other), a
//! lifting per vertex misses the wall. The triangles are then split, edge midpoint by edge
//! midpoint, where the lifting an edge's midpoint or a triangle's centroid needs exceeds the one
//! interpolated from its vertices by more than `tolerance`, until no edge so split would be
//! shorter than `min_edge`. The split mesh describes the same surface;
//! its triangles lie in those of the input (`parent`), so that the normals and densities
//! interpolated over it are the input's own.
struct WallSamplingParams {
    double reach = 0.0;     //!< the search radius of wall_thickness (wall_reach(nu, spacing))
    double nu = 0.0;        //!< Eq. 12's lifting scale, as thin_wall_lifting
    double spacing = 0.0;   //!< the sites' spacing, as thin_wall_lifting
    double tolerance = 0.0; //!< the lifting an interpolation may miss by (0.1 spacing)
    double min_edge = 0.0;  //!< edges no longer than this are not split (spacing / 4)
    long max_midpoints = 0; //!< no more vertices than this are added (twice the sites asked
                            //!< for): a bound on the memory, whatever the input
    //! > 0: the largest edge of the size field (size_field.h). The thickness is then measured up
    //! to this far too, and triangles are also split where a wall across from an edge's
    //! midpoint or a triangle's centroid is thinner than the size interpolated from its
    //! vertices, min(thickness, largest_size), by more than kWallSizeSplit: so that the
    //! density a slot asks for is not spread over the large triangles beside it.
    double largest_size = 0.0;
};

//! How much thinner than the interpolated size a wall must be to split (WallSamplingParams).
constexpr double kWallSizeSplit = 1.25;

//! The mesh's triangles split as WallSamplingParams says, all in the mesh's units.
struct WallSampling {
    Triangles triangles;                          //!< the split mesh: the input's vertices, then the midpoints
    std::vector<std::array<int32_t, 2>> midpoints; //!< vertex #V + k is the midpoint of vertices midpoints[k]
    std::vector<int32_t> parent;                   //!< per triangle, the input triangle it lies in
                                                   //!< (triangles and parent empty when nothing is split)
    Eigen::VectorXd thickness;                     //!< per vertex of the split mesh, as wall_thickness
};

//! The thickness of wall_thickness(mesh, tree, reach), sampled finely enough for the lifting
//! of thin_wall_lifting (see WallSamplingParams). Where no triangle needs splitting, nothing is
//! copied (midpoints, triangles, parent empty) and `thickness` is exactly wall_thickness's.
//! Parallel (OpenMP). Throws InvalidInput unless spacing and min_edge are positive and finite
//! and reach, nu, tolerance and max_midpoints not negative.
WallSampling sample_wall_thickness(const Mesh& mesh, const AabbTree& tree, const WallSamplingParams& params);

//! Rows of `values` (#V by any) followed by one row per midpoint, the mean of its two ends':
//! a per-vertex field linearly interpolated onto the vertices sample_wall_thickness added.
template <typename Matrix>
Matrix with_midpoints(const Matrix& values, const std::vector<std::array<int32_t, 2>>& midpoints) {
    const Eigen::Index n = values.rows();
    Matrix out(n + static_cast<Eigen::Index>(midpoints.size()), values.cols());
    out.topRows(n) = values;
    for (size_t k = 0; k < midpoints.size(); ++k)
        out.row(n + static_cast<Eigen::Index>(k)) = 0.5 * (out.row(midpoints[k][0]) + out.row(midpoints[k][1]));
    return out;
}

//! The thickness sqrt(spacing^2 - 4 nu^2) (0 if spacing <= 2 nu) from which nu alone keeps a
//! wall's sides a spacing apart: the reach wall_thickness() needs, no wall being thinner when it
//! is 0 (a spacing below 2 nu).
double wall_reach(double nu, double spacing);

//! The lifting scale for one thickness t, as thin_wall_lifting.
double wall_lifting(double t, double nu, double spacing);

//! The lifting scale per vertex, max(nu, 1/2 sqrt(spacing^2 - t^2)) for thickness t (see
//! above), exactly nu from wall_reach(nu, spacing) on. All in unit-ball units; nu >= 0,
//! spacing > 0.
Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, double spacing);

//! The same with a spacing per vertex (the size field's, size_field.h): the sides of a wall
//! need to lie only as far apart as the cells beside it are large.
Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, const Eigen::VectorXd& spacing);

} // namespace liftremesh
