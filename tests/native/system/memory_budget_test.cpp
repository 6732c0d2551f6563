// The memory estimate that lets a too large request fail at once, without refusing runs that
// fit by far (what a run really takes: end_to_end/memory_budget_test.cpp).
#include "liftremesh/exceptions.h"
#include "liftremesh/system/memory_budget.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <cstdlib>
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
