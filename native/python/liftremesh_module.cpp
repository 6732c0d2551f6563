// The Python module `liftremesh`: the core's remesh() on numpy arrays. The only C++ file that
// includes pybind11. Parameter names, kinds, ranges, defaults and help come from the core's
// parameter_table(), so the CLI, this module and the FreeCAD workbench share one source of truth.
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/components.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/params.h"
#include "liftremesh/pipeline.h"
#include "liftremesh/report.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace liftremesh;

namespace {

// Python exception types, created at import (see PYBIND11_MODULE below).
PyObject* g_error = nullptr;             // liftremesh.Error(RuntimeError): base of all
PyObject* g_invalid_input = nullptr;     // liftremesh.InvalidInput(Error, ValueError)
PyObject* g_numerical_failure = nullptr; // liftremesh.NumericalFailure(Error)
PyObject* g_topology_failure = nullptr;  // liftremesh.TopologyFailure(Error)
PyObject* g_cancelled = nullptr;         // liftremesh.Cancelled(Error)

PyObject* new_exception(py::module_& m, const char* name, PyObject* bases, const char* doc) {
    const std::string qualified = std::string("liftremesh.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
    if (!type) throw py::error_already_set();
    m.attr(name) = py::handle(type); // the module keeps a reference for as long as it lives
    return type;
}

// (n, 3) float64 points: any real dtype is accepted and converted; shape and finiteness checked.
Points to_points(const py::handle& obj) {
    // forcecast would drop the imaginary part of a complex array without a word
    if (const py::array raw = py::array::ensure(obj); raw && raw.dtype().kind() == 'c')
        throw InvalidInput("points must be real numbers, got a complex array");
    // nor would it refuse text ("1.5") or Python objects: numbers only (float, int, unsigned)
    if (const py::array raw = py::array::ensure(obj); raw && std::string("fiu").find(raw.dtype().kind()) == std::string::npos)
        throw InvalidInput("points must be an (n, 3) array of numbers, got dtype " + std::string(py::str(raw.dtype())));
    py::array_t<double, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    } catch (const py::error_already_set&) {
        a = {};
    }
    if (!a) throw InvalidInput("points must be an (n, 3) array of numbers");
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw InvalidInput("points must have shape (n, 3), got " + std::string(py::str(py::tuple(py::cast(
                                                                      std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))));
    Points points(a.shape(0), 3);
    const double* data = a.data();
    for (py::ssize_t i = 0; i < a.shape(0) * 3; ++i) {
        if (!std::isfinite(data[i]))
            throw InvalidInput("points[" + std::to_string(i / 3) + "] has a coordinate that is not finite");
        points.data()[i] = data[i];
    }
    return points;
}

// (m, 3) integer triangles: the dtype must be integral (a float array is refused, not truncated).
Triangles to_triangles(const py::handle& obj, Eigen::Index vertex_count) {
    const py::array raw = py::array::ensure(obj);
    if (!raw) throw InvalidInput("triangles must be an (m, 3) array of integers");
    if (raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
        throw InvalidInput("triangles must have an integer dtype, got " + std::string(py::str(raw.dtype())));
    if (raw.ndim() != 2 || raw.shape(1) != 3)
        throw InvalidInput("triangles must have shape (m, 3), got " + std::string(py::str(py::tuple(py::cast(
                                                                         std::vector<py::ssize_t>(raw.shape(), raw.shape() + raw.ndim()))))));
    const auto a = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(raw);
    Triangles triangles(a.shape(0), 3);
    const long long* data = a.data();
    for (py::ssize_t i = 0; i < a.shape(0) * 3; ++i) {
        if (data[i] < 0 || data[i] >= vertex_count)
            throw InvalidInput("triangles[" + std::to_string(i / 3) + "] refers to vertex " + std::to_string(data[i]) +
                               ", expected an index in [0, " + std::to_string(vertex_count) + ")");
        triangles.data()[i] = static_cast<int32_t>(data[i]);
    }
    return triangles;
}

// A parameter's value as Python sees it: int, float, str (a choice's word), bool; None for a
// parameter that replaces another and is not set (edge_length = 0).
py::object to_python(const ParameterInfo& row, const RemeshParams& params) {
    const double number = get_parameter(params, row);
    if (!row.replaces.empty() && number == 0.0) return py::none();
    if (row.kind == ParameterKind::Choice) return py::str(row.choices.at(static_cast<size_t>(number)));
    return std::visit(
        [&](auto member) -> py::object {
            if constexpr (std::is_enum_v<std::remove_reference_t<decltype(params.*member)>>)
                return py::none(); // a Choice, handled above
            else
                return py::cast(params.*member);
        },
        row.field);
}

// A bound of a range for Python: None where it is unbounded, an int for an Integer row.
py::object bound(const ParameterInfo& row, double value) {
    if (!std::isfinite(value)) return py::none();
    if (row.kind == ParameterKind::Integer) return py::int_(static_cast<long long>(value));
    return py::float_(value);
}

py::dict parameter_defaults(const std::string& mode) {
    const RemeshParams p = RemeshParams::for_mode(parse_mode(mode));
    py::dict d;
    for (const ParameterInfo& row : parameter_table()) d[row.name.c_str()] = to_python(row, p);
    return d;
}

py::list parameter_list() {
    const RemeshParams iso = RemeshParams::for_mode(Mode::Isotropic);
    const RemeshParams aniso = RemeshParams::for_mode(Mode::Anisotropic);
    py::list rows;
    for (const ParameterInfo& info : parameter_table()) {
        py::dict row;
        row["name"] = info.name;
        row["kind"] = to_string(info.kind);
        row["min"] = bound(info, info.min);
        row["max"] = bound(info, info.max);
        row["min_open"] = info.min_open;
        row["max_open"] = info.max_open;
        row["replaces"] = info.replaces.empty() ? py::object(py::none()) : py::object(py::str(info.replaces));
        row["choices"] = info.choices;
        py::dict defaults;
        defaults["isotropic"] = to_python(info, iso);
        defaults["anisotropic"] = to_python(info, aniso);
        row["defaults"] = defaults;
        row["decimals"] = info.decimals;
        row["step"] = info.kind == ParameterKind::Integer ? py::object(py::int_(static_cast<long long>(info.step)))
                                                          : py::object(py::float_(info.step));
        row["unit"] = info.unit;
        row["expected"] = info.expected();
        row["metavar"] = info.metavar;
        row["symbol"] = info.symbol;
        row["default"] = info.default_text;
        row["help"] = info.help;
        row["label"] = info.label;
        row["gui_help"] = info.gui_help;
        rows.append(row);
    }
    return rows;
}

// Sets one keyword argument of remesh() (not None) into `params`, converted as pybind converts a
// typed argument: a TypeError for a value of the wrong type, InvalidInput (ValueError) out of range.
void set_from_python(RemeshParams& params, const ParameterInfo& row, const py::handle& value) {
    if (row.kind == ParameterKind::Choice) {
        set_choice_parameter(params, row, py::cast<std::string>(value));
        return;
    }
    // A number beyond an integer parameter's range (vertices=10**12, or 1e12) is a value out of
    // range, as a smaller one is, not a type the C++ int cannot hold.
    if (row.kind == ParameterKind::Integer && (PyLong_Check(value.ptr()) || PyFloat_Check(value.ptr())) &&
        !PyBool_Check(value.ptr())) {
        const double number = PyFloat_Check(value.ptr()) ? PyFloat_AsDouble(value.ptr()) : PyLong_AsDouble(value.ptr());
        if (PyErr_Occurred()) PyErr_Clear(); // beyond a double: infinite, out of every range
        if (!row.in_range(number)) throw InvalidInput(out_of_range(row, py::str(value).cast<std::string>()));
    }
    std::visit(
        [&](auto member) {
            using T = std::remove_reference_t<decltype(params.*member)>;
            if constexpr (!std::is_enum_v<T>) params.*member = py::cast<T>(value);
        },
        row.field);
    // A given value of a parameter that replaces another must be in range: its 0 means "not set".
    if (!row.replaces.empty() && !row.in_range(get_parameter(params, row))) {
        std::ostringstream shown;
        shown << get_parameter(params, row);
        throw InvalidInput(out_of_range(row, shown.str()));
    }
}

// set_from_python() with a value of the wrong type refused as pybind refuses a typed argument.
void set_keyword(RemeshParams& params, const ParameterInfo& row, const py::handle& value) {
    try {
        set_from_python(params, row, value);
    } catch (const py::cast_error&) {
        if (PyLong_Check(value.ptr()) && !PyBool_Check(value.ptr())) // an integer beyond the C++ type (seed=2**70)
            throw InvalidInput(out_of_range(row, py::str(value).cast<std::string>()));
        throw py::type_error("remesh(): " + row.name + " must be of kind " + to_string(row.kind) + ", got " +
                             std::string(py::str(py::type::handle_of(value).attr("__name__"))));
    }
}

py::tuple remesh_arrays(const py::object& points_in, const py::object& triangles_in, const py::object& progress,
                        const py::kwargs& options) {
    Mesh input;
    input.points = to_points(points_in);
    input.triangles = to_triangles(triangles_in, input.points.rows());

    // The mode first: it sets the defaults of other parameters (nu and delta).
    RemeshParams given_mode;
    std::vector<std::pair<const ParameterInfo*, py::handle>> given;
    for (const auto& [key, value] : options) {
        const std::string name = py::cast<std::string>(key);
        const ParameterInfo* row = parameter_named(name);
        if (row == nullptr) throw py::type_error("remesh() got an unexpected keyword argument '" + name + "'");
        if (value.is_none()) continue; // the default of the mode
        if (std::holds_alternative<Mode RemeshParams::*>(row->field)) set_keyword(given_mode, *row, value);
        given.emplace_back(row, value);
    }
    RemeshParams params = RemeshParams::for_mode(given_mode.mode);
    for (const auto& [row, value] : given) set_keyword(params, *row, value);
    for (const auto& [row, value] : given)
        for (const auto& [other, other_value] : given)
            if (row->replaces == other->name)
                throw InvalidInput("give either " + other->name + " or " + row->name + ", not both");
    params.validate();
    if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw InvalidInput("progress must be callable or None");

    // The callback runs on the calling thread (progress.h) with the GIL re-acquired. It stops the
    // run when it returns False or raises; a raised exception (KeyboardInterrupt included) is
    // re-raised unchanged after the core has unwound.
    std::optional<py::error_already_set> callback_error;
    ProgressCallback callback = [&](const Progress& p) -> bool {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
            callback_error.emplace();
            return false;
        }
        if (progress.is_none()) return true;
        try {
            const py::object answer = progress(p.stage, p.iteration, p.total, p.energy);
            return !(answer.ptr() == Py_False);
        } catch (py::error_already_set& e) {
            callback_error.emplace(std::move(e));
            return false;
        }
    };

    RemeshResult result;
    {
        py::gil_scoped_release release;
        try {
            result = remesh(input, params, callback);
        } catch (const Cancelled&) {
            if (!callback_error) throw;
        }
    }
    if (callback_error) throw std::move(*callback_error);

    const py::object json = py::module_::import("json");
    py::dict report = json.attr("loads")(to_json(result.report));
    py::array_t<double> points_out({result.mesh.points.rows(), Eigen::Index(3)});
    std::copy(result.mesh.points.data(), result.mesh.points.data() + result.mesh.points.size(),
              points_out.mutable_data());
    py::array_t<int32_t> triangles_out({result.mesh.triangles.rows(), Eigen::Index(3)});
    std::copy(result.mesh.triangles.data(), result.mesh.triangles.data() + result.mesh.triangles.size(),
              triangles_out.mutable_data());
    return py::make_tuple(points_out, triangles_out, report);
}

// The pairs of triangles that pass through each other (spatial/self_intersection), as an (k, 2)
// int32 array: what a tetrahedral mesher refuses in a surface it is to fill.
py::array_t<int32_t> crossing_triangles(const py::object& points_in, const py::object& triangles_in) {
    Mesh mesh;
    mesh.points = to_points(points_in);
    mesh.triangles = to_triangles(triangles_in, mesh.points.rows());
    std::vector<std::pair<int32_t, int32_t>> pairs;
    {
        py::gil_scoped_release release;
        pairs = self_intersecting_pairs(mesh, AabbTree(mesh));
    }
    py::array_t<int32_t> out({static_cast<py::ssize_t>(pairs.size()), py::ssize_t(2)});
    for (size_t k = 0; k < pairs.size(); ++k) {
        out.mutable_at(k, 0) = pairs[k].first;
        out.mutable_at(k, 1) = pairs[k].second;
    }
    return out;
}

// The connected components of a surface (mesh/components.h) as a dict of arrays, one entry per
// component, and the component of each triangle.
py::dict components(const py::object& points_in, const py::object& triangles_in) {
    Mesh mesh;
    mesh.points = to_points(points_in);
    mesh.triangles = to_triangles(triangles_in, mesh.points.rows());
    MeshComponents split;
    {
        py::gil_scoped_release release;
        split = mesh_components(mesh);
    }
    const auto k = static_cast<py::ssize_t>(split.components.size());
    py::array_t<bool> closed(k), cavity(k);
    py::array_t<double> volume(k), area(k);
    py::array_t<int64_t> count(k);
    for (py::ssize_t c = 0; c < k; ++c) {
        const MeshComponent& part = split.components[static_cast<size_t>(c)];
        closed.mutable_at(c) = part.closed;
        cavity.mutable_at(c) = part.cavity;
        volume.mutable_at(c) = part.closed ? part.signed_volume : std::nan("");
        area.mutable_at(c) = part.area;
        count.mutable_at(c) = part.triangles;
    }
    py::array_t<int32_t> label(static_cast<py::ssize_t>(split.label.size()));
    std::copy(split.label.begin(), split.label.end(), label.mutable_data());
    py::dict out;
    out["closed"] = closed;
    out["signed_volume"] = volume;
    out["cavity"] = cavity;
    out["area"] = area;
    out["triangles"] = count;
    out["label"] = label;
    return out;
}

// The closest point of a reference surface to each point, as an (n, 3) float64 array; on its
// triangle's rim when within `rim` of it (onto_triangle_rim_within).
py::array_t<double> closest_points(const py::object& points_in, const py::object& surface_points_in,
                                   const py::object& surface_triangles_in, double rim) {
    if (!(rim >= 0.0) || !std::isfinite(rim)) throw InvalidInput("closest_points: rim must be >= 0 and finite");
    const Points points = to_points(points_in);
    Mesh surface;
    surface.points = to_points(surface_points_in);
    surface.triangles = to_triangles(surface_triangles_in, surface.points.rows());
    if (surface.triangles.rows() == 0) throw InvalidInput("the surface to project onto has no triangle");
    py::array_t<double> out({points.rows(), Eigen::Index(3)});
    double* data = out.mutable_data();
    {
        py::gil_scoped_release release;
        const AabbTree tree(surface);
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            const Eigen::Vector3d q = points.row(i).transpose();
            const ClosestPoint closest = tree.closest(q);
            const Eigen::Vector3d c = rim > 0.0 ? onto_triangle_rim_within(closest.point, corner(surface, closest.triangle, 0),
                                                                           corner(surface, closest.triangle, 1),
                                                                           corner(surface, closest.triangle, 2), rim)
                                                : closest.point;
            for (int k = 0; k < 3; ++k) data[3 * i + k] = c[k];
        }
    }
    return out;
}

} // namespace

