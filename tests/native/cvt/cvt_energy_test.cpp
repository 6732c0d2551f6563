#include "liftremesh/cvt/cvt_energy.h"
#include "liftremesh/lift/density.h"
#include "liftremesh/lift/normals.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <random>
#include <tuple>

using namespace liftremesh;

// (sigma, delta, nu): nu = 0 is d = 3, nu > 0 is d = 6.
class Gradient : public ::testing::TestWithParam<std::tuple<double, double, double>> {};

TEST_P(Gradient, MatchesCentralFiniteDifferences) {
    const auto [sigma, delta, nu] = GetParam();
    // A cube (sharp creases: the feature term matters) with a curved bump of density: the torus.
    for (const Mesh& m : {test::make_cube(0.5, 3), test::make_torus(0.6, 0.25, 20, 10)}) {
        const Points normals = vertex_normals(m, 0.05);
        const LiftedSurface s = make_lifted_surface(lift(m.points, normals, nu), m.triangles,
                                                    density_weights(triangle_density(m, normals, 0.05), delta));
        const LiftedPoints v = test::sites_near(s, 80, 0.02, 11); // generic: off the surface, in general position
        LiftedPoints grad, grad2;
        const double f = cvt_objective(s, v, sigma, 1, grad);
        // Summed chunk by chunk in a fixed order: the same bits on two threads.
        EXPECT_EQ(cvt_objective(s, v, sigma, 2, grad2), f);
        EXPECT_EQ(grad2, grad);

        std::mt19937_64 rng(5);
        std::uniform_int_distribution<long> pick_site(0, v.rows() - 1);
        std::uniform_int_distribution<int> pick_coord(0, s.dimension() - 1);
        Eigen::VectorXd analytic(60), numeric(60);
        const double h = 1e-6;
        LiftedPoints scratch;
        for (int t = 0; t < 60; ++t) {
            const long k = pick_site(rng);
            const int j = pick_coord(rng);
            LiftedPoints plus = v, minus = v;
            plus(k, j) += h;
            minus(k, j) -= h;
            numeric[t] = (cvt_objective(s, plus, sigma, 1, scratch) - cvt_objective(s, minus, sigma, 1, scratch)) / (2 * h);
            analytic[t] = grad(k, j);
        }
        const double rel = (analytic - numeric).norm() / numeric.norm();
        EXPECT_LE(rel, 1e-4) << "sigma " << sigma << " delta " << delta << " nu " << nu;
        EXPECT_GT(numeric.norm(), 0.0);
    }
}

INSTANTIATE_TEST_SUITE_P(SigmaDeltaDimension, Gradient,
                         ::testing::Combine(::testing::Values(1.0, 5.0), ::testing::Values(0.0, 0.4),
                                            ::testing::Values(0.0, 0.05)));

TEST(Objective, IsTheSecondMomentOfTheCells) {
    // One site at the centre of a unit square made of two triangles: int |x|^2 = 1/6 over [-1/2, 1/2]^2.
    const Mesh m = test::make_mesh({{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}}, {{0, 1, 2}, {0, 2, 3}});
    const LiftedSurface s = make_lifted_surface(m.points, m.triangles);
    LiftedPoints v(1, 3), grad;
    v << 0.0, 0.0, 0.3; // lifted off the plane by 0.3: adds sigma^2 * 0.09 * area
    EXPECT_NEAR(cvt_objective(s, v, 1.0, 1, grad), 1.0 / 6.0 + 0.09, 1e-12);
    EXPECT_NEAR(cvt_objective(s, v, 5.0, 1, grad), 1.0 / 6.0 + 25 * 0.09, 1e-12);
    EXPECT_NEAR(grad(0, 2), 2 * 25 * 0.3, 1e-12); // d/dz sigma^2 z^2 = 2 sigma^2 z
}
