#include "cli_options.h"

#include "liftremesh/exceptions.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace liftremesh::cli {

namespace {

double parse_number(const std::string& option, const std::string& text) {
    size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value))
        throw InvalidInput("option " + option + " expects a number, got '" + text + "'");
    return value;
}

long long parse_integer(const std::string& option, const std::string& text) {
    size_t used = 0;
    long long value = 0;
    try {
        value = std::stoll(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size()) throw InvalidInput("option " + option + " expects an integer, got '" + text + "'");
    return value;
}

int parse_int(const std::string& option, const std::string& text) {
    const long long v = parse_integer(option, text);
    if (v < -2147483647LL || v > 2147483647LL) throw InvalidInput("option " + option + " value '" + text + "' is too large");
    return static_cast<int>(v);
}

} // namespace

CliOptions parse_options(const std::vector<std::string>& args) {
    CliOptions o;
    // The mode sets the defaults of nu and delta: find it first, then apply the other options.
    Mode mode = Mode::Isotropic;
    for (size_t i = 0; i < args.size(); ++i)
        if (args[i] == "--mode") {
            if (i + 1 >= args.size()) throw InvalidInput("option --mode expects a value");
            mode = parse_mode(args[i + 1]);
        }
    o.params = RemeshParams::for_mode(mode);

    std::vector<std::string> positional;
    bool vertices_given = false, edge_given = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-h" || a == "--help") {
            o.help = true;
            return o;
        }
        if (a == "--quiet" || a == "-q") {
            o.quiet = true;
            continue;
        }
        if (a.size() < 2 || a.compare(0, 2, "--") != 0 || a == "--") {
            if (!a.empty() && a[0] == '-' && a.size() > 1) throw InvalidInput("unknown option '" + a + "' (see --help)");
            positional.push_back(a);
            continue;
        }
        static const char* known[] = {"--vertices", "--edge-length", "--mode",       "--sigma", "--delta", "--nu",
                                      "--eta",      "--iterations",  "--seed",       "--threads", "--report"};
        bool is_known = false;
        for (const char* k : known) is_known = is_known || a == k;
        if (!is_known) throw InvalidInput("unknown option '" + a + "' (see --help)");
        if (i + 1 >= args.size()) throw InvalidInput("option " + a + " expects a value");
        const std::string v = args[++i];
        RemeshParams& p = o.params;
        if (a == "--vertices") {
            p.target_vertices = parse_int(a, v);
            vertices_given = true;
        } else if (a == "--edge-length") {
            p.target_edge_length = parse_number(a, v);
            if (!(p.target_edge_length > 0.0)) throw InvalidInput("option --edge-length expects a length > 0, got '" + v + "'");
            edge_given = true;
        } else if (a == "--mode") {
            // already applied
        } else if (a == "--sigma") {
            p.sigma = parse_number(a, v);
        } else if (a == "--delta") {
            p.delta = parse_number(a, v);
        } else if (a == "--nu") {
            p.nu = parse_number(a, v);
        } else if (a == "--eta") {
            p.eta = parse_number(a, v);
        } else if (a == "--iterations") {
            p.iterations = parse_int(a, v);
        } else if (a == "--seed") {
            const long long s = parse_integer(a, v);
            if (s < 0) throw InvalidInput("option --seed expects a non-negative integer, got '" + v + "'");
            p.seed = static_cast<std::uint64_t>(s);
        } else if (a == "--threads") {
            p.threads = parse_int(a, v);
        } else if (a == "--report") {
            o.report_path = v;
        }
    }
    if (vertices_given && edge_given) throw InvalidInput("give either --vertices or --edge-length, not both");
    if (positional.size() != 2)
        throw InvalidInput("expected an input and an output file, got " + std::to_string(positional.size()) +
                           " file argument(s) (see --help)");
    o.input = positional[0];
    o.output = positional[1];
    o.params.validate();
    return o;
}

std::string usage() {
    std::ostringstream s;
    s << "usage: liftremesh IN OUT [options]\n"
         "\n"
         "Remeshes the triangle mesh IN into well-shaped triangles (feature-sensitive centroidal\n"
         "Voronoi tessellation on the normal-lifted surface) and writes OUT. Formats by extension:\n"
         ".stl (ASCII or binary in, binary out), .obj, .off. Progress goes to stderr.\n"
         "\n"
         "options (default in brackets):\n";
    auto line = [&s](std::string flag, const std::string& help) {
        flag.resize(std::max<size_t>(flag.size() + 1, 24), ' ');
        s << flag << help << "\n";
    };
    for (const ParameterInfo& p : parameter_table()) {
        std::string name = p.name;
        std::replace(name.begin(), name.end(), '_', '-');
        line("  --" + name + " " + p.metavar, p.help + " [" + p.default_text + "]");
    }
    line("  --report FILE.json", "write the quality report as JSON");
    line("  --quiet", "no progress output");
    line("  --help", "this text");
    s << "\n"
         "exit status: 0 success, 2 bad input or option, 1 other failure.\n";
    return s.str();
}

} // namespace liftremesh::cli
