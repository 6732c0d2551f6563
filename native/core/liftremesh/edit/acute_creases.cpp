#include "liftremesh/edit/acute_creases.h"

#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

AcuteCreases::AcuteCreases(const Mesh& input, double min_turn_deg, double spacing, double min_length) {
    std::unordered_map<int32_t, double> sharpest; // the sharpest crease at an input vertex
    for (const auto& [a, b, left, right, turn] : crease_edges(input, min_turn_deg, min_length)) {
        ++degree_[a];
        ++degree_[b];
        sharpest[a] = std::max(sharpest[a], turn);
        sharpest[b] = std::max(sharpest[b], turn);
        segments_.push_back({input.points.row(a).transpose(), input.points.row(b).transpose()});
        ends_.emplace_back(a, b);
        turns_.push_back(turn);
    }
    std::vector<std::pair<Eigen::Vector3d, double>> junctions;
    for (const auto& [v, count] : degree_) {
        if (count != 2) corners_.push_back(input.points.row(v).transpose());
        if (count >= 3) junctions.emplace_back(input.points.row(v).transpose(), sharpest[v]);
    }
    auto lexicographic = [](const Eigen::Vector3d& l, const Eigen::Vector3d& r) {
        return std::lexicographical_compare(l.data(), l.data() + 3, r.data(), r.data() + 3);
    };
    std::sort(corners_.begin(), corners_.end(), lexicographic);
    std::sort(junctions.begin(), junctions.end(), [&](const auto& l, const auto& r) { return lexicographic(l.first, r.first); });
    for (const auto& [x, turn] : junctions) {
        junctions_.push_back(x);
        junction_turns_.push_back(turn);
    }
    index_.emplace(segments_, spacing);
}

std::optional<AcuteCreases::Nearest> AcuteCreases::nearest(const Eigen::Vector3d& p, double radius) const {
    index_->near(p, radius, found_);
    std::optional<Nearest> best;
    double best_d2 = radius * radius;
    for (int32_t s : found_) {
        const auto& [a, b] = segments_[s];
        const Eigen::Vector3d x = closest_point_on_segment(p, a, b);
        if (const double d2 = (x - p).squaredNorm(); d2 <= best_d2) {
            best_d2 = d2;
            const double length2 = (b - a).squaredNorm();
            best = Nearest{s, length2 > 0.0 ? std::clamp((p - a).dot(b - a) / length2, 0.0, 1.0) : 0.0, x};
        }
    }
    return best;
}

std::optional<Eigen::Vector3d> AcuteCreases::closest(const Eigen::Vector3d& p, double radius) const {
    const std::optional<Nearest> found = nearest(p, radius);
    return found ? std::optional<Eigen::Vector3d>(found->point) : std::nullopt;
}

} // namespace liftremesh
