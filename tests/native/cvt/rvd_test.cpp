#include "liftremesh/cvt/rvd.h"
#include "liftremesh/cvt/sampling.h"
#include "liftremesh/lift/density.h"
#include "liftremesh/lift/normals.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

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

// Where the cutting sites lie beyond a site's 24 listed neighbours, the walk must find them in
// the tree: a cluster of 40 sites (any one's 24 nearest are all in it) among sparse ones, whose
// outer cells reach to the sparse sites' bisectors, on a slab with sites on one side only (a
// polygon on the far side lies 0.3 from its site, so its security radius reaches further
// still). The far side's cells are the near side's, projected: each site's area is twice what
// it has on the near side alone, and the areas add up to the surface's.
TEST(CellAreas, AreCompleteWhereTheSecurityRadiusOutrunsTheNeighbourList) {
    const double gap = 0.3;
    const Mesh bottom = test::make_square(1.0, 6);
    Mesh slab = bottom;
    slab.points.conservativeResize(2 * bottom.points.rows(), 3);
    slab.points.bottomRows(bottom.points.rows()) = bottom.points;
    slab.points.bottomRows(bottom.points.rows()).col(2).setConstant(gap);
    slab.triangles.conservativeResize(2 * bottom.triangles.rows(), 3);
    Triangles top = bottom.triangles.array() + static_cast<int32_t>(bottom.points.rows());
    top.col(1).swap(top.col(2));
    slab.triangles.bottomRows(bottom.triangles.rows()) = top;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Eigen::Vector3d> sites;
    for (int c = 0; c < 40; ++c) sites.emplace_back(0.3 + 0.02 * u(rng), 0.5 + 0.02 * u(rng), 0.0);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i)
            if (i > 1 || j != 2) sites.emplace_back(0.1 + 0.2 * i + 0.02 * u(rng), 0.1 + 0.2 * j + 0.02 * u(rng), 0.0);
    LiftedPoints v(static_cast<Eigen::Index>(sites.size()), 3);
    for (size_t k = 0; k < sites.size(); ++k) v.row(static_cast<Eigen::Index>(k)) = sites[k].transpose();
    const Eigen::VectorXd near = restricted_cell_areas(make_lifted_surface(bottom.points, bottom.triangles), v, 2);
    const Eigen::VectorXd both = restricted_cell_areas(make_lifted_surface(slab.points, slab.triangles), v, 2);
    EXPECT_NEAR(near.sum(), 1.0, 1e-9);
    EXPECT_NEAR(both.sum(), 2.0, 1e-9);
    EXPECT_LE((both - 2.0 * near).cwiseAbs().maxCoeff(), 1e-12);
}

