#include "liftremesh/params.h"

#include "liftremesh/exceptions.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace liftremesh {

const char* to_string(Mode mode) { return mode == Mode::Isotropic ? "isotropic" : "anisotropic"; }

Mode parse_mode(const std::string& text) {
    RemeshParams params;
    set_choice_parameter(params, find_parameter("mode"), text);
    return params.mode;
}

RemeshParams RemeshParams::for_mode(Mode mode) {
    RemeshParams p;
    for (const ParameterInfo& row : parameter_table()) set_parameter(p, row, row.default_for(mode));
    p.mode = mode; // the mode row's default is the default mode
    return p;
}

const char* to_string(ParameterKind kind) {
    switch (kind) {
    case ParameterKind::Integer: return "integer";
    case ParameterKind::Real: return "real";
    case ParameterKind::Choice: return "choice";
    case ParameterKind::Flag: return "flag";
    }
    return "?";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A number as the messages and --help show it: integers in full (20000000, not 2e+07).
std::string number_text(double value, ParameterKind kind) {
    std::ostringstream s;
    if (kind == ParameterKind::Integer && std::abs(value) < 1e18)
        s << static_cast<long long>(value);
    else
        s << value;
    return s.str();
}

std::string value_text(const ParameterInfo& row, double value) {
    switch (row.kind) {
    case ParameterKind::Choice: return row.choices.at(static_cast<size_t>(value));
    case ParameterKind::Flag: return value != 0.0 ? "yes" : "no";
    default: break;
    }
    if (!row.replaces.empty() && value == 0.0) return "unset";
    return number_text(value, row.kind);
}

// Builders of the rows below: the kind and the field, then what differs.
struct Row {
    ParameterInfo info;
    Row(std::string name, ParameterKind kind, ParameterField field) {
        info.name = std::move(name);
        info.kind = kind;
        info.field = field;
    }
    Row& range(double min, double max, bool min_open = false, bool max_open = false) {
        info.min = min;
        info.max = max;
        info.min_open = min_open;
        info.max_open = max_open;
        return *this;
    }
    Row& anisotropic(double value) { // the isotropic default is RemeshParams' initializer
        anisotropic_ = value;
        return *this;
    }
    Row& replaces(std::string name) {
        info.replaces = std::move(name);
        return *this;
    }
    Row& choices(std::vector<std::string> words) {
        info.choices = std::move(words);
        return *this;
    }
    Row& spin(int decimals, double step) {
        info.decimals = decimals;
        info.step = step;
        return *this;
    }
    Row& unit(std::string words) {
        info.unit = std::move(words);
        return *this;
    }
    Row& text(std::string metavar, std::string symbol, std::string help) {
        info.metavar = std::move(metavar);
        info.symbol = std::move(symbol);
        info.help = std::move(help);
        return *this;
    }
    Row& words(std::string label, std::string gui_help) {
        info.label = std::move(label);
        info.gui_help = std::move(gui_help);
        return *this;
    }
    std::optional<double> anisotropic_;
};

std::vector<ParameterInfo> build(std::vector<Row> rows) {
    const RemeshParams initial;
    std::vector<ParameterInfo> table;
    for (Row& row : rows) {
        ParameterInfo info = std::move(row.info);
        info.isotropic_default = get_parameter(initial, info);
        info.anisotropic_default = row.anisotropic_.value_or(info.isotropic_default);
        info.default_text = value_text(info, info.isotropic_default);
        if (info.anisotropic_default != info.isotropic_default)
            info.default_text += " (isotropic), " + value_text(info, info.anisotropic_default) + " (anisotropic)";
        table.push_back(std::move(info));
    }
    return table;
}

using K = ParameterKind;
using P = RemeshParams;

} // namespace

