#include "liftremesh/edit/acute_creases.h"

#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

AcuteCreases::AcuteCreases(const Mesh& input, const AabbTree& input_tree, double min_turn_deg, double spacing,
                           double min_length) {
    const double cos_turn = std::cos(min_turn_deg * M_PI / 180.0);
    const EdgeUses edges = edge_uses(input.triangles);
    std::vector<std::pair<int32_t, int32_t>> found;
    for (long e = 0; e < edges.size(); ++e) {
        // Two triangles using the edge in opposite directions: a consistently oriented pair.
        if (edges.count(e) != 2) continue;
        const int32_t s = edges.uses.begin(e)[0], t = edges.uses.begin(e)[1];
        if (runs_forward(input.triangles, s) == runs_forward(input.triangles, t)) continue;
        const Eigen::Vector3d n1 = input_tree.triangle_normal(s / 3), n2 = input_tree.triangle_normal(t / 3);
        if (!(n1.squaredNorm() > 0.0 && n2.squaredNorm() > 0.0) || !(n1.dot(n2) < cos_turn)) continue;
        found.emplace_back(edges.a[e], edges.b[e]);
    }
    // The creases as chains of edges joined at their vertices, each chain's length in all: a chain
    // shorter than min_length is a scan's noise or a facet's slip, not a feature of the part.
    std::unordered_map<int32_t, int32_t> parent;
    auto root = [&parent](int32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& [a, b] : found) {
        parent.emplace(a, a);
        parent.emplace(b, b);
        parent[root(a)] = root(b);
    }
    auto length = [&input](int32_t a, int32_t b) { return (input.points.row(a) - input.points.row(b)).norm(); };
    std::unordered_map<int32_t, double> chain_length;
    for (const auto& [a, b] : found) chain_length[root(a)] += length(a, b);
    std::vector<Eigen::Vector3d> samples;
    for (const auto& [a, b] : found) {
        if (chain_length[root(a)] < min_length) continue;
        const Eigen::Vector3d pa = input.points.row(a).transpose(), pb = input.points.row(b).transpose();
        ++degree_[a];
        ++degree_[b];
        const auto segment = static_cast<int32_t>(segments_.size());
        segments_.push_back({pa, pb});
        const double steps = std::min(1e5, std::ceil((pb - pa).norm() / spacing));
        for (int i = 0; i <= static_cast<int>(steps); ++i) {
            samples.push_back(pa + (pb - pa) * (i / std::max(1.0, steps)));
            sample_segment_.push_back(segment);
        }
    }
    for (const auto& [v, count] : degree_)
        if (count != 2) corners_.push_back(input.points.row(v).transpose());
    std::sort(corners_.begin(), corners_.end(), [](const Eigen::Vector3d& l, const Eigen::Vector3d& r) {
        return std::lexicographical_compare(l.data(), l.data() + 3, r.data(), r.data() + 3);
    });
    spacing_ = spacing;
    if (!samples.empty()) {
        Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> m(static_cast<Eigen::Index>(samples.size()), 3);
        for (size_t i = 0; i < samples.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
        tree_.emplace(m);
    }
}

std::optional<Eigen::Vector3d> AcuteCreases::closest(const Eigen::Vector3d& p, double radius) const {
    if (!tree_) return std::nullopt;
    found_.clear();
    tree_->within(p.data(), radius + spacing_, found_);
    std::optional<Eigen::Vector3d> best;
    double best_d2 = radius * radius;
    for (int32_t s : found_) {
        const auto& [a, b] = segments_[sample_segment_[s]];
        const Eigen::Vector3d x = closest_point_on_segment(p, a, b);
        if (const double d2 = (x - p).squaredNorm(); d2 <= best_d2) {
            best_d2 = d2;
            best = x;
        }
    }
    return best;
}

} // namespace liftremesh
