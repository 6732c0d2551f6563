// The memory estimate that lets a too large request fail at once: it must cover what a run
// really takes (measured with /usr/bin/time), without refusing runs that fit by far.
#include "liftremesh/exceptions.h"
#include "liftremesh/memory_budget.h"
#include "liftremesh/mesh_io.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace liftremesh;
namespace fs = std::filesystem;

TEST(MemoryBudget, RefusesWhatDoesNotFitAndNamesTheNumbers) {
    const std::uint64_t needed = estimated_peak_bytes(1'000'000, 5000, 2);
    EXPECT_NO_THROW(check_memory_budget(1'000'000, 5000, 2, needed));
    EXPECT_NO_THROW(check_memory_budget(1'000'000, 5000, 2, 0)); // unknown: no check
    try {
        check_memory_budget(1'000'000, 5000, 2, needed - 1);
        FAIL() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("1000000 vertices"), std::string::npos) << message;
        EXPECT_NE(message.find("GiB"), std::string::npos) << message;
    }
    EXPECT_GT(physical_memory_bytes(), std::uint64_t{1} << 28); // this platform can tell it
}

TEST(MemoryBudget, EstimateCoversAMeasuredRunWithoutOverstatingIt) {
    if (std::system("test -x /usr/bin/time") != 0) GTEST_SKIP() << "/usr/bin/time is not installed";
    const fs::path dir = fs::temp_directory_path() / "liftremesh_memory_budget";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Mesh sphere = test::make_icosphere(3);
    write_mesh((dir / "in.off").string(), sphere);
    const long sites = 100000;
    const std::string command = "/usr/bin/time -f %M -o " + (dir / "kib.txt").string() + " " + LIFTREMESH_CLI + " " +
                                (dir / "in.off").string() + " " + (dir / "out.off").string() + " --vertices " +
                                std::to_string(sites) + " --iterations 3 --threads 2 --quiet";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
    std::ifstream in(dir / "kib.txt");
    double kib = 0.0;
    in >> kib;
    fs::remove_all(dir);
    ASSERT_GT(kib, 0.0);
    const double measured = kib * 1024.0;
    const double estimate = static_cast<double>(estimated_peak_bytes(sites, sphere.triangles.rows(), 2));
    EXPECT_GE(estimate, measured);
    EXPECT_LE(estimate, 2.0 * measured);
}
