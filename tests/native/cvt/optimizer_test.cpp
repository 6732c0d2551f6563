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
    // A reseating may not change the number of sites, nor a held one.
    held.count = 50;
    held.reseat = [](LiftedPoints& s) {
        s.conservativeResize(s.rows() - 1, Eigen::NoChange);
        return 1L;
    };
    EXPECT_THROW(optimize_sites(surface, sites, 5.0, 10, 2, {}, nullptr, held), InvalidInput);
    held.reseat = [](LiftedPoints& s) {
        s(0, 0) += 1e-3;
        return 1L;
    };
    EXPECT_THROW(optimize_sites(surface, sites, 5.0, 10, 2, {}, nullptr, held), InvalidInput);
}

// With weights varying by more than kPreconditionContrast the sites are scaled by their cells'
// masses, and back: the held ones still stay where they were to the bit.
TEST(Optimizer, HeldSitesStayToTheBitWhenPreconditioned) {
    const Mesh cube = test::make_cube(0.5, 6);
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(cube.triangles.rows());
    for (Eigen::Index f = 0; f < weights.size(); f += 3) weights[f] = 4.0 * kPreconditionContrast;
    const LiftedSurface surface = make_lifted_surface(cube.points, cube.triangles, weights);
    LiftedPoints sites = random_sites(surface, 300, 7);
    const LiftedPoints start = sites;
    HeldSites held;
    held.count = 40;
    optimize_sites(surface, sites, 5.0, 30, 2, {}, nullptr, held);
    EXPECT_EQ(sites.topRows(40), start.topRows(40));
    EXPECT_GT((sites.bottomRows(260) - start.bottomRows(260)).rowwise().norm().minCoeff(), 0.0);
}
