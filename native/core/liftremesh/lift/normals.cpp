#include "liftremesh/lift/normals.h"

#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <cmath>

namespace liftremesh {

Points vertex_normals(const Mesh& mesh, double eta) {
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    Points ring = Points::Zero(nv, 3); // one-ring, area-weighted: the fallback and the side test
    for (Eigen::Index f = 0; f < nf; ++f) {
        const auto a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
        const Eigen::Vector3d weighted = triangle_area(a, b, c) * triangle_normal(a, b, c);
        for (int j = 0; j < 3; ++j) ring.row(mesh.triangles(f, j)) += weighted.transpose();
    }
    // The triangles that meet each ball, from an AABB tree: a ball query on centroids needs a
    // radius grown by the longest triangle's reach, and on a fan of long slivers (a CAD disk)
    // finds most of them from every vertex. Inside the ball a triangle weighs its whole area,
    // and the tree adds whole subtrees inside it at once: only the triangles crossing the sphere
    // are clipped, so the cost goes with the ball's rim, not its area.
    const AabbTree tree(mesh);

    // Vertices in Morton order: consecutive balls meet the same nodes, still in the cache.
    const std::vector<long> order = morton_order(mesh.points.data(), nv, 3);
    Points normals(nv, 3);
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index i = 0; i < nv; ++i) {
        const Eigen::Index v = order[i];
        const Eigen::Vector3d x = mesh.points.row(v).transpose();
        const Eigen::Vector3d own = ring.row(v).transpose().normalized();
        // Triangles turned more than 120 degrees from the vertex's own normal are the far side of
        // a thin wall: left out.
        const Eigen::Vector3d sum = tree.area_weighted_normal_in_ball(x, eta, {own, -0.5});
        const double len = sum.norm();
        normals.row(v) = (len > 0.0 ? Eigen::Vector3d(sum / len) : own).transpose();
    }
    return normals;
}

LiftedPoints lift(const Points& points, const Points& normals, double nu) {
    if (nu == 0.0) return points;
    LiftedPoints out(points.rows(), 6);
    out.leftCols(3) = points;
    out.rightCols(3) = nu * normals; // Eq. 12
    return out;
}

LiftedPoints lift(const Points& points, const Points& normals, const Eigen::VectorXd& nu) {
    LiftedPoints out(points.rows(), 6);
    out.leftCols(3) = points;
    out.rightCols(3) = normals.array().colwise() * nu.array(); // Eq. 12, nu per vertex
    return out;
}

} // namespace liftremesh
