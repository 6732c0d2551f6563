#include "liftremesh/repair/stray_components.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace liftremesh {

StrayComponentParams stray_component_params(const MeshComponents& input) {
    StrayComponentParams params;
    params.pieces = static_cast<long>(input.components.size());
    params.inward = input.inward();
    double smallest = std::numeric_limits<double>::infinity();
    for (const MeshComponent& c : input.components) smallest = std::min(smallest, c.area);
    params.max_area = input.components.empty() ? 0.0 : kStrayShare * smallest;
    return params;
}

StrayComponentStats remove_stray_components(Mesh& mesh, const StrayComponentParams& params) {
    const MeshComponents split = mesh_components(mesh);
    const std::vector<MeshComponent>& parts = split.components;
    std::vector<char> stray(parts.size(), 0);
    auto take = [&](std::vector<int>& ranked, long keep) { // those beyond `keep` that are small
        for (size_t k = static_cast<size_t>(std::max(0L, keep)); k < ranked.size(); ++k)
            if (parts[ranked[k]].area <= params.max_area) stray[ranked[k]] = 1;
    };

    // 1. Inward pieces: the input's cavities have their counterparts among the cavities first (a
    // bubble outside the solid is none), then among the larger ones.
    std::vector<int> inward;
    for (size_t c = 0; c < parts.size(); ++c)
        if (parts[c].inward()) inward.push_back(static_cast<int>(c));
    std::stable_sort(inward.begin(), inward.end(), [&](int x, int y) {
        if (parts[x].cavity != parts[y].cavity) return parts[x].cavity;
        return parts[x].signed_volume < parts[y].signed_volume;
    });
    take(inward, params.inward);

    // 2. Then the pieces left beyond the input's count, the larger ones its counterparts.
    std::vector<int> left;
    for (size_t c = 0; c < parts.size(); ++c)
        if (!stray[c]) left.push_back(static_cast<int>(c));
    std::stable_sort(left.begin(), left.end(), [&](int x, int y) { return parts[x].area > parts[y].area; });
    take(left, params.pieces);

    StrayComponentStats stats;
    for (size_t c = 0; c < parts.size(); ++c)
        if (stray[c]) {
            ++stats.removed;
            stats.inward_removed += parts[c].inward() ? 1 : 0;
        }
    if (stats.removed == 0) return stats;
    std::vector<int32_t> kept;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        if (!stray[split.label[f]]) kept.push_back(static_cast<int32_t>(f));
    stats.triangles_removed = static_cast<long>(mesh.triangles.rows()) - static_cast<long>(kept.size());
    mesh = submesh(mesh, kept);
    return stats;
}

} // namespace liftremesh
