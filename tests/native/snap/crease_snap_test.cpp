// Vertices onto the input's acute creases: a knife edge cut by a row of vertices in the wedge's
// middle plane gets the row back on the edge; a right-angled edge, not acute, is left alone. And
// the creases' bends that a mesh's creases cut across.
#include "liftremesh/exceptions.h"
#include "liftremesh/snap/crease_snap.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace liftremesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Two faces of a wedge along the z axis, face A in the plane y = 0 (x >= 0), face B at
// `angle_deg` from it, each `width` wide and `length` long, consistently oriented. With
// `step` > 0 a grid of squares of that size on each face, the vertices of the shared edge moved
// `offset` into the wedge along its bisector; with `step` 0 the input's four triangles.
Mesh wedge(double angle_deg, double width, double length, double step = 0.0, double offset = 0.0) {
    const double a = angle_deg * kPi / 180.0;
    const Eigen::Vector3d dir_a(1.0, 0.0, 0.0), dir_b(std::cos(a), std::sin(a), 0.0);
    const Eigen::Vector3d bisector = (dir_a + dir_b).normalized();
    const int across = step > 0.0 ? static_cast<int>(std::lround(width / step)) : 1;
    const int along = step > 0.0 ? static_cast<int>(std::lround(length / step)) : 1;
    const double du = width / across, dz = length / along;
    std::vector<Eigen::Vector3d> pts;
    // Index of the point at distance i (rows) from the edge on face f, row j along it.
    auto id = [&](int f, int i, int j) { return i == 0 ? j : (along + 1) + (f * across + (i - 1)) * (along + 1) + j; };
    for (int j = 0; j <= along; ++j) pts.push_back(Eigen::Vector3d(0.0, 0.0, j * dz) + offset * bisector);
    for (int f = 0; f < 2; ++f)
        for (int i = 1; i <= across; ++i)
            for (int j = 0; j <= along; ++j) pts.push_back(i * du * (f == 0 ? dir_a : dir_b) + Eigen::Vector3d(0.0, 0.0, j * dz));
    std::vector<std::array<int32_t, 3>> tris;
    for (int f = 0; f < 2; ++f)
        for (int i = 0; i < across; ++i)
            for (int j = 0; j < along; ++j) {
                const int32_t p00 = id(f, i, j), p10 = id(f, i + 1, j), p11 = id(f, i + 1, j + 1), p01 = id(f, i, j + 1);
                if (f == 0) {
                    tris.push_back({p00, p10, p11});
                    tris.push_back({p00, p11, p01});
                } else { // the other way round: the two faces use the shared edge in opposite directions
                    tris.push_back({p00, p11, p10});
                    tris.push_back({p00, p01, p11});
                }
            }
    return test::make_mesh(pts, tris);
}

CreaseSnapParams params_for(double h) {
    CreaseSnapParams p;
    p.radius = 0.35 * h;
    p.corner_radius = h;
    p.tolerance = 0.05 * h;
    return p;
}

} // namespace

TEST(CreaseSnap, PutsTheRowOfAKnifeEdgeBackOnIt) {
    const double h = 0.1, offset = 0.3 * h;
    const Mesh input = wedge(30.0, 1.0, 1.0);
    Mesh mesh = wedge(30.0, 1.0, 1.0, h, offset);
    const int row = 11; // the edge's vertices, 0 .. 10
    const test::Topology before = test::topology(mesh);
    for (int j = 0; j < row; ++j) ASSERT_NEAR(mesh.points.row(j).head<2>().norm(), offset, 1e-12);
    const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params_for(h));
    EXPECT_EQ(stats.creases, 1);
    EXPECT_EQ(stats.moved, row);
    for (int j = 0; j < row; ++j) {
        EXPECT_NEAR(mesh.points.row(j).head<2>().norm(), 0.0, 1e-12) << "vertex " << j;
        EXPECT_NEAR(mesh.points(j, 2), j * h, 1e-9) << "vertex " << j; // onto its closest point
    }
    const test::Topology after = test::topology(mesh);
    EXPECT_TRUE(after.oriented_manifold());
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_GE(test::min_kappa(mesh), 0.45);
}

