"""The remesh parameters as the add-on sees them: the rows of the C++ core's parameter table
(liftremesh.parameters(): name, kind, range, per-mode defaults, help; the one source of truth shared
with the command-line tool) plus the two rows of the tessellation used when the source is a Part
shape, which are not core parameters.

A parameter set is a plain dict {name: value}; `resolve()` fills in defaults and refuses unknown
names. `properties()` maps each name to the property a parametric feature stores it in, and
`editor_range()` gives the bounds its property and its spin box accept.
"""
import functools
import math

from . import native

# Tessellation of Part shapes, as FreeCAD's STL export does it (MeshPart.meshFromShape with an
# absolute linear deflection and an angular deflection): Preferences > Import-Export > Mesh formats
# defaults to 0.1 mm and 30 degrees. Rows shaped as liftremesh.parameters() gives them.
TESSELLATION = (
    {"name": "linear_deflection", "kind": "real", "min": 0.0, "max": None, "min_open": True, "max_open": False,
     "replaces": None, "choices": [], "defaults": {"isotropic": 0.1, "anisotropic": 0.1}, "decimals": 3,
     "step": 0.01, "unit": "length",
     "help": "tessellation of Part shapes: largest distance of the STL from the shape (mm)",
     "label": "Deviation",
     "gui_help": "Part shapes are first cut into triangles as the STL export does: the largest distance, "
                 "in mm, of those triangles from the shape. Smaller follows curved faces more closely."},
    {"name": "angular_deflection", "kind": "real", "min": 0.0, "max": None, "min_open": True, "max_open": False,
     "replaces": None, "choices": [], "defaults": {"isotropic": 30.0, "anisotropic": 30.0}, "decimals": 1,
     "step": 1.0, "unit": "angle",
     "help": "tessellation of Part shapes: largest angle between neighbouring facets (degrees)",
     "label": "Angle",
     "gui_help": "Part shapes are first cut into triangles as the STL export does: the largest angle, in "
                 "degrees, between neighbouring triangles. Smaller follows curved faces more closely."},
)
TESSELLATION_DEFAULTS = {row["name"]: row["defaults"]["isotropic"] for row in TESSELLATION}
MODE = "mode"  # the parameter whose value selects the defaults of the others

# What a Qt spin box and FreeCAD's constraint properties hold: an int, and a bound for the unbounded.
INT_LIMITS = (-2 ** 31, 2 ** 31 - 1)
REAL_LIMIT = 1e9

# A row's property: by kind, and for a real by its unit (a Length or an Angle has its own editor).
PROPERTY_TYPES = {"integer": "App::PropertyIntegerConstraint", "real": "App::PropertyFloatConstraint",
                  "choice": "App::PropertyEnumeration", "flag": "App::PropertyBool"}
UNIT_PROPERTY_TYPES = {"length": "App::PropertyLength", "angle": "App::PropertyAngle"}
CONSTRAINT_TYPES = ("App::PropertyIntegerConstraint", "App::PropertyFloatConstraint")


@functools.lru_cache(maxsize=None)
def rows():
    """Every parameter's row: the module's table, then the tessellation's. A tuple of dicts."""
    return tuple(native.load().parameters()) + TESSELLATION


def row(name):
    """The row of one parameter; KeyError for an unknown name."""
    for r in rows():
        if r["name"] == name:
            return r
    raise KeyError(name)


def modes():
    """The modes, in the table's order ("isotropic", "anisotropic")."""
    return tuple(row(MODE)["choices"])


def mode_dependent():
    """The names of the parameters whose default depends on the mode (nu and delta)."""
    return tuple(r["name"] for r in rows()
                 if r["name"] != MODE and len({repr(v) for v in r["defaults"].values()}) > 1)


def size_names():
    """(replaced, replacing): the two parameters of the target size, ("vertices", "edge_length")."""
    [replacing] = [r for r in rows() if r["replaces"]]
    return replacing["replaces"], replacing["name"]


def property_name(name):
    """The property of a parameter: its name in CamelCase (edge_length -> EdgeLength)."""
    return "".join(word.capitalize() for word in name.split("_"))


def properties():
    """name -> (property name, property type, group), for every row."""
    size = size_names()
    tessellation = {r["name"] for r in TESSELLATION}
    result = {}
    for r in rows():
        kind = UNIT_PROPERTY_TYPES.get(r["unit"]) if r["kind"] == "real" else None
        group = "Tessellation" if r["name"] in tessellation else "Size" if r["name"] in size else "Method"
        result[r["name"]] = (property_name(r["name"]), kind or PROPERTY_TYPES[r["kind"]], group)
    return result


def editor_range(r):
    """(lowest, highest, step) an editor (a spin box, a constraint property) accepts for a number
    row: its range, an open end moved in by one unit of its last shown digit, an unbounded side by
    what the editor can hold."""
    if r["kind"] == "integer":
        unit, (low, high) = 1, INT_LIMITS
    else:
        unit, (low, high) = 10.0 ** -r["decimals"], (-REAL_LIMIT, REAL_LIMIT)
    if r["min"] is not None:
        low = max(low, r["min"] + (unit if r["min_open"] else 0))
    if r["max"] is not None:
        high = min(high, r["max"] - (unit if r["max_open"] else 0))
    return low, high, r["step"]


