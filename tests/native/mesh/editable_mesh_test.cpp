// The local edits shared by patch refinement and the Hausdorff refinement: edge uses, the quad
// of an edge, splits and flips keep an oriented surface.
#include "liftremesh/mesh/editable_mesh.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace liftremesh;

namespace {
// The unit square as two triangles (0, 1, 2) and (0, 2, 3), counter-clockwise seen from +z.
Mesh square() {
    return test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

// n flags, those at `set` up.
std::vector<char> flags(size_t n, std::initializer_list<size_t> set) {
    std::vector<char> out(n, 0);
    for (const size_t i : set) out[i] = 1;
    return out;
}
} // namespace

TEST(EditableMesh, QuadOfTheDiagonalThenFlipAndSplitKeepOrientation) {
    EditableMesh m(square());
    const auto uses = m.edge_uses();
    ASSERT_EQ(uses.size(), 5u);
    EXPECT_EQ(uses.at(edge_key(0, 1)).size(), 1u); // a boundary edge
    const auto quad = m.quad_of(uses.at(edge_key(0, 2)));
    ASSERT_TRUE(quad);
    EXPECT_EQ(std::min(quad->a, quad->b), 0);
    EXPECT_EQ(std::max(quad->a, quad->b), 2);
    EXPECT_EQ(quad->c + quad->d, 4); // 1 and 3
    EXPECT_FALSE(m.quad_of(uses.at(edge_key(0, 1))));

    m.flip(*quad); // now the diagonal 1-3
    EXPECT_EQ(m.edge_uses().count(edge_key(0, 2)), 0u);
    EXPECT_EQ(m.edge_uses().at(edge_key(1, 3)).size(), 2u);
    for (const auto& t : m.tris) EXPECT_GT(m.normal(t).z(), 0.0);

    const auto diagonal = m.quad_of(m.edge_uses().at(edge_key(1, 3)));
    ASSERT_TRUE(diagonal);
    const int32_t mid = m.split_edge(*diagonal, Eigen::Vector3d(0.5, 0.5, 0.0));
    EXPECT_EQ(mid, 4);
    ASSERT_EQ(m.tris.size(), 4u);
    for (const auto& t : m.tris) EXPECT_NEAR(m.normal(t).z(), 0.5, 1e-12); // each a quarter, facing +z
    const Mesh out = m.to_mesh();
    const test::Topology topo = test::topology(out);
    EXPECT_TRUE(topo.oriented_manifold());
    EXPECT_EQ(topo.chi, 1);
    EXPECT_EQ(topo.boundary_edges, 4);
}

TEST(EditableMesh, UsesAroundFlaggedVerticesAreThoseOfTheWholeMeshThere) {
    EditableMesh m(test::make_cube(0.5, 4));
    const auto all = m.edge_uses();
    const std::vector<char> flagged = flags(m.points.size(), {7, 30});
    const auto around = m.edge_uses_around(flagged);
    ASSERT_FALSE(around.empty());
    for (const auto& [key, uses] : all) {
        const auto a = static_cast<int32_t>(key >> 32), b = static_cast<int32_t>(key & 0xffffffffu);
        const bool near = flagged[a] || flagged[b];
        ASSERT_EQ(around.count(key), near ? 1u : 0u);
        if (!near) continue;
        EXPECT_EQ(around.at(key).size(), uses.size());
        EXPECT_EQ(around.at(key)[0].tri, uses[0].tri);
        EXPECT_EQ(around.at(key)[1].tri, uses[1].tri);
    }
}

// What the flips round an edit read: the fan of every corner of every quad with a listed
// triangle, as the whole mesh's fans have it; and far from the edit, nothing.
TEST(EditableMesh, FansNearListedTrianglesAreThoseOfTheWholeMeshAtTheirQuads) {
    EditableMesh m(test::make_cube(0.5, 4));
    m.keep_fans();
    const CompressedRows all = m.fans();
    const std::vector<int> around = {5, 40};
    const EditableMesh::FanSnapshot near = m.fans_near(around);
    auto row = [](const std::pair<const int32_t*, const int32_t*>& r) { return std::vector<int32_t>(r.first, r.second); };
    std::vector<char> corner(m.points.size(), 0);
    for (const auto& [key, uses] : m.edge_uses()) {
        const auto quad = m.quad_of(uses);
        if (!quad || !(quad->t1 == 5 || quad->t1 == 40 || quad->t2 == 5 || quad->t2 == 40)) continue;
        for (const int32_t v : {quad->a, quad->b, quad->c, quad->d}) corner[v] = 1;
    }
    long empty = 0;
    for (int32_t v = 0; v < static_cast<int32_t>(m.points.size()); ++v) {
        const auto given = near(v);
        if (corner[v]) EXPECT_NE(given.first, given.second) << "point " << v;
        if (given.first != given.second)
            EXPECT_EQ(row(given), row({all.begin(v), all.end(v)})) << "point " << v; // whole, in triangle order
        else
            ++empty;
    }
    EXPECT_GT(empty, static_cast<long>(m.points.size()) / 2); // far from the two triangles
}

// The uses near some points, found through the kept fans after edits, are those a scan of the
// edited mesh finds; and the journal puts the mesh and its fans back as they were.
TEST(EditableMesh, KeptFansFollowEditsAndTheJournalUndoesThem) {
    EditableMesh m(test::make_cube(0.5, 4));
    m.keep_fans();
    const std::vector<EditableMesh::Tri> before = m.tris;
    const size_t points = m.points.size();
    auto fans_match_a_scan = [&]() {
        const CompressedRows all = m.fans();
        for (int32_t v = 0; v < static_cast<int32_t>(m.points.size()); ++v) {
            std::vector<int32_t> kept = m.fan(v);
            std::sort(kept.begin(), kept.end());
            if (kept != std::vector<int32_t>(all.begin(v), all.end(v))) return false;
        }
        return true;
    };
    m.begin_edits();
    // An edge of triangle 7 split, then every edge round the new point flipped that can be.
    const auto quad = m.quad_at(7, 0);
    ASSERT_TRUE(quad);
    const int32_t mid = m.split_edge(*quad, 0.5 * (m.points[quad->a] + m.points[quad->b]));
    std::vector<int> flipped;
    const long flips = m.flip_pass_near(m.fan(mid), [](const EditableMesh::Quad&) { return true; }, flipped);
    EXPECT_GT(flips, 0);
    EXPECT_EQ(flipped.size(), 2u * static_cast<size_t>(flips));
    EXPECT_TRUE(fans_match_a_scan());
    EXPECT_TRUE(m.joined(mid, quad->a));
    const std::vector<int32_t> near = {mid, 3};
    const auto local = m.edge_uses_near(near);
    std::vector<char> flagged(m.points.size(), 0);
    for (const int32_t v : near) flagged[v] = 1;
    const auto scanned = m.edge_uses_around(flagged);
    ASSERT_EQ(local.size(), scanned.size());
    for (const auto& [key, uses] : scanned) {
        ASSERT_EQ(local.count(key), 1u);
        EXPECT_EQ(local.at(key).size(), uses.size());
        for (int i = 0; i < std::min(uses.count, 2); ++i) {
            EXPECT_EQ(local.at(key)[i].tri, uses[i].tri);
            EXPECT_EQ(local.at(key)[i].j, uses[i].j);
        }
    }
    m.roll_back();
    EXPECT_EQ(m.tris, before);
    EXPECT_EQ(m.points.size(), points);
    EXPECT_TRUE(fans_match_a_scan());
}

TEST(EditableMesh, QualityFlipOnlyForANearlyPlanarQuadThatGetsBetter) {
    // A thin rhombus split along its long diagonal: flipping to the short one is better.
    EditableMesh flat(test::make_mesh({{0, 0, 0}, {2, -0.3, 0}, {4, 0, 0}, {2, 0.3, 0}}, {{0, 1, 2}, {0, 2, 3}}));
    const auto q = flat.quad_of(flat.edge_uses().at(edge_key(0, 2)));
    ASSERT_TRUE(q);
    EXPECT_TRUE(flat.flip_improves_quality(*q));
    flat.flip(*q);
    const auto back = flat.quad_of(flat.edge_uses().at(edge_key(1, 3)));
    ASSERT_TRUE(back);
    EXPECT_FALSE(flat.flip_improves_quality(*back)); // and not back again
    // The same rhombus folded 90 degrees along the long diagonal: a flip would change the shape.
    EditableMesh folded(test::make_mesh({{0, 0, 0}, {2, -0.3, 0}, {4, 0, 0}, {2, 0, 0.3}}, {{0, 1, 2}, {0, 2, 3}}));
    const auto f = folded.quad_of(folded.edge_uses().at(edge_key(0, 2)));
    ASSERT_TRUE(f);
    EXPECT_FALSE(folded.flip_improves_quality(*f));
}
