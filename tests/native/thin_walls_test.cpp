#include "liftremesh/aabb_tree.h"
#include "liftremesh/mesh_io.h"
#include "liftremesh/thin_walls.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace liftremesh;

namespace {

const double kNoWall = std::numeric_limits<double>::infinity(); // wall_thickness(): none within reach

// A 1 x 1 x `thickness` box centred at the origin, each face an 8 x 8 grid.
Mesh make_slab(double thickness) {
    Mesh slab = test::make_cube(0.5, 8);
    slab.points.col(2) *= thickness;
    return slab;
}

// A wedge of interior angle `degrees` along the x axis, without its other faces: the unit square
// in z = 0 facing down, and the same square turned about the x axis by that angle, facing out of
// the wedge; their vertices on the axis welded.
Mesh make_wedge(double degrees) {
    Mesh below = test::make_square(1.0, 8), above = below;
    below.triangles.col(1).swap(below.triangles.col(2)); // normal -z
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    above.points = (above.points * turn.transpose()).eval();
    Mesh wedge = test::joined(below, above);
    weld_exact(wedge);
    return wedge;
}

} // namespace

// Every vertex of a big face, rims included, has the other big face `thickness` away; the
// vertices inside the narrow sides face the opposite side, a whole unit away, beyond the reach
// (infinitely thick).
TEST(WallThickness, TheFacesOfASlabAreItsThicknessApart) {
    const double thickness = 0.05, reach = 0.2;
    const Mesh slab = make_slab(thickness);
    const Eigen::VectorXd t = wall_thickness(slab, AabbTree(slab), reach);
    long on_faces = 0;
    for (Eigen::Index v = 0; v < slab.points.rows(); ++v) {
        const bool on_a_face = std::abs(std::abs(slab.points(v, 2)) - 0.5 * thickness) < 1e-12;
        if (on_a_face)
            EXPECT_NEAR(t[v], thickness, 1e-12) << v;
        else
            EXPECT_EQ(t[v], kNoWall) << v;
        on_faces += on_a_face;
    }
    EXPECT_EQ(on_faces, 2 * 81);
    // Nothing is thinner than a reach below the thickness.
    const Eigen::VectorXd short_reach = wall_thickness(slab, AabbTree(slab), 0.5 * thickness);
    EXPECT_EQ(short_reach, Eigen::VectorXd::Constant(slab.points.rows(), kNoWall));
}

// A wedge of 10 degrees tapers like a wall: a point r from its edge is r sin(10 deg) from the
// other face. One of 45 degrees is a knife edge, whose faces are close only because they meet
// there: no wall (kWallTaperDeg is 25).
TEST(WallThickness, AKnifeEdgeIsNoWallButAThinWedgeIs) {
    for (const double degrees : {10.0, 45.0}) {
        const Mesh wedge = make_wedge(degrees);
        const Eigen::VectorXd t = wall_thickness(wedge, AabbTree(wedge), 1.0);
        long walls = 0;
        for (Eigen::Index v = 0; v < wedge.points.rows(); ++v) {
            const double r = wedge.points.row(v).tail<2>().norm(); // distance from the edge
            if (r < 1e-9) continue; // on the edge: its own triangles are both faces
            if (degrees < kWallTaperDeg)
                EXPECT_NEAR(t[v], r * std::sin(degrees * M_PI / 180.0), 1e-12) << degrees << " degrees, vertex " << v;
            else
                EXPECT_EQ(t[v], kNoWall) << degrees << " degrees, vertex " << v;
            walls += t[v] < 1.0;
        }
        EXPECT_EQ(walls, degrees < kWallTaperDeg ? 2 * 72 : 0) << degrees;
    }
}

// The two sides of a wall, with opposite normals, end up sqrt(t^2 + 4 nu_v^2) = spacing apart
// on the lifted surface wherever nu alone would leave them nearer; elsewhere nu is kept.
TEST(ThinWallLifting, LiftsTheSidesOfAThinWallASpacingApart) {
    const double nu = 0.01, spacing = 0.1;
    Eigen::VectorXd t(6);
    t << 0.0, 0.03, 0.09, 0.0995, 0.1, 0.5;
    const Eigen::VectorXd scale = thin_wall_lifting(t, nu, spacing);
    for (Eigen::Index i = 0; i < t.size(); ++i) {
        EXPECT_GE(scale[i], nu) << i;
        if (std::sqrt(t[i] * t[i] + 4 * nu * nu) < spacing)
            EXPECT_NEAR(std::sqrt(t[i] * t[i] + 4 * scale[i] * scale[i]), spacing, 1e-15) << i;
        else
            EXPECT_EQ(scale[i], nu) << i;
    }
    EXPECT_NEAR(scale[0], 0.5 * spacing, 1e-15);
    EXPECT_EQ(scale[3], nu); // 0.0995^2 + 4 nu^2 > spacing^2
    EXPECT_EQ(scale[5], nu);
    EXPECT_EQ(thin_wall_lifting(Eigen::VectorXd::Constant(1, kNoWall), nu, spacing)[0], nu);
}

// The reach is the thickness at which nu alone puts the sides a spacing apart, and nothing is
// searched (reach 0) once the spacing is no more than 2 nu: every wall's sides are 2 nu apart.
TEST(ThinWallLifting, ReachesAsFarAsNuAloneLeavesTheSidesTooClose) {
    const double nu = 0.01;
    EXPECT_NEAR(wall_reach(nu, 0.1), std::sqrt(0.1 * 0.1 - 4 * nu * nu), 1e-15);
    EXPECT_EQ(wall_reach(nu, 2 * nu), 0.0);
    EXPECT_EQ(wall_reach(nu, 0.008), 0.0);
    const double spacing = 0.05, reach = wall_reach(nu, spacing);
    Eigen::VectorXd t(3);
    t << 0.999 * reach, reach, 1.001 * reach;
    const Eigen::VectorXd scale = thin_wall_lifting(t, nu, spacing);
    EXPECT_GT(scale[0], nu);
    EXPECT_NEAR(std::sqrt(t[0] * t[0] + 4 * scale[0] * scale[0]), spacing, 1e-15);
    EXPECT_EQ(scale[1], nu);
    EXPECT_EQ(scale[2], nu);
}

// A triangle turned over in the middle of a face (a dirty soup) faces away from its neighbours
// but lies beside them, not across: no wall.
TEST(WallThickness, ATriangleTurnedOverInAFaceIsNoWall) {
    Mesh square = test::make_square(1.0, 8);
    square.triangles.row(60).tail<2>().reverseInPlace();
    const Eigen::VectorXd t = wall_thickness(square, AabbTree(square), 0.5);
    EXPECT_EQ(t, Eigen::VectorXd::Constant(square.points.rows(), kNoWall));
}