// The pipeline finds the creases once for the snap and the crease curves (crease_curves.h): the
// snap moves the vertices it moves onto the creases it finds itself, whatever their spacing.
TEST(CreaseSnap, TakesTheSameStepsWithCreasesFoundAtAnySpacing) {
    const double h = 0.1, offset = 0.3 * h;
    const Mesh input = wedge(30.0, 1.0, 1.0);
    const test::OwnedReference reference(input);
    Mesh own = wedge(30.0, 1.0, 1.0, h, offset);
    const CreaseSnapParams params = params_for(h);
    const CreaseSnapStats stats = snap_to_acute_creases(own, reference, params);
    ASSERT_EQ(stats.moved, 11);
    for (const double spacing : {0.01, 1.0, 3.0}) {
        Mesh given = wedge(30.0, 1.0, 1.0, h, offset);
        const AcuteCreases creases(input, params.min_turn_deg, spacing, params.min_length);
        const CreaseSnapStats with = snap_to_acute_creases(given, reference, creases, params);
        EXPECT_EQ(with.moved, stats.moved) << "spacing " << spacing;
        EXPECT_EQ(with.flipped, stats.flipped) << "spacing " << spacing;
        EXPECT_EQ(given.points, own.points) << "spacing " << spacing;
        EXPECT_EQ(given.triangles, own.triangles) << "spacing " << spacing;
    }
}

// Corners are where a crease ends or several meet; junctions, where three or more meet: a
// knife edge's two ends are corners, a cube's eight corners are both.
TEST(AcuteCreases, JunctionsAreTheCornersWhereThreeCreasesMeet) {
    const AcuteCreases knife(wedge(30.0, 1.0, 1.0), 120.0, 0.1);
    EXPECT_EQ(knife.corners().size(), 2u);
    EXPECT_TRUE(knife.junctions().empty());
    const AcuteCreases cube(test::make_cube(0.5, 2), 30.0, 0.1);
    ASSERT_EQ(cube.junctions().size(), 8u);
    EXPECT_EQ(cube.junctions(), cube.corners());
    for (const Eigen::Vector3d& j : cube.junctions()) EXPECT_EQ(j.cwiseAbs(), Eigen::Vector3d::Constant(0.5));
    ASSERT_EQ(cube.junction_turns().size(), 8u);
    for (const double turn : cube.junction_turns()) EXPECT_NEAR(turn, 90.0, 1e-9);
}

// A prism on the triangle (0, 0), (10, 0), (0, 4): its vertical edges turn by 90, 158.2 and
// 111.8 degrees, its caps' edges by 90, and each of its six corners is a junction, whose
// sharpest crease is its vertical edge: the two of the 21.8-degree tip are a knife edge's.
TEST(AcuteCreases, EachJunctionHasItsSharpestCreasesTurn) {
    std::vector<Eigen::Vector3d> pts;
    for (double z : {0.0, 1.0})
        for (const Eigen::Vector2d& p : {Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0), Eigen::Vector2d(0, 4)})
            pts.emplace_back(p.x(), p.y(), z);
    std::vector<std::array<int32_t, 3>> tris = {{0, 2, 1}, {3, 4, 5}};
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        tris.push_back({i, j, j + 3});
        tris.push_back({i, j + 3, i + 3});
    }
    const AcuteCreases creases(test::make_mesh(pts, tris), 30.0, 0.1);
    ASSERT_EQ(creases.junctions().size(), 6u);
    ASSERT_EQ(creases.junction_turns().size(), 6u);
    for (long s = 0; s < creases.size(); ++s) { // the caps' edges turn by 90 degrees
        const auto [a, b] = creases.ends(s);
        const bool vertical = a % 3 == b % 3;
        if (!vertical) EXPECT_NEAR(creases.turn(s), 90.0, 1e-9) << s;
    }
    for (size_t i = 0; i < 6; ++i) {
        const double expected = creases.junctions()[i].x() == 10.0 ? 158.2 : creases.junctions()[i].y() == 4.0 ? 111.8 : 90.0;
        EXPECT_NEAR(creases.junction_turns()[i], expected, 0.05) << i;
    }
}

// A prism 3 high on a regular polygon of radius 1, a corner on the x axis. On 16 sides its rims
// are chains of 90-degree creases turning by 22.5 degrees at each vertex (a hole's rim as a CAD
// tessellation gives it); its sides, turning by 22.5 degrees, are no creases at 30.
Mesh regular_prism(int sides) {
    std::vector<Eigen::Vector2d> polygon;
    for (int i = 0; i < sides; ++i) polygon.emplace_back(std::cos(2.0 * kPi * i / sides), std::sin(2.0 * kPi * i / sides));
    return test::make_prism(polygon, 3.0);
}

