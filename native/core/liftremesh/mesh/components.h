// The connected components of a triangle mesh, each measured as a solid's boundary is: closed or
// not, area, and for a closed one the signed volume it encloses (divergence theorem) and whether
// it is a cavity of another. A closed surface facing inward (negative volume) bounds no solid
// unless it lies inside another closed surface, as a hollowed part's inner wall does; TetGen and
// FEM refuse any other. Shared by the stray-component step (repair/stray_components.h) and the
// quality report (measure/quality.h). Components are joined through edges, not vertices (unlike
// solid_parts.h, which remeshes solids touching at a point together): two solids touching at a
// vertex are two closed surfaces, each with its own volume and orientation.
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <vector>

namespace liftremesh {

struct MeshComponent {
    long triangles = 0;
    double area = 0.0;
    //! No edge is used by exactly one of its triangles.
    bool closed = false;
    //! Closed ones: the volume enclosed, positive when the triangles face outward (counter-
    //! clockwise seen from outside), by the divergence theorem, V = 1/6 sum (a - o).((b - o) x
    //! (c - o)) over its triangles (a, b, c), o a point of the component (for rounding). 0 if open.
    double signed_volume = 0.0;
    //! Closed, facing inward, and inside the other closed components: their winding number at a
    //! point of it is 1 or more (a hollowed solid's inner wall). Tested for the kCavityTests
    //! largest inward components only; the others are false.
    bool cavity = false;
    bool inward() const { return closed && signed_volume < 0.0; }
};

//! How many inward components mesh_components tests for being cavities, largest |volume| first:
//! each test sums a solid angle over every triangle of the other closed components.
constexpr int kCavityTests = 64;

struct MeshComponents {
    std::vector<int> label;                //!< #F: each triangle's component
    std::vector<MeshComponent> components; //!< in order of first triangle
    long closed() const;                   //!< how many are closed
    long inward() const;                   //!< how many are closed and face inward
    long cavities() const;                 //!< how many of those are cavities
};

//! The components of `mesh`: two triangles are in one when a chain of edges, each used by
//! exactly two triangles, joins them (a non-manifold edge joins nothing, as in orientation.h).
//! Throws InvalidInput if a triangle index is out of range.
MeshComponents mesh_components(const Mesh& mesh);

//! Winding number at `p` of the triangles `ids` of `mesh`: the sum of their solid angles seen from
//! p over 4 pi (Van Oosterom and Strackee's formula); 1 inside an outward closed surface, 0
//! outside, -1 inside an inward one.
double winding_number(const Mesh& mesh, const std::vector<int32_t>& ids, const Eigen::Vector3d& p);

} // namespace liftremesh
