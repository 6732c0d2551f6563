// Putting the output's boundary onto the input's (boundary_snap.h): on meshes built here
// (remesh() on open surfaces: end_to_end/open_surface_test.cpp).
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/snap/boundary_snap.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <map>
#include <set>

using namespace liftremesh;
using namespace liftremesh::test;

namespace {

// The part of acute_triangle(degrees) at distances d to 2 d from the origin, as two triangles:
// an output whose boundary cuts the acute corner off, with no vertex within reach of it.
Mesh wedge_strip(double degrees, double d) {
    const double a = degrees * M_PI / 180.0;
    const Eigen::Vector3d u(std::cos(a), std::sin(a), 0);
    const Eigen::Vector3d a1(d, 0, 0), a2(2 * d, 0, 0), b1 = d * u, b2 = 2 * d * u;
    return test::make_mesh({{a1.x(), a1.y(), 0}, {a2.x(), a2.y(), 0}, {b2.x(), b2.y(), 0}, {b1.x(), b1.y(), 0}},
                           {{0, 1, 2}, {0, 2, 3}});
}

} // namespace

TEST(BoundarySnap, CornersAreWhereTheBoundaryTurns) {
    const Mesh plate = test::make_plate_with_hole(100, 60, 10, 5, 8);
    std::set<std::pair<double, double>> found;
    for (int32_t v : boundary_corners(plate)) found.insert({plate.points(v, 0), plate.points(v, 1)});
    // The four right angles; the hole (64 vertices, at most 9.5 degrees each) has none.
    const std::set<std::pair<double, double>> expected = {{50, -30}, {50, 30}, {-50, 30}, {-50, -30}};
    EXPECT_EQ(found, expected);
    EXPECT_EQ(boundary_corners(plate, 1.0).size(), 4u + 64u); // below the hole's turns: all of it
    EXPECT_TRUE(boundary_corners(test::make_icosphere(1)).empty());
    EXPECT_TRUE(boundary_corners(test::make_open_cylinder(1, 2, 16, 4)).empty()); // 22.5-degree turns
}

TEST(BoundarySnap, AShrunkGridGoesBackOntoTheSquare) {
    const Mesh input = test::make_square(1.0, 4);
    Mesh output = test::make_square(1.0, 6);
    const Eigen::RowVector3d centre(0.5, 0.5, 0.0);
    output.points = ((output.points.rowwise() - centre) * 0.96).rowwise() + centre; // 0.02 inside
    const Mesh before = output;

    const BoundarySnapStats s = snap_boundary(output, OwnedReference(input));
    EXPECT_EQ(s.input_corners, 4);
    EXPECT_EQ(s.corners_matched, 4);
    EXPECT_EQ(s.vertices_snapped, 20);
    EXPECT_EQ(s.moves_refused, 0);
    EXPECT_EQ(boundary_gap(output, input), 0.0);
    for (const Eigen::Vector3d c : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
                                    Eigen::Vector3d(0, 1, 0)})
        EXPECT_EQ(distance_to_nearest_vertex(output, c), 0.0);
    EXPECT_EQ(output.triangles, before.triangles);
    const std::set<int32_t> boundary = boundary_vertices_of(before);
    for (Eigen::Index v = 0; v < output.points.rows(); ++v)
        if (!boundary.count(static_cast<int32_t>(v))) EXPECT_EQ(output.points.row(v), before.points.row(v));
}

TEST(BoundarySnap, ClosedOrFarAwayBoundariesAreLeftAlone) {
    const Mesh sphere = test::make_icosphere(2), square = test::make_square(1.0, 4);
    Mesh output = test::make_square(1.0, 5);
    const Mesh before = output;
    EXPECT_EQ(snap_boundary(output, OwnedReference(sphere)).moved(), 0); // closed input
    EXPECT_EQ(output.points, before.points);
    Mesh closed = sphere;
    EXPECT_EQ(snap_boundary(closed, OwnedReference(square)).moved(), 0); // closed output
    EXPECT_EQ(closed.points, sphere.points);
    // An output boundary more than an edge length (0.2) from the input's: not the input's boundary.
    output.points.col(2).array() += 0.25;
    const Mesh lifted = output;
    EXPECT_EQ(snap_boundary(output, OwnedReference(square)).moved(), 0);
    EXPECT_EQ(output.points, lifted.points);
}

