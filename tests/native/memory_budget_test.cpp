// The memory estimate that lets a too large request fail at once: it must cover what a run
// really takes (measured with /usr/bin/time), without refusing runs that fit by far.
#include "liftremesh/exceptions.h"
#include "liftremesh/memory_budget.h"
#include "liftremesh/mesh_io.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>

using namespace liftremesh;

namespace {

//! The message with which check_memory_budget refuses `sites` vertices on `triangles` input
//! triangles (2 threads) when the machine has one byte less than the estimate.
std::string refusal(long sites, long triangles) {
    try {
        check_memory_budget(sites, triangles, 2, estimated_peak_bytes(sites, triangles, 2) - 1);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected InvalidInput for " << sites << " vertices on " << triangles << " triangles";
    return {};
}

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

TEST(MemoryBudget, RefusesWhatDoesNotFitAndNamesTheNumbers) {
    const std::uint64_t needed = estimated_peak_bytes(1'000'000, 5000, 2);
    EXPECT_NO_THROW(check_memory_budget(1'000'000, 5000, 2, needed));
    EXPECT_NO_THROW(check_memory_budget(1'000'000, 5000, 2, 0)); // unknown: no check
    const std::string many_sites = refusal(1'000'000, 5000);
    for (const char* part : {"1000000 vertices", "5000 triangles", "GiB", "fewer vertices"})
        EXPECT_NE(many_sites.find(part), std::string::npos) << many_sites;
    // An input far finer than the output: the remedy is a coarser input, not fewer vertices.
    const std::string fine_input = refusal(2000, 3'000'000);
    EXPECT_NE(fine_input.find("3000000 triangles"), std::string::npos) << fine_input;
    EXPECT_NE(fine_input.find("too fine"), std::string::npos) << fine_input;
    EXPECT_EQ(fine_input.find("fewer vertices"), std::string::npos) << fine_input;
    EXPECT_GT(physical_memory_bytes(), std::uint64_t{1} << 28); // this platform can tell it
}

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