TEST(AcuteCreases, BendsAreTheInnerVerticesWhereAChainTurns) {
    const AcuteCreases prism(regular_prism(16), 30.0, 0.1);
    const std::vector<AcuteCreases::Bend> bends = prism.bends(10.0);
    ASSERT_EQ(bends.size(), 32u);
    for (const AcuteCreases::Bend& b : bends) {
        EXPECT_NEAR(b.turn_deg, 22.5, 1e-9);
        EXPECT_NEAR(b.point.head<2>().norm(), 1.0, 1e-12);
    }
    EXPECT_TRUE(prism.bends(23.0).empty());
    // A cube's creases meet three at each corner, junctions, and run straight through the
    // middles of its edges: 12 inner vertices that turn by nothing.
    const AcuteCreases cube(test::make_cube(0.5, 2), 30.0, 0.1);
    EXPECT_EQ(cube.bends(0.0).size(), 12u);
    EXPECT_TRUE(cube.bends(1e-6).empty());
}

// The same prism remeshed as one on the octagon through every other corner: its rims' chords
// pass 1 - cos(22.5 deg) = 0.076 inside the sixteen-gon's odd corners, and its sides (turning
// by 45 degrees) 0.39 from them.
TEST(CreaseSnap, ListsTheBendsTheMeshsCreasesCutAcross) {
    const Mesh input = regular_prism(16);
    const Mesh octagonal = regular_prism(8);
    const AcuteCreases creases(input, 30.0, 0.1);
    CreaseSnapParams p = params_for(0.5);
    p.bend_distance = 0.07;
    const std::vector<AcuteCreases::Bend> off = bends_off_mesh_creases(octagonal, creases, p);
    ASSERT_EQ(off.size(), 16u);
    for (const AcuteCreases::Bend& b : off) {
        const double angle = std::atan2(b.point.y(), b.point.x()) * 8.0 / kPi; // an odd multiple of 22.5 degrees
        EXPECT_NEAR(std::abs(std::fmod(angle, 2.0)), 1.0, 1e-9) << b.point.transpose();
    }
    p.bend_distance = 0.08;
    EXPECT_TRUE(bends_off_mesh_creases(octagonal, creases, p).empty());
    p.bend_distance = 0.07;
    EXPECT_TRUE(bends_off_mesh_creases(input, creases, p).empty()); // on the mesh's own creases
    p.bend_turn_deg = 23.0;
    EXPECT_TRUE(bends_off_mesh_creases(octagonal, creases, p).empty());
    p = params_for(0.5);
    EXPECT_TRUE(bends_off_mesh_creases(octagonal, creases, p).empty()); // bend_distance 0: none
    p.bend_distance = -1.0;
    EXPECT_THROW(bends_off_mesh_creases(octagonal, creases, p), InvalidInput);
    p.bend_distance = 0.07;
    p.bend_turn_deg = 190.0;
    EXPECT_THROW(bends_off_mesh_creases(octagonal, creases, p), InvalidInput);
}

