#include "helpers.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace liftremesh;

namespace {

Eigen::Vector3d corner_of(const Mesh& m, Eigen::Index f, int j) { return m.points.row(m.triangles(f, j)).transpose(); }

//! The count by testing every pair of triangles (no tree), with the rules of the header: pairs
//! sharing an edge skipped, sides ending at a vertex of the other triangle not tested. (Touches
//! are left out: the random meshes below have none.)
long brute_force_count(const Mesh& m) {
    long pairs = 0;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (Eigen::Index g = f + 1; g < m.triangles.rows(); ++g) {
            int shared = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) shared += m.triangles(f, i) == m.triangles(g, j);
            if (shared >= 2) continue;
            bool crossing = false;
            for (const auto& [from, into] : {std::pair{f, g}, std::pair{g, f}})
                for (int i = 0; i < 3; ++i) {
                    const int32_t p = m.triangles(from, i), q = m.triangles(from, (i + 1) % 3);
                    const bool touches = (m.triangles(into, 0) == p || m.triangles(into, 1) == p || m.triangles(into, 2) == p ||
                                          m.triangles(into, 0) == q || m.triangles(into, 1) == q || m.triangles(into, 2) == q);
                    crossing = crossing || (!touches && segment_crosses_triangle(m.points.row(p).transpose(),
                                                                                 m.points.row(q).transpose(),
                                                                                 corner_of(m, into, 0), corner_of(m, into, 1),
                                                                                 corner_of(m, into, 2)));
                }
            pairs += crossing ? 1 : 0;
        }
    return pairs;
}

long count(const Mesh& m) { return count_self_intersections(m, AabbTree(m)); }

const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0); // a triangle in z = 0

} // namespace

TEST(SelfIntersection, ASegmentCrossesOnlyThroughTheInside) {
    EXPECT_TRUE(segment_crosses_triangle({0.5, 0.5, -1}, {0.5, 0.5, 1}, a, b, c));
    EXPECT_TRUE(segment_crosses_triangle({0.5, 0.5, 1}, {0.7, 0.2, -3}, a, b, c)); // either way
    EXPECT_FALSE(segment_crosses_triangle({0.5, 0.5, 0}, {0.5, 0.5, 1}, a, b, c));  // ends on it: touching
    EXPECT_FALSE(segment_crosses_triangle({0.5, 0.5, 0.1}, {0.5, 0.5, 1}, a, b, c)); // short of it
    EXPECT_FALSE(segment_crosses_triangle({1, 1, -1}, {1, 1, 1}, a, b, c));          // through its side bc
    EXPECT_FALSE(segment_crosses_triangle({0, 0, -1}, {0, 0, 1}, a, b, c));          // through its corner
    EXPECT_FALSE(segment_crosses_triangle({1.5, 1.5, -1}, {1.5, 1.5, 1}, a, b, c));  // beside it
    EXPECT_FALSE(segment_crosses_triangle({-1, 0.5, 0}, {3, 0.5, 0}, a, b, c));      // in its plane
    EXPECT_FALSE(segment_crosses_triangle({0.5, 0.5, -1}, {0.5, 0.5, 1}, a, b, 2 * b)); // degenerate
    // Scale-free: the same crossing a million times smaller and larger.
    for (double s : {1e-6, 1e6})
        EXPECT_TRUE(segment_crosses_triangle(s * Eigen::Vector3d(0.5, 0.5, -1), s * Eigen::Vector3d(0.5, 0.5, 1), s * a,
                                             s * b, s * c));
}

TEST(SelfIntersection, PairsAreCountedOnceByTheirCrossingSides) {
    auto mesh = [](std::vector<Eigen::Vector3d> pts, std::vector<std::array<int32_t, 3>> tris) {
        return test::make_mesh(pts, tris);
    };
    // Apart, crossing like an X: one pair.
    EXPECT_EQ(count(mesh({a, b, c, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.2, 0.3, 0.2}}, {{0, 1, 2}, {3, 4, 5}})), 1);
    // Sharing a vertex, the other side through the triangle: one; above it: none.
    EXPECT_EQ(count(mesh({a, b, c, {1, 0.5, -1}, {0.5, 1, 1}}, {{0, 1, 2}, {0, 3, 4}})), 1);
    EXPECT_EQ(count(mesh({a, b, c, {1, 0.5, 1}, {0.5, 1, 2}}, {{0, 1, 2}, {0, 3, 4}})), 0);
    // Sharing an edge, even folded flat onto each other: not a pair.
    EXPECT_EQ(count(mesh({a, b, c, {0.5, 0.5, 0}}, {{0, 1, 2}, {0, 1, 3}})), 0);
    // Coplanar neighbours touching at a vertex, as on a CAD face: none.
    EXPECT_EQ(count(mesh({a, b, c, {-2, 0, 0}, {-1, -2, 0}}, {{0, 1, 2}, {0, 3, 4}})), 0);
}

