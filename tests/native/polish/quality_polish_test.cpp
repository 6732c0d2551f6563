// The quality polish: a flat quad split along its longer diagonal is flipped, a sharp edge and
// a flip that moves the surface away from the input are not; a fold is flipped onto the input,
// a sharp crease of the input is not; a cap on a crease is flipped, so is one turned over onto
// the face a step lower; one on the rim of a thin plate and a triangle short of a cap are not;
// a chord across a curved wall is flipped along it, not where the new triangles would leave the
// input; a vertex pushed out of place on a flat part is moved back, one on a crease is not; a
// closed surface keeps its topology, its orientation and its worst triangle at least as good;
// the flips around given vertices leave the rest alone.
#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/polish/quality_polish.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

using namespace liftremesh;

namespace {
// The quad a = (-1, 0, 0), b = (1, 0, 0), c = (0, 0.4, 0), d as given, split along a-b:
// triangles (a, b, c) and (b, a, d), both thin (kappa 0.27); the diagonal c-d makes two of kappa
// 0.93 when flat.
Mesh kite(const Eigen::Vector3d& d) {
    return test::make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, 0.4, 0}, d}, {{0, 1, 2}, {1, 0, 3}});
}
QualityPolishParams with_tolerance(double tolerance) {
    QualityPolishParams p;
    p.tolerance = tolerance;
    return p;
}
long flips(Mesh& m, const Reference& input, double tolerance) {
    return polish_quality(m, input, with_tolerance(tolerance)).flipped;
}
bool has_edge(const Mesh& m, int32_t u, int32_t v) {
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (std::minmax(m.triangles(f, j), m.triangles(f, (j + 1) % 3)) == std::minmax(u, v)) return true;
    return false;
}
// The wall of a hole of radius 4, 10 high, finely triangulated.
Mesh wall() { return test::make_open_cylinder(4.0, 10.0, 512, 40); }
// Triangles (a, b, c) and (b, a, d) with corners on that wall, given as (degrees round, z).
Mesh on_wall(const std::vector<std::array<double, 2>>& corners) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& [degrees, z] : corners) {
        const double u = degrees * M_PI / 180.0;
        points.emplace_back(4.0 * std::cos(u), 4.0 * std::sin(u), z);
    }
    return test::make_mesh(points, {{0, 1, 2}, {1, 0, 3}});
}
} // namespace

TEST(QualityPolish, AFlatQuadGetsItsShorterDiagonal) {
    Mesh m = kite({0, -0.4, 0});
    const test::OwnedReference input(m);
    const double before = test::min_kappa(m);
    EXPECT_EQ(flips(m, input, 0.01), 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    EXPECT_GT(test::min_kappa(m), before + 0.3);
    EXPECT_EQ(test::facing_inward(m, {0, 0, -1}), 0); // both still face +z
    EXPECT_EQ(euler_characteristic(m), 1);
    EXPECT_EQ(flips(m, input, 0.01), 0); // nothing left to improve
}

TEST(QualityPolish, ASharpEdgeIsNeverFlipped) {
    Mesh m = kite({0, 0, -0.4}); // the second triangle turned by 90 degrees about a-b
    const test::OwnedReference input(m);
    EXPECT_EQ(flips(m, input, 1e3), 0);
    EXPECT_TRUE(has_edge(m, 0, 1));
}

TEST(QualityPolish, AFlipThatLeavesTheInputIsNotMade) {
    // Bent by about 10 degrees about a-b: the diagonal c-d passes 0.035 from the input (the quad).
    Mesh bent = kite({0, -0.4, 0.07});
    const test::OwnedReference input(bent);
    Mesh tight = bent;
    EXPECT_EQ(flips(tight, input, 0.05), 0); // 0.035 > half the tolerance, and a-b lies on it
    EXPECT_EQ(flips(bent, input, 0.1), 1);   // 0.035 <= 0.05
}

// The end of a wall 1 thick (sides x = 0 and x = 1, end y = 0), as t13's with seed 3: the
// quad t, v, w, u has t on the side x = 0, v on the far crease, u and w on the near crease. Split
// along t-v, its triangles cut through the wall's corner, turning by 115 degrees, up to 0.4
// from the input; the diagonal u-w puts one triangle on the side, one on the end.
Mesh wall_end() {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    auto rectangle = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
        const auto i = static_cast<int32_t>(p.size());
        p.insert(p.end(), {o, o + e1, o + e1 + e2, o + e2}); // normal e1 x e2, out of the wall
        f.push_back({i, i + 1, i + 2});
        f.push_back({i, i + 2, i + 3});
    };
    rectangle({0, 0, -1}, {0, 0, 3}, {0, 3, 0}); // side x = 0
    rectangle({0, 0, -1}, {1, 0, 0}, {0, 0, 3}); // end y = 0
    rectangle({1, 0, -1}, {0, 3, 0}, {0, 0, 3}); // side x = 1
    return test::make_mesh(p, f);
}

