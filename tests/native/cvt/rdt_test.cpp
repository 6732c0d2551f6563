#include "liftremesh/cvt/optimizer.h"
#include "liftremesh/cvt/rdt.h"
#include "liftremesh/cvt/sampling.h"
#include "liftremesh/lift/normals.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <vector>

using namespace liftremesh;

// Sites at the vertices of an icosahedron on a fine sphere: the restricted Delaunay
// triangulation is the icosahedron itself (Eq. 4), oriented like the surface.
TEST(RestrictedDelaunay, OfIcosahedronSitesOnASphereIsTheIcosahedron) {
    const Mesh sphere = test::make_icosphere(4);
    const Mesh ico = test::make_icosphere(0);
    const LiftedSurface s = make_lifted_surface(sphere.points, sphere.triangles);
    const RestrictedDelaunay rdt = restricted_delaunay(s, ico.points, 2);
    EXPECT_EQ(rdt.split_sites, 0);
    EXPECT_EQ(rdt.mesh.points, ico.points);
    const Mesh& out = rdt.mesh;
    EXPECT_EQ(out.triangles.rows(), 20);
    const test::Topology topo = test::topology(out);
    EXPECT_TRUE(topo.closed_oriented_manifold());
    EXPECT_EQ(topo.chi, 2);
    EXPECT_EQ(test::facing_inward(out, Eigen::Vector3d::Zero()), 0);
}

// The two sides of a plate thinner than the cells (two open squares 0.02 apart): sites on the
// bottom side only, so each cell is a square on the bottom and the same square on the top, two
// pieces that do not touch. The 3 x 3 inner sites get a vertex per piece (geogram's multinerve
// RDT), and no triangle among those vertices bridges the sides; with one vertex per site every
// triangle on the top would map onto the bottom one. The 16 outer cells reach the border on both
// sides, and pieces along the input's boundary are one (so that cracks close): they stay whole.
TEST(RestrictedDelaunay, PiecesOfACellOnTwoSidesOfAThinPlateGetAVertexEach) {
    const double gap = 0.02;
    Mesh bottom = test::make_square(1.0, 8), top = test::make_square(1.0, 8);
    top.points.col(2).setConstant(gap);
    top.triangles.col(1).swap(top.triangles.col(2)); // facing up: the two sides of a plate
    const Mesh plate = test::joined(bottom, top);
    const LiftedSurface s = make_lifted_surface(plate.points, plate.triangles);
    LiftedPoints sites(25, 3); // a jittered 5 x 5 grid on the bottom side
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i)
            sites.row(5 * j + i) << 0.1 + 0.2 * i + 0.01 * ((i * 7 + j * 3) % 5 - 2), 0.1 + 0.2 * j + 0.01 * ((i * 3 + j * 5) % 5 - 2), 0.0;
    const RestrictedDelaunay rdt = restricted_delaunay(s, sites, 2);
    EXPECT_EQ(rdt.split_sites, 9);
    ASSERT_EQ(rdt.mesh.points.rows(), 25 + 9);
    auto inner = [](int32_t v) { return v >= 25 || (v % 5 != 0 && v % 5 != 4 && v / 5 != 0 && v / 5 != 4); };
    long inner_triangles = 0;
    for (Eigen::Index t = 0; t < rdt.mesh.triangles.rows(); ++t) {
        const auto tri = rdt.mesh.triangles.row(t);
        if (!inner(tri[0]) || !inner(tri[1]) || !inner(tri[2])) continue;
        ++inner_triangles;
        const double z0 = rdt.mesh.points(tri[0], 2);
        EXPECT_TRUE(std::abs(rdt.mesh.points(tri[1], 2) - z0) < 1e-12 && std::abs(rdt.mesh.points(tri[2], 2) - z0) < 1e-12)
            << "triangle " << t << " bridges the sides";
    }
    EXPECT_GE(inner_triangles, 2 * 8); // the 3 x 3 inner sites make 8 triangles on each side
    // Each piece's vertex is its centroid, on its side: a split site has one on each.
    long top_vertices = 0;
    for (Eigen::Index v = 0; v < rdt.mesh.points.rows(); ++v) {
        const double z = rdt.mesh.points(v, 2);
        EXPECT_TRUE(std::abs(z) < 1e-12 || std::abs(z - gap) < 1e-12) << "vertex " << v << " at z = " << z;
        top_vertices += std::abs(z - gap) < 1e-12;
    }
    EXPECT_EQ(top_vertices, 9);
}

