#include "liftremesh/mesh/orientation.h"

#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <deque>

namespace liftremesh {

std::vector<char> orient_components(const Points& points, std::vector<std::array<int32_t, 3>>& triangles,
                                    const std::vector<char>& live) {
    const size_t n = triangles.size();
    auto alive = [&live](size_t f) { return live.empty() || live[f]; };
    static_assert(sizeof(std::array<int32_t, 3>) == 3 * sizeof(int32_t), "triangles stored as consecutive corners");
    const EdgeUses edges = edge_uses(n == 0 ? nullptr : triangles[0].data(), static_cast<long>(n), live);
    const std::vector<int32_t> edge_of = edges.edge_of_sides(static_cast<long>(n));
    // The other triangle on t's side j when exactly two live triangles use it, else -1.
    auto across = [&](int t, int j) {
        const int32_t e = edge_of[3 * static_cast<size_t>(t) + j];
        if (edges.count(e) != 2) return -1;
        const int32_t* use = edges.uses.begin(e);
        return use[0] / 3 == t ? use[1] / 3 : use[0] / 3;
    };
    auto area = [&](int t) {
        const auto& c = triangles[t];
        return triangle_area(points.row(c[0]), points.row(c[1]), points.row(c[2]));
    };
    std::vector<int> component(n, -1);
    std::vector<char> reverse(n, 0), turned(n, 0);
    std::vector<int> members;
    std::deque<int> queue;
    int next_component = 0;
    for (size_t seed = 0; seed < n; ++seed) {
        if (!alive(seed) || component[seed] >= 0) continue;
        members.clear();
        component[seed] = next_component;
        queue.push_back(static_cast<int>(seed));
        while (!queue.empty()) {
            const int t = queue.front();
            queue.pop_front();
            members.push_back(t);
            for (int j = 0; j < 3; ++j) {
                const int32_t a = triangles[t][j], b = triangles[t][(j + 1) % 3];
                const int u = across(t, j);
                if (u < 0 || component[u] >= 0) continue;
                component[u] = next_component;
                // t, once reoriented, runs a -> b iff it is not reversed; u must then run b -> a.
                reverse[u] = traverses(triangles[u], a, b) == !reverse[t] ? 1 : 0;
                queue.push_back(u);
            }
        }
        double kept_area = 0.0, reversed_area = 0.0;
        for (int t : members) (reverse[t] ? reversed_area : kept_area) += area(t);
        const bool invert = reversed_area > kept_area;
        for (int t : members) {
            if (static_cast<bool>(reverse[t]) == invert) continue;
            std::swap(triangles[t][1], triangles[t][2]);
            turned[t] = 1;
        }
        ++next_component;
    }
    return turned;
}

} // namespace liftremesh
