"""The parametric remesh feature: a Mesh::Feature (Mesh::FeaturePython) that remembers its source
and parameters and recomputes when either changes, and the document-level functions that create
such features (one undo step; a failure leaves the document as it was: document.py).
"""
import json

import FreeCAD

from . import document
from . import meshing
from . import parameters

FEATURE_TYPE = "Mesh::FeaturePython"

# Read-only properties that show the last result's quality: name -> (type, path in report, help)
QUALITY_PROPERTIES = {
    "KappaMin": ("App::PropertyFloat", ("output", "kappa_min"), "smallest triangle aspect ratio (Eq. 26, 1 = equilateral)"),
    "KappaMean": ("App::PropertyFloat", ("output", "kappa_mean"), "mean triangle aspect ratio (Eq. 26)"),
    "MinAngle": ("App::PropertyFloat", ("output", "min_angle_deg"), "smallest triangle angle (degrees)"),
    "HausdorffRelative": ("App::PropertyFloat", ("hausdorff_relative",),
                          "two-sided Hausdorff distance to the source / its bounding-box diagonal"),
    "SelfIntersections": ("App::PropertyInteger", ("output", "self_intersections"),
                          "pairs of triangles passing through each other: 0 for a surface to fill with "
                          "tetrahedra (-1: not counted, a result saved before the count)"),
    "Report": ("App::PropertyString", (), "the full quality report (JSON, as the command-line tool writes it)"),
}


# The GUI gives a new feature its view provider through this one hook, set when LiftRemesh.gui is
# imported (gui/__init__.py): App modules never import gui/, as FEM's ObjectsFem attaches its view
# providers only when FreeCAD.GuiUp. Without the GUI (FreeCADCmd) no hook is set.
_view_provider_hook = None


def set_view_provider_hook(hook):
    """Sets the callable hook(view_object) that attaches the view provider of new features."""
    global _view_provider_hook
    _view_provider_hook = hook


def attach_view_provider(obj):
    """Attaches the GUI's view provider to a new feature, when the GUI is up and has set the hook."""
    if FreeCAD.GuiUp and _view_provider_hook is not None and getattr(obj, "ViewObject", None) is not None:
        _view_provider_hook(obj.ViewObject)


def _store(obj, name, value):
    """Stores a parameter in its property, with the property's constraints (the table's range:
    FreeCAD keeps no constraints in the document, they are set again on every store). An unset
    edge length (None) is 0; an unset vertex count (replaced by the edge length) keeps its value."""
    prop, kind, _ = parameters.properties()[name]
    if value is None:
        if name != parameters.size_names()[1]:
            return
        value = 0.0
    if kind in parameters.CONSTRAINT_TYPES:
        row = parameters.row(name)
        low, high, step = parameters.editor_range(row)
        number = int if row["kind"] == "integer" else float
        value = (number(min(max(value, low), high)), number(low), number(high), number(step))
    setattr(obj, prop, value)


class StatelessProxy:
    """Base of the add-on's proxies (feature and view provider): they keep no state of their own
    (everything is in properties), so the document saves nothing for them. FreeCAD 0.20 asks
    __getstate__/__setstate__, 0.21 and later dumps/loads."""

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


class RemeshFeature(StatelessProxy):
    """Proxy of a remeshed mesh: Source (link to a Part shape or a mesh) + parameter properties.
    Its `execute` tessellates the source if it is a shape, remeshes and sets Mesh."""

    def __init__(self, obj, mode="isotropic"):
        obj.Proxy = self
        self.add_properties(obj, mode)

    @staticmethod
    def add_properties(obj, mode="isotropic"):
        """Adds the properties `obj` lacks, with the defaults of `mode`; a parameter stored with
        another property type (an earlier version's App::PropertyInteger or PropertyFloat for a
        constrained one) gets the table's type, keeping its value when it is in range."""
        defaults = parameters.defaults(mode)
        if "Source" not in obj.PropertiesList:
            obj.addProperty("App::PropertyLink", "Source", "Base", "the Part shape or mesh that is remeshed")
        for name, (prop, kind, group) in parameters.properties().items():
            value = defaults[name]
            if prop in obj.PropertiesList:
                if obj.getTypeIdOfProperty(prop) == kind:
                    continue
                value = _stored_value(obj, name, defaults[name])
                obj.removeProperty(prop)
            row = parameters.row(name)
            obj.addProperty(kind, prop, group, row["help"])
            if kind == "App::PropertyEnumeration":
                setattr(obj, prop, list(row["choices"]))
            _store(obj, name, value)
        for prop, (kind, _, doc) in QUALITY_PROPERTIES.items():
            if prop not in obj.PropertiesList:
                obj.addProperty(kind, prop, "Quality", doc)
                obj.setEditorMode(prop, 1)  # read-only
                obj.setPropertyStatus(prop, "Output")  # setting it asks for no recompute

    def onDocumentRestored(self, obj):
        # A document saved by an earlier version lacks the properties added since: they are added
        # and, for a quality figure, read from the stored report (-1 where it lacks the figure too).
        # The constraints of the parameters' properties are not saved: they are set again.
        missing = [prop for prop in QUALITY_PROPERTIES if prop not in obj.PropertiesList]
        touched = "Touched" in obj.State
        self.add_properties(obj, obj.Mode if "Mode" in obj.PropertiesList else "isotropic")
        for name, (prop, kind, _) in parameters.properties().items():
            if kind in parameters.CONSTRAINT_TYPES:
                _store(obj, name, getattr(obj, prop))
        if not touched:
            obj.purgeTouched()  # opening a document asks for no recompute
        try:
            report = json.loads(obj.Report)
        except ValueError:
            report = {}
        for prop in missing:
            kind, path, _ = QUALITY_PROPERTIES[prop]
            if path:
                _set_quality(obj, prop, kind, _lookup(report, path), missing=-1)

    def onChanged(self, obj, prop):
        # A new mode brings its own nu and delta (Section 6.1), as --mode does on the command line.
        properties = parameters.properties()
        if prop != properties[parameters.MODE][0] or "Restore" in obj.State:
            return
        defaults = parameters.defaults(getattr(obj, prop))
        for name in parameters.mode_dependent():
            if properties[name][0] in obj.PropertiesList and getattr(obj, properties[name][0]) != defaults[name]:
                _store(obj, name, defaults[name])

    def execute(self, obj):
        if obj.Source is None:
            raise ValueError("%s has no source to remesh" % obj.Label)
        result = meshing.remesh_source(obj.Source, **params_of(obj))
        apply_result(obj, result)


