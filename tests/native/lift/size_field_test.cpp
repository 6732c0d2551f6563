#include "liftremesh/cvt/rvd.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/lift/size_field.h"
#include "liftremesh/lift/thin_walls.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace liftremesh;

namespace {

Points random_points(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Points p(n, 3);
    for (int i = 0; i < n; ++i) p.row(i) << u(rng), u(rng), u(rng);
    return p;
}

} // namespace

// The grading is the lower envelope of the cones h(y) + (g - 1) |x - y| (the brute force), and
// its slope is at most g - 1 between any two points.
TEST(SizeField, GradingIsTheLowerEnvelopeOfTheCones) {
    const Points p = random_points(400, 3);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.02, 1.0);
    Eigen::VectorXd size(p.rows());
    for (Eigen::Index i = 0; i < size.size(); ++i) size[i] = i % 7 == 0 ? u(rng) : 1.0;
    const double g = 1.3, largest = 1.0;
    const Eigen::VectorXd h = graded(p, size, g, largest);
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
        double brute = size[i];
        for (Eigen::Index j = 0; j < p.rows(); ++j)
            brute = std::min(brute, size[j] + (g - 1.0) * (p.row(i) - p.row(j)).norm());
        EXPECT_NEAR(h[i], brute, 1e-12) << i;
        for (Eigen::Index j = 0; j < p.rows(); ++j)
            EXPECT_LE(h[i], h[j] + (g - 1.0) * (p.row(i) - p.row(j)).norm() + 1e-12);
    }
    EXPECT_EQ(graded(p, size, 1.0, largest), size); // gradation 1: no grading
}

// A slab thinner than the largest size gets its thickness as the size on its two large faces,
// and the report's wall area is theirs.
TEST(SizeField, AWallThinnerThanTheLargestSizeSetsTheSize) {
    Mesh slab = test::make_cube(0.5, 8);
    slab.points.col(2) *= 0.1; // 1 x 1 x 0.1
    const AabbTree tree(slab);
    const Eigen::VectorXd thickness = wall_thickness(slab, tree, 0.5);
    SizeFieldParams params;
    params.largest = 0.5;
    params.smallest = 0.02;
    const SizeField field = size_field(slab, thickness, Eigen::VectorXd::Zero(slab.triangles.rows()), params);
    for (Eigen::Index v = 0; v < slab.points.rows(); ++v) {
        EXPECT_GE(field.size[v], params.smallest);
        // On the two large faces the thickness; on the rims' faces, 0.05 at most from one, graded.
        const bool on_a_side = std::abs(std::abs(slab.points(v, 2)) - 0.05) < 1e-12;
        EXPECT_LE(field.size[v], on_a_side ? 0.1 + 1e-9 : 0.1 + 0.3 * 0.05 + 1e-9) << v;
    }
    EXPECT_GT(field.wall_area, 1.9); // the two 1 x 1 faces, and the rims
    EXPECT_EQ(field.curvature_area, 0.0);
    EXPECT_NEAR(field.graded_area, surface_area(slab), 1e-9);
    // Thicker than the largest size: no wall, no refinement.
    const SizeField thick = size_field(slab, Eigen::VectorXd::Constant(slab.points.rows(), 0.6),
                                       Eigen::VectorXd::Zero(slab.triangles.rows()), params);
    EXPECT_EQ(thick.size, Eigen::VectorXd::Constant(slab.points.rows(), 0.5));
    EXPECT_EQ(thick.graded_area, 0.0);
}

// A cylinder's facets show its curvature 1 / r; a cube's creases are not bends; the bend sets
// the size kSizeTurn r.
TEST(SizeField, BendsAreTheCurvatureOfSmoothFacetsNotCreases) {
    const double r = 0.2;
    const Mesh cylinder = test::make_open_cylinder(r, 1.0, 48, 20);
    const Eigen::VectorXd bend = triangle_bend(cylinder, 45.0);
    for (Eigen::Index f = 0; f < bend.size(); ++f) EXPECT_NEAR(bend[f] * r, 1.0, 0.05) << f;
    const Mesh cube = test::make_cube(0.5, 4);
    EXPECT_EQ(triangle_bend(cube, 45.0).maxCoeff(), 0.0); // flat faces, 90-degree creases
    SizeFieldParams params;
    params.largest = 1.0;
    params.smallest = 0.01;
    params.gradation = 1.0;
    const Eigen::VectorXd none = Eigen::VectorXd::Constant(cylinder.points.rows(), std::numeric_limits<double>::infinity());
    const SizeField field = size_field(cylinder, none, bend, params);
    EXPECT_NEAR(field.size.maxCoeff(), kSizeTurn * r, 0.05 * kSizeTurn * r);
    EXPECT_NEAR(field.curvature_area, surface_area(cylinder), 1e-9);
}

