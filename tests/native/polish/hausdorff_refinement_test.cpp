// Inserting the input's farthest points: a sharp edge cut off by a chamfer (edge crunching,
// Section 6.2.2) gets its crease back; a mesh that already lies on its input is left alone. And
// inserting given points of the input (the creases' junctions).
#include "liftremesh/exceptions.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/polish/hausdorff_refinement.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace liftremesh;

namespace {

// Rows of points across columns y = 0, s, ..., n s, joined strip by strip into an oriented
// surface: row r and row r + 1 make a strip of 2 n triangles.
Mesh strips(const std::vector<std::vector<Eigen::Vector3d>>& rows) {
    const int columns = static_cast<int>(rows[0].size());
    std::vector<Eigen::Vector3d> pts;
    for (const auto& row : rows) pts.insert(pts.end(), row.begin(), row.end());
    std::vector<std::array<int32_t, 3>> tris;
    for (int r = 0; r + 1 < static_cast<int>(rows.size()); ++r)
        for (int i = 0; i + 1 < columns; ++i) {
            const int32_t a = r * columns + i, b = a + 1, c = a + columns + 1, d = a + columns;
            tris.push_back({a, b, c});
            tris.push_back({a, c, d});
        }
    return test::make_mesh(pts, tris);
}

// A row of points along y at the given x and z.
std::vector<Eigen::Vector3d> row(double x, double z, int n, double s) {
    std::vector<Eigen::Vector3d> r;
    for (int i = 0; i <= n; ++i) r.emplace_back(x, i * s, z);
    return r;
}

constexpr int kColumns = 8;
constexpr double kSpacing = 0.25;

// An L: the floor z = 0 (0 <= x <= 1) and the wall x = 0 (0 <= z <= 1), meeting at a 90 degree
// crease along y, in four triangles.
Mesh crease_input() { return strips({row(1, 0, 1, kColumns * kSpacing), row(0, 0, 1, kColumns * kSpacing), row(0, 1, 1, kColumns * kSpacing)}); }

// The same L meshed at edge length kSpacing with no vertex on the crease: its two rows next
// to it, at x = 0.2 and z = 0.2, are joined across it by a chamfer 0.14 deep.
Mesh chamfered() {
    return strips({row(1, 0, kColumns, kSpacing), row(0.6, 0, kColumns, kSpacing), row(0.2, 0, kColumns, kSpacing),
                   row(0, 0.2, kColumns, kSpacing), row(0, 0.6, kColumns, kSpacing), row(0, 1, kColumns, kSpacing)});
}

// Largest distance from points along the crease to the mesh.
double crease_gap(const Mesh& m) {
    const AabbTree tree(m);
    double worst = 0.0;
    for (int i = 0; i <= 100; ++i)
        worst = std::max(worst, std::sqrt(tree.closest(Eigen::Vector3d(0, i * kColumns * kSpacing / 100.0, 0)).squared_distance));
    return worst;
}

HausdorffRefinementParams params_for(double h) {
    HausdorffRefinementParams p;
    p.tolerance = 0.15 * h;
    p.sample_spacing = 0.5 * h;
    return p;
}

} // namespace

TEST(HausdorffRefinement, ChamferedCreaseGetsItsCreaseBack) {
    const Mesh input = crease_input();
    Mesh m = chamfered();
    const test::Topology before = test::topology(m);
    const double kappa_before = test::min_kappa(m);
    const double gap_before = crease_gap(m);
    ASSERT_NEAR(gap_before, 0.2 / std::sqrt(2.0), 1e-9);
    const HausdorffRefinementParams p = params_for(kSpacing);

    const HausdorffRefinementStats stats = refine_towards_input(m, test::OwnedReference(input), p);

    EXPECT_GE(stats.inserted, kColumns);
    EXPECT_GT(stats.flipped, 0); // the chamfer's diagonals turn to run along the crease
    EXPECT_EQ(m.points.rows(), chamfered().points.rows() + stats.inserted);
    // Every point of the crease is within the tolerance now, and so is the whole input.
    EXPECT_LE(crease_gap(m), p.tolerance);
    const DistanceStats d = hausdorff_distance(input, m, 20000, 3);
    EXPECT_LE(d.hausdorff, p.tolerance);
    // Splits and flips only: the same oriented surface with a boundary, no worse triangle
    // than the floor or than the mesh had. The crease's two ends split the boundary edges
    // that cut them off.
    const test::Topology after = test::topology(m);
    EXPECT_TRUE(after.oriented_manifold());
    EXPECT_EQ(after.chi, before.chi);
    long on_boundary = 0;
    for (Eigen::Index v = chamfered().points.rows(); v < m.points.rows(); ++v)
        if (m.points(v, 1) == 0.0 || m.points(v, 1) == kColumns * kSpacing) ++on_boundary;
    EXPECT_EQ(on_boundary, 2);
    EXPECT_EQ(after.boundary_edges, before.boundary_edges + on_boundary);
    EXPECT_GE(test::min_kappa(m), std::min(kappa_before, p.kappa_floor));
}