PYBIND11_MODULE(liftremesh, m) {
    m.doc() = "LiftRemesh: feature-sensitive isotropic and anisotropic remeshing of triangle surfaces "
              "(centroidal Voronoi tessellation on the normal-lifted surface).";
    m.attr("__version__") = LIFTREMESH_VERSION;

    g_error = new_exception(m, "Error", PyExc_RuntimeError, "Base of every error LiftRemesh raises.");
    const py::tuple invalid_bases = py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError));
    g_invalid_input = new_exception(m, "InvalidInput", invalid_bases.ptr(),
                                    "Bad arrays, mesh or parameters (also a ValueError).");
    g_numerical_failure = new_exception(m, "NumericalFailure", g_error, "The computation produced non-finite values.");
    g_topology_failure = new_exception(m, "TopologyFailure", g_error, "The output could not be made a valid surface.");
    g_cancelled = new_exception(m, "Cancelled", g_error, "The progress callback asked to stop; nothing is returned.");

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InvalidInput& e) {
            PyErr_SetString(g_invalid_input, e.what());
        } catch (const NumericalFailure& e) {
            PyErr_SetString(g_numerical_failure, e.what());
        } catch (const TopologyFailure& e) {
            PyErr_SetString(g_topology_failure, e.what());
        } catch (const Cancelled& e) {
            PyErr_SetString(g_cancelled, e.what());
        } catch (const Error& e) {
            PyErr_SetString(g_error, e.what());
        }
    });

    m.def("remesh", &remesh_arrays, py::arg("points"), py::arg("triangles"), py::kw_only(),
          py::arg("progress") = py::none(),
          R"doc(Remesh a triangle surface.

points: (n, 3) float64 array of vertex positions.
triangles: (m, 3) integer array of vertex indices (a soup is fine: exactly equal vertices are welded).
Every parameter of parameters() by keyword (None = the default of the mode, see defaults(mode)):
vertices / edge_length: target size (one of them; default: defaults()['vertices']).
mode: "isotropic" (with local density) or "anisotropic"; sets the defaults of nu and delta.
sigma, feature_angle, delta, nu, eta, iterations, seed, threads, fill_holes: see parameters().
progress: None or a callable (stage, iteration, total, energy); returning False cancels, which
raises liftremesh.Cancelled.

Returns (points, triangles, report): (N, 3) float64, (M, 3) int32, and a dict with the same
fields as the command-line tool's JSON report. The GIL is released while it runs.
Raises InvalidInput (a ValueError) for bad arrays or parameters, Cancelled, NumericalFailure,
TopologyFailure (all subclasses of liftremesh.Error).)doc");
    m.def("crossing_triangles", &crossing_triangles, py::arg("points"), py::arg("triangles"),
          R"doc(Pairs of triangles that pass through each other: a side of one through the inside of the
other (touching and coplanar overlaps are not crossing), as a tetrahedral mesher refuses them.

points: (n, 3) float64 array; triangles: (m, 3) integer array of vertex indices.
Returns a (k, 2) int32 array of triangle indices (s, t), s < t, sorted; empty when none cross.
Raises InvalidInput (a ValueError) for bad arrays. The GIL is released while it runs.)doc");
    m.def("components", &components, py::arg("points"), py::arg("triangles"),
          R"doc(The connected components of a triangle surface (triangles joined through edges used by
exactly two triangles), measured as a
solid's boundary: the report's "components" of input and output.

