#include "liftremesh/normals.h"

#include "liftremesh/geometry.h"
#include "liftremesh/neighbor_search.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace liftremesh {

namespace {

// Triangles grouped by bounding radius so that a ball query on centroids with radius
// eta + (the group's largest radius) finds every triangle that can reach the ball, without
// letting a few long needles force a huge radius on all queries.
struct TriangleGroups {
    std::vector<std::vector<int32_t>> members;
    std::vector<double> radius;
    std::vector<std::unique_ptr<KdTree>> trees;
};

TriangleGroups group_triangles(const std::vector<Eigen::Vector3d>& centroid, const std::vector<double>& bound) {
    TriangleGroups g;
    const double rmax = *std::max_element(bound.begin(), bound.end());
    const int levels = 12; // radius classes rmax / 2^c; the last takes everything smaller
    g.members.resize(levels);
    g.radius.assign(levels, 0.0);
    for (size_t f = 0; f < bound.size(); ++f) {
        int c = bound[f] > 0.0 ? static_cast<int>(std::floor(std::log2(rmax / bound[f]))) : levels - 1;
        c = std::clamp(c, 0, levels - 1);
        g.members[c].push_back(static_cast<int32_t>(f));
        g.radius[c] = std::max(g.radius[c], bound[f]);
    }
    for (int c = 0; c < levels; ++c) {
        LiftedPoints pts(static_cast<Eigen::Index>(g.members[c].size()), 3);
        for (size_t i = 0; i < g.members[c].size(); ++i) pts.row(i) = centroid[g.members[c][i]].transpose();
        g.trees.push_back(std::make_unique<KdTree>(pts));
    }
    return g;
}

} // namespace

Points vertex_normals(const Mesh& mesh, double eta) {
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    std::vector<Eigen::Vector3d> face_normal(nf), centroid(nf);
    std::vector<double> area(nf), bound(nf);
    Points ring = Points::Zero(nv, 3); // one-ring, area-weighted: the fallback and the side test
    for (Eigen::Index f = 0; f < nf; ++f) {
        const auto a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
        face_normal[f] = triangle_normal(a, b, c);
        area[f] = triangle_area(a, b, c);
        centroid[f] = (a + b + c) / 3.0;
        bound[f] = std::max({(a - centroid[f]).norm(), (b - centroid[f]).norm(), (c - centroid[f]).norm()});
        for (int j = 0; j < 3; ++j) ring.row(mesh.triangles(f, j)) += area[f] * face_normal[f].transpose();
    }
    const TriangleGroups groups = group_triangles(centroid, bound);

    Points normals(nv, 3);
#pragma omp parallel
    {
        std::vector<int32_t> found;
#pragma omp for schedule(dynamic, 256)
        for (Eigen::Index v = 0; v < nv; ++v) {
            const Eigen::Vector3d x = mesh.points.row(v).transpose();
            const Eigen::Vector3d own = ring.row(v).transpose().normalized();
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for (size_t c = 0; c < groups.trees.size(); ++c) {
                if (groups.members[c].empty()) continue;
                found.clear();
                groups.trees[c]->within(x.data(), eta + groups.radius[c], found);
                for (int32_t i : found) {
                    const int32_t f = groups.members[c][i];
                    if (own.dot(face_normal[f]) < -0.5) continue; // far side of a thin wall
                    const double w = triangle_ball_intersection_area(x, eta, corner(mesh, f, 0), corner(mesh, f, 1),
                                                                     corner(mesh, f, 2));
                    sum += w * face_normal[f];
                }
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
