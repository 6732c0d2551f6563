#include "liftremesh/mesh/creases.h"

#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace liftremesh {

std::vector<CreaseEdge> crease_edges(const Mesh& input, double min_turn_deg) {
    const double cos_turn = std::cos(min_turn_deg * M_PI / 180.0);
    const EdgeUses edges = edge_uses(input.triangles);
    auto normal = [&input](int32_t f) {
        return triangle_normal(input.points.row(input.triangles(f, 0)).transpose(), input.points.row(input.triangles(f, 1)).transpose(),
                               input.points.row(input.triangles(f, 2)).transpose());
    };
    std::vector<CreaseEdge> found;
    for (long e = 0; e < edges.size(); ++e) {
        // Two triangles using the edge in opposite directions: a consistently oriented pair.
        if (edges.count(e) != 2) continue;
        const int32_t s = edges.uses.begin(e)[0], t = edges.uses.begin(e)[1];
        if (runs_forward(input.triangles, s) == runs_forward(input.triangles, t)) continue;
        const Eigen::Vector3d n1 = normal(s / 3), n2 = normal(t / 3);
        if (!(n1.squaredNorm() > 0.0 && n2.squaredNorm() > 0.0) || !(n1.dot(n2) < cos_turn)) continue;
        const double cos = std::clamp(n1.normalized().dot(n2.normalized()), -1.0, 1.0);
        found.push_back({edges.a[e], edges.b[e], s / 3, t / 3, std::acos(cos) * 180.0 / M_PI});
    }
    return found;
}

std::vector<CreaseEdge> long_crease_chains(const Mesh& input, const std::vector<CreaseEdge>& found, double min_length) {
    if (!(min_length > 0.0)) return found;
    // The creases as chains of edges joined at their vertices, each chain's length in all: a chain
    // shorter than min_length is a scan's noise or a facet's slip, not a feature of the part.
    std::unordered_map<int32_t, int32_t> parent;
    auto root = [&parent](int32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const CreaseEdge& e : found) {
        parent.emplace(e.a, e.a);
        parent.emplace(e.b, e.b);
        parent[root(e.a)] = root(e.b);
    }
    auto length = [&input](int32_t a, int32_t b) { return (input.points.row(a) - input.points.row(b)).norm(); };
    std::unordered_map<int32_t, double> chain_length;
    for (const CreaseEdge& e : found) chain_length[root(e.a)] += length(e.a, e.b);
    std::vector<CreaseEdge> kept;
    for (const CreaseEdge& e : found)
        if (!(chain_length[root(e.a)] < min_length)) kept.push_back(e);
    return kept;
}

std::vector<CreaseEdge> crease_edges(const Mesh& input, double min_turn_deg, double min_length) {
    return long_crease_chains(input, crease_edges(input, min_turn_deg), min_length);
}

} // namespace liftremesh
