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

TEST(EdgeCollapse, NeverJoinsTwoBoundaryVerticesThroughTheInside) {
    // A strip one cell wide: every rung joins its two boundaries. Rung 5 is pinched to a short
    // edge; cells 4 and 5 are split by diagonals from its ends, the others fanned around a middle
    // vertex (so the vertices opposite the rung have four triangles). Collapsing the rung would
    // join the two boundaries at one vertex: a non-manifold vertex, the strip cut in two.
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    for (int i = 0; i <= 10; ++i) {
        p.emplace_back(i, 0.0, 0.0);
        p.emplace_back(i, i == 5 ? 0.04 : 1.0, 0.0);
    }
    for (int32_t i = 0; i < 10; ++i) {
        const int32_t a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1; // counter-clockwise
        if (i == 4) {
            f.push_back({a, b, d});
            f.push_back({d, b, c});
        } else if (i == 5) {
            f.push_back({a, b, c});
            f.push_back({a, c, d});
        } else {
            const auto m = static_cast<int32_t>(p.size());
            p.push_back((p[a] + p[b] + p[c] + p[d]) / 4.0);
            f.push_back({a, b, m});
            f.push_back({b, c, m});
            f.push_back({c, d, m});
            f.push_back({d, a, m});
        }
    }
    Mesh m = test::make_mesh(p, f);
    const test::Topology before = test::topology(m);
    ASSERT_TRUE(before.oriented_manifold());
    collapse_short_edges(m);
    const test::Topology after = test::topology(m);
    EXPECT_EQ(after.nonmanifold_vertices, 0);
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_EQ(after.boundary_edges, before.boundary_edges);
}