TEST(QualityPolish, AFoldIsFlippedOntoTheInput) {
    // t, v, w, u; the triangles (t, v, w) and (v, t, u).
    Mesh m = test::make_mesh({{0, 0.8, 0.4}, {1, 0, 0.4}, {0, 0, 0.8}, {0, 0, 0}}, {{0, 1, 2}, {1, 0, 3}});
    const test::OwnedReference input(wall_end());
    ASSERT_GT(test::largest_dihedral_deg(m), 110.0);
    Mesh near_enough = m; // the fold is within a tolerance of 0.5: left as it is
    EXPECT_EQ(polish_quality(near_enough, input, with_tolerance(0.5)).unfolded, 0);
    const QualityPolishStats stats = polish_quality(m, input, with_tolerance(0.1));
    EXPECT_EQ(stats.unfolded, 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    for (Eigen::Index f = 0; f < 2; ++f) // on the input now (its corners were already)
        EXPECT_LE(input.tree.closest((corner(m, f, 0) + corner(m, f, 1) + corner(m, f, 2)) / 3.0).squared_distance, 1e-24);
    EXPECT_LT(test::largest_dihedral_deg(m), 90.0 + 1e-9);
    EXPECT_GE(test::min_kappa(m), 0.3);
}

// A pair folded shut on a plane, as a corner pin hole's rim left one on a frame's top face: the
// apex c of (b, a, c) lies inside (a, b, d), facing down onto it, on the input but for its side.
// Within any tolerance, and the flip leaves (c, d, a) nearly flat (c near the line a-d): taken
// all the same, since a mesher refuses the pair; the mending of triangles under 0.3 comes after.
TEST(QualityPolish, APairFoldedShutOnTheInputIsFlippedWhateverTheNewShape) {
    Mesh m = test::make_mesh({{0, 0, 0}, {2, 0, 0}, {0.5, 0.55, 0}, {1.2, 1.4, 0}}, {{0, 1, 3}, {1, 0, 2}});
    const test::OwnedReference input(test::make_square(4.0, 4));
    ASSERT_GT(test::largest_dihedral_deg(m), 179.0);
    const QualityPolishStats stats = polish_quality(m, input, with_tolerance(0.5));
    EXPECT_EQ(stats.unfolded, 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    EXPECT_LT(test::largest_dihedral_deg(m), 1e-6); // both up, on the plane
    EXPECT_LT(test::min_kappa(m), 0.1);
}

// A blade of the input: two faces turning by 135 degrees about a-b. Followed by the mesh, it is
// no fold, and flipping it would cut the blade.
TEST(QualityPolish, ASharpCreaseOfTheInputIsNoFold) {
    const double s = std::sqrt(0.5);
    Mesh m = test::make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, -s, s}}, {{1, 0, 2}, {0, 1, 3}});
    const test::OwnedReference input(m);
    const QualityPolishStats stats = polish_quality(m, input, with_tolerance(1e3));
    EXPECT_EQ(stats.unfolded, 0);
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_TRUE(has_edge(m, 0, 1));
}