// A knife edge: two faces 3 wide meeting along the z axis at 30 degrees, sites held on the edge
// 1 apart and a row on each face. The cell of site c, on face A 1.3 from the edge halfway between
// the edge's sites a and b, reaches round onto face B, where b's and a's cells leave a small
// piece of it between them and face B's row (under min_piece of its cell, facing away from the
// rest). Taken as c, that piece gave the triangle (a, b, c) turned over beside face A's own, a
// pair folded shut that the manifold repair removes, edge (a, b) with it (as with the edge's
// sites not said to be held). Taken as face B's nearest site there, it gives face B's triangle
// on the edge.
TEST(RestrictedDelaunay, APieceOfACellReachingRoundAKnifeEdgeIsTakenAsTheCellOnItsSide) {
    const double wedge = 30.0 * M_PI / 180.0;
    const int n = 12; // 0.25 apart
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    // Vertex (face, i, j): at distance 3 i / n from the edge on face A (face 0, y = 0) or B, at
    // height 3 j / n; the edge's vertices (i = 0) shared.
    auto id = [&](int face, int i, int j) { return i == 0 ? j : (n + 1) + (face * n + i - 1) * (n + 1) + j; };
    for (int j = 0; j <= n; ++j) p.emplace_back(0.0, 0.0, 3.0 * j / n);
    for (int face = 0; face < 2; ++face)
        for (int i = 1; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const double d = 3.0 * i / n, angle = face == 0 ? 0.0 : wedge;
                p.emplace_back(d * std::cos(angle), d * std::sin(angle), 3.0 * j / n);
            }
    for (int face = 0; face < 2; ++face)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const int32_t a = id(face, i, j), b = id(face, i + 1, j), c = id(face, i + 1, j + 1), d = id(face, i, j + 1);
                if (face == 0) { // facing -y, out of the wedge
                    f.push_back({a, b, c});
                    f.push_back({a, c, d});
                } else {
                    f.push_back({a, c, b});
                    f.push_back({a, d, c});
                }
            }
    const Mesh knife = test::make_mesh(p, f);
    const LiftedSurface s = make_lifted_surface(knife.points, knife.triangles);
    auto on = [&](int face, double d, double z) {
        const double angle = face == 0 ? 0.0 : wedge;
        return Eigen::RowVector3d(d * std::cos(angle), d * std::sin(angle), z);
    };
    std::vector<Eigen::RowVector3d> rows = {on(0, 0.0, 0.0), on(0, 0.0, 1.0), on(0, 0.0, 2.0), on(0, 0.0, 3.0),
                                            on(0, 1.3, 1.5)}; // a = 1, b = 2, c = 4
    for (double z : {0.5, 2.5}) rows.push_back(on(0, 1.3, z));
    for (double z : {0.0, 1.0, 2.0, 3.0}) rows.push_back(on(0, 2.6, z));
    for (double z : {0.5, 1.5, 2.5}) rows.push_back(on(1, 1.5, z));
    for (double z : {0.0, 1.0, 2.0, 3.0}) rows.push_back(on(1, 2.6, z));
    LiftedPoints sites(static_cast<Eigen::Index>(rows.size()), 3);
    for (size_t k = 0; k < rows.size(); ++k) sites.row(static_cast<Eigen::Index>(k)) = rows[k];
    RestrictedDelaunayParams params;
    params.held = 4; // the edge's
    const RestrictedDelaunay rdt = restricted_delaunay(s, sites, 2, params);
    const Mesh& out = rdt.mesh;
    // No triangle twice, turned over, no edge in more than two; edge (a, b) in two triangles,
    // with c on face A and face B's middle site (12).
    std::set<std::array<int32_t, 3>> seen;
    std::map<std::pair<int32_t, int32_t>, int> uses;
    std::vector<int32_t> across; // the third vertices of the triangles on edge (a, b)
    for (Eigen::Index t = 0; t < out.triangles.rows(); ++t) {
        std::array<int32_t, 3> tri = {out.triangles(t, 0), out.triangles(t, 1), out.triangles(t, 2)};
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        EXPECT_FALSE(seen.count({tri[0], tri[2], tri[1]})) << "triangle " << t << " folded onto another";
        seen.insert(tri);
        for (int j = 0; j < 3; ++j) ++uses[std::minmax(tri[j], tri[(j + 1) % 3])];
        const int ab = (std::count(tri.begin(), tri.end(), 1) > 0) + (std::count(tri.begin(), tri.end(), 2) > 0);
        if (ab == 2) across.push_back(tri[0] + tri[1] + tri[2] - 3);
    }
    for (const auto& [edge, count] : uses) EXPECT_LE(count, 2) << edge.first << "-" << edge.second;
    std::sort(across.begin(), across.end());
    EXPECT_EQ(across, (std::vector<int32_t>{4, 12}));
    EXPECT_EQ(out.points.rows(), sites.rows()); // no cell split
}

