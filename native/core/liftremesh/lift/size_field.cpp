#include "liftremesh/lift/size_field.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/neighbor_search.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace liftremesh {

namespace {

double area_of(const Mesh& mesh, Eigen::Index f) {
    return triangle_area(mesh.points.row(mesh.triangles(f, 0)), mesh.points.row(mesh.triangles(f, 1)),
                         mesh.points.row(mesh.triangles(f, 2)));
}

} // namespace

Eigen::VectorXd triangle_bend(const Mesh& mesh, double max_turn_deg) {
    const Eigen::Index nf = mesh.triangles.rows();
    Points normal(nf, 3);
    Eigen::VectorXd area(nf);
    for (Eigen::Index f = 0; f < nf; ++f) {
        const Eigen::Vector3d a = mesh.points.row(mesh.triangles(f, 0)), b = mesh.points.row(mesh.triangles(f, 1)),
                              c = mesh.points.row(mesh.triangles(f, 2));
        normal.row(f) = triangle_normal(a, b, c).transpose();
        area[f] = triangle_area(a, b, c);
    }
    const double max_turn = max_turn_deg * M_PI / 180.0;
    Eigen::VectorXd bend = Eigen::VectorXd::Zero(nf);
    const EdgeUses edges = edge_uses(mesh.triangles);
    for (long e = 0; e < edges.size(); ++e) {
        if (edges.count(e) != 2) continue;
        const int32_t f = edges.uses.begin(e)[0] / 3, g = edges.uses.begin(e)[1] / 3;
        if (normal.row(f).isZero() || normal.row(g).isZero()) continue;
        const double turn = std::acos(std::clamp(normal.row(f).dot(normal.row(g)), -1.0, 1.0));
        // The normal is constant over each triangle and turns at the edge: over the mean of the
        // two triangles' widths across it, a facet's chord on a cylinder however long the facet.
        const double length = (mesh.points.row(edges.a[e]) - mesh.points.row(edges.b[e])).norm();
        const double width = (area[f] + area[g]) / length; // mean of the altitudes 2 |T| / |e|
        if (!(turn < max_turn) || !(width > 0.0)) continue;
        bend[f] = std::max(bend[f], turn / width);
        bend[g] = std::max(bend[g], turn / width);
    }
    return bend;
}

Eigen::VectorXd graded(const Points& points, const Eigen::VectorXd& size, double gradation, double largest) {
    Eigen::VectorXd h = size;
    if (!(gradation > 1.0) || points.rows() == 0) return h;
    const double slope = gradation - 1.0;
    std::vector<int32_t> order;
    for (Eigen::Index v = 0; v < size.size(); ++v)
        if (size[v] < largest) order.push_back(static_cast<int32_t>(v));
    if (order.empty()) return h;
    // Smallest first: a vertex whose size a smaller source's cone lowered below its own has a
    // cone under that source's (the triangle inequality), and is walked no more.
    std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return size[a] < size[b]; });
    const KdTree tree(points);
    std::vector<int32_t> near;
    for (const int32_t u : order) {
        if (h[u] < size[u]) continue;
        near.clear();
        tree.within(points.row(u).data(), (largest - size[u]) / slope, near);
        for (const int32_t v : near)
            h[v] = std::min(h[v], size[u] + slope * (points.row(v) - points.row(u)).norm());
    }
    return h;
}

SizeField size_field(const Mesh& mesh, const Eigen::VectorXd& thickness, const Eigen::VectorXd& turn,
                     const SizeFieldParams& params) {
    if (!(params.smallest > 0.0) || !(params.smallest <= params.largest) || !std::isfinite(params.largest) ||
        !(params.gradation >= 1.0) || !std::isfinite(params.gradation))
        throw InvalidInput("size_field: expected 0 < smallest <= largest, finite, and a gradation of at least 1");
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    if (thickness.size() != nv || turn.size() != nf)
        throw InvalidInput("size_field: expected a thickness per vertex and a turn rate per triangle");
    Eigen::VectorXd fastest = Eigen::VectorXd::Zero(nv), vertex_area = Eigen::VectorXd::Zero(nv);
    for (Eigen::Index f = 0; f < nf; ++f) {
        const double third = area_of(mesh, f) / 3.0;
        for (int j = 0; j < 3; ++j) {
            const int32_t v = mesh.triangles(f, j);
            fastest[v] = std::max(fastest[v], turn[f]);
            vertex_area[v] += third;
        }
    }
    SizeField field;
    Eigen::VectorXd raw(nv);
    for (Eigen::Index v = 0; v < nv; ++v) {
        const double wall = thickness[v];
        const double bend = fastest[v] > 0.0 ? kSizeTurn / fastest[v] : params.largest;
        raw[v] = std::clamp(std::min({params.largest, wall, bend}), params.smallest, params.largest);
        if (wall < params.largest && wall <= bend) field.wall_area += vertex_area[v];
        else if (bend < params.largest) field.curvature_area += vertex_area[v];
    }
    field.size = graded(mesh.points, raw, params.gradation, params.largest);
    for (Eigen::Index v = 0; v < nv; ++v)
        if (field.size[v] < params.largest) field.graded_area += vertex_area[v];
    return field;
}

Eigen::VectorXd site_density(const Mesh& mesh, const Eigen::VectorXd& size, double reference) {
    const Eigen::Index nf = mesh.triangles.rows();
    Eigen::VectorXd density(nf);
    for (Eigen::Index f = 0; f < nf; ++f) {
        const double h[3] = {size[mesh.triangles(f, 0)], size[mesh.triangles(f, 1)], size[mesh.triangles(f, 2)]};
        const double lo = std::min({h[0], h[1], h[2]}), hi = std::max({h[0], h[1], h[2]});
        // The mean of (reference / h)^2 over n^2 equal sub-triangles' centroids: exact for a
        // constant h, within about 1% where h varies by a factor n / 2 across the triangle.
        const int n = std::clamp(static_cast<int>(std::ceil(2.0 * hi / lo)), 1, 16);
        double sum = 0.0;
        const auto add = [&](double a, double b) {
            const double at = (1.0 - a - b) * h[0] + a * h[1] + b * h[2];
            sum += (reference / at) * (reference / at);
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                add((i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n); // the sub-triangle pointing up
                if (i + j < n - 1) add((i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n); // and down
            }
        density[f] = sum / (n * n);
    }
    return density;
}

Eigen::VectorXd sized_weights(const Eigen::VectorXd& density_weights, const Eigen::VectorXd& site_density) {
    return density_weights.cwiseProduct(site_density.cwiseProduct(site_density));
}

double sized_vertex_count(const Mesh& mesh, const Eigen::VectorXd& site_density, double reference) {
    double count = 0.0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) count += area_of(mesh, f) * site_density[f];
    return count / (std::sqrt(3.0) / 2.0 * reference * reference);
}

} // namespace liftremesh
