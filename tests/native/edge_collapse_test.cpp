#include "liftremesh/edge_collapse.h"
#include "liftremesh/quality.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

TEST(EdgeCollapse, RemovesACrowdedVertexAndKeepsTopology) {
    Mesh m = test::make_icosphere(3);
    // Pull vertex 50 almost onto one of its neighbours: two very short edges' worth of slivers.
    int32_t neighbour = -1;
    for (Eigen::Index f = 0; f < m.triangles.rows() && neighbour < 0; ++f)
        for (int j = 0; j < 3; ++j)
            if (m.triangles(f, j) == 50) neighbour = m.triangles(f, (j + 1) % 3);
    m.points.row(50) = 0.97 * m.points.row(neighbour) + 0.03 * m.points.row(50);
    const double before = test::min_kappa(m);
    const long vertices = m.points.rows();
    const long collapsed = collapse_short_edges(m);
    EXPECT_GE(collapsed, 1);
    EXPECT_EQ(m.points.rows(), vertices - collapsed);
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_GT(test::min_kappa(m), std::max(0.3, 2 * before));
    EXPECT_EQ(test::facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(EdgeCollapse, LeavesAGoodMeshAlone) {
    Mesh m = test::make_icosphere(3);
    const Mesh original = m;
    EXPECT_EQ(collapse_short_edges(m), 0);
    EXPECT_EQ(m.triangles, original.triangles);
}

TEST(EdgeCollapse, RefusesCollapsesThatBreakTheLinkCondition) {
    // A tetrahedron: every collapse would make it degenerate.
    Mesh m = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.01}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
    EXPECT_EQ(collapse_short_edges(m, 10.0), 0);
    EXPECT_EQ(m.triangles.rows(), 4);
}