// The pipeline hands the optimiser's RvdCache (neighbour lists made at earlier iterates, a seed
// site per triangle) to the triangulation instead of building them again: the triangulation
// is the same as from scratch, and no list is rebuilt for it.
TEST(RestrictedDelaunay, FromTheOptimisersCacheIsTheSameAsFromScratch) {
    const Mesh torus = test::make_torus(1.0, 0.3, 40, 16);
    const LiftedSurface s =
        make_lifted_surface(lift(torus.points, vertex_normals(torus, 0.05), 0.05), torus.triangles);
    LiftedPoints sites = random_sites(s, 600, 7);
    RvdCache cache;
    optimize_sites(s, sites, 5.0, 20, 2, {}, &cache);
    ASSERT_GT(cache.rebuilds, 0);
    const long rebuilds = cache.rebuilds;
    const RestrictedDelaunay reused = restricted_delaunay(s, sites, 2, {}, &cache);
    EXPECT_EQ(cache.rebuilds, rebuilds);
    RvdCache empty; // a cache the triangulation does use: it fills it
    const RestrictedDelaunay fresh = restricted_delaunay(s, sites, 2, {}, &empty);
    EXPECT_EQ(empty.rebuilds, 1);
    EXPECT_EQ(reused.mesh.points, fresh.mesh.points);
    EXPECT_EQ(reused.mesh.triangles, fresh.mesh.triangles);
    EXPECT_EQ(reused.split_sites, fresh.split_sites);
    const test::Topology topo = test::topology(reused.mesh);
    EXPECT_TRUE(topo.closed_oriented_manifold());
    EXPECT_EQ(topo.chi, 0);
}

TEST(Sampling, IsReproducibleAndOnTheSurface) {
    const Mesh m = test::make_torus(1.0, 0.3, 30, 12);
    const LiftedSurface s = make_lifted_surface(m.points, m.triangles);
    const LiftedPoints a = random_sites(s, 500, 42), b = random_sites(s, 500, 42), c = random_sites(s, 500, 43);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
    const AabbTree tree(m);
    for (Eigen::Index i = 0; i < a.rows(); ++i)
        EXPECT_LT(tree.closest(a.row(i).transpose()).squared_distance, 1e-24) << "site " << i << " is off the surface";
}
