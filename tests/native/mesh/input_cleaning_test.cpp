// clean_input (mesh/input_cleaning.h): a careless export's facets made into the surface they
// describe, and a two-sided sheet left two-sided.
#include "liftremesh/mesh/input_cleaning.h"

#include "liftremesh/exceptions.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <array>
#include <set>

using namespace liftremesh;

namespace {

// The facets as the coordinates of their corners, from the smallest corner on (so that the
// same facet listed from another corner compares equal, and its other winding does not):
// independent of how the vertices are numbered.
using Corners = std::array<std::array<double, 3>, 3>;
std::multiset<Corners> facets_of(const Mesh& m) {
    std::multiset<Corners> out;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
        Corners c;
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) c[j][k] = m.points(m.triangles(f, j), k);
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        out.insert(c);
    }
    return out;
}

Mesh cleaned(Mesh m, InputCleaning& done) {
    done = clean_input(m);
    remove_unreferenced_vertices(m);
    return m;
}

} // namespace

// The cube: every third facet turned, ten written twice (every other one the second
// time reversed), three zero-area facets. Cleaned, it is the cube again, facet for facet, in
// the cube's winding.
TEST(InputCleaning, ACarelessCubeExportIsTheCubeAgain) {
    const Mesh cube = test::make_cube(1.0, 5);
    test::CarelessExport what;
    const Mesh messy = test::carelessly_exported(cube, what);
    ASSERT_EQ(messy.triangles.rows(), cube.triangles.rows() + 13);
    ASSERT_FALSE(test::topology(messy).closed_oriented_manifold());
    InputCleaning done;
    const Mesh m = cleaned(messy, done);
    EXPECT_EQ(done.duplicates_removed, 10);
    EXPECT_EQ(done.degenerate_removed, 3);
    EXPECT_EQ(done.facets_turned, what.turned);
    EXPECT_EQ(what.turned, (cube.triangles.rows() + 2) / 3);
    EXPECT_EQ(facets_of(m), facets_of(cube));
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
}

// The same defects at random (seeded) on a torus: its facets back, whatever the seed.
TEST(InputCleaning, RandomDefectsOnATorusAreAllRepaired) {
    const Mesh torus = test::make_torus(1.0, 0.35, 30, 12);
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        test::CarelessExport what;
        what.turn_every = 0;
        what.repeats = 40;
        what.zero_area = 12;
        what.seed = seed;
        InputCleaning done;
        const Mesh m = cleaned(test::carelessly_exported(torus, what), done);
        EXPECT_EQ(done.duplicates_removed, 40) << "seed " << seed;
        EXPECT_EQ(done.degenerate_removed, 12) << "seed " << seed;
        EXPECT_EQ(done.facets_turned, what.turned) << "seed " << seed;
        EXPECT_EQ(facets_of(m), facets_of(torus)) << "seed " << seed;
    }
}

// A facet repeated the other way round inside a closed surface is a duplicate, wherever it is
// listed: before the original too (the first listed stays and is turned to its neighbours).
TEST(InputCleaning, AReversedRepeatListedFirstIsTheDuplicateTurned) {
    const Mesh sphere = test::make_icosphere(2);
    Mesh m = sphere;
    m.triangles.conservativeResize(m.triangles.rows() + 1, 3);
    m.triangles.bottomRows(m.triangles.rows() - 1) = sphere.triangles; // shifted down a row
    m.triangles.row(0) << sphere.triangles(4, 0), sphere.triangles(4, 2), sphere.triangles(4, 1);
    InputCleaning done;
    const Mesh out = cleaned(m, done);
    EXPECT_EQ(done.duplicates_removed, 1);
    EXPECT_EQ(done.facets_turned, 1);
    EXPECT_EQ(facets_of(out), facets_of(sphere));
}

