#include "liftremesh/mesh/creases.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace liftremesh;

// A cube whose faces are 6 x 6 squares, each cut in two: its 12 edges are 72 crease edges turning
// by 90 degrees, and no edge inside a face turns at all.
TEST(Creases, OfACubeAreItsEdgesAtNinetyDegrees) {
    const Mesh cube = test::make_cube(0.5, 6);
    const std::vector<CreaseEdge> creases = crease_edges(cube, 30.0);
    ASSERT_EQ(creases.size(), 72u);
    for (const CreaseEdge& e : creases) {
        EXPECT_NEAR(e.turn_deg, 90.0, 1e-9);
        const Eigen::Vector3d a = cube.points.row(e.a).transpose(), b = cube.points.row(e.b).transpose();
        // Both ends on the same cube edge: two coordinates at +-0.5 shared.
        int on_edge = 0;
        for (int i = 0; i < 3; ++i) on_edge += std::abs(std::abs(a[i]) - 0.5) < 1e-12 && a[i] == b[i];
        EXPECT_EQ(on_edge, 2);
        EXPECT_NEAR((a - b).norm(), 1.0 / 6.0, 1e-12);
    }
    EXPECT_TRUE(crease_edges(cube, 90.5).empty());
}

// The chains are the cube's edges all joined (12 in all): shorter than that in all, none is kept.
TEST(Creases, ChainsShorterThanTheMinimumLengthAreLeftOut) {
    const Mesh cube = test::make_cube(0.5, 6);
    EXPECT_EQ(crease_edges(cube, 30.0, 11.9).size(), 72u);
    EXPECT_TRUE(crease_edges(cube, 30.0, 12.1).empty());
}
