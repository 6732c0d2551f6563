#include "liftremesh/density.h"
#include "liftremesh/normals.h"
#include "liftremesh/rvd.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <random>

using namespace liftremesh;

namespace {

// Sites near the surface: random points on random triangles, pushed off by a little noise.
LiftedPoints sites_near(const LiftedSurface& s, int n, double noise, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<long> pick(0, s.triangles.rows() - 1);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::normal_distribution<double> gauss(0.0, noise);
    LiftedPoints v(n, s.dimension());
    for (int k = 0; k < n; ++k) {
        const long f = pick(rng);
        double a = u01(rng), b = u01(rng);
        if (a + b > 1) { a = 1 - a; b = 1 - b; }
        v.row(k) = (1 - a - b) * s.points.row(s.triangles(f, 0)) + a * s.points.row(s.triangles(f, 1)) +
                   b * s.points.row(s.triangles(f, 2));
        for (int j = 0; j < s.dimension(); ++j) v(k, j) += gauss(rng);
    }
    return v;
}

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
        const LiftedPoints v = sites_near(s, 300, 0.01, 3);
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
    LiftedPoints v = sites_near(s, 60, 0.0, 5);
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