// A closed surface listed twice, the second time reversed (no volume: one surface), is one.
TEST(InputCleaning, AClosedSurfaceListedInBothWindingsIsOne) {
    const Mesh sphere = test::make_icosphere(1);
    Mesh reversed = sphere;
    reversed.triangles.col(1).swap(reversed.triangles.col(2));
    InputCleaning done;
    const Mesh out = cleaned(test::joined(sphere, reversed), done);
    EXPECT_EQ(done.duplicates_removed, sphere.triangles.rows());
    EXPECT_EQ(facets_of(out), facets_of(sphere));
}

// A two-sided sheet: an open square meshed on both sides, sharing its vertices, no volume
// between. Both sides stay (its repeats in the same winding go); a reversed facet inside it
// stays a duplicate only where other facets touch it.
TEST(InputCleaning, ATwoSidedSheetStaysTwoSided) {
    const Mesh front = test::make_square(1.0, 4);
    Mesh back = front;
    back.triangles.col(1).swap(back.triangles.col(2));
    Mesh sheet = front;
    sheet.triangles.conservativeResize(2 * front.triangles.rows(), 3);
    sheet.triangles.bottomRows(front.triangles.rows()) = back.triangles;
    InputCleaning done;
    Mesh out = cleaned(sheet, done);
    EXPECT_EQ(done.duplicates_removed, 0);
    EXPECT_EQ(done.facets_turned, 0);
    EXPECT_EQ(facets_of(out), facets_of(sheet));

    Mesh twice = sheet; // each side written twice: one of each stays
    twice.triangles.conservativeResize(3 * front.triangles.rows(), 3);
    twice.triangles.bottomRows(front.triangles.rows()) = front.triangles;
    out = cleaned(twice, done);
    EXPECT_EQ(done.duplicates_removed, front.triangles.rows());
    EXPECT_EQ(facets_of(out), facets_of(sheet));

    Mesh one_side = front; // a single facet reversed on a one-sided square: a duplicate
    one_side.triangles.conservativeResize(front.triangles.rows() + 1, 3);
    one_side.triangles.bottomRows(1) = back.triangles.row(5);
    out = cleaned(one_side, done);
    EXPECT_EQ(done.duplicates_removed, 1);
    EXPECT_EQ(facets_of(out), facets_of(front));
}

// A zero-area sliver that closes a T-junction (its three sides each shared with one other
// facet) stays: dropped, it would open a slit. A zero-area facet along a side goes.
TEST(InputCleaning, AZeroAreaSliverClosingATJunctionStays) {
    // Two triangles over the segment a-b from above, one from below over a-m, m-b with m the
    // midpoint, and the sliver (a, m, b) between: a closed fan around nothing but a flat disk.
    const Mesh m = test::make_mesh({{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, -1, 0}, {1.5, -1, 0}},
                                   {{0, 1, 3}, {0, 4, 2}, {2, 5, 1}, {2, 4, 5}, {0, 2, 1}});
    InputCleaning done;
    const Mesh out = cleaned(m, done);
    EXPECT_EQ(done.degenerate_removed, 0);
    EXPECT_EQ(out.triangles.rows(), 5);
    EXPECT_EQ(test::topology(out).boundary_edges, test::topology(m).boundary_edges);
}

// A facet listed twice through welded copies of its vertices (as an STL lists corners) is one.
TEST(InputCleaning, RepeatsThroughWeldedCopiesAreDuplicates) {
    const Mesh sphere = test::make_icosphere(2);
    InputCleaning done;
    Mesh twice = test::joined(sphere, sphere); // a second copy of every vertex and facet
    const Mesh out = cleaned(twice, done);
    EXPECT_EQ(done.duplicates_removed, sphere.triangles.rows());
    EXPECT_EQ(out.points.rows(), sphere.points.rows());
    EXPECT_EQ(facets_of(out), facets_of(sphere));

    Mesh bad = test::make_mesh({{0, 0, 0}}, {{0, 0, 1}});
    EXPECT_THROW(clean_input(bad), InvalidInput);
}
