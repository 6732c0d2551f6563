"""The remesh parameters as the add-on sees them: the module's own (names, defaults, help, from the
C++ core's parameter table, the one source of truth shared with the CLI) plus the tessellation
deflections used when the source is a Part shape.

A parameter set is a plain dict {name: value}; `resolve()` fills in defaults and refuses unknown
names. `PROPERTIES` maps each name to the property a parametric feature stores it in.
"""
from . import native

# Tessellation of Part shapes, as FreeCAD's STL export does it (MeshPart.meshFromShape with an
# absolute linear deflection and an angular deflection): Preferences > Import-Export > Mesh formats
# defaults to 0.1 mm and 30 degrees.
TESSELLATION_DEFAULTS = {"linear_deflection": 0.1, "angular_deflection": 30.0}
TESSELLATION_HELP = {
    "linear_deflection": "tessellation of Part shapes: largest distance of the STL from the shape (mm)",
    "angular_deflection": "tessellation of Part shapes: largest angle between neighbouring facets (degrees)",
}
MODES = ("isotropic", "anisotropic")

# name -> (property name, property type, group)
PROPERTIES = {
    "vertices": ("Vertices", "App::PropertyInteger", "Size"),
    "edge_length": ("EdgeLength", "App::PropertyLength", "Size"),
    "mode": ("Mode", "App::PropertyEnumeration", "Method"),
    "sigma": ("Sigma", "App::PropertyFloat", "Method"),
    "delta": ("Delta", "App::PropertyFloat", "Method"),
    "nu": ("Nu", "App::PropertyFloat", "Method"),
    "eta": ("Eta", "App::PropertyFloat", "Method"),
    "iterations": ("Iterations", "App::PropertyInteger", "Method"),
    "seed": ("Seed", "App::PropertyInteger", "Method"),
    "threads": ("Threads", "App::PropertyInteger", "Method"),
    "fill_holes": ("FillHoles", "App::PropertyBool", "Method"),
    "linear_deflection": ("LinearDeflection", "App::PropertyLength", "Tessellation"),
    "angular_deflection": ("AngularDeflection", "App::PropertyAngle", "Tessellation"),
}


def defaults(mode="isotropic"):
    """Every parameter's default for a mode: the module's, then the tessellation's."""
    values = dict(native.load().defaults(mode))
    values.update(TESSELLATION_DEFAULTS)
    return values


def help_texts():
    """name -> one-line help, for tooltips."""
    texts = {row["name"]: row["help"] for row in native.load().parameters()}
    texts.setdefault("fill_holes", "fill the holes of the result that the input does not have")
    texts.update(TESSELLATION_HELP)
    return texts


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
    mode = params.get("mode") or "isotropic"
    if mode not in MODES:
        raise ValueError("mode %r is not known: expected %s" % (mode, " or ".join(map(repr, MODES))))
    if not params.get("edge_length"):
        params.pop("edge_length", None)  # 0 (a feature's unset length) or None: use the vertex count
    values = defaults(mode)
    if params.get("edge_length"):
        values["vertices"] = None
    values.update({k: v for k, v in params.items() if v is not None})
    if values.get("edge_length") is not None and values.get("vertices") is not None:
        raise ValueError("give either vertices or edge_length, not both")
    for name in TESSELLATION_DEFAULTS:
        if not values[name] > 0:
            raise ValueError("%s = %r is out of range: expected a number > 0" % (name, values[name]))
    return values


def module_arguments(values):
    """The keyword arguments of liftremesh.remesh() among a resolved parameter dict."""
    return {k: v for k, v in values.items() if k not in TESSELLATION_DEFAULTS}
