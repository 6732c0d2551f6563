#include "helpers.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/mesh/mesh_io.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numeric>
#include <vector>

using namespace liftremesh;

namespace {

//! Flat patch of equilateral triangles: a triangular lattice of `n` rows (n^2 triangles).
Mesh make_equilateral_patch(int n) {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    std::vector<std::vector<int32_t>> id(n + 1);
    for (int row = 0; row <= n; ++row)
        for (int k = 0; k <= n - row; ++k) {
            id[row].push_back(static_cast<int32_t>(p.size()));
            p.emplace_back(k + 0.5 * row, row * std::sqrt(3.0) / 2, 0.0);
        }
    for (int row = 0; row < n; ++row)
        for (int k = 0; k < n - row; ++k) {
            f.push_back({id[row][k], id[row][k + 1], id[row + 1][k]});
            if (k + 1 < n - row) f.push_back({id[row][k + 1], id[row + 1][k + 1], id[row + 1][k]});
        }
    return test::make_mesh(p, f);
}

double total_edge_length(const Mesh& mesh) {
    double total = 0.0;
    for (const EdgeCount& e : edge_counts(mesh.triangles))
        total += (mesh.points.row(e.a) - mesh.points.row(e.b)).norm();
    return total;
}

long histogram_total(const MeshQuality& q) {
    return std::accumulate(q.kappa_histogram.begin(), q.kappa_histogram.end(), 0L);
}

} // namespace

TEST(Quality, EquilateralPatchHasKappaOne) {
    const Mesh mesh = make_equilateral_patch(6);
    const MeshQuality q = measure_quality(mesh);
    EXPECT_EQ(q.triangles, 36);
    EXPECT_EQ(q.vertices, 28);
    EXPECT_NEAR(q.kappa_min, 1.0, 1e-12);
    EXPECT_NEAR(q.kappa_mean, 1.0, 1e-12);
    EXPECT_EQ(q.kappa_histogram[9], 36); // kappa == 1 belongs to the last bin
    EXPECT_EQ(histogram_total(q), 36);
    EXPECT_NEAR(q.min_angle_deg, 60.0, 1e-9);
    EXPECT_EQ(q.boundary_edges, 18); // 3 sides of 6 unit edges
    EXPECT_EQ(q.boundary_loops, 1);
    EXPECT_EQ(q.nonmanifold_edges, 0);
    EXPECT_EQ(q.nonmanifold_vertices, 0);
    EXPECT_TRUE(q.oriented);
    EXPECT_EQ(q.euler_characteristic, 1);
    EXPECT_EQ(q.sharp_edge_length, 0.0);
}

TEST(Quality, IcosphereIsClosedOrientedGenusZero) {
    const Mesh mesh = test::make_icosphere(2);
    const MeshQuality q = measure_quality(mesh);
    EXPECT_EQ(q.vertices, 162);
    EXPECT_EQ(q.triangles, 320);
    EXPECT_EQ(q.boundary_edges, 0);
    EXPECT_EQ(q.boundary_loops, 0);
    EXPECT_EQ(q.nonmanifold_edges, 0);
    EXPECT_EQ(q.nonmanifold_vertices, 0);
    EXPECT_TRUE(q.oriented);
    EXPECT_EQ(q.euler_characteristic, 2);
    EXPECT_EQ(histogram_total(q), 320);
    EXPECT_GT(q.kappa_min, 0.8); // subdivided icosahedron: nearly equilateral
    EXPECT_LE(q.kappa_min, q.kappa_mean);
    EXPECT_LE(q.kappa_mean, 1.0);
    EXPECT_GT(q.min_angle_deg, 45.0);
    EXPECT_LT(q.min_angle_deg, 60.0);
}

TEST(Quality, FlippingOneTriangleBreaksOrientation) {
    Mesh mesh = test::make_icosphere(2);
    std::swap(mesh.triangles(17, 1), mesh.triangles(17, 2));
    const MeshQuality q = measure_quality(mesh);
    EXPECT_FALSE(q.oriented);
    EXPECT_EQ(q.boundary_edges, 0);
    EXPECT_EQ(q.euler_characteristic, 2);
}

TEST(Quality, RemovingOneTriangleOpensThreeBoundaryEdges) {
    Mesh mesh = test::make_icosphere(2);
    mesh.triangles.row(5) = mesh.triangles.row(mesh.triangles.rows() - 1);
    mesh.triangles.conservativeResize(mesh.triangles.rows() - 1, 3);
    const MeshQuality q = measure_quality(mesh);
    EXPECT_EQ(q.boundary_edges, 3);
    EXPECT_EQ(q.boundary_loops, 1);
    EXPECT_EQ(q.euler_characteristic, 1);
    EXPECT_TRUE(q.oriented);
    EXPECT_EQ(q.nonmanifold_vertices, 0);
}

