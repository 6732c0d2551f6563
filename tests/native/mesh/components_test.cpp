// components.h: connected components, closedness, signed volumes, cavities, winding numbers.
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/components.h"
#include "liftremesh/mesh/mesh_io.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <numeric>

using namespace liftremesh;

namespace {

std::vector<int32_t> all_triangles(const Mesh& mesh) {
    std::vector<int32_t> ids(static_cast<size_t>(mesh.triangles.rows()));
    std::iota(ids.begin(), ids.end(), 0);
    return ids;
}

} // namespace

// Two boxes apart, the second inside-out: two closed components, volumes +6 and -1 exactly (a
// polyhedron's divergence-theorem volume is exact), areas 22 and 6, and the inside-out one is no
// cavity, lying outside the first.
TEST(Components, TwoBoxesOneInsideOut) {
    const Mesh mesh = test::joined(test::make_box({0, 0, 0}, {1, 2, 3}, 3), test::turned(test::make_box({5, 0, 0}, {6, 1, 1}, 2)));
    const MeshComponents split = mesh_components(mesh);
    ASSERT_EQ(split.components.size(), 2u);
    const MeshComponent &big = split.components[0], &small = split.components[1];
    EXPECT_TRUE(big.closed);
    EXPECT_TRUE(small.closed);
    EXPECT_NEAR(big.signed_volume, 6.0, 1e-12);
    EXPECT_NEAR(small.signed_volume, -1.0, 1e-12);
    EXPECT_NEAR(big.area, 22.0, 1e-12);
    EXPECT_NEAR(small.area, 6.0, 1e-12);
    EXPECT_EQ(big.triangles, 6 * 2 * 9);
    EXPECT_EQ(small.triangles, 6 * 2 * 4);
    EXPECT_FALSE(big.inward());
    EXPECT_TRUE(small.inward());
    EXPECT_FALSE(small.cavity);
    EXPECT_EQ(split.closed(), 2);
    EXPECT_EQ(split.inward(), 1);
    EXPECT_EQ(split.cavities(), 0);
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        EXPECT_EQ(split.label[f], f < big.triangles ? 0 : 1);
}

// A hollowed box: the outer wall facing out (+64), the inner wall facing in (-8), a cavity. The
// solid's volume is their sum.
TEST(Components, AHollowBoxsInnerWallIsACavity) {
    const Mesh mesh = test::joined(test::make_box({-2, -2, -2}, {2, 2, 2}, 4), test::turned(test::make_cube(1.0, 2)));
    const MeshComponents split = mesh_components(mesh);
    ASSERT_EQ(split.components.size(), 2u);
    EXPECT_NEAR(split.components[0].signed_volume, 64.0, 1e-12);
    EXPECT_NEAR(split.components[1].signed_volume, -8.0, 1e-12);
    EXPECT_FALSE(split.components[0].cavity);
    EXPECT_TRUE(split.components[1].cavity);
    EXPECT_EQ(split.inward(), 1);
    EXPECT_EQ(split.cavities(), 1);
    // The same inner box outside the outer one is no cavity.
    Mesh apart = test::turned(test::make_cube(1.0, 2));
    apart.points.col(0).array() += 10.0;
    EXPECT_EQ(mesh_components(test::joined(test::make_box({-2, -2, -2}, {2, 2, 2}, 4), apart)).cavities(), 0);
}

// An open patch: one component, not closed, no volume (its "volume" depends on the origin).
TEST(Components, AnOpenPatchHasNoVolume) {
    Mesh square = test::make_square(2.0, 3);
    square.points.col(2).array() += 5.0; // off the origin: a cone volume 2*2*5/3 were it counted
    const MeshComponents split = mesh_components(square);
    ASSERT_EQ(split.components.size(), 1u);
    EXPECT_FALSE(split.components[0].closed);
    EXPECT_EQ(split.components[0].signed_volume, 0.0);
    EXPECT_NEAR(split.components[0].area, 4.0, 1e-12);
    EXPECT_EQ(split.closed(), 0);
    EXPECT_EQ(split.inward(), 0);
}

// The icosphere's volume converges to the ball's from below; translated far from the origin it is
// the same (computed about a point of the component).
TEST(Components, VolumeDoesNotDependOnWhereTheSolidIs) {
    Mesh sphere = test::make_icosphere(3);
    const double at_origin = mesh_components(sphere).components[0].signed_volume;
    EXPECT_LT(at_origin, 4.0 / 3.0 * M_PI);
    EXPECT_GT(at_origin, 0.98 * 4.0 / 3.0 * M_PI);
    sphere.points.col(0).array() += 1e6;
    EXPECT_NEAR(mesh_components(sphere).components[0].signed_volume, at_origin, 1e-9 * at_origin);
}

// Spheres touching at a vertex are two closed surfaces, each with its own volume and
// orientation (solid_parts.h remeshes them together): the helper's second sphere is the first
// reflected through a point, which turns it inside-out. Cubes sharing an edge (used by four
// triangles) are two components, each closed.
TEST(Components, ComponentsAreJoinedThroughEdgesNotVertices) {
    const MeshComponents spheres = mesh_components(test::make_touching_spheres(1));
    ASSERT_EQ(spheres.components.size(), 2u);
    EXPECT_TRUE(spheres.components[0].closed);
    EXPECT_TRUE(spheres.components[1].closed);
    EXPECT_NEAR(spheres.components[1].signed_volume, -spheres.components[0].signed_volume, 1e-12);
    EXPECT_GT(spheres.components[0].signed_volume, 0.0);
    EXPECT_EQ(spheres.inward(), 1);
    EXPECT_EQ(spheres.cavities(), 0);

    Mesh pair = test::joined(test::make_box({0, 0, 0}, {1, 1, 1}, 1), test::make_box({1, 1, 0}, {2, 2, 1}, 1));
    weld_exact(pair); // the edge x = y = 1 now used by four triangles
    const MeshComponents cubes = mesh_components(pair);
    ASSERT_EQ(cubes.components.size(), 2u);
    EXPECT_TRUE(cubes.components[0].closed);
    EXPECT_TRUE(cubes.components[1].closed);
    EXPECT_NEAR(cubes.components[0].signed_volume, 1.0, 1e-12);
    EXPECT_NEAR(cubes.components[1].signed_volume, 1.0, 1e-12);
}

TEST(Components, WindingNumberIsOneInsideZeroOutsideMinusOneInsideOut) {
    const Mesh cube = test::make_cube(1.0, 3);
    const std::vector<int32_t> ids = all_triangles(cube);
    EXPECT_NEAR(winding_number(cube, ids, {0.2, -0.3, 0.9}), 1.0, 1e-12);
    EXPECT_NEAR(winding_number(cube, ids, {3.0, 0.1, 0.2}), 0.0, 1e-12);
    EXPECT_NEAR(winding_number(test::turned(cube), ids, {0.0, 0.0, 0.0}), -1.0, 1e-12);
}

TEST(Components, BadIndexIsInvalidInput) {
    Mesh cube = test::make_cube(1.0, 1);
    cube.triangles(3, 1) = 99;
    EXPECT_THROW(mesh_components(cube), InvalidInput);
}
