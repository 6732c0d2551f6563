// Untangling: flips, then vertex moves, that take triangles out of each other, and only where they
// keep the surface on the input.
#include "helpers.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/repair/untangle.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <utility>
#include <vector>

using namespace liftremesh;

namespace {

// A quad a, c, b, d (a = origin, b = (1, 1, 0), c = (1, 0, 1), d = (0, 1, 1)), all four of its
// triangles either way equilateral, and a small upright triangle T at x = 0.7 standing in the
// tetrahedron abcd. Split along a-b (the valley: a, b low, c, d high) the quad passes through
// T, where it is at z = x - y = 0.5; split along c-d (the tent) it is at z = x + y = 0.9, above.
const std::vector<Eigen::Vector3d> kPoints = {
    {0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {0.7, 0.15, 0.3}, {0.7, 0.25, 0.3}, {0.7, 0.2, 0.7}};
const std::array<int32_t, 3> kT = {4, 5, 6};

Mesh valley() { return make_mesh(kPoints, {{0, 1, 2}, {1, 0, 3}, kT}); }
Mesh tent() { return make_mesh(kPoints, {{0, 3, 2}, {3, 1, 2}, kT}); }

std::vector<std::pair<int32_t, int32_t>> crossings(const Mesh& m) { return self_intersecting_pairs(m, AabbTree(m)); }

UntangleParams with_tolerance(double tolerance) {
    UntangleParams p;
    p.tolerance = tolerance;
    return p;
}

} // namespace

TEST(Untangle, AFlipTakesAQuadOutOfATriangleItPassesThrough) {
    Mesh m = valley();
    const auto before = crossings(m);
    ASSERT_EQ(before.size(), 1u); // the valley's first triangle and T
    EXPECT_EQ(crossings(tent()).size(), 0u);
    // The input is the tent: the flip puts the quad on it.
    const Mesh input = tent();
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.flipped, 1);
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    EXPECT_EQ(m.triangles.rows(), 3);
    EXPECT_EQ(m.points, valley().points); // no vertex moved or added
    EXPECT_EQ(euler_characteristic(m), euler_characteristic(valley()));
}

TEST(Untangle, NoFlipTakesTheSurfaceOffTheInput) {
    // The input is the valley itself: the tent lies up to 0.5 off it, beyond the tolerance, so
    // the crossing stays; with a tolerance past that distance the flip is made.
    Mesh m = valley();
    const Mesh input = valley();
    const UntangleStats kept = untangle(m, test::OwnedReference(input), with_tolerance(0.05));
    EXPECT_EQ(kept.flipped, 0);
    EXPECT_EQ(kept.crossings.size(), 1u);
    EXPECT_EQ(m.triangles, valley().triangles);
    const UntangleStats flipped = untangle(m, test::OwnedReference(input), with_tolerance(1.0));
    EXPECT_EQ(flipped.flipped, 1);
    EXPECT_TRUE(flipped.crossings.empty());
}

TEST(Untangle, AFlipThatLeavesAsManyCrossingsIsNotMade) {
    // T stretched from z = -0.5 to 1.5: through the valley and through the tent alike.
    std::vector<Eigen::Vector3d> points = kPoints;
    points[4].z() = points[5].z() = -0.5;
    points[6].z() = 1.5;
    Mesh m = make_mesh(points, {{0, 1, 2}, {1, 0, 3}, kT});
    ASSERT_EQ(crossings(m).size(), 1u);
    ASSERT_EQ(crossings(make_mesh(points, {{0, 3, 2}, {3, 1, 2}, kT})).size(), 1u);
    const Mesh input = m;
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(1.0));
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(m.triangles, input.triangles);
}

TEST(Untangle, LeavesAMeshWithoutCrossingsOrWithoutAFlipThatHelpsAsItIs) {
    Mesh sphere = test::make_icosphere(2);
    const Mesh original = sphere;
    EXPECT_EQ(untangle(sphere, test::OwnedReference(original), with_tolerance(0.01)).flipped, 0);
    EXPECT_EQ(sphere.triangles, original.triangles);
    // Two loose triangles through each other: no edge to flip.
    Mesh pair = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -0.5}, {0.3, 0.2, 0.5}, {0.2, 0.3, 0.5}},
                          {{0, 1, 2}, {3, 4, 5}});
    ASSERT_EQ(crossings(pair).size(), 1u);
    const UntangleStats stats = untangle(pair, test::OwnedReference(pair), with_tolerance(0.01));
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(stats.moved, 0); // their corners end edges of one triangle: on a border, never moved
    EXPECT_EQ(stats.crossings.size(), 1u);
}

TEST(Untangle, AVertexPushedThroughTheOtherSideIsMovedBackOntoTheInput) {
    // A sphere with one vertex pushed through its centre to 0.3 beyond the far side: its fan
    // passes through the far side, which flips cannot undo (they only lessen it). The vertex
    // goes back onto the input, near the centroid of its neighbours; no other vertex moves.
    const Mesh input = test::make_icosphere(3);
    Mesh m = input;
    const Eigen::Index v = 0;
    const Eigen::Vector3d p = m.points.row(v);
    m.points.row(v) = -1.3 * p;
    ASSERT_FALSE(crossings(m).empty());
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.moved, 1);
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    const Eigen::Vector3d back = m.points.row(v);
    EXPECT_NEAR(back.norm(), 1.0, 0.01);   // on the input (the sphere's flat facets)
    EXPECT_LT((back - p).norm(), 0.1);     // among its neighbours again (edges of about 0.16)
    EXPECT_EQ(euler_characteristic(m), 2); // flips keep the topology
    for (Eigen::Index w = 1; w < m.points.rows(); ++w) EXPECT_EQ(m.points.row(w), input.points.row(w)) << w;
}

TEST(Untangle, NoMoveMakesATriangleFaceAgainstTheInput) {
    // The same vertex pushed through, with an input that is the sphere turned inside out: the
    // move back would leave the vertex's fan facing against it, so the crossings stay.
    Mesh input = test::make_icosphere(3);
    input.triangles.col(1).swap(input.triangles.col(2));
    Mesh m = test::make_icosphere(3);
    m.points.row(0) *= -1.3;
    const Mesh pushed = m;
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.moved, 0);
    EXPECT_FALSE(stats.crossings.empty());
    EXPECT_EQ(m.points, pushed.points);
}

TEST(Untangle, RefusesABadTolerance) {
    Mesh m = valley();
    const AabbTree input(tent());
    for (double tolerance : {0.0, -1.0, std::numeric_limits<double>::infinity()})
        EXPECT_THROW(untangle(m, {tent(), input}, with_tolerance(tolerance)), InvalidInput) << tolerance;
}
