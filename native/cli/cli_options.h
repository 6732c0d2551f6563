// Command-line options of the liftremesh tool, parsed into the core's RemeshParams.
#pragma once

#include "liftremesh/params.h"

#include <string>
#include <vector>

namespace liftremesh::cli {

struct CliOptions {
    std::string input;       //!< mesh to read (.stl, .obj, .off)
    std::string output;      //!< mesh to write (format by extension)
    std::string report_path; //!< JSON report file, or "" for none
    bool quiet = false;      //!< no progress on stderr
    bool help = false;       //!< --help was given: print usage and exit 0
    RemeshParams params;
};

//! Parses argv[1..]. Throws InvalidInput with a one-line message naming the bad option.
CliOptions parse_options(const std::vector<std::string>& args);

//! The --help text: usage and every option with its default (from parameter_table()).
std::string usage();

} // namespace liftremesh::cli
