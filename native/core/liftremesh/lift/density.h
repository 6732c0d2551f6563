// Local density rho_p of each input triangle from the variation of the lifted normal
// (Section 4.2, Eqs. 22-24), and the objective's per-triangle weights rho_p^delta (Eq. 25).
#pragma once

#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

//! #F max_i |dn_i|, the fastest turn of the interpolated vertex normals over each triangle
//! (Eqs. 22, 23; the curvature where the normals are exact), capped at 2 / eta as
//! triangle_density says; 0 for a degenerate triangle. In the mesh's inverse units.
Eigen::VectorXd triangle_normal_turn(const Mesh& mesh, const Points& normals, double eta);

//! #F rho_p = 1 + max_i |dn_i| (Eq. 24), with dn/dx = sum_j n_j (dlambda_j/dx)^t (Eqs. 22, 23)
//! the Jacobian of the linearly interpolated vertex normals over the triangle, and dn_i its
//! rows. `normals` is #V by 3. Because the normals are averages over balls of radius eta, their
//! true variation is at most about 2 / eta; a needle triangle can make the interpolated
//! Jacobian far larger (Section 6.2.3), so |dn_i| is capped at 2 / eta. Degenerate triangles get 1.
Eigen::VectorXd triangle_density(const Mesh& mesh, const Points& normals, double eta);

//! #F weights rho_p^delta (Eq. 25).
Eigen::VectorXd density_weights(const Eigen::VectorXd& rho, double delta);

} // namespace liftremesh
