#include "liftremesh/cvt/crease_sites.h"
#include "liftremesh/cvt/sampling.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace liftremesh;

namespace {

// The cube of edge 1 with 6 x 6 faces, lifted with unit weights (one spacing everywhere), and its
// creases.
struct Cube {
    Mesh mesh = test::make_cube(0.5, 6);
    LiftedSurface surface = make_lifted_surface(mesh.points, mesh.triangles);
    std::vector<CreaseEdge> creases = crease_edges(mesh, 30.0);
};

// The spacing of `sites` sites on an area A with unit weights: sqrt((A / N) / (sqrt(3) / 2)).
double spacing_of(double area, long sites) { return std::sqrt(area / static_cast<double>(sites) / (std::sqrt(3.0) / 2.0)); }
double cube_spacing(long sites) { return spacing_of(6.0, sites); }

// The distance from p to the nearest edge of the cube of edge 1 centred at the origin.
double distance_to_cube_edges(const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis)
        for (int c = 0; c < 4; ++c) {
            Eigen::Vector3d a, b;
            a[axis] = -0.5;
            b[axis] = 0.5;
            a[(axis + 1) % 3] = b[(axis + 1) % 3] = c & 1 ? 0.5 : -0.5;
            a[(axis + 2) % 3] = b[(axis + 2) % 3] = c & 2 ? 0.5 : -0.5;
            best = std::min(best, (closest_point_on_segment(p, a, b) - p).norm());
        }
    return best;
}

} // namespace

// Every corner is a site, exactly; each edge gets round(1 / h) - 1 more, evenly spaced on it.
TEST(CreaseSites, OnACubeAreItsCornersAndEvenlySpacedPointsOfItsEdges) {
    const Cube cube;
    const long sites = 1200;
    const CreaseSites creases(cube.surface, cube.creases, sites);
    const LiftedPoints& held = creases.held();
    const long per_edge = std::lround(1.0 / cube_spacing(sites)) - 1;
    ASSERT_EQ(held.rows(), 8 + 12 * per_edge);
    for (int c = 0; c < 8; ++c)
        for (int i = 0; i < 3; ++i) EXPECT_EQ(std::abs(held(c, i)), 0.5) << "corner " << c;
    for (Eigen::Index k = 0; k < held.rows(); ++k) {
        const Eigen::Vector3d p = held.row(k).leftCols<3>().transpose();
        EXPECT_LT(distance_to_cube_edges(p), 1e-12) << k;
        // Along its edge (the coordinate not at +-0.5), at a multiple of 1 / (per_edge + 1).
        for (int i = 0; i < 3; ++i)
            if (std::abs(std::abs(p[i]) - 0.5) > 1e-12) {
                const double t = (p[i] + 0.5) * static_cast<double>(per_edge + 1);
                EXPECT_NEAR(t, std::round(t), 1e-9) << k;
            }
    }
}

// Past the budget's share for creases, the corners alone; past it again, none.
TEST(CreaseSites, ABudgetTooSmallForTheCreasesHoldsTheCornersOrNothing) {
    const Cube cube;
    // 40 sites: h = 0.42, one site an edge (2 pieces) and the 8 corners, 20, are over a quarter
    // of the budget (10); the corners alone are not. 24 sites: a quarter is 6, under 8 corners.
    const CreaseSites corners(cube.surface, cube.creases, 40);
    EXPECT_EQ(corners.held().rows(), 8);
    EXPECT_EQ(CreaseSites(cube.surface, cube.creases, 24).held().rows(), 0);
    EXPECT_EQ(CreaseSites(cube.surface, {}, 1200).held().rows(), 0);
}

// Two creases nearer than half the spacing cannot both have a row: the second is left out. On
// the unit square cut 8 x 8, rows of grid edges along x taken as creases: 16 sites give a spacing
// of 0.27, so row 5, 0.125 from row 4, gets no site, and row 8 gets its own.
TEST(CreaseSites, ACreaseNearerThanHalfTheSpacingToOneTakenGetsNoRow) {
    const Mesh square = test::make_square(1.0, 8);
    const LiftedSurface surface = make_lifted_surface(square.points, square.triangles);
    auto row = [](int j) {
        std::vector<CreaseEdge> out;
        for (int i = 0; i < 8; ++i) out.push_back({j * 9 + i, j * 9 + i + 1, -1, -1, 90.0});
        return out;
    };
    auto both = [&](int j, int k) {
        std::vector<CreaseEdge> out = row(j), more = row(k);
        out.insert(out.end(), more.begin(), more.end());
        return out;
    };
    CreaseSitesParams params;
    params.max_fraction = 1.0;
    const long one = CreaseSites(surface, row(4), 16, params).held().rows();
    EXPECT_EQ(one, 2 + std::lround(1.0 / spacing_of(1.0, 16)) - 1); // its two ends, and the row cut at the spacing
    EXPECT_EQ(CreaseSites(surface, both(4, 5), 16, params).held().rows(), one);
    EXPECT_EQ(CreaseSites(surface, both(4, 8), 16, params).held().rows(), 2 * one);
    std::vector<CreaseEdge> bad = row(4);
    bad.push_back({0, static_cast<int32_t>(square.points.rows()), -1, -1, 90.0});
    EXPECT_THROW(CreaseSites(surface, bad, 16, params), InvalidInput);
    params.max_fraction = 1.5;
    EXPECT_THROW(CreaseSites(surface, row(4), 16, params), InvalidInput);
}

