#include "liftremesh/exceptions.h"
#include "liftremesh/lift/thin_walls.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/spatial/aabb_tree.h"
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

namespace {

// Whether the point (x, y) of the plane z = 0 lies in both sheets, at least `margin` inside.
bool in_overlap(double x, double y, double margin) {
    return std::abs(x) <= 1.0 - margin && std::abs(y) <= 1.0 - margin &&
           std::abs(x) + std::abs(y) <= 1.2 - std::sqrt(2.0) * margin;
}

// sample_wall_thickness() of the sheets, at the given spacing, nu 0.01 and its defaults.
WallSamplingParams sheet_sampling(double spacing) {
    WallSamplingParams p;
    p.nu = 0.01;
    p.spacing = spacing;
    p.reach = wall_reach(p.nu, spacing);
    p.tolerance = 0.1 * spacing;
    p.min_edge = 0.25 * spacing;
    p.max_midpoints = 1000;
    return p;
}

// Every vertex of the split square inside the overlap (one at least) has the diamond `gap` away.
void expect_the_square_sees_the_gap(const Points& points, const WallSampling& s, double gap) {
    long inside = 0;
    for (Eigen::Index v = 0; v < points.rows(); ++v)
        if (points(v, 2) == 0.0 && in_overlap(points(v, 0), points(v, 1), 1e-9)) {
            EXPECT_NEAR(s.thickness[v], gap, 1e-12) << v;
            ++inside;
        }
    EXPECT_GE(inside, 1);
}

} // namespace

// The slot's sides share no vertex across: per vertex there is no wall (the lifting misses it).
// Split, every vertex of the square inside the overlap has the diamond `gap` away, and the
// lifting interpolated over the split triangles is within the tolerance of what each point of
// the overlap needs (but near its rim, where the need drops to nu within less than min_edge).
TEST(WallSampling, SplitsTrianglesWhereOnlyTheirInsideLiesAcrossAWall) {
    const double gap = 0.05;
    const Mesh sheets = test::make_offset_sheets(gap);
    const AabbTree tree(sheets);
    const WallSamplingParams params = sheet_sampling(0.2);
    EXPECT_EQ(wall_thickness(sheets, tree, params.reach), Eigen::VectorXd::Constant(8, kNoWall));

    const WallSampling s = sample_wall_thickness(sheets, tree, params);
    ASSERT_FALSE(s.midpoints.empty());
    const Points points = with_midpoints(sheets.points, s.midpoints);
    ASSERT_EQ(s.thickness.size(), points.rows());
    ASSERT_EQ(s.parent.size(), static_cast<size_t>(s.triangles.rows()));
    expect_the_square_sees_the_gap(points, s, gap);

    const double needed = wall_lifting(gap, params.nu, params.spacing);
    ASSERT_GT(needed, params.nu + params.tolerance);
    long probed = 0;
    for (double x = -1.0; x <= 1.0; x += 0.01)
        for (double y = -1.0; y <= 1.0; y += 0.01) {
            if (!in_overlap(x, y, params.min_edge)) continue;
            // The square's split triangle holding (x, y, 0), and the lifting interpolated there.
            double lifting = -1.0;
            for (Eigen::Index f = 0; f < s.triangles.rows() && lifting < 0.0; ++f) {
                if (s.parent[static_cast<size_t>(f)] >= 2) continue; // the diamond's
                const Eigen::Vector3d a = points.row(s.triangles(f, 0)), b = points.row(s.triangles(f, 1)),
                                      c = points.row(s.triangles(f, 2));
                const Eigen::Vector3d q(x, y, 0.0);
                const double area = (b - a).cross(c - a).z();
                const double la = (b - q).cross(c - q).z() / area, lb = (c - q).cross(a - q).z() / area;
                const double lc = 1.0 - la - lb;
                if (la < -1e-12 || lb < -1e-12 || lc < -1e-12) continue;
                lifting = la * wall_lifting(s.thickness[s.triangles(f, 0)], params.nu, params.spacing) +
                          lb * wall_lifting(s.thickness[s.triangles(f, 1)], params.nu, params.spacing) +
                          lc * wall_lifting(s.thickness[s.triangles(f, 2)], params.nu, params.spacing);
            }
            ASSERT_GE(lifting, 0.0) << x << " " << y;
            EXPECT_GE(lifting, needed - params.tolerance - 1e-12) << x << " " << y;
            ++probed;
        }
    EXPECT_GT(probed, 10000);
}

// The split mesh is the same surface: each triangle lies in its parent, the parents' areas are
// covered exactly, and the split is conforming (no edge is used three times, and the boundary
// is the sheets' own, its length unchanged).
TEST(WallSampling, TheSplitTrianglesCoverTheInputsExactly) {
    const Mesh sheets = test::make_offset_sheets(0.05);
    const WallSampling s = sample_wall_thickness(sheets, AabbTree(sheets), sheet_sampling(0.2));
    Mesh split;
    split.points = with_midpoints(sheets.points, s.midpoints);
    split.triangles = s.triangles;
    std::vector<double> covered(static_cast<size_t>(sheets.triangles.rows()), 0.0);
    for (Eigen::Index f = 0; f < split.triangles.rows(); ++f) {
        const int32_t p = s.parent[static_cast<size_t>(f)];
        const Eigen::Vector3d n = triangle_normal(corner(sheets, p, 0), corner(sheets, p, 1), corner(sheets, p, 2));
        EXPECT_GT(triangle_normal(corner(split, f, 0), corner(split, f, 1), corner(split, f, 2)).dot(n), 1.0 - 1e-12) << f;
        for (int j = 0; j < 3; ++j) // each corner in the parent's plane and within its edges
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector3d a = corner(sheets, p, k), b = corner(sheets, p, (k + 1) % 3);
                EXPECT_GE((b - a).cross(corner(split, f, j) - a).dot(n), -1e-12) << f;
            }
        covered[static_cast<size_t>(p)] += triangle_area(corner(split, f, 0), corner(split, f, 1), corner(split, f, 2));
    }
    for (Eigen::Index p = 0; p < sheets.triangles.rows(); ++p)
        EXPECT_NEAR(covered[static_cast<size_t>(p)],
                    triangle_area(corner(sheets, p, 0), corner(sheets, p, 1), corner(sheets, p, 2)), 1e-12);
    const auto boundary_length = [](const Mesh& m) {
        double length = 0.0;
        for (const EdgeCount& e : edge_counts(m.triangles)) {
            EXPECT_LE(e.count, 2);
            if (e.count == 1) length += (m.points.row(e.a) - m.points.row(e.b)).norm();
        }
        return length;
    };
    EXPECT_NEAR(boundary_length(split), boundary_length(sheets), 1e-12);
}

