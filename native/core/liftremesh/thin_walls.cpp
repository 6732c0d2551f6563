#include "liftremesh/thin_walls.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace liftremesh {

Eigen::VectorXd wall_thickness(const Mesh& mesh, const AabbTree& tree, double reach) {
    const Eigen::Index nv = mesh.points.rows();
    const CompressedRows around = vertex_triangles(mesh);
    const double cos_parallel = -std::cos(kWallTaperDeg * M_PI / 180.0);
    Eigen::VectorXd thickness(nv);
#pragma omp parallel
    {
        std::vector<Eigen::Vector3d> own;
#pragma omp for schedule(dynamic, 256)
        for (Eigen::Index v = 0; v < nv; ++v) {
            own.clear();
            for (const int32_t* f = around.begin(v); f != around.end(v); ++f) own.push_back(tree.triangle_normal(*f));
            const Eigen::Vector3d x = mesh.points.row(v).transpose();
            // Antiparallel to one of the vertex's own triangles (the tree skips the rest), not one
            // of them, and across: the way to it along its normal.
            const auto far_side = [&](int32_t f, const Eigen::Vector3d& p) {
                if (mesh.triangles(f, 0) == v || mesh.triangles(f, 1) == v || mesh.triangles(f, 2) == v) return false;
                return std::abs((x - p).dot(tree.triangle_normal(f))) >= -cos_parallel * (x - p).norm();
            };
            const ClosestPoint wall = tree.closest_where(x, reach, {own, cos_parallel}, far_side);
            thickness[v] = wall.triangle >= 0 ? std::sqrt(wall.squared_distance) : std::numeric_limits<double>::infinity();
        }
    }
    return thickness;
}

double wall_reach(double nu, double spacing) { return std::sqrt(std::max(0.0, spacing * spacing - 4.0 * nu * nu)); }

Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, double spacing) {
    const double reach = wall_reach(nu, spacing);
    Eigen::VectorXd scale(thickness.size());
    for (Eigen::Index v = 0; v < thickness.size(); ++v) {
        const double t = thickness[v];
        scale[v] = t >= reach ? nu : std::max(nu, 0.5 * std::sqrt(spacing * spacing - t * t));
    }
    return scale;
}

} // namespace liftremesh