TEST(Quality, BoundaryLoopsAreTheComponentsOfTheBoundary) {
    // Two triangles far apart removed: two loops, each chi -1.
    Mesh mesh = test::make_icosphere(2);
    const Eigen::Index nf = mesh.triangles.rows();
    std::vector<char> keep(nf, 1);
    keep[0] = 0;
    const Eigen::Vector3d c0 = (corner(mesh, 0, 0) + corner(mesh, 0, 1) + corner(mesh, 0, 2)) / 3.0;
    Eigen::Index far = 0;
    for (Eigen::Index f = 0; f < nf; ++f)
        if (((corner(mesh, f, 0) + corner(mesh, f, 1) + corner(mesh, f, 2)) / 3.0).dot(c0) <
            ((corner(mesh, far, 0) + corner(mesh, far, 1) + corner(mesh, far, 2)) / 3.0).dot(c0))
            far = f;
    keep[far] = 0;
    Triangles kept(nf - 2, 3);
    for (Eigen::Index f = 0, k = 0; f < nf; ++f)
        if (keep[f]) kept.row(k++) = mesh.triangles.row(f);
    mesh.triangles = kept;
    const MeshQuality q = measure_quality(mesh);
    EXPECT_EQ(q.boundary_edges, 6);
    EXPECT_EQ(q.boundary_loops, 2);
    EXPECT_EQ(q.euler_characteristic, 0);

    // Two triangles touching at one vertex (a bow tie): their borders meet there, one loop.
    const Mesh bowtie =
        test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
    EXPECT_EQ(measure_quality(bowtie).boundary_loops, 1);
    // Apart: two.
    const Mesh apart =
        test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {-0.5, 0, 0}}, {{0, 1, 2}, {5, 3, 4}});
    EXPECT_EQ(measure_quality(apart).boundary_loops, 2);
}

TEST(Quality, NonManifoldEdgesAndVertices) {
    // Three triangles on the edge (0, 1).
    const Mesh fin =
        test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
    const MeshQuality qf = measure_quality(fin);
    EXPECT_EQ(qf.nonmanifold_edges, 1);
    EXPECT_EQ(qf.boundary_edges, 6);
    EXPECT_EQ(qf.nonmanifold_vertices, 0); // the fans stay edge-connected

    // Two triangles touching at vertex 0 only (a bow tie).
    const Mesh bowtie =
        test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
    const MeshQuality qb = measure_quality(bowtie);
    EXPECT_EQ(qb.nonmanifold_vertices, 1);
    EXPECT_EQ(qb.extra_vertex_fans, 1);
    EXPECT_EQ(qb.nonmanifold_edges, 0);
    // A third triangle at the same vertex: one vertex, two fans beyond the first.
    const Mesh three = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {0, 1, 1}, {0, 2, 1}},
                                       {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}});
    EXPECT_EQ(measure_quality(three).nonmanifold_vertices, 1);
    EXPECT_EQ(measure_quality(three).extra_vertex_fans, 2);
    EXPECT_EQ(qf.extra_vertex_fans, 0);

    // Two closed spheres glued at one vertex: only that vertex is non-manifold.
    const Mesh glued = test::make_touching_spheres(1);
    const MeshQuality qg = measure_quality(glued);
    EXPECT_EQ(qg.vertices, 2 * 42 - 1);
    EXPECT_EQ(qg.nonmanifold_vertices, 1);
    EXPECT_EQ(qg.extra_vertex_fans, 1);
    EXPECT_EQ(qg.nonmanifold_edges, 0);
    EXPECT_EQ(qg.boundary_edges, 0);
    EXPECT_EQ(qg.euler_characteristic, 3);
}