// RvdCache: neighbour lists made for earlier positions must give the same diagram as fresh
// ones, including when a list runs out and is extended (irregular, unoptimised sites).
TEST(CellAreas, AreTheSameWithNeighbourListsFromEarlierPositions) {
    const Mesh m = test::make_torus(0.6, 0.25, 40, 16);
    const LiftedSurface s = lifted(m, 0.05, 0.0);
    LiftedPoints v = test::sites_near(s, 500, 0.002, 21);
    auto areas_with = [&](const LiftedPoints& sites, RvdCache* cache) {
        return restricted_cell_areas(s, sites, 2, cache);
    };
    RvdCache cache;
    areas_with(v, &cache);
    ASSERT_EQ(cache.rebuilds, 1);
    std::mt19937_64 rng(8);
    std::normal_distribution<double> step(0.0, 0.25 * cache.rebuild_distance);
    long reused = 0;
    for (int round = 0; round < 6; ++round) {
        for (Eigen::Index i = 0; i < v.rows(); ++i)
            for (int j = 0; j < 3; ++j) v(i, j) += step(rng) / std::sqrt(6.0);
        const long rebuilds = cache.rebuilds;
        const Eigen::VectorXd cached = areas_with(v, &cache), fresh = areas_with(v, nullptr);
        reused += cache.rebuilds == rebuilds;
        EXPECT_LT((cached - fresh).cwiseAbs().maxCoeff(), 1e-12 * fresh.sum()) << "round " << round;
    }
    EXPECT_GT(reused, 0); // the stale lists were actually used

    // A few movers (sites jumping up to several spacings, some across the torus) are checked on
    // their own: no rebuild, the same diagram. Many movers make a rebuild.
    const double spacing = cache.spacing;
    std::uniform_int_distribution<Eigen::Index> pick(0, v.rows() - 1);
    std::uniform_real_distribution<double> jump(-4.0 * spacing, 4.0 * spacing);
    for (const int movers : {1, 12, 15, 200}) {
        const long rebuilds = cache.rebuilds;
        for (int i = 0; i < movers; ++i) {
            const Eigen::Index site = pick(rng);
            if (i % 5 == 4) v.row(site) = v.row(pick(rng)) + 0.5 * spacing * LiftedPoints::Ones(1, v.cols());
            else
                for (int j = 0; j < 3; ++j) v(site, j) += jump(rng);
        }
        const long moved = ((v.leftCols(3) - cache.anchor).rowwise().norm().array() > cache.rebuild_distance).count();
        const Eigen::VectorXd cached = areas_with(v, &cache), fresh = areas_with(v, nullptr);
        EXPECT_LT((cached - fresh).cwiseAbs().maxCoeff(), 1e-12 * fresh.sum()) << movers << " movers";
        // Up to max(32, 500 / 128) = 32 movers are allowed.
        EXPECT_EQ(cache.rebuilds - rebuilds, moved > 32 ? 1 : 0) << moved << " sites moved since the lists were made";
    }
}

// Threads take chunks of triangles as they come, and the areas are added chunk by chunk, each
// site's by its rank in the chunk: the same areas, to the bit, on any number of threads, in a
// smaller team than asked for (a nested region, which the runtime gives one thread), and with
// chunks split by the work measured on the last diagram.
TEST(CellAreas, AreTheSameToTheBitWhateverTheThreadCount) {
    const Mesh m = test::make_torus(0.6, 0.25, 30, 14);
    const LiftedSurface s = lifted(m, 0.05, 0.0);
    const LiftedPoints v = test::sites_near(s, 300, 0.01, 5);
    ASSERT_GT(rvd_chunks(s), 1);

    // Ranks: 0, 1, 2, ... in each chunk, one per site of the chunk.
    std::vector<std::map<int32_t, int32_t>> rank(rvd_chunks(s));
    Eigen::VectorXd by_site = Eigen::VectorXd::Zero(v.rows());
    compute_rvd(s, v, 1, [&](int chunk, const RvdPolygon& poly) {
        auto& ranks = rank[chunk];
        const auto [it, added] = ranks.emplace(poly.site, static_cast<int32_t>(ranks.size()));
        EXPECT_EQ(poly.chunk_rank, it->second) << "chunk " << chunk << " site " << poly.site;
        by_site[poly.site] += polygon_area(poly);
    });
    const Eigen::VectorXd reference = restricted_cell_areas(s, v, 1);
    EXPECT_LT((reference - by_site).cwiseAbs().maxCoeff(), 1e-14 * reference.sum());

    for (int threads : {2, 3}) EXPECT_EQ(restricted_cell_areas(s, v, threads), reference) << threads << " threads";
    Eigen::VectorXd nested;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        nested = restricted_cell_areas(s, v, 3);
    }
    EXPECT_EQ(nested, reference);
    RvdCache one, three;
    for (int call = 0; call < 3; ++call) // the first call splits by count, the next ones by work
        EXPECT_EQ(restricted_cell_areas(s, v, 3, &three), restricted_cell_areas(s, v, 1, &one)) << "call " << call;
    EXPECT_EQ(static_cast<long>(one.work.size()), static_cast<long>(s.triangles.rows()));
}

