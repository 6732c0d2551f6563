#include "liftremesh/spatial/segment_index.h"

#include <algorithm>
#include <cmath>

namespace liftremesh {

SegmentIndex::SegmentIndex(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments, double step)
    : step_(step) {
    std::vector<Eigen::Vector3d> samples;
    for (size_t s = 0; s < segments.size(); ++s) {
        const auto& [a, b] = segments[s];
        const double steps = std::min(1e5, std::ceil((b - a).norm() / step));
        for (int i = 0; i <= static_cast<int>(steps); ++i) {
            samples.push_back(a + (b - a) * (i / std::max(1.0, steps)));
            sample_segment_.push_back(static_cast<int32_t>(s));
        }
    }
    if (samples.empty()) return;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> m(static_cast<Eigen::Index>(samples.size()), 3);
    for (size_t i = 0; i < samples.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
    tree_.emplace(m);
}

void SegmentIndex::near(const Eigen::Vector3d& p, double r, std::vector<int32_t>& out) const {
    out.clear();
    if (!tree_) return;
    tree_->within(p.data(), r + step_, out);
    for (int32_t& s : out) s = sample_segment_[s];
    // A segment has a sample every step: a point near it finds several, one is enough.
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

} // namespace liftremesh
