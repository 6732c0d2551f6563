#include "liftremesh/mesh/solid_parts.h"

namespace liftremesh {

std::vector<SolidPart> solid_parts(const Mesh& mesh) {
    const Eigen::Index nf = mesh.triangles.rows();
    std::vector<std::pair<int, int>> links; // each triangle's corners to its first
    links.reserve(2 * static_cast<size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int j = 1; j < 3; ++j) links.emplace_back(mesh.triangles(f, 0), mesh.triangles(f, j));
    std::vector<int> component;
    const int count = connected_components(static_cast<int>(mesh.points.rows()), links, component);
    std::vector<char> closed(static_cast<size_t>(count), 1);
    for (const EdgeCount& e : edge_counts(mesh.triangles))
        if (e.count < 2) closed[component[e.a]] = 0;
    // Pieces numbered in order of first triangle; the open components share the last. Vertices
    // no triangle uses are components of their own, and no piece.
    std::vector<int> piece(static_cast<size_t>(count), -1);
    int closed_pieces = 0;
    bool any_open = false;
    for (Eigen::Index f = 0; f < nf; ++f) {
        const int c = component[mesh.triangles(f, 0)];
        if (!closed[c])
            any_open = true;
        else if (piece[c] < 0)
            piece[c] = closed_pieces++;
    }
    if (closed_pieces + (any_open ? 1 : 0) <= 1) {
        SolidPart all;
        all.triangles.resize(static_cast<size_t>(nf));
        for (Eigen::Index f = 0; f < nf; ++f) all.triangles[f] = static_cast<int32_t>(f);
        all.closed = !any_open;
        return {std::move(all)};
    }
    std::vector<SolidPart> parts(static_cast<size_t>(closed_pieces + (any_open ? 1 : 0)));
    for (int k = 0; k < closed_pieces; ++k) parts[k].closed = true;
    for (Eigen::Index f = 0; f < nf; ++f) {
        const int c = component[mesh.triangles(f, 0)];
        parts[closed[c] ? piece[c] : closed_pieces].triangles.push_back(static_cast<int32_t>(f));
    }
    return parts;
}

} // namespace liftremesh
