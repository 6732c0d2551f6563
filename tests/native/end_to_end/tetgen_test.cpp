// FEM preprocessing, checked by a tetrahedral mesher: TetGen (Debian's `tetgen`, installed by
// scripts/install-deps.sh) fills the remeshed surface with quality tetrahedra (-pq1.4) keeping
// its triangles as the boundary (-Y), as a FEM user fills a shell to get a solid mesh. TetGen
// refuses a surface with triangles passing through each other; the first test shows it does.
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/pipeline.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace liftremesh;
namespace fs = std::filesystem;

namespace {

struct TetgenRun {
    int exit_code = -1;
    long tetrahedra = 0, boundary_triangles = 0; // counts of TetGen's .1.ele and .1.face
};

long first_number(const fs::path& p) {
    std::ifstream in(p);
    long n = 0;
    return in >> n ? n : 0;
}

class TetGen : public ::testing::Test {
protected:
    const test::TestDir scratch{"liftremesh_tetgen_"};
    const fs::path dir = scratch.path();
    void SetUp() override {
        if (std::string(LIFTREMESH_TETGEN).empty()) FAIL() << "tetgen was not found at configure time: make deps installs it";
    }

    TetgenRun fill(const Mesh& surface) const {
        const fs::path off = dir / "surface.off";
        write_mesh(off.string(), surface);
        const std::string command =
            std::string(LIFTREMESH_TETGEN) + " -pq1.4YQ " + off.string() + " >" + (dir / "log.txt").string() + " 2>&1";
        const int status = std::system(command.c_str());
        TetgenRun r;
        r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1; // TetGen aborts when it refuses
        if (r.exit_code == 0) {
            r.tetrahedra = first_number(dir / "surface.1.ele");
            r.boundary_triangles = first_number(dir / "surface.1.face");
        }
        return r;
    }
};

} // namespace

TEST_F(TetGen, RefusesTwoSpheresThroughEachOther) {
    const Mesh sphere = test::make_icosphere(3);
    Mesh other = sphere;
    other.points *= 0.8;
    other.points.rowwise() += Eigen::RowVector3d(1.0, 0.1, 0.05);
    EXPECT_NE(fill(test::joined(sphere, other)).exit_code, 0);
    const TetgenRun alone = fill(sphere);
    EXPECT_EQ(alone.exit_code, 0);
    EXPECT_EQ(alone.boundary_triangles, sphere.triangles.rows());
}

TEST_F(TetGen, FillsRemeshedBuiltShapes) {
    for (const Mesh& input : {test::make_cube(1.0, 8), test::make_torus(1.0, 0.3, 48, 16)}) {
        const Mesh out = remesh(input, test::params_with(1500)).mesh;
        const TetgenRun r = fill(out);
        EXPECT_EQ(r.exit_code, 0);
        EXPECT_GT(r.tetrahedra, out.triangles.rows() / 2);
        EXPECT_EQ(r.boundary_triangles, out.triangles.rows()); // -Y: the surface kept as it is
    }
}

class TetGenShared : public TetGen, public ::testing::WithParamInterface<const char*> {};

TEST_P(TetGenShared, FillsTheRemeshedCadPart) {
    LIFTREMESH_REQUIRE_SHARED(path, GetParam());
    const Mesh out = remesh(read_mesh(path), RemeshParams{}).mesh; // default settings, 6000 vertices
    const TetgenRun r = fill(out);
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_GT(r.tetrahedra, out.triangles.rows() / 2);
    EXPECT_EQ(r.boundary_triangles, out.triangles.rows());
}

INSTANTIATE_TEST_SUITE_P(Acceptance, TetGenShared, ::testing::ValuesIn(test::kAcceptanceMeshes), test::mesh_name);
