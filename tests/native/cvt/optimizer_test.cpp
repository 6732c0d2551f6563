#include "liftremesh/cvt/optimizer.h"
#include "liftremesh/cvt/sampling.h"
#include "liftremesh/exceptions.h"
#include "helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

// Held sites stay where they are to the bit, the others move; the reseating runs once.
TEST(Optimizer, HeldSitesDoNotMoveAndTheReseatingRunsOnce) {
    const Mesh cube = test::make_cube(0.5, 6);
    const LiftedSurface surface = make_lifted_surface(cube.points, cube.triangles);
    LiftedPoints sites = random_sites(surface, 300, 4);
    const LiftedPoints start = sites;
    HeldSites held;
    held.count = 50;
    int calls = 0;
    held.reseat = [&](LiftedPoints&) {
        ++calls;
        return 0L;
    };
    optimize_sites(surface, sites, 5.0, 30, 2, {}, nullptr, held);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(sites.topRows(50), start.topRows(50));
    EXPECT_GT((sites.bottomRows(250) - start.bottomRows(250)).rowwise().norm().minCoeff(), 0.0);
    held.count = 301;
    EXPECT_THROW(optimize_sites(surface, sites, 5.0, 5, 2, {}, nullptr, held), InvalidInput);
}