def params_of(obj):
    """The parameter dict stored in a feature's properties."""
    values = {}
    for name, (prop, kind, _) in parameters.properties().items():
        value = getattr(obj, prop)
        if hasattr(value, "Value"):  # Quantity (Length, Angle)
            value = value.Value
        values[name] = value
    replaced, replacing = parameters.size_names()
    if values[replacing] > 0:
        values[replaced] = None
    else:
        values[replacing] = None
    return values


def _stored_value(obj, name, default):
    """A parameter's value in a property of an earlier version's type, or `default` when it is
    outside the table's range (an earlier Vertices = 0 meant "the default count")."""
    value = getattr(obj, parameters.properties()[name][0])
    value = getattr(value, "Value", value)
    row = parameters.row(name)
    if row["kind"] not in ("integer", "real"):
        return value
    low, high, _ = parameters.editor_range(row)
    if row["replaces"] and value == 0:
        return None
    return value if low <= value <= high else default


def set_params(obj, params):
    """Stores a (resolved) parameter dict in a feature's properties."""
    values = parameters.resolve(params)
    _store(obj, parameters.MODE, values[parameters.MODE])  # first: a new mode resets nu and delta
    for name in parameters.properties():
        if name != parameters.MODE:
            _store(obj, name, values[name])


def apply_result(obj, result):
    """Sets a feature's mesh and quality properties from a Result."""
    obj.Mesh = result.mesh
    for prop, (kind, path, _) in QUALITY_PROPERTIES.items():
        if prop == "Report":
            obj.Report = json.dumps(result.report, indent=2)
        else:
            _set_quality(obj, prop, kind, _lookup(result.report, path), missing=0)


def _lookup(report, path):
    """report[path[0]][path[1]]...; None where a key is missing."""
    value = report
    for key in path:
        if not isinstance(value, dict) or key not in value:
            return None
        value = value[key]
    return value


def _set_quality(obj, prop, kind, value, missing):
    """Sets a quality property to a report figure (`missing` when the report has none)."""
    number = int if kind == "App::PropertyInteger" else float
    setattr(obj, prop, number(missing if value is None else value))


def create_feature(doc, source, params, result=None):
    """Adds a remesh feature for `source` (no transaction of its own). With `result` (computed
    beforehand, e.g. in a worker thread) its mesh is used as it is and the feature is not touched;
    otherwise the feature is computed now. Returns the feature."""
    obj = doc.addObject(FEATURE_TYPE, source.Name + "_Remesh")
    RemeshFeature(obj, params.get(parameters.MODE) or parameters.modes()[0])
    obj.Label = source.Label + " (remeshed)"
    set_params(obj, params)
    obj.Source = source
    attach_view_provider(obj)
    if result is None:
        obj.recompute()
        if not obj.isValid():
            raise RuntimeError("%s could not be computed" % obj.Label)
    else:
        apply_result(obj, result)
        obj.purgeTouched()
    return obj


def check_sources(doc, objects):
    """ValueError unless `objects` is a non-empty list of this document's shapes or meshes."""
    if doc is None:
        raise ValueError("no document")
    if not objects:
        raise ValueError("nothing to remesh: select Part shapes or meshes")
    for obj in objects:
        if obj is None or obj.Document is not doc:
            raise ValueError("%s is not in document %s" % (getattr(obj, "Label", obj), doc.Name))
        if meshing.source_kind(obj) is None:
            raise ValueError("%s is neither a Part shape nor a mesh" % obj.Label)


def remesh_objects(doc, objects, progress=None, **params):
    """Remeshes each of `objects` (Part shapes or meshes of `doc`) into a new parametric
    Mesh::Feature named after it, in one undo step. Everything is computed before the document
    changes, so any failure (bad object, remesh error, Cancelled) leaves it exactly as it was.
    Returns the created features."""
    check_sources(doc, objects)
    parameters.resolve(params)  # bad parameters fail before any work
    results = [meshing.remesh_source(obj, progress=progress, **params) for obj in objects]
    return add_results(doc, objects, params, results)


def add_results(doc, objects, params, results):
    """Adds one feature per (source, precomputed result) in one transaction; returns them."""
    with document.document_change(doc, "Remesh"):
        created = [create_feature(doc, obj, params, result) for obj, result in zip(objects, results)]
        doc.recompute()  # nothing to compute (purged), but leaves the document clean
    return created
