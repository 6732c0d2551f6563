#include "liftremesh/mesh/components.h"

#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

long MeshComponents::closed() const {
    return std::count_if(components.begin(), components.end(), [](const MeshComponent& c) { return c.closed; });
}

long MeshComponents::inward() const {
    return std::count_if(components.begin(), components.end(), [](const MeshComponent& c) { return c.inward(); });
}

long MeshComponents::cavities() const {
    return std::count_if(components.begin(), components.end(), [](const MeshComponent& c) { return c.cavity; });
}

double winding_number(const Mesh& mesh, const std::vector<int32_t>& ids, const Eigen::Vector3d& p) {
    double angle = 0.0;
    for (const int32_t f : ids) {
        const Eigen::Vector3d a = corner(mesh, f, 0) - p, b = corner(mesh, f, 1) - p, c = corner(mesh, f, 2) - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        // tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)
        angle += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
    }
    return angle / (4.0 * M_PI);
}

MeshComponents mesh_components(const Mesh& mesh) {
    check_indices(mesh, "mesh_components");
    const Eigen::Index nf = mesh.triangles.rows();
    std::vector<std::pair<int, int>> links; // each triangle's corners to its first
    links.reserve(2 * static_cast<size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int j = 1; j < 3; ++j) links.emplace_back(mesh.triangles(f, 0), mesh.triangles(f, j));
    std::vector<int> vertex_label;
    connected_components(static_cast<int>(mesh.points.rows()), links, vertex_label);

    // Components numbered in order of first triangle (the vertices' numbering counts vertices no
    // triangle uses).
    MeshComponents result;
    result.label.resize(static_cast<size_t>(nf));
    std::vector<int> number(mesh.points.rows() > 0 ? static_cast<size_t>(mesh.points.rows()) : 0, -1);
    std::vector<Eigen::Vector3d> origin;
    for (Eigen::Index f = 0; f < nf; ++f) {
        int& c = number[vertex_label[mesh.triangles(f, 0)]];
        if (c < 0) {
            c = static_cast<int>(result.components.size());
            result.components.emplace_back();
            result.components.back().closed = true;
            origin.push_back(corner(mesh, f, 0));
        }
        result.label[f] = c;
        MeshComponent& part = result.components[c];
        const Eigen::Vector3d a = corner(mesh, f, 0) - origin[c], b = corner(mesh, f, 1) - origin[c],
                              d = corner(mesh, f, 2) - origin[c];
        ++part.triangles;
        part.area += 0.5 * (b - a).cross(d - a).norm();
        part.signed_volume += a.dot(b.cross(d)) / 6.0;
    }
    for (const EdgeCount& e : edge_counts(mesh.triangles))
        if (e.count < 2) result.components[number[vertex_label[e.a]]].closed = false;
    for (MeshComponent& c : result.components)
        if (!c.closed) c.signed_volume = 0.0;

    // An inward component is a cavity when the other closed components wind around a point of it.
    std::vector<int> inward;
    for (size_t c = 0; c < result.components.size(); ++c)
        if (result.components[c].inward()) inward.push_back(static_cast<int>(c));
    if (inward.empty()) return result;
    std::sort(inward.begin(), inward.end(), [&](int x, int y) {
        return result.components[x].signed_volume < result.components[y].signed_volume; // largest |V| first
    });
    if (inward.size() > static_cast<size_t>(kCavityTests)) inward.resize(kCavityTests);
    std::vector<int32_t> first(result.components.size(), -1);
    std::vector<std::vector<int32_t>> members(result.components.size());
    for (Eigen::Index f = 0; f < nf; ++f) {
        const int c = result.label[f];
        if (first[c] < 0) first[c] = static_cast<int32_t>(f);
        if (result.components[c].closed) members[c].push_back(static_cast<int32_t>(f));
    }
    for (const int c : inward) {
        const Eigen::Vector3d p = (corner(mesh, first[c], 0) + corner(mesh, first[c], 1) + corner(mesh, first[c], 2)) / 3.0;
        double winding = 0.0;
        for (size_t d = 0; d < members.size(); ++d)
            if (static_cast<int>(d) != c) winding += winding_number(mesh, members[d], p);
        result.components[c].cavity = winding >= 0.5;
    }
    return result;
}

} // namespace liftremesh
