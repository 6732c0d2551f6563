#include "liftremesh/exceptions.h"
#include "liftremesh/params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

using namespace liftremesh;

namespace {
std::string text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// The number of members of an aggregate: the largest N for which T{any, ..., any} (N times)
// compiles. No reflection in C++17; this counts RemeshParams' fields without naming them.
struct AnyValue {
    template <typename U>
    operator U() const;
};
template <typename T, typename... Args>
constexpr auto brace_constructible(int) -> decltype(T{std::declval<Args>()...}, true) {
    return true;
}
template <typename T, typename... Args>
constexpr bool brace_constructible(...) {
    return false;
}
template <typename T, typename... Args>
constexpr size_t field_count() {
    if constexpr (sizeof...(Args) < 64 && brace_constructible<T, Args..., AnyValue>(0))
        return field_count<T, Args..., AnyValue>();
    else
        return sizeof...(Args);
}

bool is_unsigned_field(const ParameterInfo& row) {
    return std::holds_alternative<std::uint64_t RemeshParams::*>(row.field);
}

// Params with one row's field set to `value`; the others default.
RemeshParams with(const ParameterInfo& row, double value) {
    RemeshParams p;
    set_parameter(p, row, value);
    return p;
}

// Just outside a bound, on the side away from the range.
double beyond(const ParameterInfo& row, double bound, double away) {
    return row.kind == ParameterKind::Integer ? bound + away : std::nextafter(bound, away * HUGE_VAL);
}
} // namespace

// The table is the one list of the parameters: every field of RemeshParams has exactly one row.
TEST(Params, EveryFieldHasExactlyOneRow) {
    std::set<std::string> names;
    for (size_t i = 0; i < parameter_table().size(); ++i) {
        const ParameterInfo& row = parameter_table()[i];
        EXPECT_TRUE(names.insert(row.name).second) << "two rows named " << row.name;
        for (size_t j = 0; j < i; ++j)
            EXPECT_FALSE(parameter_table()[j].field == row.field)
                << parameter_table()[j].name << " and " << row.name << " are the same field";
        // The row reads and writes its own field, and no other.
        if (row.kind == ParameterKind::Integer || row.kind == ParameterKind::Real) {
            const double value = std::isfinite(row.max) ? row.max : row.min + 1;
            const RemeshParams p = with(row, value);
            EXPECT_EQ(get_parameter(p, row), value) << row.name;
            for (const ParameterInfo& other : parameter_table()) {
                if (&other == &row) continue;
                EXPECT_EQ(get_parameter(p, other), other.isotropic_default) << row.name << " wrote " << other.name;
            }
        }
    }
    EXPECT_EQ(parameter_table().size(), (field_count<RemeshParams>()))
        << "a RemeshParams field has no row in parameter_table()";
}

// for_mode() takes every default from the table; the isotropic ones are the struct's initializers.
TEST(Params, ForModeGivesTheTableDefaults) {
    const RemeshParams initial;
    for (Mode mode : {Mode::Isotropic, Mode::Anisotropic}) {
        const RemeshParams p = RemeshParams::for_mode(mode);
        EXPECT_EQ(p.mode, mode);
        for (const ParameterInfo& row : parameter_table()) {
            if (row.name == "mode") continue; // for_mode(mode).mode is mode
            EXPECT_EQ(get_parameter(p, row), row.default_for(mode)) << row.name << " " << to_string(mode);
            EXPECT_EQ(get_parameter(initial, row), row.isotropic_default) << row.name;
        }
        EXPECT_NO_THROW(p.validate());
    }
}

// validate() checks every field through its row: the ends of the range are accepted (a closed
// end) or refused (an open one), and a value just beyond each end is refused, naming the field.
TEST(Params, ValidateFollowsEveryRowsRange) {
    int checked = 0;
    for (const ParameterInfo& row : parameter_table()) {
        if (row.kind != ParameterKind::Integer && row.kind != ParameterKind::Real) continue;
        ++checked;
        auto refused = [&](double value) {
            try {
                with(row, value).validate();
            } catch (const InvalidInput& e) {
                EXPECT_EQ(std::string(e.what()).rfind(row.name + " = ", 0), 0u) << e.what();
                EXPECT_NE(std::string(e.what()).find(row.expected()), std::string::npos) << e.what();
                return true;
            }
            return false;
        };
        // A row that replaces another takes 0 for "not set".
        const bool zero_unsets = !row.replaces.empty();
        if (std::isfinite(row.min)) {
            if (row.min_open) {
                EXPECT_TRUE(zero_unsets && row.min == 0 ? !refused(row.min) : refused(row.min)) << row.name;
                EXPECT_FALSE(refused(std::nextafter(row.min, HUGE_VAL))) << row.name;
            } else {
                EXPECT_FALSE(refused(row.min)) << row.name;
            }
            if (!(is_unsigned_field(row) && row.min == 0)) { // -1 does not fit the field
                EXPECT_TRUE(refused(beyond(row, row.min, -1))) << row.name << " below " << row.min;
            }
        }
        if (std::isfinite(row.max)) {
            EXPECT_EQ(refused(row.max), row.max_open) << row.name;
            EXPECT_TRUE(refused(beyond(row, row.max, +1))) << row.name << " above " << row.max;
        } else if (!is_unsigned_field(row)) {
            EXPECT_FALSE(refused(row.kind == ParameterKind::Integer ? 2e9 : 1e300)) << row.name;
        }
        if (row.kind == ParameterKind::Real) {
            EXPECT_TRUE(refused(std::numeric_limits<double>::quiet_NaN())) << row.name;
            EXPECT_TRUE(refused(HUGE_VAL)) << row.name;
        }
    }
    EXPECT_GE(checked, 8);
}

