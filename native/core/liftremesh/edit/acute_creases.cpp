#include "liftremesh/edit/acute_creases.h"

#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

double AcuteCreases::distance_across(const Eigen::Vector3d& p, long s, double radius) const {
    double nearest = std::numeric_limits<double>::infinity();
    if (!index_) return nearest;
    index_->near(p, radius, found_);
    for (const int32_t k : found_) {
        if (k == s) continue;
        const auto& [a, b] = segments_[k];
        const Eigen::Vector3d ab = b - a;
        const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), std::numeric_limits<double>::min()), 0.0, 1.0);
        // Nearest at an end it shares with s: the crease turning on, not another running beside.
        const int32_t at = t == 0.0 ? ends_[k].first : t == 1.0 ? ends_[k].second : -1;
        if (at >= 0 && (at == ends_[s].first || at == ends_[s].second)) continue;
        nearest = std::min(nearest, (a + t * ab - p).norm());
    }
    return nearest;
}

std::vector<AcuteCreases::Bend> AcuteCreases::bends(double min_turn_deg) const {
    // Each inner vertex's two crease edges.
    std::unordered_map<int32_t, std::pair<long, long>> edges_at;
    for (long s = 0; s < size(); ++s)
        for (const int32_t v : {ends_[s].first, ends_[s].second})
            if (degree_.at(v) == 2) {
                auto [it, fresh] = edges_at.try_emplace(v, s, -1L);
                if (!fresh) it->second.second = s;
            }
    const double min_cos = std::cos(min_turn_deg * M_PI / 180.0);
    std::vector<Bend> out;
    for (const auto& [v, pair] : edges_at) {
        const auto& [s, t] = pair;
        if (t < 0) continue;
        // Both edges' directions taken away from v: a straight chain has them opposite.
        auto away = [&](long e) {
            const auto& [a, b] = segments_[e];
            return ends_[e].first == v ? Eigen::Vector3d(b - a) : Eigen::Vector3d(a - b);
        };
        const Eigen::Vector3d u = away(s), w = away(t);
        const double lengths = u.norm() * w.norm();
        if (!(lengths > 0.0)) continue;
        const double cosine = -u.dot(w) / lengths;
        if (cosine > min_cos) continue;
        const Eigen::Vector3d x = ends_[s].first == v ? segments_[s].first : segments_[s].second;
        out.push_back({x, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI});
    }
    std::sort(out.begin(), out.end(), [](const Bend& l, const Bend& r) {
        return std::lexicographical_compare(l.point.data(), l.point.data() + 3, r.point.data(), r.point.data() + 3);
    });
    return out;
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
