// The flip rules' guard against folds across a quad's rim (flip_rules.h: flip_folds_rim).
#include "liftremesh/edit/flip_rules.h"
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
    return flip_folds_rim(mesh, *quad, mesh.fans());
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
