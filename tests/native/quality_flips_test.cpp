// Quality flips: a flat quad split along its longer diagonal is flipped, a sharp edge and a
// flip that moves the surface away from the input are not, and a closed surface keeps its
// topology, its orientation and its worst triangle at least as good.
#include "liftremesh/exceptions.h"
#include "liftremesh/quality.h"
#include "liftremesh/quality_flips.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <random>

using namespace liftremesh;

namespace {
// The quad a = (-1, 0, 0), b = (1, 0, 0), c = (0, 0.4, 0), d as given, split along a-b:
// triangles (a, b, c) and (b, a, d), both thin (kappa 0.27); the diagonal c-d makes two of kappa
// 0.93 when flat.
Mesh kite(const Eigen::Vector3d& d) {
    return test::make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, 0.4, 0}, d}, {{0, 1, 2}, {1, 0, 3}});
}
bool has_edge(const Mesh& m, int32_t u, int32_t v) {
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (std::minmax(m.triangles(f, j), m.triangles(f, (j + 1) % 3)) == std::minmax(u, v)) return true;
    return false;
}
} // namespace

TEST(QualityFlips, AFlatQuadGetsItsShorterDiagonal) {
    Mesh m = kite({0, -0.4, 0});
    const AabbTree input(m);
    const double before = test::min_kappa(m);
    EXPECT_EQ(flip_for_quality(m, input, 0.01), 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    EXPECT_GT(test::min_kappa(m), before + 0.3);
    EXPECT_EQ(test::facing_inward(m, {0, 0, -1}), 0); // both still face +z
    EXPECT_EQ(euler_characteristic(m), 1);
    EXPECT_EQ(flip_for_quality(m, input, 0.01), 0); // nothing left to improve
}

TEST(QualityFlips, ASharpEdgeIsNeverFlipped) {
    Mesh m = kite({0, 0, -0.4}); // the second triangle turned by 90 degrees about a-b
    const AabbTree input(m);
    EXPECT_EQ(flip_for_quality(m, input, 1e3), 0);
    EXPECT_TRUE(has_edge(m, 0, 1));
}

TEST(QualityFlips, AFlipThatLeavesTheInputIsNotMade) {
    // Bent by about 10 degrees about a-b: the diagonal c-d passes 0.035 from the input (the quad).
    Mesh bent = kite({0, -0.4, 0.07});
    const AabbTree input(bent);
    Mesh tight = bent;
    EXPECT_EQ(flip_for_quality(tight, input, 0.05), 0); // 0.035 > half the tolerance, and a-b lies on it
    EXPECT_EQ(flip_for_quality(bent, input, 0.1), 1);   // 0.035 <= 0.05
}

TEST(QualityFlips, AClosedSurfaceKeepsItsTopologyAndGetsNoWorse) {
    Mesh m = test::make_icosphere(3);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v) {
        m.points.row(v) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
        m.points.row(v).normalize();
    }
    const AabbTree input(m);
    const double before = test::min_kappa(m);
    const long flips = flip_for_quality(m, input, 0.05);
    EXPECT_GT(flips, 0);
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(test::facing_inward(m, Eigen::Vector3d::Zero()), 0);
    EXPECT_GT(test::min_kappa(m), before);
    EXPECT_LE(hausdorff_distance(m, test::make_icosphere(3)).hausdorff, 0.05);
}

TEST(QualityFlips, BadArgumentsAreRejected) {
    Mesh m = kite({0, -0.4, 0});
    const AabbTree input(m);
    EXPECT_THROW(flip_for_quality(m, input, 0.0), InvalidInput);
    EXPECT_THROW(flip_for_quality(m, input, std::nan("")), InvalidInput);
    EXPECT_THROW(flip_for_quality(m, input, 0.1, -1), InvalidInput);
    m.triangles(0, 0) = 9;
    EXPECT_THROW(flip_for_quality(m, input, 0.1), InvalidInput);
}
