// liftremesh: the command-line remesher. Reads a mesh, remeshes it, writes it and a report.
#include "cli_options.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/pipeline.h"
#include "liftremesh/report.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

using namespace liftremesh;

namespace {

// One line on stderr for every error, whatever it is.
int fail(const std::string& message, int code) {
    std::string line = message;
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::cerr << "liftremesh: error: " << line << "\n";
    return code;
}

bool print_progress(const Progress& p) {
    if (p.stage == "optimize" && p.total > 0) {
        if (p.iteration % 10 == 0 || p.iteration == p.total)
            std::fprintf(stderr, "  optimize %3d/%d  energy %.6g  |grad| %.3g\n", p.iteration, p.total, p.energy,
                         p.gradient_norm);
    } else if (p.total == 0) {
        std::fprintf(stderr, "liftremesh: %s\n", p.stage.c_str());
    }
    return true;
}

// Refuses, before the work, a file the run could not write at its end: one in a directory that
// does not exist or cannot be written to, a read-only file, or a name that is a directory.
// Without this, a long run was lost at its last step.
void check_writable(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path target = fs::absolute(path, error);
    if (fs::is_directory(target, error)) throw InvalidInput("cannot write '" + path + "': it is a directory");
    const fs::path directory = target.parent_path();
    if (!fs::is_directory(directory, error))
        throw InvalidInput("cannot write '" + path + "': no directory '" + directory.string() + "'");
    if (::access(directory.c_str(), W_OK) != 0)
        throw InvalidInput("cannot write '" + path + "': directory '" + directory.string() + "' is not writable");
    if (fs::exists(target, error) && ::access(target.c_str(), W_OK) != 0)
        throw InvalidInput("cannot write '" + path + "': the file is read-only");
}

// Threads that wait for work sleep rather than spin. libgomp's waiting threads spin for some
// milliseconds first (GOMP_SPINCOUNT) at every barrier and between parallel regions; with
// another process busy on one of the cores, the spinning thread takes the core from the one that
// has the work, and the run slows down to well below one thread's speed. libgomp reads the policy
// once, when it is loaded, before main: so the CLI runs itself again with the variable set
// (run_in_its_environment), unless the user has chosen a policy (then theirs stands). Returns
// whether it set it.
bool sleep_while_waiting() {
    if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return false;
    return ::setenv("OMP_WAIT_POLICY", "PASSIVE", 1) == 0;
}

// Large arrays in huge pages where the kernel gives them on request (transparent huge pages in
// its "madvise" mode, Debian's default). A run on a million input triangles fills most of a
// gigabyte of fresh memory, and its diagram reads rows scattered over a hundred megabytes at
// every evaluation: in 4 KiB pages each first touch is a fault, and reads spread over more pages
// than the TLB covers miss it.
// glibc's malloc asks for huge pages with its tunable glibc.malloc.hugetlb=1, read once, before
// main, as libgomp's policy is; a user's own setting of it stands. Returns whether it set it.
bool use_huge_pages() {
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    std::string value = tunables ? tunables : "";
    if (value.find("glibc.malloc.hugetlb") != std::string::npos) return false;
    value += (value.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
    return ::setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0;
}

// Runs the CLI again with the environment the two settings above ask for, once: the run it
// starts finds them set. The result does not depend on either.
void run_in_its_environment(char** argv) {
    const bool policy = sleep_while_waiting();
    const bool pages = use_huge_pages();
    if (policy || pages) ::execv("/proc/self/exe", argv); // returns only on failure: go on as we are
}

} // namespace

int main(int argc, char** argv) {
    run_in_its_environment(argv);
    cli::CliOptions options;
    try {
        options = cli::parse_options(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const std::exception& e) {
        return fail(e.what(), 2);
    }
    if (options.help) {
        std::cout << cli::usage();
        return 0;
    }
    try {
        check_mesh_extension(options.output); // refuse a bad output name before the work
        check_writable(options.output);
        if (!options.report_path.empty()) check_writable(options.report_path);
        const Mesh input = read_mesh(options.input);
        const RemeshResult result =
            remesh(input, options.params, options.quiet ? ProgressCallback() : ProgressCallback(print_progress));
        write_mesh(options.output, result.mesh);
        if (!options.report_path.empty()) {
            std::ofstream out(options.report_path);
            out << to_json(result.report) << "\n";
            if (!out) return fail("cannot write the report '" + options.report_path + "'", 2);
        }
        if (!options.quiet) {
            const MeshQuality& q = result.report.output;
            std::string repaired; // why chi differs from the input's, when it is the repair asked for
            if (const long cracks = cracks_closed(result.report); cracks > 0)
                repaired += "; " + std::to_string(cracks) + " crack(s) of the input closed";
            if (const long fans = vertex_fans_split(result.report); fans > 0)
                repaired += "; " + std::to_string(fans) + " fan(s) of its non-manifold vertices split";
            std::fprintf(stderr,
                         "liftremesh: wrote %s: %ld vertices, %ld triangles, kappa min %.3f mean %.3f, "
                         "min angle %.1f deg, Hausdorff %.2e of the diagonal, chi %d (input %d%s)\n",
                         options.output.c_str(), q.vertices, q.triangles, q.kappa_min, q.kappa_mean, q.min_angle_deg,
                         result.report.hausdorff_relative, q.euler_characteristic,
                         result.report.input.euler_characteristic, repaired.c_str());
        }
        for (const std::string& warning : result.report.warnings) // shown even with --quiet
            std::fprintf(stderr, "liftremesh: warning: %s\n", warning.c_str());
        return 0;
    } catch (const InvalidInput& e) {
        return fail(e.what(), 2);
    } catch (const std::bad_alloc&) {
        return fail("out of memory", 1);
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
}