TEST(SelfIntersection, ACornerOnAnotherTriangleIsATouch) {
    auto mesh = [](std::vector<Eigen::Vector3d> pts, std::vector<std::array<int32_t, 3>> tris) {
        return test::make_mesh(pts, tris);
    };
    // Two sheets meeting along a crease, a corner of one on a side of the other, in its plane
    // (the connector's housings, FreeCAD's check) or leaning away from it: one pair each way.
    for (const Eigen::Vector3d& far : {Eigen::Vector3d(1, -1, 0), Eigen::Vector3d(1, -1, 1)}) {
        EXPECT_EQ(count(mesh({a, b, c, {1, 0, 0}, {0.5, -1, 0}, far}, {{0, 1, 2}, {3, 4, 5}})), 1) << far.transpose();
        EXPECT_EQ(count(mesh({a, b, c, {1, 0, 0}, {0.5, -1, 0}, far}, {{3, 4, 5}, {0, 1, 2}})), 1) << far.transpose();
    }
    // On the inside, and on a corner of the other at another index.
    EXPECT_EQ(count(mesh({a, b, c, {0.5, 0.5, 0}, {0.5, -1, -1}, {1, -1, 1}}, {{0, 1, 2}, {3, 4, 5}})), 1);
    EXPECT_EQ(count(mesh({a, b, c, {2, 0, 0}, {3, -1, 0}, {3, 1, 1}}, {{0, 1, 2}, {3, 4, 5}})), 1);
    // A thousandth of the side off the other triangle, beside it or above it: apart.
    EXPECT_EQ(count(mesh({a, b, c, {1, -2e-3, 0}, {0.5, -1, 0}, {1, -1, 1}}, {{0, 1, 2}, {3, 4, 5}})), 0);
    EXPECT_EQ(count(mesh({a, b, c, {0.5, 0.5, 2e-3}, {0.5, -1, 1}, {1, -1, 1}}, {{0, 1, 2}, {3, 4, 5}})), 0);
    // Sharing a vertex, the other corner on a side of the other (a T-junction, or a fold within
    // a fan): a touch; the shared corner itself is none.
    EXPECT_EQ(count(mesh({a, b, c, {1, 0, 0}, {1, -1, 0}}, {{0, 1, 2}, {0, 4, 3}})), 1);
    EXPECT_EQ(count(mesh({a, b, c, {-1, -1, 0}, {1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}})), 0);
}

TEST(SelfIntersection, ClosedSurfacesHaveNone) {
    EXPECT_EQ(count(test::make_icosphere(3)), 0);
    EXPECT_EQ(count(test::make_torus(1.0, 0.3, 48, 16)), 0);
    EXPECT_EQ(count(test::make_cube(1.0, 6)), 0);
}

TEST(SelfIntersection, TheTreeFindsWhatEveryPairFinds) {
    // A sphere with its vertices pushed about by up to two edge lengths: many crossings.
    Mesh m = test::make_icosphere(2); // edges of about 0.3
    std::mt19937 random(3);
    std::uniform_real_distribution<double> push(-0.3, 0.3);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v)
        for (int k = 0; k < 3; ++k) m.points(v, k) += push(random);
    const long expected = brute_force_count(m);
    EXPECT_GT(expected, 20);
    EXPECT_EQ(count(m), expected);
    // Two spheres through each other, as one mesh: the pairs where they cross.
    Mesh moved = test::make_icosphere(2);
    moved.points.rowwise() += Eigen::RowVector3d(0.9, 0.1, 0.05);
    const Mesh two = test::joined(test::make_icosphere(2), moved);
    const long crossing = brute_force_count(two);
    EXPECT_GT(crossing, 0);
    EXPECT_EQ(count(two), crossing);
}

TEST(SelfIntersection, PairsAreTheCountedOnesInOrderEachCrossing) {
    Mesh m = test::make_icosphere(2);
    std::mt19937 random(4);
    std::uniform_real_distribution<double> push(-0.3, 0.3);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v)
        for (int k = 0; k < 3; ++k) m.points(v, k) += push(random);
    const AabbTree tree(m);
    const auto pairs = self_intersecting_pairs(m, tree);
    EXPECT_GT(pairs.size(), 20u);
    EXPECT_EQ(static_cast<long>(pairs.size()), count_self_intersections(m, tree));
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    EXPECT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end());
    auto triangle = [&](int32_t f) {
        return std::array<int32_t, 3>{m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)};
    };
    auto at = [&](int32_t f) { return std::array<Eigen::Vector3d, 3>{corner_of(m, f, 0), corner_of(m, f, 1), corner_of(m, f, 2)}; };
    for (const auto& [s, t] : pairs) {
        EXPECT_LT(s, t);
        EXPECT_TRUE(triangles_cross(triangle(s), at(s), triangle(t), at(t))) << s << " " << t;
    }
}
