#include "liftremesh/edit/acute_creases.h"

#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

AcuteCreases::AcuteCreases(const Mesh& input, double min_turn_deg, double spacing, double min_length) {
    std::vector<Eigen::Vector3d> samples;
    for (const auto& [a, b, left, right, turn] : crease_edges(input, min_turn_deg, min_length)) {
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
