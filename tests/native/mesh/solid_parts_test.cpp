// solid_parts.h: which triangles are remeshed on their own, and the sub-meshes they make.
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/solid_parts.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

namespace {

Mesh moved(Mesh mesh, double dx) {
    mesh.points.col(0).array() += dx;
    return mesh;
}

} // namespace

TEST(SolidParts, OneComponentIsOnePart) {
    const std::vector<SolidPart> sphere = solid_parts(test::make_icosphere(2));
    ASSERT_EQ(sphere.size(), 1u);
    EXPECT_TRUE(sphere[0].closed);
    EXPECT_EQ(sphere[0].triangles.size(), static_cast<size_t>(test::make_icosphere(2).triangles.rows()));
    const std::vector<SolidPart> square = solid_parts(test::make_square(1.0, 4));
    ASSERT_EQ(square.size(), 1u);
    EXPECT_FALSE(square[0].closed);
}

// Spheres touching at a vertex share it: one component, one part.
TEST(SolidParts, PartsSharingAVertexAreOnePart) {
    EXPECT_EQ(solid_parts(test::make_touching_spheres(2)).size(), 1u);
}

// Each closed component is a part, in order of first triangle, the open ones together last;
// the parts hold every triangle once.
TEST(SolidParts, EachClosedComponentAloneAndTheOpenOnesTogether) {
    const Mesh sphere = test::make_icosphere(1), square = test::make_square(1.0, 3), torus = test::make_torus(1, 0.3, 8, 6);
    const Mesh mesh = test::joined(test::joined(test::joined(moved(square, 5), sphere), moved(square, 8)), moved(torus, -4));
    const std::vector<SolidPart> parts = solid_parts(mesh);
    ASSERT_EQ(parts.size(), 3u);
    EXPECT_TRUE(parts[0].closed);
    EXPECT_TRUE(parts[1].closed);
    EXPECT_FALSE(parts[2].closed);
    EXPECT_EQ(parts[0].triangles.size(), static_cast<size_t>(sphere.triangles.rows()));
    EXPECT_EQ(parts[1].triangles.size(), static_cast<size_t>(torus.triangles.rows()));
    EXPECT_EQ(parts[2].triangles.size(), 2 * static_cast<size_t>(square.triangles.rows()));
    EXPECT_EQ(test::topology(submesh(mesh, parts[0].triangles)).chi, 2);
    EXPECT_EQ(test::topology(submesh(mesh, parts[1].triangles)).chi, 0);
    // Open ones only: one part, as the whole mesh.
    EXPECT_EQ(solid_parts(test::joined(square, moved(square, 3))).size(), 1u);
}

// A part's sub-mesh has its triangles' vertices only, in order of first use; appending the
// parts again gives the mesh's area and Euler characteristic.
TEST(SolidParts, SubmeshesAppendedGiveTheMeshBack) {
    const Mesh mesh = test::joined(test::make_icosphere(2), moved(test::make_torus(1, 0.3, 10, 8), 4));
    const std::vector<SolidPart> parts = solid_parts(mesh);
    ASSERT_EQ(parts.size(), 2u);
    Mesh again;
    for (const SolidPart& part : parts) {
        const Mesh piece = submesh(mesh, part.triangles);
        EXPECT_EQ(piece.points.rows(), static_cast<Eigen::Index>(referenced_vertices(piece).size()));
        for (size_t k = 0; k < part.triangles.size(); ++k)
            for (int j = 0; j < 3; ++j)
                EXPECT_EQ(piece.points.row(piece.triangles(static_cast<Eigen::Index>(k), j)),
                          mesh.points.row(mesh.triangles(part.triangles[k], j)));
        append(again, piece);
    }
    EXPECT_EQ(again.triangles.rows(), mesh.triangles.rows());
    EXPECT_EQ(again.points.rows(), mesh.points.rows());
    EXPECT_NEAR(surface_area(again), surface_area(mesh), 1e-12 * surface_area(mesh));
    EXPECT_EQ(test::topology(again).chi, 2);
}