points: (n, 3) float64 array; triangles: (m, 3) integer array of vertex indices.
Returns a dict of arrays with one entry per component, in order of first triangle:
"closed" (k,) bool (no edge used by one triangle only); "signed_volume" (k,) float64, the volume
enclosed by a closed one, negative when it faces inward, NaN for an open one; "cavity" (k,) bool,
facing inward and inside the other closed components (a hollowed solid's inner wall); "area" (k,)
float64; "triangles" (k,) int64; and "label" (m,) int32, each triangle's component.
Raises InvalidInput (a ValueError) for bad arrays. The GIL is released while it runs.)doc");
    m.def("closest_points", &closest_points, py::arg("points"), py::arg("surface_points"),
          py::arg("surface_triangles"), py::arg("rim") = 0.0,
          R"doc(The closest point of a triangle surface to each of `points`.

points: (n, 3) float64; surface_points: (k, 3) float64; surface_triangles: (m, 3) integer, m > 0.
rim: a closest point within this distance of its triangle's corner or edge is put on it (the
corner first), so that a point a rounding off a crease between two planar facets lies on both
planes; 0 (the default) leaves it. Returns an (n, 3) float64 array. Raises InvalidInput (a
ValueError) for bad arrays or a negative rim. The GIL is released while it runs.)doc");
    m.def("defaults", &parameter_defaults, py::arg("mode") = "isotropic",
          "The default value of every parameter of remesh() for a mode, as a dict.");
    m.def("parameters", &parameter_list,
          "One dict per parameter of remesh(), in the core's table: name, kind ('integer', 'real', "
          "'choice', 'flag'), min and max (None: unbounded), min_open and max_open (the end excluded), "
          "replaces (the parameter a set value replaces, 0 meaning unset; or None), choices, defaults "
          "({'isotropic': v, 'anisotropic': v}), decimals and step (for spin boxes), unit ('length', "
          "'unit-ball' or ''), expected (the accepted values in words), metavar, symbol (the paper's), "
          "default (as text), help, label (the name a GUI shows) and gui_help (what it does to the mesh, in "
          "a CAD user's words, lengths in mm).");
}