namespace {
// An input with a right-angled crease along the x axis: face A, z = 0 and y in [0, 1], facing +z;
// face B, y = 0 and z in [-1, 0], facing -y.
Mesh right_crease() {
    return test::make_mesh({{-1.5, 0, 0}, {1.5, 0, 0}, {1.5, 1, 0}, {-1.5, 1, 0}, {1.5, 0, -1}, {-1.5, 0, -1}},
                           {{0, 1, 2}, {0, 2, 3}, {1, 0, 5}, {1, 5, 4}});
}
// On it, the crease edge a = (-1, 0, 0), b = (1, 0, 0), with the triangle (a, b, c) on face A,
// c = (0, off, 0), and (b, a, d) on face B, d = (0, 0, -0.8); beyond c on face A, (a, c, e) and
// (c, b, e), e = (0, 0.8, 0).
Mesh crease_pair(double off) {
    return test::make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, off, 0}, {0, 0, -0.8}, {0, 0.8, 0}},
                           {{0, 1, 2}, {1, 0, 3}, {0, 2, 4}, {2, 1, 4}});
}
} // namespace

TEST(QualityPolish, ACapOnACreaseIsFlippedAndTheCreaseRunsThroughItsApex) {
    // c 0.05 off the crease: an angle of 174 degrees at c, kappa 0.09.
    Mesh m = crease_pair(0.05);
    const test::OwnedReference input(right_crease());
    ASSERT_LT(test::min_kappa(m), 0.1);
    ASSERT_NEAR(measure_quality(m).sharp_edge_length, 2.0, 1e-12); // a-b
    Mesh strict = m; // c lies 0.05 off face B: beyond a tolerance of 0.01, the flip is not made
    polish_quality(strict, input, with_tolerance(0.01));
    EXPECT_TRUE(has_edge(strict, 0, 1));
    EXPECT_GE(flips(m, input, 0.1), 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    EXPECT_GT(test::min_kappa(m), 0.4);
    for (Eigen::Index f : {0, 1}) // on face B now
        EXPECT_GT((corner(m, f, 1) - corner(m, f, 0)).cross(corner(m, f, 2) - corner(m, f, 0)).normalized().dot(
                      Eigen::Vector3d(0, -1, 0)), 0.99);
    // The crease runs a-c-b: 0.1% longer than a-b.
    EXPECT_NEAR(measure_quality(m).sharp_edge_length, 2.0 * std::sqrt(1.0 + 0.05 * 0.05), 1e-9);
}

TEST(QualityPolish, ACapOnTheRimOfAThinPlateIsKept) {
    // A plate 0.05 thick (y < 0, z in [-0.05, 0]) and its rim face y = 0, facing +y; the cap
    // (a, b, c) stands on the rim, c = (0, 0, -0.05); (b, a, d) on the top, (a, c, e) and (c, b, e)
    // on the bottom. Flipped, the two new triangles would lie on the top within 0.1 and be far
    // better, but would turn by 176 degrees from the bottom ones: the plate folded onto itself.
    const Mesh input = test::make_mesh({{-1.5, 0, 0}, {1.5, 0, 0}, {1.5, -1, 0}, {-1.5, -1, 0}, {-1.5, 0, -0.05},
                                        {1.5, 0, -0.05}, {1.5, -1, -0.05}, {-1.5, -1, -0.05}},
                                       {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {4, 5, 6}, {4, 6, 7}});
    Mesh m = test::make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, 0, -0.05}, {0, -0.8, 0}, {0, -0.8, -0.05}},
                             {{0, 1, 2}, {1, 0, 3}, {0, 2, 4}, {2, 1, 4}});
    const AabbTree tree(input);
    EditableMesh editable(m);
    const auto quad = editable.quad_of(editable.edge_uses().at(edge_key(0, 1)));
    ASSERT_TRUE(quad.has_value());
    ASSERT_TRUE(cap_flip_fits_input(editable, *quad, tree, 0.1)); // on its own, the flip would do
    polish_quality(m, {input, tree}, with_tolerance(0.1));
    EXPECT_TRUE(has_edge(m, 0, 1));
}