// Past the budget's share for creases, the corners fit, and the parts of two chains that bound a
// strip narrower than the cells are held with them. On the unit square cut 40 x 40, seven rows
// of grid edges along x taken as creases: 150 sites give a spacing of 0.088, so the rows cut in
// 11 pieces are 84 sites, over a quarter of the budget (37), and their 14 ends are not. Rows 20
// and 22 lie 0.05 (0.57 spacings) apart: their sites two spacings or more from an end (8 a row)
// are held; the other rows lie 0.15 or more from any other.
TEST(CreaseSites, TheCrowdedPartsOfTheChainsAreHeldWithTheCorners) {
    const int cuts = 40;
    const Mesh square = test::make_square(1.0, cuts);
    const LiftedSurface surface = make_lifted_surface(square.points, square.triangles);
    std::vector<CreaseEdge> creases;
    for (const int j : {0, 6, 12, 20, 22, 30, 36})
        for (int i = 0; i < cuts; ++i) {
            const int32_t a = j * (cuts + 1) + i;
            creases.push_back({a, a + 1, -1, -1, 90.0});
        }
    const long sites = 150;
    const CreaseSites held(surface, creases, sites);
    ASSERT_EQ(held.held().rows(), 14 + 16);
    const double y20 = square.points(20 * (cuts + 1), 1), y22 = square.points(22 * (cuts + 1), 1);
    for (Eigen::Index k = 14; k < held.held().rows(); ++k) {
        const double y = held.held()(k, 1);
        EXPECT_TRUE(y == y20 || y == y22) << k;
    }
    CreaseSitesParams corners_only;
    corners_only.crowded = 0.0;
    EXPECT_EQ(CreaseSites(surface, creases, sites, corners_only).held().rows(), 14);
    corners_only.crowded = -1.0;
    EXPECT_THROW(CreaseSites(surface, creases, sites, corners_only), InvalidInput);
}

// The free sites keep the clearance from every crease (at right angles: half the spacing), and
// are random_sites' draw otherwise: as many, on the surface.
TEST(CreaseSites, FreeSitesKeepTheirClearanceFromTheCreases) {
    const Cube cube;
    const long sites = 1200;
    const CreaseSites creases(cube.surface, cube.creases, sites);
    const LiftedPoints free = creases.free_sites(cube.surface, sites - creases.held().rows(), 5);
    ASSERT_EQ(free.rows(), sites - creases.held().rows());
    const double clearance = 0.5 * cube_spacing(sites);
    for (Eigen::Index k = 0; k < free.rows(); ++k) {
        const Eigen::Vector3d p = free.row(k).leftCols<3>().transpose();
        EXPECT_GE(distance_to_cube_edges(p), clearance * (1.0 - 1e-9)) << k;
        EXPECT_NEAR(p.cwiseAbs().maxCoeff(), 0.5, 1e-12) << k; // on a face
    }
    // Without the clearance, random_sites' draw has sites that close.
    const LiftedPoints drawn = random_sites(cube.surface, free.rows(), 5);
    int close = 0;
    for (Eigen::Index k = 0; k < drawn.rows(); ++k) close += distance_to_cube_edges(drawn.row(k).leftCols<3>().transpose()) < clearance;
    EXPECT_GT(close, 0);
}

// The sites that crowd a crease are replaced and counted; the others stay as they were.
TEST(CreaseSites, ReseatingReplacesOnlyTheSitesThatCrowdACrease) {
    const Cube cube;
    const long sites = 1200;
    const CreaseSites creases(cube.surface, cube.creases, sites);
    LiftedPoints all = random_sites(cube.surface, sites, 9);
    const LiftedPoints before = all;
    const double clearance = 0.5 * cube_spacing(sites);
    const long first = 100;
    long crowding = 0;
    for (Eigen::Index k = first; k < all.rows(); ++k)
        crowding += distance_to_cube_edges(all.row(k).leftCols<3>().transpose()) < clearance;
    ASSERT_GT(crowding, 0);
    EXPECT_EQ(creases.reseat_crowding_sites(cube.surface, all, first, 11), crowding);
    EXPECT_EQ(all.topRows(first), before.topRows(first));
    for (Eigen::Index k = first; k < all.rows(); ++k) {
        const double d = distance_to_cube_edges(before.row(k).leftCols<3>().transpose());
        if (d >= clearance) EXPECT_EQ(all.row(k), before.row(k)) << k;
        EXPECT_GE(distance_to_cube_edges(all.row(k).leftCols<3>().transpose()), clearance * (1.0 - 1e-9)) << k;
    }
}