// A set edge length replaces the vertex count, which is then not checked.
TEST(Params, AReplacedParameterIsNotChecked) {
    RemeshParams p;
    p.target_vertices = 0;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.target_edge_length = 0.5;
    EXPECT_NO_THROW(p.validate());
    EXPECT_EQ(find_parameter("edge_length").replaces, "vertices");
    EXPECT_THROW(find_parameter("vertexes"), InvalidInput);
}

// parameter_table() feeds --help and the bindings: its defaults must be the struct's.
TEST(Params, TableDefaultsAreTheStructDefaults) {
    std::map<std::string, std::string> table;
    for (const ParameterInfo& p : parameter_table()) table[p.name] = p.default_text;
    const RemeshParams iso = RemeshParams::for_mode(Mode::Isotropic);
    const RemeshParams aniso = RemeshParams::for_mode(Mode::Anisotropic);
    EXPECT_EQ(table.at("vertices"), std::to_string(iso.target_vertices));
    EXPECT_EQ(table.at("sigma"), text(iso.sigma));
    EXPECT_EQ(table.at("eta"), text(iso.eta));
    EXPECT_EQ(table.at("iterations"), std::to_string(iso.iterations));
    EXPECT_EQ(table.at("seed"), std::to_string(iso.seed));
    EXPECT_EQ(table.at("threads"), std::to_string(iso.threads));
    EXPECT_EQ(table.at("mode"), to_string(RemeshParams().mode));
    EXPECT_EQ(table.at("delta"), text(iso.delta) + " (isotropic), " + text(aniso.delta) + " (anisotropic)");
    EXPECT_EQ(table.at("nu"), text(iso.nu) + " (isotropic), " + text(aniso.nu) + " (anisotropic)");
    EXPECT_EQ(table.at("edge_length"), "unset");
    EXPECT_EQ(table.at("fill_holes"), iso.fill_holes ? "yes" : "no");
    // Section 6.1.
    EXPECT_EQ(iso.sigma, 5.0);
    EXPECT_EQ(iso.nu, 0.01);
    EXPECT_EQ(iso.delta, 0.4);
    EXPECT_EQ(aniso.nu, 0.05);
    EXPECT_EQ(aniso.delta, 0.0);
}

// The GUI's words (issue 34): every row has the name a panel shows and a description in a CAD
// user's words, without the method's terms or the command line's options; a length says mm.
TEST(Params, EveryRowHasPlainWordsForTheGui) {
    for (const ParameterInfo& p : parameter_table()) {
        EXPECT_FALSE(p.label.empty()) << p.name;
        EXPECT_FALSE(p.gui_help.empty()) << p.name;
        for (const char* jargon : {"unit-ball", "rho^", "L-BFGS", "sites", "--", "input units"})
            EXPECT_EQ(p.gui_help.find(jargon), std::string::npos) << p.name << ": " << jargon;
        if (p.unit == "length") EXPECT_NE(p.gui_help.find("mm"), std::string::npos) << p.name;
    }
}

TEST(Params, ValidateNamesTheFieldAndTheRange) {
    RemeshParams p;
    p.delta = 3.0;
    try {
        p.validate();
        FAIL() << "delta = 3 accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("delta = 3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("[0, 2]"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_mode("sideways"), InvalidInput);
    EXPECT_NO_THROW(RemeshParams().validate());
}

TEST(Params, VertexCountIsBoundedBothWays) {
    RemeshParams p;
    for (int bad : {3, kMaxVertices + 1}) {
        p.target_vertices = bad;
        try {
            p.validate();
            FAIL() << "vertices = " << bad << " accepted";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("vertices = " + std::to_string(bad)), std::string::npos) << e.what();
        }
    }
    p.target_vertices = kMaxVertices;
    EXPECT_NO_THROW(p.validate());
}