TEST(QualityPolish, ACapTurnedOverAboveAStepIsFlippedDownIt) {
    // A step 0.3 high: the face z = 0 for x up to its rim, which bends from (0, -1.5) out to
    // (0.05, 0) and back to (0, 1.5), the face z = -0.3 beyond. Three output vertices on the rim,
    // a, c and b, make a cap turned over onto (b, a, d), d on the lower face: the cap faces -z,
    // the others +z. Flipped, the triangles from the rim down to d lie up to 0.15 off the input:
    // beyond a tolerance of 0.1, within twice it.
    const double s = 0.3;
    const Mesh input = test::make_mesh(
        {{-1, 0, 0}, {-1, -1.5, 0}, {0, -1.5, 0}, {0.05, 0, 0}, {0, 1.5, 0}, {-1, 1.5, 0}, // upper face
         {0, -1.5, -s}, {0.05, 0, -s}, {0, 1.5, -s}, {1, 1.5, -s}, {1, -1.5, -s}},        // lower face
        {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, // upper, fanned from (-1, 0, 0)
         {2, 6, 7}, {2, 7, 3}, {3, 7, 8}, {3, 8, 4}, // the wall, facing +x
         {6, 10, 7}, {7, 10, 9}, {7, 9, 8}});        // lower
    Mesh m = test::make_mesh({{0, -1, 0}, {0, 1, 0}, {0.05, 0, 0}, {0.8, 0, -s}, {-0.8, 0, 0}},
                             {{0, 1, 2}, {1, 0, 3}, {2, 1, 4}, {0, 2, 4}});
    const AabbTree tree(input);
    EditableMesh editable(m);
    ASSERT_LT(editable.normal(editable.tris[0]).z(), 0.0); // turned over
    const auto quad = editable.quad_of(editable.edge_uses().at(edge_key(0, 1)));
    ASSERT_TRUE(quad.has_value());
    EXPECT_TRUE(cap_flip_fits_input(editable, *quad, tree, 0.1));
    EXPECT_FALSE(cap_flip_fits_input(editable, *quad, tree, 0.07)); // 0.15 off: beyond twice 0.07
    polish_quality(m, {input, tree}, with_tolerance(0.1));
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        EXPECT_GT((corner(m, f, 1) - corner(m, f, 0)).cross(corner(m, f, 2) - corner(m, f, 0)).z(), 0.0) << f;
}

TEST(QualityPolish, ATriangleShortOfACapIsNotFlippedAcrossACrease) {
    // c 0.3 off the crease: 147 degrees at c.
    Mesh m = crease_pair(0.3);
    const test::OwnedReference input(right_crease());
    polish_quality(m, input, with_tolerance(0.5));
    EXPECT_TRUE(has_edge(m, 0, 1));
}

