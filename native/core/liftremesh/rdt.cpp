#include "liftremesh/rdt.h"

#include <algorithm>
#include <array>

namespace liftremesh {

Triangles restricted_delaunay(const LiftedSurface& surface, const LiftedPoints& sites, int threads) {
    std::vector<ChunkSlot<std::vector<std::array<int32_t, 3>>>> found(rvd_chunks(surface));
    compute_rvd(surface, sites, threads, [&](int chunk, const RvdPolygon& poly) {
        for (int i = 0; i < poly.size; ++i) {
            // Vertex i joins the edge before it (from i-1) and the edge after it (from i).
            const int32_t l = poly.edges[(i + poly.size - 1) % poly.size], m = poly.edges[i];
            if (l < 0 || m < 0 || l == m) continue;
            std::array<int32_t, 3> t = {poly.site, l, m};
            // Rotate so the smallest index comes first: the three cells report the same triangle.
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            found[chunk].value.push_back(t);
        }
    });
    std::vector<std::array<int32_t, 3>> all;
    for (auto& f : found) all.insert(all.end(), f.value.begin(), f.value.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    Triangles out(static_cast<Eigen::Index>(all.size()), 3);
    for (size_t i = 0; i < all.size(); ++i)
        for (int j = 0; j < 3; ++j) out(static_cast<Eigen::Index>(i), j) = all[i][j];
    return out;
}

} // namespace liftremesh