// A slab's two long vertical creases at either end run 0.1 apart: a strip. The output's
// rhombus stands for each pair by one crease at its tip, between them, 0.05 from each.
TEST(CreaseSnap, ListsTheCreasePointsOfAStripThatTheMeshsCreasesPassFarFrom) {
    const Mesh input = test::make_prism({{0.0, 0.0}, {2.0, 0.0}, {2.0, 0.1}, {0.0, 0.1}}, 3.0);
    const Mesh rhombus = test::make_prism({{0.0, 0.05}, {1.0, 0.0}, {2.0, 0.05}, {1.0, 0.1}}, 3.0);
    const AcuteCreases creases(input, 30.0, 0.1);
    CreaseSnapParams p = params_for(0.5);
    p.bend_distance = 0.03;
    p.gap_separation = 0.25;
    const std::vector<Eigen::Vector3d> gaps = crease_gaps(rhombus, creases, p);
    // One of each pair of vertical creases along its 3 high, a point every 0.27 or so (the
    // samples' step is 0.03), the other crease of the pair within the separation of those; and
    // points of the long rims, a strip too, which the rhombus's rims cross diagonally.
    long vertical = 0;
    for (size_t i = 0; i < gaps.size(); ++i) {
        const Eigen::Vector3d& g = gaps[i];
        EXPECT_TRUE(g.y() == 0.0 || g.y() == 0.1) << g.transpose();
        if (g.x() == 0.0 || g.x() == 2.0) {
            ++vertical;
            EXPECT_GE(g.z(), 0.03); // the output's rims pass within 0.03 of the crease's ends
            EXPECT_LE(g.z(), 2.97);
        } else {
            EXPECT_TRUE(g.z() == 0.0 || g.z() == 3.0) << g.transpose();
        }
        for (size_t j = 0; j < i; ++j) EXPECT_GE((gaps[j] - g).norm(), 0.25);
    }
    EXPECT_GE(vertical, 20);
    EXPECT_LE(vertical, 24);
    EXPECT_TRUE(crease_gaps(input, creases, p).empty()); // on the mesh's own creases
    p.bend_distance = 0.06;                                // the tips pass within 0.05
    EXPECT_TRUE(crease_gaps(rhombus, creases, p).empty());
    p.bend_distance = 0.03;
    p.gap_separation = 0.04; // another crease within 0.08 of a point, across: none
    EXPECT_TRUE(crease_gaps(rhombus, creases, p).empty());
    p.gap_separation = 0.0;
    EXPECT_TRUE(crease_gaps(rhombus, creases, p).empty());
    p.gap_separation = -1.0;
    EXPECT_THROW(crease_gaps(rhombus, creases, p), InvalidInput);
    p.gap_separation = 0.25;
    p.bend_distance = std::nan("");
    EXPECT_THROW(crease_gaps(rhombus, creases, p), InvalidInput);
}

// The sixteen-gon's rims pass 0.076 outside the octagon's at their odd corners: bends the
// octagon's chords cut across (above), no strip between two creases. Its chords are 0.39 long:
// the corner after next lies that far from an odd corner, within twice a separation of 0.25.
TEST(CreaseSnap, ListsNoCreaseGapsWhereTheMeshsCreaseIsAChordOfTheSameCrease) {
    const AcuteCreases creases(regular_prism(16), 30.0, 0.1);
    CreaseSnapParams p = params_for(0.5);
    p.bend_distance = 0.07;
    p.gap_separation = 0.1;
    EXPECT_TRUE(crease_gaps(regular_prism(8), creases, p).empty());
    EXPECT_EQ(bends_off_mesh_creases(regular_prism(8), creases, p).size(), 16u);
    p.gap_separation = 0.25;
    EXPECT_EQ(crease_gaps(regular_prism(8), creases, p).size(), 16u);
}

TEST(CreaseSnap, LeavesARightAngleAndACutWithinTheToleranceAlone) {
    const double h = 0.1;
    {
        const Mesh input = wedge(90.0, 1.0, 1.0); // the normals turn by 90 degrees: not acute
        Mesh mesh = wedge(90.0, 1.0, 1.0, h, 0.3 * h);
        const Mesh was = mesh;
        const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params_for(h));
        EXPECT_EQ(stats.creases, 0);
        EXPECT_EQ(stats.moved, 0);
        EXPECT_TRUE(mesh.points == was.points);
        EXPECT_TRUE(mesh.triangles == was.triangles);
    }
    {
        const Mesh input = wedge(30.0, 1.0, 1.0);
        Mesh mesh = wedge(30.0, 1.0, 1.0, h, 0.3 * h);
        CreaseSnapParams params = params_for(h);
        params.tolerance = 0.5 * h; // the row cuts the edge less deep than that
        params.corner_radius = 0.1 * h;
        const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params);
        EXPECT_EQ(stats.creases, 1);
        EXPECT_EQ(stats.moved, 0);
    }
}

TEST(CreaseSnap, RejectsBadParameters) {
    const Mesh input = wedge(30.0, 1.0, 1.0);
    Mesh mesh = wedge(30.0, 1.0, 1.0, 0.1, 0.03);
    const AabbTree tree(input);
    CreaseSnapParams p = params_for(0.1);
    p.radius = 0.0;
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
    p = params_for(0.1);
    p.tolerance = std::nan("");
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
    p = params_for(0.1);
    p.min_turn_deg = 200.0;
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
    p = params_for(0.1);
    p.knife_kappa_floor = -0.1;
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
    p = params_for(0.1);
    p.knife_turn_deg = 181.0;
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
    p = params_for(0.1);
    p.bend_distance = std::numeric_limits<double>::infinity();
    EXPECT_THROW(snap_to_acute_creases(mesh, {input, tree}, p), InvalidInput);
}