const std::vector<ParameterInfo>& parameter_table() {
    static const std::vector<ParameterInfo> table = build({
        Row("vertices", K::Integer, &P::target_vertices)
            .range(4, kMaxVertices)
            .spin(0, 500)
            .text("N", "", "target number of output vertices (sites), 4 to 20000000")
            .words("Vertex count",
                   "How many vertices the new mesh has, 4 to 20000000: more vertices give smaller triangles."),
        Row("edge_length", K::Real, &P::target_edge_length)
            .range(0, kInf, true)
            .replaces("vertices")
            .spin(3, 0.1)
            .unit("length")
            .text("H", "h", "target edge length in input units; replaces --vertices")
            .words("Edge length",
                   "The length the triangle edges aim at, in mm (used instead of the vertex count): smaller gives "
                   "more, smaller triangles."),
        Row("mode", K::Choice, &P::mode)
            .choices({"isotropic", "anisotropic"})
            .text("MODE", "", "isotropic (with local density) or anisotropic; sets nu and delta defaults")
            .words("Mode",
                   "Isotropic: triangles close to equilateral, smaller where the surface bends. Anisotropic: "
                   "triangles stretched along the direction in which the surface bends least, fewer for the same "
                   "accuracy. Choosing a mode sets Density and Lifting to its defaults."),
        Row("sigma", K::Real, &P::sigma)
            .range(1, 100)
            .spin(2, 0.5)
            .text("S", "sigma", "feature sensitivity (>= 1): pulls vertices onto sharp edges and corners")
            .words("Sensitivity",
                   "How strongly vertices are pulled onto sharp edges and corners, 1 to 100: higher keeps edges and "
                   "corners sharper, 1 leaves them rounded."),
        Row("feature_angle", K::Real, &P::feature_angle)
            .range(0, 180, true)
            .spin(1, 5)
            .text("DEG", "", "input edges turning by more than this many degrees are creases the output follows "
                             "(180 = none)")
            .words("Feature angle",
                   "Edges of the part where its faces meet at an angle sharper than this, in degrees, keep a row of "
                   "triangle edges along them and a vertex on every corner where they meet, above 0 to 180: 30 "
                   "keeps the edges of chamfers and steps, 180 leaves sharp edges to Sensitivity alone."),
        Row("hold_creases", K::Flag, &P::hold_creases)
            .text("yes|no", "", "vertices held on the creases over the feature angle and their corners from the start")
            .words("Hold creases",
                   "Put vertices on the part's sharp edges and corners (those the feature angle finds, but edges "
                   "closer together than half an edge length) from the start, so that the triangles along them "
                   "are as well shaped as the others."),
        Row("local_sizing", K::Flag, &P::local_sizing)
            .text("yes|no", "", "smaller edges where the part is thinner than the edge length or bends tightly")
            .words("Local sizing",
                   "Make the triangles smaller where the part is thinner than the edge length (walls, slots, "
                   "small parts) or bends tightly (small holes and fillets), so that they keep their shape."),
        Row("gradation", K::Real, &P::gradation)
            .range(1, 3)
            .spin(2, 0.05)
            .text("G", "", "neighbouring edges of the local sizing differ by at most this factor")
            .words("Growth rate",
                   "How fast the triangles may grow away from a thin or tightly bent place, 1 to 3: each edge at "
                   "most this many times its neighbour's length."),
        Row("min_edge", K::Real, &P::min_edge)
            .range(0, kInf)
            .spin(3, 0.1)
            .unit("length")
            .text("H", "", "smallest edge of the local sizing, in input units (0 = a quarter of the largest)")
            .words("Smallest edge",
                   "The shortest edge local sizing may make, in mm (0: a quarter of the largest)."),
        Row("max_edge", K::Real, &P::max_edge)
            .range(0, kInf)
            .spin(3, 0.1)
            .unit("length")
            .text("H", "", "largest edge, in input units (0 = the edge length or the vertex count's); "
                           "more vertices than asked for if it needs them")
            .words("Largest edge",
                   "The longest edge, in mm (0: the edge length, or what the vertex count gives). The vertex "
                   "count grows if this needs more vertices."),
        Row("delta", K::Real, &P::delta)
            .range(0, 2)
            .anisotropic(0.0) // Section 6.1
            .spin(3, 0.05)
            .text("D", "delta", "exponent of the curvature density rho^delta")
            .words("Density",
                   "How much smaller the triangles get where the surface bends, 0 to 2: 0 gives the same size "
                   "everywhere, higher gives smaller triangles on fillets and holes."),
        Row("nu", K::Real, &P::nu)
            .range(0, 1)
            .anisotropic(0.05) // Section 6.1
            .spin(4, 0.005)
            .unit("unit-ball")
            .text("NU", "nu", "normal lifting scale, in unit-ball units")
            .words("Lifting",
                   "How much the direction of the surface steers the vertices, 0 to 1 (relative to the part's size):"
                   " higher puts vertices closer to sharp edges and follows curved areas more closely, 0 looks at "
                   "positions only."),
        Row("eta", K::Real, &P::eta)
            .range(0, 0.5, true)
            .spin(3, 0.005)
            .unit("unit-ball")
            .text("ETA", "eta", "radius of the neighbourhood for vertex normals, in unit-ball units")
            .words("Normal radius",
                   "How far around each point the direction of the surface is averaged, as a fraction of the part's "
                   "size (above 0, at most 0.5): larger smooths out small bumps and noise, smaller keeps small "
                   "details."),
        Row("iterations", K::Integer, &P::iterations)
            .range(1, 100000)
            .spin(0, 10)
            .text("K", "", "L-BFGS iterations (last 10%, at least 10, with sigma)")
            .words("Iterations",
                   "How many steps move the vertices to better places, 1 to 100000: more give better-shaped "
                   "triangles and take longer."),
        Row("seed", K::Integer, &P::seed)
            .range(0, kInf)
            .text("R", "", "seed of the random initial sampling")
            .words("Seed",
                   "The number that chooses the random starting vertices: the same seed and settings give the same "
                   "mesh."),
        Row("threads", K::Integer, &P::threads)
            .range(0, 1024)
            .text("T", "", "worker threads (0 = all cores); the result does not depend on it")
            .words("Threads",
                   "How many processor cores work on it (0 = all); the mesh is the same whatever the number."),
        Row("fill_holes", K::Flag, &P::fill_holes)
            .text("yes|no", "", "fill the holes of the result that the input does not have")
            .words("Fill new holes",
                   "Close holes that appear in the new mesh where the source has none."),
    });
    return table;
}