TEST(HausdorffRefinement, FloorOnKappaStopsInsertionsThatMakeSlivers) {
    const Mesh input = crease_input();
    Mesh m = chamfered();
    HausdorffRefinementParams p = params_for(kSpacing);
    p.kappa_floor = 0.99; // no split of these triangles reaches it
    const HausdorffRefinementStats stats = refine_towards_input(m, test::OwnedReference(input), p);
    EXPECT_EQ(stats.inserted, 0);
    EXPECT_EQ(m.triangles, chamfered().triangles);
    EXPECT_NEAR(crease_gap(m), 0.2 / std::sqrt(2.0), 1e-9);
}

TEST(HausdorffRefinement, MeshOnItsInputIsLeftAsItIs) {
    // A finer meshing of the same cube: every input point lies on it.
    const Mesh input = test::make_cube(0.5, 1);
    Mesh m = test::make_cube(0.5, 5);
    const Mesh original = m;
    const HausdorffRefinementStats stats = refine_towards_input(m, test::OwnedReference(input), params_for(0.2));
    EXPECT_EQ(stats.inserted, 0);
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(m.points, original.points);
    EXPECT_EQ(m.triangles, original.triangles);
}

TEST(HausdorffRefinement, BadArgumentsAreRejected) {
    const Mesh input = crease_input();
    Mesh m = chamfered();
    HausdorffRefinementParams p = params_for(kSpacing);
    p.tolerance = 0.0;
    EXPECT_THROW(refine_towards_input(m, test::OwnedReference(input), p), InvalidInput);
    p = params_for(kSpacing);
    p.sample_spacing = std::nan("");
    EXPECT_THROW(refine_towards_input(m, test::OwnedReference(input), p), InvalidInput);
    Mesh broken = chamfered();
    broken.triangles(0, 0) = 1000;
    EXPECT_THROW(refine_towards_input(broken, test::OwnedReference(input), params_for(kSpacing)), InvalidInput);
    Mesh empty;
    EXPECT_EQ(refine_towards_input(empty, test::OwnedReference(input), params_for(kSpacing)).inserted, 0);
}

TEST(HausdorffRefinement, CapAndLargestDistanceLimitWhatIsInserted) {
    const Mesh input = crease_input();
    HausdorffRefinementParams p = params_for(kSpacing);
    p.max_inserted = 3;
    Mesh capped = chamfered();
    EXPECT_EQ(refine_towards_input(capped, test::OwnedReference(input), p).inserted, 3);
    EXPECT_EQ(capped.points.rows(), chamfered().points.rows() + 3);
    // The chamfer is 0.14 deep: a largest distance of 0.1 takes its crease for a lost part;
    // in one round only points of the input's faces nearer than that to the chamfer come in
    // (a later round measures against the mesh those made).
    p = params_for(kSpacing);
    p.max_distance = 0.1;
    p.rounds = 1;
    Mesh far = chamfered();
    refine_towards_input(far, test::OwnedReference(input), p);
    const AabbTree before(chamfered());
    for (Eigen::Index v = chamfered().points.rows(); v < far.points.rows(); ++v)
        EXPECT_LE(before.closest(far.points.row(v).transpose()).squared_distance, 0.1 * 0.1) << v;
    EXPECT_GT(far.points.rows(), chamfered().points.rows()); // some did come in
    p.max_distance = 0.0;
    EXPECT_THROW(refine_towards_input(far, test::OwnedReference(input), p), InvalidInput);
}