TEST(BoundarySnap, AMoveThatWouldCollapseATriangleIsRefused) {
    // A boundary vertex v at the origin whose fan spans 270 degrees (v, p1, a), (v, p2, p1),
    // (v, b, p2); the input's boundary is the line x = 0.8. v's nearest point (0.8, 0) lies out
    // of the output, but the thin triangle (v, p1, a) would keep 20% of its area there. (Other
    // vertices may move too; the test is about v.)
    const Mesh output = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0.6, -0.3, 0}, {-1, 0, 0}, {0, 1, 0}},
                                        {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}});
    const Mesh input = test::make_mesh({{0.8, -5, 0}, {0.8, 5, 0}, {-5, 5, 0}, {-5, -5, 0}}, {{0, 1, 2}, {0, 2, 3}});
    auto area = [](const Mesh& m, Eigen::Index f) {
        return triangle_area(corner(m, f, 0), corner(m, f, 1), corner(m, f, 2));
    };
    Mesh refused = output;
    EXPECT_GE(snap_boundary(refused, OwnedReference(input)).moves_refused, 1);
    EXPECT_EQ(refused.points.row(0), output.points.row(0));
    for (Eigen::Index f = 0; f < output.triangles.rows(); ++f) EXPECT_GE(area(refused, f), 0.25 * area(output, f));
    EXPECT_EQ(test::facing_inward(refused, Eigen::Vector3d(0, 0, -1)), 0); // none flipped

    BoundarySnapParams lenient;
    lenient.min_area_ratio = 0.1;
    Mesh moved = output;
    snap_boundary(moved, OwnedReference(input), lenient);
    EXPECT_EQ(moved.points.row(0), Eigen::RowVector3d(0.8, 0, 0));
    EXPECT_EQ(test::facing_inward(moved, Eigen::Vector3d(0, 0, -1)), 0);
}

TEST(BoundarySnap, AnAcuteCornerOutOfReachGetsAVertexAndATriangle) {
    // The strip's nearest vertices are d = 0.1 from the corner, their boundary edges 0.1 and
    // 0.035 long: no vertex is within reach (the mean of its boundary edges).
    const Mesh input = acute_triangle(20);
    Mesh output = wedge_strip(20, 0.1);
    const Mesh before = output;
    const BoundarySnapStats s = snap_boundary(output, OwnedReference(input));
    EXPECT_EQ(s.input_corners, 3);
    EXPECT_EQ(s.corners_matched, 0);
    EXPECT_EQ(s.corners_inserted, 1);
    ASSERT_EQ(output.points.rows(), before.points.rows() + 1);
    ASSERT_EQ(output.triangles.rows(), before.triangles.rows() + 1);
    EXPECT_EQ(output.points.row(4), Eigen::RowVector3d(0, 0, 0)); // exactly the corner
    const test::Topology t = test::topology(output);
    EXPECT_TRUE(t.oriented_manifold());
    EXPECT_EQ(t.chi, test::topology(before).chi);
    EXPECT_EQ(boundary_edges_of(output).size(), boundary_edges_of(before).size() + 1);
    EXPECT_EQ(test::facing_inward(output, Eigen::Vector3d(0, 0, -1)), 0); // facing +z as the strip
    const Eigen::Index ear = output.triangles.rows() - 1;
    // The isosceles triangle of 20 degrees at the corner.
    EXPECT_NEAR(triangle_kappa(corner(output, ear, 0), corner(output, ear, 1), corner(output, ear, 2)), 0.574, 0.001);

    // At 10 degrees the only triangle has kappa 0.318: made above half the default floor, not
    // above half of 0.7.
    Mesh sharp = wedge_strip(10, 0.1);
    EXPECT_EQ(snap_boundary(sharp, OwnedReference(acute_triangle(10))).corners_inserted, 1);
    BoundarySnapParams strict;
    strict.min_kappa = 0.7;
    Mesh kept = wedge_strip(10, 0.1);
    EXPECT_EQ(snap_boundary(kept, OwnedReference(acute_triangle(10)), strict).corners_inserted, 0);
    EXPECT_EQ(kept.points, wedge_strip(10, 0.1).points);
    EXPECT_EQ(kept.triangles, wedge_strip(10, 0.1).triangles);

    // An input made of the strip and, apart from it, the tip of the wedge up to 0.03 from the
    // corner: a triangle to the corner would bridge the gap between 0.03 and 0.1, off the input.
    const double a = 20 * M_PI / 180.0;
    const Mesh strip = wedge_strip(20, 0.1);
    Mesh parts = strip;
    parts.points.conservativeResize(7, Eigen::NoChange);
    parts.points.bottomRows(3) << 0, 0, 0, 0.03, 0, 0, 0.03 * std::cos(a), 0.03 * std::sin(a), 0;
    parts.triangles.conservativeResize(3, Eigen::NoChange);
    parts.triangles.row(2) << 4, 5, 6;
    Mesh apart = strip;
    EXPECT_EQ(snap_boundary(apart, OwnedReference(parts)).corners_inserted, 0);
    EXPECT_EQ(apart.points, strip.points);
    EXPECT_EQ(apart.triangles, strip.triangles);
}