// The surface keeps its triangles along a Morton curve whatever order they come in (a torus's
// triangles shuffled here), each row the given triangle with its weight, row_of saying where
// each went: neighbouring rows are neighbours on the surface, which the given order's are not.
// The cells are those of the triangles in their own order, up to rounding, and the sites a seed
// draws are those of the given order.
TEST(LiftedSurface, KeepsItsTrianglesAlongAMortonCurveWhateverTheirOrder) {
    const Mesh m = test::make_torus(0.6, 0.25, 60, 28);
    Mesh shuffled = m;
    std::vector<int32_t> order(static_cast<size_t>(m.triangles.rows()));
    for (size_t f = 0; f < order.size(); ++f) order[f] = static_cast<int32_t>(f);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    Eigen::VectorXd weights(m.triangles.rows());
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
        shuffled.triangles.row(f) = m.triangles.row(order[f]);
        weights[f] = 1.0 + 0.001 * order[f];
    }
    const LiftedSurface s = make_lifted_surface(LiftedPoints(shuffled.points), shuffled.triangles, weights);
    ASSERT_EQ(s.row_of.size(), order.size());
    std::vector<char> taken(order.size(), 0);
    for (size_t g = 0; g < order.size(); ++g) {
        const int32_t f = s.row_of[g];
        ASSERT_TRUE(f >= 0 && f < static_cast<int32_t>(order.size()) && !taken[f]) << "triangle " << g;
        taken[f] = 1;
        EXPECT_EQ(s.triangles.row(f), shuffled.triangles.row(static_cast<Eigen::Index>(g)));
        EXPECT_EQ(s.weights[f], weights[static_cast<Eigen::Index>(g)]);
    }
    // Mean distance between the centroids of consecutive triangles, over the mean edge length.
    auto mean_step = [](const LiftedPoints& points, const Triangles& triangles) {
        auto centroid = [&](Eigen::Index f) -> Eigen::Vector3d {
            return (points.row(triangles(f, 0)) + points.row(triangles(f, 1)) + points.row(triangles(f, 2))).transpose() / 3.0;
        };
        double steps = 0.0, edges = 0.0;
        for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
            if (f > 0) steps += (centroid(f) - centroid(f - 1)).norm();
            edges += (points.row(triangles(f, 1)) - points.row(triangles(f, 0))).norm();
        }
        return (steps / static_cast<double>(triangles.rows() - 1)) / (edges / static_cast<double>(triangles.rows()));
    };
    EXPECT_GT(mean_step(LiftedPoints(shuffled.points), shuffled.triangles), 5.0);
    EXPECT_LT(mean_step(s.points, s.triangles), 2.0);

    const LiftedSurface in_order = make_lifted_surface(LiftedPoints(m.points), m.triangles);
    const LiftedSurface unweighted = make_lifted_surface(LiftedPoints(shuffled.points), shuffled.triangles);
    const LiftedPoints v = test::sites_near(in_order, 400, 0.01, 3);
    const Eigen::VectorXd areas = restricted_cell_areas(unweighted, v, 2), reference = restricted_cell_areas(in_order, v, 2);
    EXPECT_LT((areas - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.sum());
    // The sums and the draws go by the given order: stored the other way round, the same.
    LiftedSurface reversed = unweighted;
    const Eigen::Index nf = unweighted.triangles.rows();
    for (Eigen::Index f = 0; f < nf; ++f) {
        reversed.triangles.row(nf - 1 - f) = unweighted.triangles.row(f);
        reversed.weights[nf - 1 - f] = unweighted.weights[f];
        reversed.u1.row(nf - 1 - f) = unweighted.u1.row(f);
        reversed.u2.row(nf - 1 - f) = unweighted.u2.row(f);
        reversed.valid[nf - 1 - f] = unweighted.valid[f];
    }
    for (int32_t& f : reversed.row_of) f = static_cast<int32_t>(nf - 1 - f);
    EXPECT_EQ(random_sites(reversed, 50, 11), random_sites(unweighted, 50, 11));
    EXPECT_EQ(sampling_mass(reversed), sampling_mass(unweighted));
    EXPECT_EQ(lifted_area(reversed), lifted_area(unweighted));
}