// A step lower than the edge length whose wall leans out over the floor (RLF_7030's terminals):
// the floor z = 0 (0 <= x <= 1), the wall up to its top rim at x = 0.03, z = 0.09, and the top
// z = 0.09 (x <= 0.03). The mesh runs along the floor to the bottom rim and across the top rim
// by a chamfer to x = -0.3. A point of the top rim lies nearer the floor's triangles than the
// chamfer: splitting one of them there stood a triangle on the bottom rim leaning back over the
// wall, facing into the part, and the next point inserted beside it folded a triangle onto it.
TEST(HausdorffRefinement, APointOverALowStepsWallStandsNoTriangleAgainstIt) {
    constexpr double kRim = 0.03, kStep = 0.09;
    const Mesh input = strips({row(1, 0, 1, kColumns * kSpacing), row(0, 0, 1, kColumns * kSpacing),
                               row(kRim, kStep, 1, kColumns * kSpacing), row(-1, kStep, 1, kColumns * kSpacing)});
    auto stepped = [&] {
        return strips({row(1, 0, kColumns, kSpacing), row(0.5, 0, kColumns, kSpacing), row(0, 0, kColumns, kSpacing),
                       row(-0.3, kStep, kColumns, kSpacing), row(-1, kStep, kColumns, kSpacing)});
    };
    Mesh m = stepped();
    const test::Topology before = test::topology(m);
    const HausdorffRefinementStats stats = refine_towards_input(m, test::OwnedReference(input), params_for(kSpacing));
    EXPECT_GT(stats.inserted, 0);
    const test::Topology after = test::topology(m);
    EXPECT_TRUE(after.oriented_manifold());
    EXPECT_EQ(after.chi, before.chi);
    // No triangle is turned over, by more than 150 degrees, from the input's triangle nearest to
    // its centroid (those across the top rim lean over the wall, by up to about 115 degrees).
    const AabbTree tree(input);
    for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
        const Eigen::Vector3d a = m.points.row(m.triangles(t, 0)).transpose(), b = m.points.row(m.triangles(t, 1)).transpose(),
                              c = m.points.row(m.triangles(t, 2)).transpose();
        const ClosestPoint near = tree.closest((a + b + c) / 3.0);
        EXPECT_GT((b - a).cross(c - a).normalized().dot(tree.triangle_normal(near.triangle)), -std::sqrt(3.0) / 2.0)
            << "triangle " << t;
    }
}

namespace {

// The L of crease_input() meshed at edge length kSpacing with a row of vertices on its crease:
// right triangles of kappa 0.87 on either side.
Mesh creased() {
    std::vector<std::vector<Eigen::Vector3d>> rows;
    for (int i = 4; i > 0; --i) rows.push_back(row(i * kSpacing, 0, kColumns, kSpacing));
    for (int i = 0; i <= 4; ++i) rows.push_back(row(0, i * kSpacing, kColumns, kSpacing));
    return strips(rows);
}

// Whether two meshes are the same, row for row (the sizes first: Eigen compares equal sizes only).
void expect_same_mesh(const Mesh& got, const Mesh& want) {
    ASSERT_EQ(got.points.rows(), want.points.rows());
    ASSERT_EQ(got.triangles.rows(), want.triangles.rows());
    EXPECT_EQ(got.points, want.points);
    EXPECT_EQ(got.triangles, want.triangles);
}

// The worst kappa of the three triangles a split of triangle t at p makes.
double worst_of_split(const Mesh& m, Eigen::Index t, const Eigen::Vector3d& p) {
    double worst = 1.0;
    for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d a = m.points.row(m.triangles(t, j)).transpose(), b = m.points.row(m.triangles(t, (j + 1) % 3)).transpose();
        worst = std::min(worst, triangle_kappa(a, b, p));
    }
    return worst;
}

} // namespace

// A junction of creases a quarter of an edge from the vertex on the crease next to it (t13's
// clusters of corners 0.25-0.39 h apart): the triangle it falls in, split there, leaves a needle
// under the floor; the flips round it and the splits of the needles' long edges give it a vertex
// with every triangle at the floor or better. Without those splits the point was left out.
TEST(InsertInputPoints, AJunctionAQuarterEdgeFromAVertexGetsItsOwn) {
    const Mesh input = crease_input();
    Mesh m = creased();
    const Mesh original = m;
    const Eigen::Vector3d junction(0.0, 4 * kSpacing + 0.25 * kSpacing, 0.0);
    const ClosestPoint near = AabbTree(m).closest(junction);
    ASSERT_GE(near.triangle, 0);
    const HausdorffRefinementParams p = params_for(kSpacing);
    EXPECT_LT(worst_of_split(m, near.triangle, junction), p.kappa_floor);
    const test::Topology before = test::topology(m);
    const HausdorffRefinementStats stats = insert_input_points(m, test::OwnedReference(input), {junction}, 0.02 * kSpacing, p);
    EXPECT_GT(stats.inserted, 1); // the junction and the splits that mend its needle
    EXPECT_EQ(stats.inserted, m.points.rows() - original.points.rows());
    EXPECT_EQ(test::distance_to_nearest_vertex(m, junction), 0.0);
    EXPECT_GE(test::min_kappa(m), p.kappa_floor);
    const test::Topology after = test::topology(m);
    EXPECT_TRUE(after.oriented_manifold());
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_EQ(after.boundary_edges, before.boundary_edges);
    // Every vertex on the input (the L's floor or wall), the old ones where they were.
    const AabbTree tree(input);
    for (Eigen::Index v = 0; v < m.points.rows(); ++v)
        EXPECT_LT(tree.closest(m.points.row(v).transpose()).squared_distance, 1e-20) << v;
    EXPECT_EQ(m.points.topRows(original.points.rows()), original.points);
}