def label(name):
    """The name a user sees for a parameter ("Edge length"), as the task panel shows it."""
    return row(name).get("label") or name


def gui_help(name):
    """What a parameter does to the mesh, in a CAD user's words (tooltips, property docs)."""
    r = row(name)
    return r.get("gui_help") or r["help"]


UNIT_SUFFIX = {"length": " mm", "angle": "\u00b0"}


def value_text(name, value):
    """A value as the panel shows it, with its unit: "0.001 mm", "30\u00b0", "3"."""
    r = row(name)
    return "%s%s" % ("%g" % value if isinstance(value, float) else value, UNIT_SUFFIX.get(r["unit"], ""))


def clamp(name, value):
    """`value` moved into the range the editors of that number parameter accept (editor_range)."""
    r = row(name)
    low, high, _ = editor_range(r)
    value = min(max(value, low), high)
    return int(round(value)) if r["kind"] == "integer" else float(value)


def edge_length_for(area, vertices):
    """The edge length of an ideal mesh with `vertices` vertices on `area` (equilateral triangles,
    about 2 per vertex; the core's target_site_count() inverted): 0 when either is not positive."""
    if area <= 0 or vertices <= 0:
        return 0.0
    return math.sqrt(2.0 * area / (math.sqrt(3.0) * vertices))


def vertices_for(area, edge_length):
    """The inverse of edge_length_for(): the vertex count an edge length gives on `area`."""
    if area <= 0 or edge_length <= 0:
        return 0
    return int(round(2.0 * area / (math.sqrt(3.0) * edge_length ** 2)))


def check(values, area=None):
    """ValueError naming the first setting of a resolved parameter dict that is out of range, as
    the panel names it and with its unit ("Edge length 0.001 mm gives ... vertices ..."). With the
    source's `area` (mm^2), also an edge length giving too few or too many vertices. The core checks
    again when it runs; this one speaks the user's words."""
    for r in rows():
        value = values.get(r["name"])
        if r["kind"] not in ("integer", "real") or value is None or (r["replaces"] and value == 0):
            continue
        low, high = r["min"], r["max"]
        below = low is not None and (value <= low if r["min_open"] else value < low)
        above = high is not None and (value >= high if r["max_open"] else value > high)
        if below or above:
            raise ValueError("%s %s is out of range: expected %s%s" % (
                label(r["name"]), value_text(r["name"], value), r.get("expected") or "a number > 0",
                UNIT_SUFFIX.get(r["unit"], "")))
    replaced, replacing = size_names()
    length = values.get(replacing)
    if area and length:
        count = vertices_for(area, length)
        low, high, _ = editor_range(row(replaced))
        if not low <= count <= high:
            raise ValueError(
                "%s %s gives %d vertices on this surface of %.4g mm\u00b2: expected an edge length giving "
                "%d to %d vertices (%s to %s)" % (
                    label(replacing), value_text(replacing, length), count, area, low, high,
                    value_text(replacing, float("%.3g" % edge_length_for(area, high))),
                    value_text(replacing, float("%.3g" % edge_length_for(area, low)))))


def defaults(mode="isotropic"):
    """Every parameter's default for a mode: the module's, then the tessellation's."""
    values = dict(native.load().defaults(mode))
    values.update(TESSELLATION_DEFAULTS)
    return values


def resolve(params):
    """A complete parameter dict: `params` over the defaults of its mode.

    Unknown names raise ValueError listing the known ones. A given `edge_length` replaces the
    default vertex count (give one of the two). Values are checked by the module when it runs.
    """
    params = dict(params)
    known = set(defaults())
    unknown = sorted(set(params) - known)
    if unknown:
        raise ValueError("unknown parameter%s %s; known: %s"
                         % ("s" if len(unknown) > 1 else "", ", ".join(map(repr, unknown)), ", ".join(sorted(known))))
    mode = params.get(MODE) or modes()[0]
    if mode not in modes():
        raise ValueError("mode %r is not known: expected %s" % (mode, " or ".join(map(repr, modes()))))
    replaced, replacing = size_names()
    if not params.get(replacing):
        params.pop(replacing, None)  # 0 (a feature's unset length) or None: use the vertex count
    values = defaults(mode)
    if params.get(replacing):
        values[replaced] = None
    values.update({k: v for k, v in params.items() if v is not None})
    if values.get(replacing) is not None and values.get(replaced) is not None:
        raise ValueError("give either %s or %s, not both" % (replaced, replacing))
    for r in TESSELLATION:
        if not values[r["name"]] > 0:
            raise ValueError("%s = %r is out of range: expected a number > 0" % (r["name"], values[r["name"]]))
    return values


def module_arguments(values):
    """The keyword arguments of liftremesh.remesh() among a resolved parameter dict."""
    return {k: v for k, v in values.items() if k not in TESSELLATION_DEFAULTS}