// The frame's case: a part beside two small inside-out boxes is "oriented" (neighbours agree)
// but has two closed components facing inward, which the counts give; the list holds the
// largest components first with their signed volumes, at most kListedComponents of them.
TEST(Quality, ComponentsCountsAndList) {
    Mesh part = test::make_cube(2.0, 4); // volume 64
    for (int k = 0; k < 2; ++k) {
        part = test::joined(part, test::turned(test::make_box({5.0 + 2 * k, 0, 0}, {5.5 + 2 * k, 0.5, 0.5 + k}, 1)));
    }
    const MeshQuality q = measure_quality(part);
    EXPECT_TRUE(q.oriented);
    EXPECT_EQ(q.components, 3);
    EXPECT_EQ(q.closed_components, 3);
    EXPECT_EQ(q.inward_components, 2);
    EXPECT_EQ(q.cavities, 0);
    ASSERT_EQ(q.component_list.size(), 3u);
    EXPECT_NEAR(q.component_list[0].signed_volume, 64.0, 1e-12);
    EXPECT_NEAR(q.component_list[1].signed_volume, -0.375, 1e-12); // 0.5 x 0.5 x 1.5, the larger
    EXPECT_NEAR(q.component_list[2].signed_volume, -0.125, 1e-12);

    Mesh many = test::make_square(1.0, 1);
    for (int k = 1; k < kListedComponents + 5; ++k) {
        Mesh square = test::make_square(1.0 + 0.01 * k, 1);
        square.points.col(2).array() += k;
        many = test::joined(many, square);
    }
    const MeshQuality m = measure_quality(many);
    EXPECT_EQ(m.components, kListedComponents + 5);
    EXPECT_EQ(m.closed_components, 0);
    ASSERT_EQ(m.component_list.size(), static_cast<size_t>(kListedComponents));
    EXPECT_NEAR(m.component_list.front().area, std::pow(1.0 + 0.01 * (kListedComponents + 4), 2), 1e-12);
    for (size_t k = 1; k < m.component_list.size(); ++k)
        EXPECT_GT(m.component_list[k - 1].area, m.component_list[k].area);
}

TEST(Quality, SharpEdgeLengthOfCubeAndSphere) {
    const double s = 0.75; // cube [-s, s]^3: 12 edges of length 2 s
    for (int n : {1, 3}) {
        Mesh cube = test::make_cube(s, n);
        EXPECT_NEAR(measure_quality(cube).sharp_edge_length, 12 * 2 * s, 1e-12) << n;
        EXPECT_NEAR(measure_quality(cube, {89.0}).sharp_edge_length, 12 * 2 * s, 1e-12) << n;
        EXPECT_EQ(measure_quality(cube, {91.0}).sharp_edge_length, 0.0) << n;
        // The measure does not depend on a triangle's orientation.
        std::swap(cube.triangles(0, 1), cube.triangles(0, 2));
        EXPECT_NEAR(measure_quality(cube).sharp_edge_length, 12 * 2 * s, 1e-12) << n;
    }
    const Mesh sphere = test::make_icosphere(3);
    EXPECT_EQ(measure_quality(sphere, {60.0}).sharp_edge_length, 0.0);
    EXPECT_NEAR(measure_quality(sphere, {0.5}).sharp_edge_length, total_edge_length(sphere), 1e-9);
}

// A triangle and, across its edge 0-2, a flap laid back flat onto it: neighbours that agree, yet
// turned by 180 degrees. A knife edge folds as much under 10 degrees.
TEST(Quality, AFlapLaidBackFlatIsAFoldedEdgeAndACubeHasNone) {
    const Mesh flap = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.7, 0.2, 0}},
                                      {{0, 1, 2}, {2, 3, 0}, {0, 2, 4}});
    // The pair alone: (0, 2, 3) runs 0-2 against (0, 1, 2) and faces -z, its apex beyond 0-2.
    const Mesh pair = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.7, 0.2, 0}}, {{0, 1, 2}, {0, 2, 3}});
    const MeshQuality folded = measure_quality(pair);
    EXPECT_TRUE(folded.oriented); // its neighbours agree: only the geometry folds
    EXPECT_EQ(folded.folded_edges, 1);
    EXPECT_NEAR(folded.folded_edge_length, std::sqrt(2.0), 1e-12);
    EXPECT_EQ(measure_quality(flap).folded_edges, 0); // 0-2 has three triangles: not manifold
    // A knife edge of 9 degrees (turning by 171): folded; of 11: not.
    for (const double deg : {171.0, 169.0}) {
        const double a = (180.0 - deg) * M_PI / 180.0;
        const Mesh knife = test::make_mesh({{0, 0, 0}, {0, 1, 0}, {1, 0.5, 0}, {std::cos(a), 0.5, std::sin(a)}},
                                           {{0, 2, 1}, {1, 3, 0}});
        EXPECT_EQ(measure_quality(knife).folded_edges, deg > kFoldedTurnDeg ? 1 : 0) << deg;
    }
    EXPECT_EQ(measure_quality(test::make_cube(0.5, 3)).folded_edges, 0);
}

// A plate 1 x 1 x 0.01: its rims (8 edges of 1) and its corners (4 of 0.01) all border a side
// triangle 0.01 wide (its altitude over the diagonal: 0.01 / sqrt(1.0001)), so a width under
// that counts them all and one over it none, whatever their angle.
TEST(Quality, SharpEdgesOfTrianglesNarrowerThanTheWidthDoNotCount) {
    const Mesh plate = test::make_box({0.0, 0.0, 0.0}, {1.0, 1.0, 0.01}, 1);
    const double side_width = 0.01 / std::sqrt(1.0001);
    EXPECT_NEAR(measure_quality(plate).sharp_edge_length, 8.04, 1e-12);
    EXPECT_NEAR(measure_quality(plate, {60.0, 0.999 * side_width}).sharp_edge_length, 8.04, 1e-12);
    EXPECT_EQ(measure_quality(plate, {60.0, 1.001 * side_width}).sharp_edge_length, 0.0);
    // A cube's faces are wide: the same width leaves its 12 edges counted.
    EXPECT_NEAR(measure_quality(test::make_box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 1), {60.0, 0.02}).sharp_edge_length,
                12.0, 1e-12);
}