// Where the vertices see the walls there is nothing to split: a slab whose faces are grids is
// left as it is (and not copied), and its thickness is wall_thickness's to the bit.
TEST(WallSampling, LeavesAMeshWhoseVerticesSeeItsWallsAsItIs) {
    const Mesh slab = make_slab(0.05);
    const AabbTree tree(slab);
    WallSamplingParams params = sheet_sampling(0.2);
    const WallSampling s = sample_wall_thickness(slab, tree, params);
    EXPECT_TRUE(s.midpoints.empty());
    EXPECT_EQ(s.triangles.rows(), 0); // nothing copied: the slab's own
    EXPECT_TRUE(s.parent.empty());
    EXPECT_EQ(s.thickness, wall_thickness(slab, tree, params.reach));
}

// No split could end (min_edge 0) or none would mean anything: refused.
TEST(WallSampling, RejectsBadParameters) {
    const Mesh sheets = test::make_offset_sheets(0.05);
    const AabbTree tree(sheets);
    WallSamplingParams p = sheet_sampling(0.2);
    p.min_edge = 0.0;
    EXPECT_THROW(sample_wall_thickness(sheets, tree, p), InvalidInput);
    p = sheet_sampling(0.2);
    p.spacing = std::nan("");
    EXPECT_THROW(sample_wall_thickness(sheets, tree, p), InvalidInput);
    p = sheet_sampling(0.2);
    p.tolerance = -0.1;
    EXPECT_THROW(sample_wall_thickness(sheets, tree, p), InvalidInput);
    p = sheet_sampling(0.2);
    p.max_midpoints = -1;
    EXPECT_THROW(sample_wall_thickness(sheets, tree, p), InvalidInput);
    EXPECT_NO_THROW(sample_wall_thickness(sheets, tree, sheet_sampling(0.2)));
}

// The midpoints are bounded (the memory with them): a round that would add more than
// max_midpoints in all is not made, and what it leaves is still a conforming split.
TEST(WallSampling, AddsNoMoreThanMaxMidpoints) {
    const Mesh sheets = test::make_offset_sheets(0.05);
    const AabbTree tree(sheets);
    const size_t all = sample_wall_thickness(sheets, tree, sheet_sampling(0.2)).midpoints.size();
    ASSERT_GT(all, 20u);
    WallSamplingParams p = sheet_sampling(0.2);
    p.max_midpoints = static_cast<long>(all) - 1;
    const WallSampling capped = sample_wall_thickness(sheets, tree, p);
    EXPECT_LT(capped.midpoints.size(), all);
    EXPECT_EQ(capped.thickness.size(), static_cast<Eigen::Index>(8 + capped.midpoints.size()));
    double boundary = 0.0;
    const Points points = with_midpoints(sheets.points, capped.midpoints);
    for (const EdgeCount& e : edge_counts(capped.triangles)) {
        EXPECT_LE(e.count, 2);
        if (e.count == 1) boundary += (points.row(e.a) - points.row(e.b)).norm();
    }
    EXPECT_NEAR(boundary, 8.0 + 4.0 * std::sqrt(2.0) * 1.2, 1e-12); // the square's and the diamond's rims
    p.max_midpoints = 0;
    EXPECT_TRUE(sample_wall_thickness(sheets, tree, p).midpoints.empty());
}

// The size field's splitting (WallSamplingParams::largest_size) without any lifting to ask for
// it (reach 0): the sheets' triangles are split where the slot, 0.05 across, is thinner than the
// size interpolated from their vertices (the largest, 0.4, none seeing the wall) by more than
// kWallSizeSplit, and the square's vertices inside the overlap see the wall. Without a largest
// size nothing is split.
TEST(ThinWalls, TheSizeFieldSplitsWhereAWallIsThinnerThanTheInterpolatedSize) {
    const double gap = 0.05;
    const Mesh sheets = test::make_offset_sheets(gap);
    const AabbTree tree(sheets);
    WallSamplingParams params = sheet_sampling(0.4);
    params.reach = 0.0;
    EXPECT_TRUE(sample_wall_thickness(sheets, tree, params).midpoints.empty());
    params.largest_size = 0.4;
    const WallSampling s = sample_wall_thickness(sheets, tree, params);
    ASSERT_FALSE(s.midpoints.empty());
    const Points points = with_midpoints(sheets.points, s.midpoints);
    expect_the_square_sees_the_gap(points, s, gap);
    params.largest_size = -1.0;
    EXPECT_THROW(sample_wall_thickness(sheets, tree, params), InvalidInput);
}
