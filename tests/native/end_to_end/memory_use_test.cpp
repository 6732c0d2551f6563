// The memory estimate (system/memory_budget.h) against what a run of the command-line tool
// really takes, measured with /usr/bin/time.
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/system/memory_budget.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>

using namespace liftremesh;

namespace {

//! Peak resident size in bytes of the CLI remeshing `mesh` at `sites` vertices (3 iterations,
//! 2 threads), from /usr/bin/time.
double measured_peak_bytes(const Mesh& mesh, long sites) {
    const test::TestDir dir("liftremesh_memory_budget_");
    write_mesh((dir.path() / "in.off").string(), mesh);
    const std::string command = "/usr/bin/time -f %M -o " + (dir.path() / "kib.txt").string() + " " + LIFTREMESH_CLI +
                                " " + (dir.path() / "in.off").string() + " " + (dir.path() / "out.off").string() +
                                " --vertices " + std::to_string(sites) + " --iterations 3 --threads 2 --quiet";
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
    std::ifstream in(dir.path() / "kib.txt");
    double kib = 0.0;
    in >> kib;
    return kib * 1024.0;
}

} // namespace

TEST(MemoryBudget, EstimateCoversAMeasuredRunWithoutOverstatingIt) {
    if (std::system("test -x /usr/bin/time") != 0) GTEST_SKIP() << "/usr/bin/time is not installed";
    // Many sites on a coarse input, then few sites on a fine one (the input's share of the
    // estimate: a 1.2M-triangle torus at 6000 vertices measured 828 MB against 1.3 GB).
    const Mesh coarse = test::make_icosphere(3), fine = test::make_torus(1.0, 0.3, 800, 200);
    for (const auto& [mesh, sites] : {std::pair<const Mesh&, long>{coarse, 100000}, {fine, 2000}}) {
        const double measured = measured_peak_bytes(mesh, sites);
        ASSERT_GT(measured, 0.0);
        const double estimate = static_cast<double>(estimated_peak_bytes(sites, mesh.triangles.rows(), 2));
        EXPECT_GE(estimate, measured) << mesh.triangles.rows() << " triangles";
        EXPECT_LE(estimate, 2.0 * measured) << mesh.triangles.rows() << " triangles";
    }
}