TEST(BoundarySnap, AFlapBeyondTheBoundaryIsRemoved) {
    // The 4 x 4 square with one more triangle hanging below its bottom edge (0.25, 0) - (0.5, 0),
    // its apex 0.05 below: the apex's nearest boundary point lies back inside the output.
    const Mesh square = test::make_square(1.0, 4);
    Mesh output = square;
    output.points.conservativeResize(26, Eigen::NoChange);
    output.points.row(25) << 0.375, -0.05, 0.0;
    output.triangles.conservativeResize(output.triangles.rows() + 1, Eigen::NoChange);
    output.triangles.row(output.triangles.rows() - 1) << 2, 1, 25;
    ASSERT_TRUE(test::topology(output).oriented_manifold());
    const BoundarySnapStats s = snap_boundary(output, OwnedReference(square));
    EXPECT_EQ(s.flaps_removed, 1);
    EXPECT_EQ(output.triangles.rows(), square.triangles.rows());
    ASSERT_EQ(output.points.rows(), square.points.rows());
    std::set<std::array<double, 3>> kept, expected;
    for (Eigen::Index v = 0; v < 25; ++v) {
        kept.insert({output.points(v, 0), output.points(v, 1), output.points(v, 2)});
        expected.insert({square.points(v, 0), square.points(v, 1), square.points(v, 2)});
    }
    EXPECT_EQ(kept, expected);
    EXPECT_EQ(test::topology(output).chi, 1);
    EXPECT_EQ(boundary_gap(output, square), 0.0);

    // An apex beyond the boundary in two triangles, over (0.25, 0) - (0.5, 0) - (0.75, 0), is
    // not a flap of one cell: both triangles stay, as does every vertex.
    Mesh two = square;
    two.points.conservativeResize(26, Eigen::NoChange);
    two.points.row(25) << 0.5, -0.05, 0.0;
    two.triangles.conservativeResize(two.triangles.rows() + 2, Eigen::NoChange);
    two.triangles.bottomRows(2) << 2, 1, 25, 3, 2, 25;
    ASSERT_TRUE(test::topology(two).oriented_manifold());
    EXPECT_EQ(snap_boundary(two, OwnedReference(square)).flaps_removed, 0);
    EXPECT_EQ(two.triangles.rows(), square.triangles.rows() + 2);
    EXPECT_EQ(two.points.rows(), 26);
}

TEST(BoundarySnap, BadOptionsAreRejected) {
    const Mesh square = test::make_square(1.0, 2);
    Mesh output = square;
    BoundarySnapParams o;
    o.corner_angle_deg = 180;
    EXPECT_THROW(snap_boundary(output, OwnedReference(square), o), InvalidInput);
    o = {};
    o.reach = 0;
    EXPECT_THROW(snap_boundary(output, OwnedReference(square), o), InvalidInput);
    o = {};
    o.min_area_ratio = 1;
    EXPECT_THROW(snap_boundary(output, OwnedReference(square), o), InvalidInput);
}
