#include "liftremesh/aabb_tree.h"
#include "liftremesh/rdt.h"
#include "liftremesh/sampling.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

// Sites at the vertices of an icosahedron on a fine sphere: the restricted Delaunay
// triangulation is the icosahedron itself (Eq. 4), oriented like the surface.
TEST(RestrictedDelaunay, OfIcosahedronSitesOnASphereIsTheIcosahedron) {
    const Mesh sphere = test::make_icosphere(4);
    const Mesh ico = test::make_icosphere(0);
    const LiftedSurface s = make_lifted_surface(sphere.points, sphere.triangles);
    const Triangles t = restricted_delaunay(s, ico.points, 2);
    EXPECT_EQ(t.rows(), 20);
    Mesh out{ico.points, t};
    const test::Topology topo = test::topology(out);
    EXPECT_TRUE(topo.closed_oriented_manifold());
    EXPECT_EQ(topo.chi, 2);
    EXPECT_EQ(test::facing_inward(out, Eigen::Vector3d::Zero()), 0);
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