const ParameterInfo* parameter_named(const std::string& name) {
    for (const ParameterInfo& row : parameter_table())
        if (row.name == name) return &row;
    return nullptr;
}

const ParameterInfo& find_parameter(const std::string& name) {
    if (const ParameterInfo* row = parameter_named(name)) return *row;
    std::string known;
    for (const ParameterInfo& row : parameter_table()) known += (known.empty() ? "" : ", ") + row.name;
    throw InvalidInput("unknown parameter '" + name + "': expected one of " + known);
}

std::string out_of_range(const ParameterInfo& row, const std::string& value_text) {
    return row.name + " = " + value_text + " is out of range: expected " + row.expected();
}

void set_choice_parameter(RemeshParams& params, const ParameterInfo& row, const std::string& word) {
    const auto it = std::find(row.choices.begin(), row.choices.end(), word);
    if (it == row.choices.end()) throw InvalidInput(row.name + " '" + word + "' is not known: expected " + row.expected());
    set_parameter(params, row, static_cast<double>(it - row.choices.begin()));
}

bool ParameterInfo::in_range(double value) const {
    if (kind != ParameterKind::Integer && kind != ParameterKind::Real) return true;
    if (std::isnan(value) || std::isinf(value)) return false;
    return (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
}

std::string ParameterInfo::expected() const {
    switch (kind) {
    case ParameterKind::Choice: {
        std::string words;
        for (size_t i = 0; i < choices.size(); ++i)
            words += (i == 0 ? "'" : i + 1 == choices.size() ? " or '" : ", '") + choices[i] + "'";
        return words;
    }
    case ParameterKind::Flag: return "yes or no";
    default: break;
    }
    std::string text = kind == ParameterKind::Integer ? "an integer" : "a number";
    const bool low = std::isfinite(min), high = std::isfinite(max);
    if (low && high)
        text += std::string(" in ") + (min_open ? "(" : "[") + number_text(min, kind) + ", " + number_text(max, kind) +
                (max_open ? ")" : "]");
    else if (low)
        text += (min_open ? " > " : " >= ") + number_text(min, kind);
    else if (high)
        text += (max_open ? " < " : " <= ") + number_text(max, kind);
    return text;
}

double get_parameter(const RemeshParams& params, const ParameterInfo& row) {
    return std::visit(
        [&](auto member) {
            if constexpr (std::is_enum_v<std::remove_reference_t<decltype(params.*member)>>)
                return static_cast<double>(static_cast<int>(params.*member));
            else
                return static_cast<double>(params.*member);
        },
        row.field);
}

void set_parameter(RemeshParams& params, const ParameterInfo& row, double value) {
    std::visit(
        [&](auto member) {
            using T = std::remove_reference_t<decltype(params.*member)>;
            if constexpr (std::is_same_v<T, bool>)
                params.*member = value != 0.0;
            else if constexpr (std::is_enum_v<T> || std::is_integral_v<T>)
                params.*member = static_cast<T>(std::llround(value));
            else
                params.*member = value;
        },
        row.field);
}

void set_integer_parameter(RemeshParams& params, const ParameterInfo& row, long long value) {
    std::visit(
        [&](auto member) {
            using T = std::remove_reference_t<decltype(params.*member)>;
            if constexpr (std::is_same_v<T, int>) {
                if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
                    throw InvalidInput(out_of_range(row, std::to_string(value)));
                params.*member = static_cast<int>(value);
            } else if constexpr (std::is_same_v<T, std::uint64_t>) {
                if (value < 0) throw InvalidInput(out_of_range(row, std::to_string(value)));
                params.*member = static_cast<std::uint64_t>(value);
            } else {
                throw std::logic_error("set_integer_parameter: " + row.name + " is not an integer field");
            }
        },
        row.field);
}

void RemeshParams::validate() const {
    for (const ParameterInfo& row : parameter_table()) {
        const double value = get_parameter(*this, row);
        if (!row.replaces.empty() && value == 0.0) continue; // not set
        // A parameter replaced by one that is set is not used.
        bool replaced = false;
        for (const ParameterInfo& other : parameter_table())
            replaced = replaced || (other.replaces == row.name && get_parameter(*this, other) > 0.0);
        if (replaced || row.in_range(value)) continue;
        std::ostringstream shown; // the field's own type: an int as an int
        std::visit(
            [&](auto member) {
                if constexpr (std::is_arithmetic_v<std::remove_reference_t<decltype(this->*member)>>)
                    shown << this->*member;
            },
            row.field);
        const std::string unset = row.replaces.empty() ? "" : " (or 0 to use " + row.replaces + ")";
        throw InvalidInput(out_of_range(row, shown.str()) + unset);
    }
    if (min_edge > 0.0 && max_edge > 0.0 && min_edge > max_edge) {
        std::ostringstream message;
        message << "min_edge = " << min_edge << " is larger than max_edge = " << max_edge
                << ": expected the smallest edge at most the largest";
        throw InvalidInput(message.str());
    }
}

} // namespace liftremesh
