#include "liftremesh/density.h"
#include "liftremesh/normals.h"
#include "liftremesh/rvd.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <random>

using namespace liftremesh;

namespace {

LiftedSurface lifted(const Mesh& m, double nu, double delta) {
    const Points n = vertex_normals(m, 0.05);
    return make_lifted_surface(lift(m.points, n, nu), m.triangles,
                               density_weights(triangle_density(m, n, 0.05), delta));
}

} // namespace

class CellAreas : public ::testing::TestWithParam<double> {};

TEST_P(CellAreas, AddUpToTheLiftedSurfaceArea) {
    const double nu = GetParam();
    for (const Mesh& m : {test::make_cube(0.5, 4), test::make_torus(0.6, 0.25, 30, 14)}) {
        const LiftedSurface s = lifted(m, nu, 0.0);
        const LiftedPoints v = test::sites_near(s, 300, 0.01, 3);
        for (int threads : {1, 2}) {
            const Eigen::VectorXd areas = restricted_cell_areas(s, v, threads);
            const double expected = lifted_area(s);
            EXPECT_NEAR(areas.sum(), expected, 1e-9 * expected) << "nu " << nu << " threads " << threads;
            EXPECT_GE(areas.minCoeff(), 0.0);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Dimensions, CellAreas, ::testing::Values(0.0, 0.05));

TEST(CellAreas, FarSiteHasAnEmptyCellAndCoincidentSitesShareNothing) {
    const Mesh m = test::make_icosphere(2);
    const LiftedSurface s = lifted(m, 0.0, 0.0);
    LiftedPoints v = test::sites_near(s, 60, 0.0, 5);
    v.row(0) << 50.0, 0.0, 0.0; // far away: everything is nearer to another site
    v.row(2) = v.row(1);        // coincident pair: exactly one of them gets the cell
    const Eigen::VectorXd areas = restricted_cell_areas(s, v, 2);
    EXPECT_EQ(areas[0], 0.0);
    EXPECT_EQ(areas[2], 0.0);
    EXPECT_GT(areas[1], 0.0);
    EXPECT_NEAR(areas.sum(), lifted_area(s), 1e-9 * lifted_area(s));
}

TEST(CellAreas, ASingleSiteOwnsTheWholeSurface) {
    const Mesh m = test::make_cube(1.0, 2);
    const LiftedSurface s = lifted(m, 0.0, 0.0);
    LiftedPoints v(1, 3);
    v << 0.1, 0.2, 0.3;
    EXPECT_NEAR(restricted_cell_areas(s, v)[0], 24.0, 1e-12);
}
