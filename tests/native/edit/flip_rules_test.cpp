// The flip rules' guards against folds across a quad's rim and against crossings round its
// corners (flip_rules.h: flip_folds_rim, flip_crosses_fans), and the counts they rest on.
#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

namespace {

// The quad a = (0, 0, 0), b = (0.5, 1, 0), c = (1, 0, 0), d = (-0.5, 0.8, 0.214): triangles
// (a, b, c), facing -z, and (b, a, d); flipped, (a, d, c) faces (0, 0.26, -0.97), turned 15
// degrees from it. Across the rim edge c-a lies (a, c, e).
bool flip_folds(const Eigen::Vector3d& e) {
    const Mesh m = test::make_mesh({{0, 0, 0}, {0.5, 1, 0}, {1, 0, 0}, {-0.5, 0.8, 0.214}, e}, {{0, 1, 2}, {1, 0, 3}, {0, 2, 4}});
    const EditableMesh mesh(m);
    const auto quad = mesh.quad_of(mesh.edge_uses().at(edge_key(0, 1)));
    EXPECT_TRUE(quad.has_value());
    return flip_folds_rim(mesh, *quad, fans_of(mesh.fans()));
}

// The same quad with (a, e, f) on its corner a, standing where the flip's (a, d, c), which rises
// to z = 0.2675 y over (a, b, c) at z = 0, would lie.
bool flip_crosses(const Eigen::Vector3d& e, const Eigen::Vector3d& f) {
    const Mesh m =
        test::make_mesh({{0, 0, 0}, {0.5, 1, 0}, {1, 0, 0}, {-0.5, 0.8, 0.214}, e, f}, {{0, 1, 2}, {1, 0, 3}, {0, 4, 5}});
    const EditableMesh mesh(m);
    const auto quad = mesh.quad_of(mesh.edge_uses().at(edge_key(0, 1)));
    EXPECT_TRUE(quad.has_value());
    return flip_crosses_fans(mesh, *quad, fans_of(mesh.fans()));
}

} // namespace

TEST(FlipRules, AFlipThatFoldsATriangleOntoItsRimNeighbourIsCaught) {
    // (a, c, e) turned back over (a, b, c) by 165 degrees, a knife edge of 15: the flip's
    // (a, d, c) turns from it by 180.
    EXPECT_TRUE(flip_folds({0.5, 0.966, 0.259}));
    // (a, c, e) in the plane of (a, b, c): the flip turns its new triangle from it by 15 degrees.
    EXPECT_FALSE(flip_folds({0.5, -1, 0}));
    // (a, c, e) folded onto (a, b, c) already (by 174 degrees): no new fold.
    EXPECT_FALSE(flip_folds({0.5, 1, 0.1}));
}

TEST(FlipRules, FoldedEdgesAreCountedOnceOnEitherKindOfMesh) {
    // (a, c, e) folded onto (a, b, c) by 174 degrees along c-a: one edge, seen from both sides.
    const Mesh m = test::make_mesh({{0, 0, 0}, {0.5, 1, 0}, {1, 0, 0}, {-0.5, 0.8, 0.214}, {0.5, 1, 0.1}},
                                   {{0, 1, 2}, {1, 0, 3}, {0, 2, 4}});
    const EditableMesh mesh(m);
    const CompressedRows fans = mesh.fans();
    const TrianglesOf of = [&fans](int32_t v) { return std::make_pair(fans.begin(v), fans.end(v)); };
    EXPECT_EQ(folded_edges_among(mesh, {0, 1, 2, 2}, of), 1);
    EXPECT_EQ(folded_edges_among(mesh, {0, 1}, of), 1); // (a, b, c)'s edge c-a, found through the fans
    EXPECT_EQ(folded_edges_among(mesh, {1}, of), 0);
    auto corners = [&m](int32_t f) { return std::array<int32_t, 3>{m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)}; };
    auto normal = [&m, &corners](int32_t f) {
        const auto t = corners(f);
        return triangle_normal(m.points.row(t[0]).transpose(), m.points.row(t[1]).transpose(), m.points.row(t[2]).transpose());
    };
    EXPECT_EQ(count_folded_edges(std::vector<int32_t>{2}, corners, normal, [&fans](int32_t v) { return fans.row(v); }), 1);
    // Turned back by 165 degrees only: none.
    const Mesh knife = test::make_mesh({{0, 0, 0}, {0.5, 1, 0}, {1, 0, 0}, {-0.5, 0.8, 0.214}, {0.5, 0.966, 0.259}},
                                       {{0, 1, 2}, {1, 0, 3}, {0, 2, 4}});
    const EditableMesh knife_mesh(knife);
    const CompressedRows knife_fans = knife_mesh.fans();
    const TrianglesOf knife_of = [&knife_fans](int32_t v) { return std::make_pair(knife_fans.begin(v), knife_fans.end(v)); };
    EXPECT_EQ(folded_edges_among(knife_mesh, {0, 1, 2}, knife_of), 0);
}

TEST(FlipRules, AFlipThatLaysATriangleThroughOneRoundItsCornersIsCaught) {
    // (a, e, f) rises from between the two surfaces at (0.3, 0.3), where the flip's (a, d, c)
    // lies at z = 0.08: the flip lays that triangle through it.
    EXPECT_TRUE(flip_crosses({0.3, 0.3, 0.05}, {0.35, 0.3, 0.5}));
    // Standing above both surfaces there: crossed by neither.
    EXPECT_FALSE(flip_crosses({0.3, 0.3, 0.3}, {0.35, 0.3, 0.5}));
    // Rising from below (a, b, c), which it crosses already: the flip adds no crossing.
    EXPECT_FALSE(flip_crosses({0.3, 0.3, -0.05}, {0.35, 0.3, 0.5}));
}

TEST(FlipRules, CrossingsAmongTrianglesAreCountedOncePerPair) {
    const Mesh m = test::make_mesh({{0, 0, 0}, {0.5, 1, 0}, {1, 0, 0}, {-0.5, 0.8, 0.214}, {0.3, 0.3, -0.05}, {0.35, 0.3, 0.5}},
                                   {{0, 1, 2}, {1, 0, 3}, {0, 4, 5}});
    const EditableMesh mesh(m);
    EXPECT_EQ(crossings_among(mesh, {0, 1, 2}), 1); // (a, e, f) through (a, b, c)
    EXPECT_EQ(crossings_among(mesh, {2, 0, 2, 0}), 1);
    EXPECT_EQ(crossings_among(mesh, {1, 2}), 0);
}
