// RemeshParams: every knob of the method, with its default, range and the paper's symbol.
// `parameter_table()` lists them, one row each (kind, range, per-mode default, help): the single
// source of truth for validate(), the CLI's options and --help, and for the Python module and
// FreeCAD workbench built on top of the core.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace liftremesh {

//! Isotropic: small nearly lifted surface (nu = 0.01) with density rho^delta (delta = 0.4):
//! well-shaped triangles, smaller where the surface bends (what FEM wants).
//! Anisotropic: stronger lifting (nu = 0.05), no density (delta = 0): triangles stretched along
//! the directions of low curvature (Section 2.5).
enum class Mode { Isotropic, Anisotropic };

//! Most output vertices one remeshing may ask for, by count or by edge length (the memory it
//! needs, about 1.2 kB a vertex, is checked against the machine's too: see memory_budget.h).
constexpr int kMaxVertices = 20'000'000;

const char* to_string(Mode mode);
//! Parses "isotropic" / "anisotropic"; throws InvalidInput naming the value otherwise.
Mode parse_mode(const std::string& text);

struct RemeshParams {
    //! Target number of output vertices (= number of sites). Range [4, kMaxVertices]. Default 6000.
    //! Ignored when target_edge_length > 0.
    int target_vertices = 6000;
    //! Target edge length h in input units; > 0 replaces target_vertices by
    //! round(area / (sqrt(3)/2 h^2)), the vertex count of an equilateral mesh of that edge length.
    //! Default 0 (use target_vertices).
    double target_edge_length = 0.0;
    //! Isotropic or anisotropic defaults for nu and delta (Section 6.1). Default isotropic.
    Mode mode = Mode::Isotropic;
    //! sigma: feature sensitivity, weight of the normal component of the distance (Eq. 9, 14).
    //! Range >= 1 (1 = no feature sensitivity). Default 5 (Section 6.1).
    double sigma = 5.0;
    //! Feature angle in degrees: the input's edges whose two faces turn by more than this are
    //! creases, and the output gets vertices on their corners and edges along them after the
    //! optimisation (crease_snap.h). Range (0, 180]; 180 turns the explicit creases off (the sigma
    //! term still pulls vertices onto sharp edges, as in the paper). Default 30.
    double feature_angle = 30.0;
    //! Sites held on every crease over the feature angle and on its corners through the
    //! optimisation (crease_sites.h), so that they come out as vertices exactly on them with
    //! triangles of CVT shape along them, rather than only moved there afterwards (false: the
    //! crease snap alone, after the triangulation). Default true: a part whose surface they break
    //! is remeshed with its creases snapped to (pipeline.h); on soups of intersecting parts they
    //! cost (docs/known-gaps.md).
    bool hold_creases = true;
    //! Local sizing (size_field.h): smaller edges where the part is thinner than the edge
    //! length or bends tightly, graded and bounded by the three below, through the CVT's density
    //! (times rho^delta). Default false: with a vertex count the sites a thin part takes are
    //! missing elsewhere, and at scale the wall search costs (docs/known-gaps.md).
    bool local_sizing = false;
    //! Gradation g: neighbouring edges of the size field differ by at most this factor. Range
    //! [1, 3]. Default 1.3.
    double gradation = 1.3;
    //! Smallest edge of the size field, in input units; 0 = a quarter of the largest. Default 0.
    double min_edge = 0.0;
    //! Largest edge, in input units; 0 = the edge length (or the vertex count's). With an edge
    //! length or a largest edge the field's sizes are lengths and the vertex count is what they
    //! need (at least the count asked for); with a vertex count alone that count is the budget
    //! and all sizes scale together to meet it. Default 0.
    double max_edge = 0.0;
    //! delta: exponent of the local density rho_p^delta (Eq. 21, 25). Range [0, 2].
    //! Default 0.4 isotropic, 0 anisotropic (Section 6.1).
    double delta = 0.4;
    //! nu: scale of the normal in the 6D lifting x + nu n (Eq. 12), in unit-ball units.
    //! Range [0, 1] (0 = no lifting, remesh in 3D). Default 0.01 isotropic, 0.05 anisotropic.
    double nu = 0.01;
    //! eta: radius of the geometric neighbourhood over which vertex normals are averaged
    //! (Section 5.2.1), in unit-ball units. Range (0, 0.5]. Default 0.02 rather than 0.01: the
    //! wider ball averages over more of a CAD tessellation's slivers, so the normals near them
    //! are smoother (the measurements are in the history: git log -S'eta = 0.02'). A part whose
    //! surface breaks with it is lifted again over smaller balls (pipeline.h).
    double eta = 0.02;
    //! Number of L-BFGS iterations in all. The first 90% use sigma = 1, the rest (at least 10)
    //! use sigma (Section 6.2.2). Range >= 1. Default 100.
    int iterations = 100;
    //! Seed of the random initial sampling: a given seed gives the same result, to the bit, on
    //! any number of threads. Default 1.
    std::uint64_t seed = 1;
    //! Worker threads for every parallel stage (the diagram and objective, normals, refinement,
    //! quality measures); 0 = all cores. The result is the same, to the bit, for any count.
    int threads = 0;
    //! Fill the holes of the restricted Delaunay triangulation that the input does not have
    //! (Section 5.2.2), with vertices added inside the patches (patch_refinement.h). Default true.
    bool fill_holes = true;