// Two triangles on the wall of a hole of radius 4 (the FreeCAD bracket's, edges of 2.5), split
// along a chord round the wall spanning 48 degrees, whose midpoint lies 0.35 off it: a curved
// tet10 element bending that edge back onto the wall was inverted, and FEM lost the faces. The
// other diagonal runs nearly along the axis, 0.01 off, with both triangles above kappa 0.55.
TEST(QualityPolish, AChordAcrossACurvedWallIsFlippedAlongIt) {
    const test::OwnedReference input(wall());
    // a-b the chord, c above it and d below; both triangles face outwards, as the input does.
    const Mesh quad = on_wall({{124.3, 5.936}, {172.4, 6.034}, {139.8, 7.874}, {146.7, 4.224}});
    Mesh m = quad;
    EXPECT_EQ(flips(m, input, 0.15 * 2.5), 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_FALSE(has_edge(m, 0, 1));
    EXPECT_GE(test::min_kappa(m), kKappaFloorChord);
    EXPECT_EQ(test::facing_inward(m, {0, 0, 6}), 0);
    // Within half the tolerance the chord is left as the optimisation made it.
    Mesh loose = quad;
    EXPECT_EQ(flips(loose, input, 1.0), 0);
    EXPECT_TRUE(has_edge(loose, 0, 1));
}

// A chord of 120 degrees round a wall of radius 4 (2.0 off it), whose other diagonal runs along
// the axis: flipped, the new triangles would span 60 degrees each, their edges 0.54 off the
// wall, over the tolerance of 0.5. A flip whose triangles do not lie on the input is not made
// (on a thread's crests such flips left edges folded shut).
TEST(QualityPolish, AChordFlipWhoseTrianglesLeaveTheInputIsNotMade) {
    const test::OwnedReference input(wall());
    Mesh m = on_wall({{90.0, 5.0}, {210.0, 5.0}, {150.0, 8.5}, {150.0, 1.5}});
    EXPECT_EQ(flips(m, input, 0.5), 0);
    EXPECT_TRUE(has_edge(m, 0, 1));
}

TEST(QualityPolish, AVertexPushedOutOfPlaceOnAFlatPartIsMovedBack) {
    Mesh m = test::make_square(4.0, 4); // unit cells, vertex 12 at (2, 2)
    m.points.row(12) << 2.7, 2.6, 0.0;
    const test::OwnedReference input(test::make_square(4.0, 4));
    QualityPolishParams no_flips = with_tolerance(0.1);
    no_flips.flip_passes = 0;
    const double before = test::min_kappa(m);
    const QualityPolishStats stats = polish_quality(m, input, no_flips);
    EXPECT_GE(stats.moved, 1);
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_GT(test::min_kappa(m), before + 0.1);
    EXPECT_EQ(m.points.col(2).cwiseAbs().maxCoeff(), 0.0); // all still on the plane
    EXPECT_EQ(test::facing_inward(m, {2, 2, -1}), 0);
    // The border stays where it was.
    const Mesh grid = test::make_square(4.0, 4);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v)
        if (grid.points(v, 0) == 0.0 || grid.points(v, 0) == 4.0 || grid.points(v, 1) == 0.0 || grid.points(v, 1) == 4.0)
            EXPECT_EQ(m.points.row(v), grid.points.row(v)) << v;
}

// A vertex pushed across its fan's rim, in the plane, turns a triangle over onto its neighbours:
// well shaped, the triangle was no relaxation's candidate, and the fan, not flat, was left as it
// was (the frame of test_components at 1.5 mm edges came out with five such, each counted three
// times as an edge folded shut). Now its vertex is moved so that every triangle faces the
// others' way.
TEST(QualityPolish, ATriangleTurnedOverOnAFlatPartIsTurnedBack) {
    Mesh m = test::make_square(4.0, 4); // unit cells, vertex 12 at (2, 2)
    m.points.row(12) << 3.3, 2.4, 0.0;
    ASSERT_GT(test::facing_inward(m, {2, 2, -1}), 0);
    const test::OwnedReference input(test::make_square(4.0, 4));
    QualityPolishParams no_flips = with_tolerance(0.1);
    no_flips.flip_passes = 0;
    const QualityPolishStats stats = polish_quality(m, input, no_flips);
    EXPECT_GE(stats.moved, 1);
    EXPECT_EQ(test::facing_inward(m, {2, 2, -1}), 0);
    EXPECT_GT(test::min_kappa(m), 0.5);
    EXPECT_EQ(m.points.col(2).cwiseAbs().maxCoeff(), 0.0);
    // Against an input facing down, the triangle facing down is the one that faces as it should:
    // the others are not turned over to it.
    Mesh down = test::make_square(4.0, 4);
    down.triangles.col(1).swap(down.triangles.col(2));
    Mesh pushed = test::make_square(4.0, 4);
    pushed.points.row(12) << 3.3, 2.4, 0.0;
    const long facing_down = test::facing_inward(pushed, {2, 2, -1});
    polish_quality(pushed, test::OwnedReference(down), no_flips);
    EXPECT_EQ(test::facing_inward(pushed, {2, 2, -1}), facing_down);
}