// A point with a vertex within the gap is on it already; one whose triangles cannot reach the
// floor is left out, the mesh as it was.
TEST(InsertInputPoints, APointOnAVertexOrUnderTheFloorChangesNothing) {
    const Mesh input = crease_input();
    const Mesh original = creased();
    Mesh m = original;
    const Eigen::Vector3d vertex(0.0, 4 * kSpacing, 0.0);
    const HausdorffRefinementParams p = params_for(kSpacing);
    EXPECT_EQ(insert_input_points(m, test::OwnedReference(input), {vertex + Eigen::Vector3d(0, 0.01 * kSpacing, 0)},
                                  0.02 * kSpacing, p).inserted, 0);
    expect_same_mesh(m, original);
    HausdorffRefinementParams strict = p;
    strict.kappa_floor = 0.99; // no triangle of a split reaches it
    EXPECT_EQ(insert_input_points(m, test::OwnedReference(input), {vertex + Eigen::Vector3d(0, 0.25 * kSpacing, 0)},
                                  0.02 * kSpacing, strict).inserted, 0);
    expect_same_mesh(m, original);
    // Nor a point farther from the mesh than the largest distance: a part the output lost.
    HausdorffRefinementParams near = p;
    near.max_distance = 0.1;
    EXPECT_EQ(insert_input_points(m, test::OwnedReference(input), {Eigen::Vector3d(0.5, 1.0, 0.2)}, 0.0, near).inserted, 0);
    expect_same_mesh(m, original);
}

// A try that fails is undone whole, whatever a try before it or after it did: with a point that
// stands and one that cannot (on the floor's plane 0.05 edges from a vertex, every split and
// mend of it under the floor), the mesh is the one the first point gives alone.
TEST(InsertInputPoints, AFailedTryLeavesTheOthersAsTheyWere) {
    const Mesh input = crease_input();
    const HausdorffRefinementParams p = params_for(kSpacing);
    const Eigen::Vector3d stands(0.0, 4 * kSpacing + 0.25 * kSpacing, 0.0); // AJunctionAQuarterEdge...'s
    const Eigen::Vector3d fails = Eigen::Vector3d(2 * kSpacing, 2 * kSpacing, 0.0) + Eigen::Vector3d(0.05, 0.0, 0.0) * kSpacing;
    Mesh alone = creased();
    const long one = insert_input_points(alone, test::OwnedReference(input), {stands}, 0.02 * kSpacing, p).inserted;
    ASSERT_GT(one, 0);
    Mesh failing = creased();
    ASSERT_EQ(insert_input_points(failing, test::OwnedReference(input), {fails}, 0.02 * kSpacing, p).inserted, 0);
    for (const auto& order : {std::vector<Eigen::Vector3d>{stands, fails}, std::vector<Eigen::Vector3d>{fails, stands}}) {
        Mesh both = creased();
        EXPECT_EQ(insert_input_points(both, test::OwnedReference(input), order, 0.02 * kSpacing, p).inserted, one);
        expect_same_mesh(both, alone);
    }
}

// A point's own floor holds for its try in place of the refinement's: the point
// AFailedTryLeavesTheOthersAsTheyWere cannot insert under 0.45 stands under a lower one, and the
// other points keep theirs.
TEST(InsertInputPoints, APointsOwnFloorHoldsForItsTry) {
    const Mesh input = crease_input();
    const HausdorffRefinementParams p = params_for(kSpacing);
    const Eigen::Vector3d stands(0.0, 4 * kSpacing + 0.25 * kSpacing, 0.0);
    const Eigen::Vector3d fails = Eigen::Vector3d(2 * kSpacing, 2 * kSpacing, 0.0) + Eigen::Vector3d(0.05, 0.0, 0.0) * kSpacing;
    Mesh same = creased();
    EXPECT_EQ(insert_input_points(same, test::OwnedReference(input), {fails}, 0.02 * kSpacing, p, {p.kappa_floor}).inserted, 0);
    expect_same_mesh(same, creased());
    Mesh m = creased();
    const double low = 0.05;
    EXPECT_GT(insert_input_points(m, test::OwnedReference(input), {stands, fails}, 0.02 * kSpacing, p, {p.kappa_floor, low})
                  .inserted,
              1);
    EXPECT_EQ(test::distance_to_nearest_vertex(m, fails), 0.0);
    EXPECT_EQ(test::distance_to_nearest_vertex(m, stands), 0.0);
    EXPECT_GE(test::min_kappa(m), low);
    EXPECT_TRUE(test::topology(m).oriented_manifold());
}