    //! The defaults of Section 6.1 for a mode (nu and delta depend on it).
    static RemeshParams for_mode(Mode mode);

    //! Throws InvalidInput naming the field, its value and the accepted range (its table row's).
    void validate() const;
};

//! What a parameter's value is.
enum class ParameterKind {
    Integer, //!< a whole number (int or std::uint64_t field)
    Real,    //!< a finite floating-point number (double field)
    Choice,  //!< one word of `choices` (an enum field; the index is the enum's value)
    Flag     //!< yes or no (bool field)
};
const char* to_string(ParameterKind kind);

//! The RemeshParams member a parameter row reads and writes.
using ParameterField = std::variant<int RemeshParams::*, std::uint64_t RemeshParams::*, double RemeshParams::*,
                                    Mode RemeshParams::*, bool RemeshParams::*>;

//! One row per user-facing parameter: the one list of them. validate(), for_mode(), the CLI's
//! options and --help, the Python module's keywords, defaults() and parameters(), and the FreeCAD
//! properties and task panel are all read from it.
struct ParameterInfo {
    std::string name;    //!< snake_case name (CLI: --name-with-dashes; Python keyword; messages)
    ParameterKind kind = ParameterKind::Real;
    ParameterField field; //!< the member of RemeshParams that holds it
    //! Accepted range of Integer and Real values; +-infinity where a side is unbounded. An open
    //! end is excluded. Choice and Flag rows have no range (the whole line).
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;
    bool max_open = false;
    //! Non-empty: the name of the parameter this one replaces when it is set (> 0). Its value 0
    //! means "not set" and is accepted besides the range; giving both is refused.
    std::string replaces;
    std::vector<std::string> choices; //!< Choice: the accepted words, in the enum's order
    //! Default in each mode (Section 6.1), as a number: a Choice's index, a Flag's 0 or 1. The
    //! isotropic one is the RemeshParams initializer's; for_mode() applies the anisotropic one.
    double isotropic_default = 0.0;
    double anisotropic_default = 0.0;
    int decimals = 0;    //!< Real: digits a spin box shows; an editor keeps 10^-decimals off an open end
    double step = 1.0;   //!< increment of a spin box
    std::string unit;    //!< "length" (input units), "unit-ball" (units of the unit ball), or ""
    std::string metavar; //!< placeholder of the value in usage texts ("N", "SIGMA", ...)
    std::string symbol;  //!< the paper's symbol, or "" if none
    std::string default_text; //!< default as text ("0.4 (isotropic), 0 (anisotropic)")
    std::string help;    //!< one-line meaning (CLI --help, Python; may use the method's words)
    std::string label;   //!< the name a GUI shows ("Edge length"), as the FreeCAD task panel does
    //! What the setting does to the mesh, in words a CAD user knows (lengths in mm, no method
    //! terms): the FreeCAD add-on's tooltips and property descriptions.
    std::string gui_help;

    //! The default of a mode, as a number (see isotropic_default).
    double default_for(Mode mode) const { return mode == Mode::Anisotropic ? anisotropic_default : isotropic_default; }
    //! True when `value` lies in the range (a NaN or an infinity never does).
    bool in_range(double value) const;
    //! The accepted values in words: "an integer in [4, 20000000]", "a number in (0, 0.5]",
    //! "a number > 0", "'isotropic' or 'anisotropic'".
    std::string expected() const;
};

//! Every user-facing parameter, in --help order.
const std::vector<ParameterInfo>& parameter_table();

//! The row of that name, or nullptr.
const ParameterInfo* parameter_named(const std::string& name);

//! The row of that name; throws InvalidInput naming it and listing the known names otherwise.
const ParameterInfo& find_parameter(const std::string& name);

//! The message for a value outside `row`'s range: "NAME = VALUE is out of range: expected ...",
//! with the value as the caller shows it.
std::string out_of_range(const ParameterInfo& row, const std::string& value_text);

//! The field of `row` in `params`, as a number (a Choice's index, a Flag's 0 or 1).
double get_parameter(const RemeshParams& params, const ParameterInfo& row);

//! Sets the field of `row` in `params` from a number (a Choice's index, a Flag's 0 or 1), exactly
//! for integers up to 2^53. No range check: validate() does it.
void set_parameter(RemeshParams& params, const ParameterInfo& row, double value);

//! Sets an Integer field exactly (a seed may exceed 2^53). The value must be >= 0 for an
//! unsigned field and fit an int for an int field: InvalidInput naming the parameter otherwise.
void set_integer_parameter(RemeshParams& params, const ParameterInfo& row, long long value);

//! Sets a Choice field from one of its words; InvalidInput ("NAME 'WORD' is not known: expected
//! ...") for any other word.
void set_choice_parameter(RemeshParams& params, const ParameterInfo& row, const std::string& word);

} // namespace liftremesh