TEST(QualityPolish, AVertexOnACreaseIsNotMoved) {
    Mesh m = test::make_cube(0.5, 4);
    // A vertex in the middle of the edge x = y = 0.5, pushed along the edge: bad triangles on
    // both faces, but its fan turns by 90 degrees.
    Eigen::Index v = 0;
    while (!(std::abs(m.points(v, 0) - 0.5) < 1e-12 && std::abs(m.points(v, 1) - 0.5) < 1e-12 &&
             std::abs(m.points(v, 2)) < 1e-12))
        ++v;
    m.points(v, 2) = 0.2;
    const test::OwnedReference input(m);
    QualityPolishParams no_flips = with_tolerance(0.05);
    no_flips.flip_passes = 0;
    const Eigen::RowVector3d at = m.points.row(v);
    Mesh any_fan = m;
    polish_quality(m, input, no_flips);
    EXPECT_EQ(m.points.row(v), at);
    // What the flat-fan rule prevents: allowed any fan, the vertex moves.
    no_flips.flat_angle_deg = 180.0;
    polish_quality(any_fan, input, no_flips);
    EXPECT_NE(any_fan.points.row(v), at);
}

TEST(QualityPolish, AClosedSurfaceKeepsItsTopologyAndGetsNoWorse) {
    Mesh m = test::make_icosphere(3);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v) {
        m.points.row(v) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
        m.points.row(v).normalize();
    }
    const test::OwnedReference input(m);
    const double before = test::min_kappa(m);
    const QualityPolishStats stats = polish_quality(m, input, with_tolerance(0.05));
    EXPECT_GT(stats.flipped, 0);
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(test::facing_inward(m, Eigen::Vector3d::Zero()), 0);
    EXPECT_GT(test::min_kappa(m), before);
    EXPECT_LE(hausdorff_distance(m, test::make_icosphere(3)).hausdorff, 0.05);
}

TEST(QualityPolish, FlipsAroundGivenVerticesTouchNothingElse) {
    // Two kites, the second 10 along x: flips around the first's vertex c flip its diagonal alone.
    const Mesh one = kite({0, -0.4, 0});
    Mesh two = one;
    two.points.col(0).array() += 10.0;
    const Mesh both = test::joined(one, two);
    const test::OwnedReference input(both);
    Mesh m = both;
    EXPECT_EQ(flip_around(m, input, with_tolerance(0.01), {}), 0);
    EXPECT_EQ(m.triangles, both.triangles);
    EXPECT_EQ(flip_around(m, input, with_tolerance(0.01), {2}), 1);
    EXPECT_TRUE(has_edge(m, 2, 3));
    EXPECT_TRUE(has_edge(m, 4, 5)); // the second kite's long diagonal, kept
    EXPECT_FALSE(has_edge(m, 6, 7));
    EXPECT_EQ(m.points, both.points);
    EXPECT_EQ(euler_characteristic(m), 2);
    EXPECT_THROW(flip_around(m, input, with_tolerance(0.01), {8}), InvalidInput);
    EXPECT_THROW(flip_around(m, input, with_tolerance(0.0), {2}), InvalidInput);
}

TEST(QualityPolish, BadArgumentsAreRejected) {
    Mesh m = kite({0, -0.4, 0});
    const test::OwnedReference input(m);
    EXPECT_THROW(polish_quality(m, input, with_tolerance(0.0)), InvalidInput);
    EXPECT_THROW(polish_quality(m, input, with_tolerance(std::nan(""))), InvalidInput);
    QualityPolishParams p = with_tolerance(0.1);
    p.flip_passes = -1;
    EXPECT_THROW(polish_quality(m, input, p), InvalidInput);
    p = with_tolerance(0.1);
    p.relax_passes = -1;
    EXPECT_THROW(polish_quality(m, input, p), InvalidInput);
    m.triangles(0, 0) = 9;
    EXPECT_THROW(polish_quality(m, input, with_tolerance(0.1)), InvalidInput);
}
