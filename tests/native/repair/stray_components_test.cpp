// stray_components.h: closed pieces of an output that stand for no part of the input.
#include "liftremesh/repair/stray_components.h"
#include "helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

namespace {

//! A small box of side `s` at `at`, inside-out.
Mesh inverted_box(const Eigen::Vector3d& at, double s) {
    return test::turned(test::make_box(at, at + Eigen::Vector3d::Constant(s), 1));
}

StrayComponentParams params_of(const Mesh& input) { return stray_component_params(mesh_components(input)); }

} // namespace

TEST(StrayComponents, ParamsCountTheInputsPiecesAndCavities) {
    const Mesh hollow = test::joined(test::make_cube(2.0, 4), test::turned(test::make_cube(1.0, 2)));
    const StrayComponentParams p = params_of(hollow);
    EXPECT_EQ(p.pieces, 2);
    EXPECT_EQ(p.inward, 1);
    EXPECT_NEAR(p.max_area, kStrayShare * 24.0, 1e-12); // the inner cube's area, the smaller
}

// The frame's case: the part and two small inside-out bubbles beside it (one inside its
// material, one outside). Both go, the part stays as it was.
TEST(StrayComponents, SmallInsideOutPiecesAreRemoved) {
    const Mesh part = test::make_cube(2.0, 6); // area 96, max_area 0.96
    const Mesh output = test::joined(test::joined(part, inverted_box({0.1, 0.1, 0.1}, 0.3)), inverted_box({3, 0, 0}, 0.2));
    Mesh cleaned = output;
    const StrayComponentStats stats = remove_stray_components(cleaned, params_of(part));
    EXPECT_EQ(stats.removed, 2);
    EXPECT_EQ(stats.inward_removed, 2);
    EXPECT_EQ(stats.triangles_removed, 24);
    ASSERT_EQ(cleaned.triangles.rows(), part.triangles.rows());
    ASSERT_EQ(cleaned.points.rows(), part.points.rows());
    EXPECT_EQ(cleaned.points, part.points);
    EXPECT_EQ(cleaned.triangles, part.triangles);
    const MeshComponents after = mesh_components(cleaned);
    EXPECT_EQ(after.components.size(), 1u);
    EXPECT_EQ(after.inward(), 0);
}

// A hollowed solid keeps its cavity; a second inward piece beyond the input's one goes, the
// cavity (inside the outer wall) kept rather than the piece outside, though that is larger.
TEST(StrayComponents, ACavityOfTheInputIsKept) {
    const Mesh hollow = test::joined(test::make_cube(2.0, 4), test::turned(test::make_cube(0.3, 2)));
    Mesh same = hollow;
    EXPECT_EQ(remove_stray_components(same, params_of(hollow)).removed, 0);
    EXPECT_EQ(same.triangles, hollow.triangles);
    Mesh with_bubble = test::joined(hollow, inverted_box({5, 0, 0}, 1.0)); // volume -1, the cavity's -0.216
    StrayComponentParams p = params_of(hollow);
    p.max_area = 10.0; // both inward pieces small enough: the ranking chooses
    const StrayComponentStats stats = remove_stray_components(with_bubble, p);
    EXPECT_EQ(stats.removed, 1);
    const MeshComponents after = mesh_components(with_bubble);
    ASSERT_EQ(after.components.size(), 2u);
    EXPECT_EQ(after.cavities(), 1);
    EXPECT_NEAR(after.components[1].signed_volume, -0.216, 1e-12);
}

// A small outward piece beyond the input's count goes; a large one stays (a part that broke
// off is geometry of the input: the report warns instead); so does a large inverted piece.
TEST(StrayComponents, OnlySmallPiecesBeyondTheCountsGo) {
    const Mesh part = test::make_cube(2.0, 6);
    Mesh small_outward = test::joined(part, test::make_box({5, 0, 0}, {5.2, 0.2, 0.2}, 1));
    EXPECT_EQ(remove_stray_components(small_outward, params_of(part)).removed, 1);
    EXPECT_EQ(small_outward.triangles.rows(), part.triangles.rows());
    for (const Mesh& large : {test::make_box({5, 0, 0}, {7, 2, 2}, 1), inverted_box({5, 0, 0}, 2.0)}) {
        Mesh output = test::joined(part, large);
        EXPECT_EQ(remove_stray_components(output, params_of(part)).removed, 0);
        EXPECT_EQ(output.triangles.rows(), part.triangles.rows() + large.triangles.rows());
    }
    // As many pieces as the input has: none is stray, however small.
    const Mesh two = test::joined(part, test::make_box({5, 0, 0}, {5.2, 0.2, 0.2}, 1));
    Mesh out = two;
    EXPECT_EQ(remove_stray_components(out, params_of(two)).removed, 0);
}
