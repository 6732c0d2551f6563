// Segments found near a point through samples along them: the crease edges the snap moves
// vertices onto (edit/acute_creases.h) and those the held creases keep free sites off
// (cvt/crease_sites.h).
#pragma once

#include "liftremesh/spatial/neighbor_search.h"

#include <optional>
#include <utility>
#include <vector>

namespace liftremesh {

class SegmentIndex {
public:
    //! Over `segments`, each sampled at its ends and every `step` or closer between (at most 1e5
    //! pieces a segment). `step` positive.
    SegmentIndex(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments, double step);

    //! Replaces `out` by the segments with a sample within r + step of p, each once, by index:
    //! every segment that passes within r of p is among them. Thread-safe (const).
    void near(const Eigen::Vector3d& p, double r, std::vector<int32_t>& out) const;

private:
    std::optional<KdTree> tree_;
    std::vector<int32_t> sample_segment_;
    double step_ = 0.0;
};

} // namespace liftremesh
