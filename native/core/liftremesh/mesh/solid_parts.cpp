#include "liftremesh/mesh/solid_parts.h"

#include "liftremesh/mesh/components.h"

namespace liftremesh {

std::vector<SolidPart> solid_parts(const Mesh& mesh) {
    const Eigen::Index nf = mesh.triangles.rows();
    const MeshComponents split = mesh_components(mesh);
    const std::vector<int>& component = split.label;
    // Pieces numbered in order of first triangle (as the components are); the open components
    // share the last.
    std::vector<int> piece(split.components.size(), -1);
    int closed_pieces = 0;
    bool any_open = false;
    for (size_t c = 0; c < split.components.size(); ++c) {
        if (!split.components[c].closed)
            any_open = true;
        else
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
        const int c = component[f];
        parts[split.components[c].closed ? piece[c] : closed_pieces].triangles.push_back(static_cast<int32_t>(f));
    }
    return parts;
}

} // namespace liftremesh