// A move onto a crease edge turning by more than knife_turn_deg keeps knife_kappa_floor, the
// others kappa_floor: on a 30-degree wedge (its edge turns by 150 degrees) whose row lies 0.3 h
// off the edge, the row moves under a knife floor of 0.45 whatever kappa_floor asks, and not
// under one of 0.99; with knife_turn_deg at 160 the edge is no knife edge and kappa_floor holds.
TEST(CreaseSnap, MovesOntoAKnifeEdgeKeepTheKnifeFloor) {
    const double h = 0.1;
    const Mesh input = wedge(30.0, 1.0, 1.0);
    auto moved = [&](double floor, double knife_floor, double knife_turn) {
        Mesh mesh = wedge(30.0, 1.0, 1.0, h, 0.3 * h);
        CreaseSnapParams p = params_for(h);
        p.corner_radius = 0.0; // the row only
        p.kappa_floor = floor;
        p.knife_kappa_floor = knife_floor;
        p.knife_turn_deg = knife_turn;
        return snap_to_acute_creases(mesh, test::OwnedReference(input), p).moved;
    };
    EXPECT_GT(moved(0.99, 0.45, 120.0), 0);
    EXPECT_EQ(moved(0.99, 0.45, 120.0), moved(0.45, 0.45, 120.0));
    EXPECT_EQ(moved(0.45, 0.99, 120.0), 0);
    EXPECT_EQ(moved(0.99, 0.45, 160.0), 0);
    EXPECT_EQ(moved(0.45, 0.99, 160.0), moved(0.45, 0.45, 120.0));
}

// The feature angle's creases (steps.h, feature_snap): a 32-degree crease (faces at 148 degrees)
// whose row of vertices lies 0.04 h off it, less deep than the tolerance of 0.05 h, is left alone
// by the knife edges' repair (not acute, and within the tolerance) and put on the crease with a
// smaller turn and depth, its triangles kept as good as the floor.
TEST(CreaseSnap, PutsAShallowCreaseCutLessThanTheToleranceOnTheRow) {
    const double h = 0.1, offset = 0.04 * h;
    const Mesh input = wedge(148.0, 1.0, 1.0);
    const int row = 11;
    {
        Mesh mesh = wedge(148.0, 1.0, 1.0, h, offset);
        CreaseSnapParams params = params_for(h);
        params.min_turn_deg = 30.0; // the crease found, but cut less deep than the tolerance
        const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params);
        EXPECT_EQ(stats.creases, 1);
        EXPECT_EQ(stats.moved, 0);
    }
    Mesh mesh = wedge(148.0, 1.0, 1.0, h, offset);
    const test::Topology before = test::topology(mesh);
    CreaseSnapParams params = params_for(h);
    params.min_turn_deg = 30.0;
    params.min_depth = 0.02 * h;
    const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params);
    EXPECT_EQ(stats.creases, 1);
    EXPECT_EQ(stats.moved, row);
    for (int j = 0; j < row; ++j) EXPECT_NEAR(mesh.points.row(j).head<2>().norm(), 0.0, 1e-12) << "vertex " << j;
    const test::Topology after = test::topology(mesh);
    EXPECT_TRUE(after.oriented_manifold());
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_GE(test::min_kappa(mesh), 0.45);
}