// The sites a triangle needs: exact for a constant size; for a size varying by a factor 4
// across it, the mean of (reference / h)^2 within 2% of a fine quadrature's.
TEST(SizeField, SiteDensityIsTheMeanOfTheInverseSquaredSize) {
    const Mesh square = test::make_square(1.0, 1); // two triangles
    Eigen::VectorXd size = Eigen::VectorXd::Constant(square.points.rows(), 0.5);
    const Eigen::VectorXd uniform = site_density(square, size, 1.0);
    for (Eigen::Index f = 0; f < uniform.size(); ++f) EXPECT_DOUBLE_EQ(uniform[f], 4.0);
    EXPECT_NEAR(sized_vertex_count(square, uniform, 1.0), surface_area(square) / (std::sqrt(3.0) / 2.0 * 0.25), 1e-9);
    size << 0.25, 1.0, 1.0, 1.0;
    const Eigen::VectorXd varying = site_density(square, size, 1.0);
    for (Eigen::Index f = 0; f < square.triangles.rows(); ++f) {
        const double h[3] = {size[square.triangles(f, 0)], size[square.triangles(f, 1)], size[square.triangles(f, 2)]};
        const int n = 400;
        double sum = 0.0;
        long count = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j, ++count) {
                const double a = (i + 1.0 / 3.0) / n, b = (j + 1.0 / 3.0) / n;
                const double at = (1.0 - a - b) * h[0] + a * h[1] + b * h[2];
                sum += 1.0 / (at * at);
            }
        EXPECT_NEAR(varying[f] / (sum / count), 1.0, 0.02) << f;
    }
}

TEST(SizeField, BadBoundsAreInvalidInput) {
    const Mesh square = test::make_square(1.0, 2);
    const Eigen::VectorXd t = Eigen::VectorXd::Ones(square.points.rows()), bend = Eigen::VectorXd::Zero(square.triangles.rows());
    SizeFieldParams params;
    params.largest = 1.0;
    params.smallest = 2.0;
    EXPECT_THROW(size_field(square, t, bend, params), InvalidInput);
    params.smallest = 0.1;
    params.gradation = 0.5;
    EXPECT_THROW(size_field(square, t, bend, params), InvalidInput);
    params.gradation = 1.3;
    EXPECT_THROW(size_field(square, Eigen::VectorXd::Ones(2), bend, params), InvalidInput);
}

// The cells' masses add up to the weighted area of the surface, sum_p w_p |T_p|.
TEST(SizeField, CellMassesAddUpToTheWeightedArea) {
    const Mesh sphere = test::make_icosphere(3);
    Eigen::VectorXd weights(sphere.triangles.rows());
    double weighted = 0.0;
    for (Eigen::Index f = 0; f < weights.size(); ++f) {
        weights[f] = 1.0 + 100.0 * (f % 5);
        weighted += weights[f] * triangle_area(sphere.points.row(sphere.triangles(f, 0)),
                                               sphere.points.row(sphere.triangles(f, 1)),
                                               sphere.points.row(sphere.triangles(f, 2)));
    }
    const LiftedSurface surface = make_lifted_surface(LiftedPoints(sphere.points), sphere.triangles, weights);
    const LiftedPoints sites = test::sites_near(surface, 200, 0.0, 7);
    const Eigen::VectorXd mass = restricted_cell_masses(surface, sites);
    EXPECT_NEAR(mass.sum() / weighted, 1.0, 1e-9);
    EXPECT_GT(mass.minCoeff(), 0.0);
}
