#include "liftremesh/lift/density.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace liftremesh {

namespace {
// Gradient of the barycentric coordinate of x1 in triangle (x1, x2, x3): h1 / |h1|^2 (Eq. 23).
Eigen::Vector3d barycentric_gradient(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
    const Eigen::Vector3d e = x3 - x2;
    const double ee = e.squaredNorm();
    if (!(ee > 0.0)) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d h = (x1 - x2) - ((x1 - x2).dot(e) / ee) * e; // height through x1
    const double hh = h.squaredNorm();
    return hh > 0.0 ? Eigen::Vector3d(h / hh) : Eigen::Vector3d::Zero();
}
} // namespace

Eigen::VectorXd triangle_normal_turn(const Mesh& mesh, const Points& normals, double eta) {
    const Eigen::Index nf = mesh.triangles.rows();
    const double cap = 2.0 / eta;
    Eigen::VectorXd turn(nf);
    for (Eigen::Index f = 0; f < nf; ++f) {
        Eigen::Vector3d x[3], n[3];
        for (int j = 0; j < 3; ++j) {
            x[j] = mesh.points.row(mesh.triangles(f, j)).transpose();
            n[j] = normals.row(mesh.triangles(f, j)).transpose();
        }
        if (!((x[1] - x[0]).cross(x[2] - x[0]).norm() > 0.0)) {
            turn[f] = 0.0;
            continue;
        }
        Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero(); // dn/dx, Eq. 22
        for (int j = 0; j < 3; ++j)
            jacobian += n[j] * barycentric_gradient(x[j], x[(j + 1) % 3], x[(j + 2) % 3]).transpose();
        const double largest_row = jacobian.rowwise().norm().maxCoeff();
        turn[f] = std::min(largest_row, cap);
    }
    return turn;
}

Eigen::VectorXd triangle_density(const Mesh& mesh, const Points& normals, double eta) {
    return (1.0 + triangle_normal_turn(mesh, normals, eta).array()).matrix(); // Eq. 24
}

Eigen::VectorXd density_weights(const Eigen::VectorXd& rho, double delta) {
    return rho.array().pow(delta).matrix();
}

} // namespace liftremesh
