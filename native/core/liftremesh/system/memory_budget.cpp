#include "liftremesh/system/memory_budget.h"

#include "liftremesh/exceptions.h"

#include <cstdio>
#include <string>

#if defined(_WIN32)
#ifndef NOMINMAX
#define NOMINMAX // no min/max macros
#endif
#include <windows.h>
#else
#include <unistd.h>
#endif

namespace liftremesh {

namespace {

//! The parts of the estimate (memory_budget.h): what the sites take, and what the input does.
std::uint64_t sites_bytes(long sites, int threads) {
    const std::uint64_t per_site = 1200 + 128 * static_cast<std::uint64_t>(threads > 0 ? threads : 1);
    return static_cast<std::uint64_t>(sites) * per_site;
}
std::uint64_t input_bytes(long triangles) { return static_cast<std::uint64_t>(triangles) * 1024; }

} // namespace

std::uint64_t estimated_peak_bytes(long sites, long triangles, int threads) {
    return sites_bytes(sites, threads) + input_bytes(triangles) + (std::uint64_t{64} << 20);
}

std::uint64_t physical_memory_bytes() {
#if defined(_WIN32)
    MEMORYSTATUSEX status;
    status.dwLength = sizeof(status);
    return GlobalMemoryStatusEx(&status) ? static_cast<std::uint64_t>(status.ullTotalPhys) : 0;
#else
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
#endif
}

void check_memory_budget(long sites, long triangles, int threads, std::uint64_t available) {
    const std::uint64_t needed = estimated_peak_bytes(sites, triangles, threads);
    if (available == 0 || needed <= available) return;
    auto gib = [](std::uint64_t bytes) {
        char text[32];
        std::snprintf(text, sizeof(text), "%.1f GiB", static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0));
        return std::string(text);
    };
    // Name the part that weighs most: on an input much finer than the output, fewer vertices
    // would not help.
    const std::string remedy = input_bytes(triangles) > sites_bytes(sites, threads)
                                   ? "the input is too fine for this machine: export it with a coarser tessellation"
                                   : "ask for fewer vertices or a larger edge length";
    throw InvalidInput(std::to_string(sites) + " vertices on an input of " + std::to_string(triangles) +
                       " triangles need about " + gib(needed) + " of memory, more than the " + gib(available) +
                       " of this machine: " + remedy);
}

} // namespace liftremesh
