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
    const EdgeUses edges = edge_uses(mesh.triangles);
    std::vector<std::pair<int, int>> links; // the two triangles of each edge used by exactly two
    for (long e = 0; e < edges.size(); ++e)
        if (edges.count(e) == 2) links.emplace_back(edges.uses.begin(e)[0] / 3, edges.uses.begin(e)[1] / 3);

    // connected_components numbers them in order of first triangle.
    MeshComponents result;
    const int count = connected_components(static_cast<int>(nf), links, result.label);
    result.components.resize(static_cast<size_t>(count));
    std::vector<Eigen::Vector3d> origin(static_cast<size_t>(count));
    std::vector<char> seen(static_cast<size_t>(count), 0);
    for (Eigen::Index f = 0; f < nf; ++f) {
        const int c = result.label[f];
        MeshComponent& part = result.components[c];
        if (!seen[c]) {
            seen[c] = 1;
            part.closed = true;
            origin[c] = corner(mesh, f, 0);
        }
        const Eigen::Vector3d a = corner(mesh, f, 0) - origin[c], b = corner(mesh, f, 1) - origin[c],
                              d = corner(mesh, f, 2) - origin[c];
        ++part.triangles;
        part.area += 0.5 * (b - a).cross(d - a).norm();
        part.signed_volume += a.dot(b.cross(d)) / 6.0;
    }
    // Open: an edge used by exactly one of its triangles (a boundary edge, or one of several
    // components meeting at a non-manifold edge with a single triangle).
    std::vector<int> uses_in;
    for (long e = 0; e < edges.size(); ++e) {
        if (edges.count(e) == 2) continue; // both in one component
        uses_in.clear();
        for (const int32_t* u = edges.uses.begin(e); u != edges.uses.end(e); ++u) uses_in.push_back(result.label[*u / 3]);
        std::sort(uses_in.begin(), uses_in.end());
        for (size_t i = 0; i < uses_in.size(); ++i) {
            const bool alone = (i == 0 || uses_in[i - 1] != uses_in[i]) && (i + 1 == uses_in.size() || uses_in[i + 1] != uses_in[i]);
            if (alone) result.components[uses_in[i]].closed = false;
        }
    }
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