namespace {
constexpr int kCells = 10;
constexpr double kCell = 0.1;

// A point in each cell of the kCells x kCells square, 0.3 of a cell from its lower corner on both
// axes, the last one `last_at` of a cell.
std::vector<Eigen::Vector3d> point_per_cell(double last_at) {
    std::vector<Eigen::Vector3d> points;
    for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
            const bool last = i == kCells - 1 && j == kCells - 1;
            points.push_back(Eigen::Vector3d(i, j, 0.0) * kCell + Eigen::Vector3d(1.0, 1.0, 0.0) * (last ? last_at : 0.3) * kCell);
        }
    return points;
}
} // namespace

// A scan's creases can meet in thousands of junctions, and each point tried passes over the
// whole mesh: 64 are tried, the farthest from a vertex first. A 10 x 10 square of cells has a
// point in each, all but the last 0.04 from the cell's lower corner, the last at its centre.
TEST(InsertInputPoints, TriesSixtyFourPointsFarthestFromAVertexFirst) {
    const Mesh square = test::make_square(kCells * kCell, kCells);
    const std::vector<Eigen::Vector3d> points = point_per_cell(0.5);
    Mesh m = square;
    const HausdorffRefinementStats stats =
        insert_input_points(m, test::OwnedReference(square), points, 0.02 * kCell, params_for(kCell));
    EXPECT_EQ(stats.inserted, 64);
    EXPECT_EQ(m.points.rows(), square.points.rows() + 64); // each a split that reached the floor
    EXPECT_EQ(test::distance_to_nearest_vertex(m, points.back()), 0.0);
    EXPECT_GT(test::distance_to_nearest_vertex(m, points[kCells * kCells - 2]), 0.0); // the 99th: not tried
    EXPECT_GE(test::min_kappa(m), params_for(kCell).kappa_floor);
    EXPECT_TRUE(test::topology(m).oriented_manifold());
}

// And none once params.max_inserted vertices were added: the creases' bends may be many, and
// the vertices asked for stay the budget (steps.cpp: 1% of them).
TEST(InsertInputPoints, StopsOnceTheMostInsertionsWereMade) {
    const Mesh square = test::make_square(kCells * kCell, kCells);
    for (const long most : {0L, 1L, 10L}) {
        Mesh m = square;
        HausdorffRefinementParams p = params_for(kCell);
        p.max_inserted = most;
        EXPECT_EQ(insert_input_points(m, test::OwnedReference(square), point_per_cell(0.3), 0.02 * kCell, p).inserted, most);
        EXPECT_EQ(m.points.rows(), square.points.rows() + most);
        EXPECT_TRUE(test::topology(m).oriented_manifold());
    }
}

TEST(InsertInputPoints, BadArgumentsAreRejected) {
    const Mesh input = crease_input();
    Mesh m = creased();
    const std::vector<Eigen::Vector3d> points = {Eigen::Vector3d(0.0, 0.3, 0.0)};
    const HausdorffRefinementParams p = params_for(kSpacing);
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, -1.0, p), InvalidInput);
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, std::nan(""), p), InvalidInput);
    HausdorffRefinementParams negative = p;
    negative.kappa_floor = -0.1;
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, 0.0, negative), InvalidInput);
    HausdorffRefinementParams no_tolerance = p;
    no_tolerance.tolerance = 0.0;
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, 0.0, no_tolerance), InvalidInput);
    HausdorffRefinementParams fewer_than_none = p;
    fewer_than_none.max_inserted = -1;
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, 0.0, fewer_than_none), InvalidInput);
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, 0.0, p, {0.3, 0.3}), InvalidInput);
    EXPECT_THROW(insert_input_points(m, test::OwnedReference(input), points, 0.0, p, {-0.1}), InvalidInput);
    Mesh broken = creased();
    broken.triangles(0, 0) = 1000;
    EXPECT_THROW(insert_input_points(broken, test::OwnedReference(input), points, 0.0, p), InvalidInput);
    Mesh empty;
    EXPECT_EQ(insert_input_points(empty, test::OwnedReference(input), points, 0.0, p).inserted, 0);
}