TEST(Quality, EmptyMeshAndBadIndices) {
    Mesh empty;
    empty.points.resize(0, 3);
    empty.triangles.resize(0, 3);
    const MeshQuality q = measure_quality(empty);
    EXPECT_EQ(q.vertices, 0);
    EXPECT_EQ(q.triangles, 0);
    EXPECT_EQ(histogram_total(q), 0);

    Mesh bad = test::make_icosphere(0);
    bad.triangles(2, 2) = 12;
    EXPECT_THROW(measure_quality(bad), InvalidInput);
}

TEST(Quality, HausdorffOfAMeshWithItselfIsZero) {
    const Mesh mesh = test::make_torus(1.0, 0.3, 30, 12);
    const DistanceStats d = hausdorff_distance(mesh, mesh, 20000);
    EXPECT_LT(d.hausdorff, 1e-12);
    EXPECT_LT(d.mean, 1e-12);
}

TEST(Quality, HausdorffBetweenConcentricSpheres) {
    const Mesh a = test::make_icosphere(3, 1.0), b = test::make_icosphere(3, 1.1);
    const DistanceStats d = hausdorff_distance(a, b, 20000);
    // b's vertices lie 0.1 outside a's, and are b's farthest points from a (a is convex and
    // inscribed in the unit sphere); every point of a is within 0.1 of b.
    EXPECT_NEAR(d.hausdorff, 0.1, 1e-9);
    EXPECT_NEAR(d.b_to_a, 0.1, 1e-9);
    EXPECT_LE(d.a_to_b, 0.1 + 1e-12);
    EXPECT_GT(d.a_to_b, 0.09);
    EXPECT_NEAR(d.mean, 0.1, 0.002);
    EXPECT_LE(d.mean, d.hausdorff);
}

TEST(Quality, HausdorffOfAShiftedCube) {
    // Shifting the cube [-1, 1]^3 by 0.25 along z: its bottom face is 0.25 from the other's.
    const Mesh a = test::make_cube(1.0, 2);
    Mesh b = a;
    b.points.col(2).array() += 0.25;
    const DistanceStats d = hausdorff_distance(a, b, 5000);
    EXPECT_NEAR(d.a_to_b, 0.25, 1e-12);
    EXPECT_NEAR(d.b_to_a, 0.25, 1e-12);
    EXPECT_NEAR(d.hausdorff, 0.25, 1e-12);
    EXPECT_GT(d.mean, 0.0);
    EXPECT_LT(d.mean, 0.25);
}

TEST(Quality, HausdorffIsDeterministic) {
    const Mesh a = test::make_icosphere(2, 1.0), b = test::make_torus(0.8, 0.3, 20, 10);
    const DistanceStats d1 = hausdorff_distance(a, b, 5000, 11), d2 = hausdorff_distance(a, b, 5000, 11);
    EXPECT_EQ(d1.hausdorff, d2.hausdorff);
    EXPECT_EQ(d1.a_to_b, d2.a_to_b);
    EXPECT_EQ(d1.b_to_a, d2.b_to_a);
    EXPECT_EQ(d1.mean, d2.mean);
    const DistanceStats d3 = hausdorff_distance(a, b, 5000, 12);
    EXPECT_NE(d1.mean, d3.mean); // a different seed draws different points
    EXPECT_THROW(hausdorff_distance(a, Mesh{}), InvalidInput);
}

TEST(Quality, HausdorffDoesNotDependOnTheThreadCount) {
    // Samples are drawn per triangle in parallel, distances found in parallel with warm starts.
    const Mesh a = test::make_icosphere(3, 1.0), b = test::make_torus(0.8, 0.3, 40, 16);
    const int before = omp_get_max_threads();
    omp_set_num_threads(1);
    const DistanceStats one = hausdorff_distance(a, b, 30000);
    omp_set_num_threads(3);
    const DistanceStats three = hausdorff_distance(a, b, 30000);
    omp_set_num_threads(before);
    EXPECT_EQ(one.a_to_b, three.a_to_b);
    EXPECT_EQ(one.b_to_a, three.b_to_a);
    EXPECT_EQ(one.mean, three.mean);
}
