#include "liftremesh/lift/normals.h"

#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

Points vertex_normals(const Mesh& mesh, double eta) {
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    std::vector<Eigen::Vector3d> face_normal(nf);
    std::vector<PlaneFrame> frame(nf); // each triangle meets many balls
    Points ring = Points::Zero(nv, 3); // one-ring, area-weighted: the fallback and the side test
    for (Eigen::Index f = 0; f < nf; ++f) {
        const auto a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
        face_normal[f] = triangle_normal(a, b, c);
        frame[f] = plane_frame(a, b, c);
        const double area = triangle_area(a, b, c);
        for (int j = 0; j < 3; ++j) ring.row(mesh.triangles(f, j)) += area * face_normal[f].transpose();
    }
    // The triangles that meet each ball, from an AABB tree: a ball query on centroids needs a
    // radius grown by the longest triangle's reach, and on a fan of long slivers (a CAD disk)
    // finds most of them from every vertex.
    const AabbTree tree(mesh);

    Points normals(nv, 3);
#pragma omp parallel
    {
        std::vector<int32_t> found;
#pragma omp for schedule(dynamic, 256)
        for (Eigen::Index v = 0; v < nv; ++v) {
            const Eigen::Vector3d x = mesh.points.row(v).transpose();
            const Eigen::Vector3d own = ring.row(v).transpose().normalized();
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            found.clear();
            tree.triangles_within(x, eta, found);
            std::sort(found.begin(), found.end()); // a sum in the mesh's order, whatever the tree's
            for (int32_t f : found) {
                if (own.dot(face_normal[f]) < -0.5) continue; // far side of a thin wall
                const double w = triangle_ball_intersection_area(x, eta, corner(mesh, f, 0), corner(mesh, f, 1),
                                                                 corner(mesh, f, 2), frame[f]);
                sum += w * face_normal[f];
            }
            const double len = sum.norm();
            normals.row(v) = (len > 0.0 ? Eigen::Vector3d(sum / len) : own).transpose();
        }
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
