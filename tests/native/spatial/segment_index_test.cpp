#include "liftremesh/spatial/segment_index.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace liftremesh;

// Two segments 1 apart, one 10 long and sampled every 0.25: from a point 0.4 off the first's
// middle (far from any of its ends) the first is near within 0.5, the second is not; within 1.5
// both are. Every segment within r comes out, whatever the sampling.
TEST(SegmentIndex, FindsTheSegmentsPassingWithinTheRadius) {
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments = {
        {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0)}, {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(10, 1, 0)}};
    const SegmentIndex index(segments, 0.25);
    std::vector<int32_t> found;
    auto has = [&found](int32_t s) { return std::find(found.begin(), found.end(), s) != found.end(); };
    index.near(Eigen::Vector3d(5.1, -0.4, 0), 0.5, found);
    EXPECT_TRUE(has(0));
    EXPECT_FALSE(has(1));
    index.near(Eigen::Vector3d(5.1, -0.4, 0), 1.5, found);
    EXPECT_EQ(found, (std::vector<int32_t>{0, 1})); // each once, though several samples are near
    index.near(Eigen::Vector3d(5.1, 5.0, 0), 0.5, found);
    EXPECT_TRUE(found.empty());
    const SegmentIndex none({}, 0.25);
    none.near(Eigen::Vector3d::Zero(), 1.0, found);
    EXPECT_TRUE(found.empty());
}
