#include "cli_options.h"

#include "liftremesh/exceptions.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace liftremesh::cli {

namespace {

// --name-with-dashes of a parameter row.
std::string option_of(const ParameterInfo& row) {
    std::string flag = "--" + row.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    return flag;
}

// The row whose option is `flag`, or nullptr.
const ParameterInfo* row_of_option(const std::string& flag) {
    for (const ParameterInfo& row : parameter_table())
        if (option_of(row) == flag) return &row;
    return nullptr;
}

[[noreturn]] void refuse(const std::string& option, const std::string& expected, const std::string& text) {
    throw InvalidInput("option " + option + " expects " + expected + ", got '" + text + "'");
}

double parse_number(const std::string& option, const std::string& text) {
    size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value)) refuse(option, "a number", text);
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
    if (used == 0 || used != text.size()) refuse(option, "an integer", text);
    return value;
}

// Sets the parameter of `row` from its option's text, checked against the row's range (a given
// value that replaces another parameter must be in range: its 0 only means "not given").
void apply(RemeshParams& params, const ParameterInfo& row, const std::string& text) {
    const std::string option = option_of(row);
    switch (row.kind) {
    case ParameterKind::Integer: {
        const long long value = parse_integer(option, text);
        if (!row.in_range(static_cast<double>(value))) refuse(option, row.expected(), text);
        set_integer_parameter(params, row, value);
        return;
    }
    case ParameterKind::Real: {
        const double value = parse_number(option, text);
        if (!row.in_range(value)) refuse(option, row.expected(), text);
        set_parameter(params, row, value);
        return;
    }
    case ParameterKind::Choice:
        set_choice_parameter(params, row, text);
        return;
    case ParameterKind::Flag: {
        static const char* yes[] = {"yes", "true", "on", "1"};
        static const char* no[] = {"no", "false", "off", "0"};
        for (int i = 0; i < 4; ++i) {
            if (text == yes[i]) return set_parameter(params, row, 1.0);
            if (text == no[i]) return set_parameter(params, row, 0.0);
        }
        refuse(option, row.expected(), text);
    }
    }
}

} // namespace

CliOptions parse_options(const std::vector<std::string>& args) {
    CliOptions o;
    // The mode sets the defaults of other parameters (nu and delta): find it first, then apply the
    // other options over the defaults of that mode.
    RemeshParams given_mode;
    for (size_t i = 0; i < args.size(); ++i) {
        const ParameterInfo* row = row_of_option(args[i]);
        if (row == nullptr || !std::holds_alternative<Mode RemeshParams::*>(row->field)) continue;
        if (i + 1 >= args.size()) throw InvalidInput("option " + args[i] + " expects a value");
        apply(given_mode, *row, args[i + 1]);
    }
    o.params = RemeshParams::for_mode(given_mode.mode);

    std::vector<std::string> positional;
    std::vector<const ParameterInfo*> given;
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
        const ParameterInfo* row = row_of_option(a);
        if (row == nullptr && a != "--report") throw InvalidInput("unknown option '" + a + "' (see --help)");
        if (i + 1 >= args.size()) throw InvalidInput("option " + a + " expects a value");
        const std::string& value = args[++i];
        if (row == nullptr) {
            o.report_path = value;
            continue;
        }
        apply(o.params, *row, value);
        given.push_back(row);
    }
    for (const ParameterInfo* row : given)
        for (const ParameterInfo* other : given)
            if (row->replaces == other->name)
                throw InvalidInput("give either " + option_of(*other) + " or " + option_of(*row) + ", not both");
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
    for (const ParameterInfo& p : parameter_table())
        line("  " + option_of(p) + " " + p.metavar, p.help + " [" + p.default_text + "]");
    line("  --report FILE.json", "write the quality report as JSON");
    line("  --quiet", "no progress output");
    line("  --help", "this text");
    s << "\n"
         "exit status: 0 success, 2 bad input or option, 1 other failure.\n";
    return s.str();
}

} // namespace liftremesh::cli