namespace {

// The bottom face (z = 0, facing -z) of a part round a bore of radius r along the z axis, out to
// radius `outer`, and the bore's wall up to z = height (facing the axis), sharing the rim: n
// points round, `rings` rings on the face and `rows` on the wall.
Mesh face_and_bore(double r, double outer, double height, int n, int rings, int rows) {
    std::vector<Eigen::Vector3d> pts;
    for (int j = 0; j <= rings; ++j) // the face's rings, the rim first
        for (int i = 0; i < n; ++i) {
            const double u = 2.0 * kPi * i / n, rho = r + (outer - r) * j / rings;
            pts.emplace_back(rho * std::cos(u), rho * std::sin(u), 0.0);
        }
    const int wall = static_cast<int>(pts.size()) - n; // the wall's rows above the rim
    for (int k = 1; k <= rows; ++k)
        for (int i = 0; i < n; ++i) {
            const double u = 2.0 * kPi * i / n;
            pts.emplace_back(r * std::cos(u), r * std::sin(u), height * k / rows);
        }
    auto face = [n](int i, int j) { return static_cast<int32_t>(j * n + i % n); };
    auto bore = [n, wall](int i, int k) { return static_cast<int32_t>(k == 0 ? i % n : wall + k * n + i % n); };
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < rings; ++j) {
            tris.push_back({face(i, j), face(i + 1, j), face(i, j + 1)});
            tris.push_back({face(i + 1, j), face(i + 1, j + 1), face(i, j + 1)});
        }
        for (int k = 0; k < rows; ++k) {
            tris.push_back({bore(i, k), bore(i, k + 1), bore(i + 1, k)});
            tris.push_back({bore(i + 1, k), bore(i, k + 1), bore(i + 1, k + 1)});
        }
    }
    return test::make_mesh(pts, tris);
}

} // namespace

// The fan of a vertex of a part's face 0.35 mm beside the rim of a 1.8 mm bore, in the output
// of the frame at 30,000 vertices (tests/freecad/test_components.py, seed 3), whose triangle
// up the wall was left at kappa 0.22. Moved onto the rim, the vertex leaves that triangle at
// 0.26, which the flip of its long edge mends (0.74 and 0.73 there); that flip's diagonal
// spans more of the bore than the old one, a chord 0.13 mm deep against 0.08, farther than
// half the tolerance (0.1 mm at edges of 2 mm) but within it, as the move itself may be.
TEST(CreaseSnap, TakesTheFlipThatMendsAMoveOntoTheRimOfABoreWithinTheTolerance) {
    const Mesh input = face_and_bore(0.9, 5.0, 5.0, 256, 20, 40);
    const std::vector<Eigen::Vector3d> pts = {
        {-3.133, 1.500, 0.000}, {-1.859, -0.372, 0.000}, {-3.345, -1.500, 0.000}, {-1.500, -1.500, 0.000},
        {0.000, -0.900, 0.000}, {-0.779, -0.450, 0.000}, {-1.500, 1.500, 0.000},  {-1.076, 0.634, 0.006},
        {-1.500, 3.443, 0.000}, {1.500, 3.648, 0.000},   {0.000, 0.900, 0.000},   {0.899, 0.037, 0.000},
        {1.500, 1.500, 0.000},  {-0.751, 0.582, 1.097},  {-0.868, -0.370, 2.338}, {0.076, -0.953, 1.663},
        {-0.609, 0.732, 3.234}, {0.415, 0.856, 1.981},   {-0.916, -0.244, 4.450}, {0.011, -0.948, 3.699}};
    const int32_t v = 7;
    Mesh mesh = test::make_mesh(pts, {{0, 1, 2},    {3, 1, 5},    {0, 6, 1},    {6, 7, 1},    {8, 9, 6},
                                      {6, 10, 7},   {12, 10, 9},  {12, 11, 10}, {7, 13, 14},  {4, 5, 15},
                                      {5, 14, 15},  {7, 10, 13},  {9, 10, 6},   {13, 16, 14}, {13, 17, 16},
                                      {13, 10, 17}, {16, 18, 14}, {14, 19, 15}, {14, 18, 19}, {17, 10, 11},
                                      {5, 4, 3},    {5, 7, 14},   {1, 7, 5},    {1, 3, 2}});
    const double h = 2.0;
    const test::Topology before = test::topology(mesh);
    ASSERT_LT(test::min_kappa(mesh), 0.3);
    CreaseSnapParams params = params_for(h);
    params.min_turn_deg = 30.0; // the feature angle's creases (steps.h: feature_snap)
    params.radius = 0.5 * h;
    params.tolerance = 0.1 * h;
    params.min_depth = 0.02 * h;
    const CreaseSnapStats stats = snap_to_acute_creases(mesh, test::OwnedReference(input), params);
    EXPECT_EQ(stats.creases, 256);
    EXPECT_GE(stats.flipped, 1);
    EXPECT_NEAR(mesh.points.row(v).head<2>().norm(), 0.9, 1e-4); // on the rim's chords
    EXPECT_NEAR(mesh.points(v, 2), 0.0, 1e-12);
    const test::Topology after = test::topology(mesh);
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_GE(test::min_kappa(mesh), 0.45);
}
