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

def _relative(report):
    return report.get("hausdorff_relative")


def _scaled(report, factor):
    """hausdorff_relative * factor (a number, or the report's bbox_diagonal), None when missing."""
    relative = report.get("hausdorff_relative")
    if isinstance(factor, str):
        factor = report.get(factor)
    return None if relative is None or factor is None else relative * factor


# Read-only properties that show the last result's quality: name -> (type, value from the report
# (None when the report lacks it), help, editor mode: 1 read-only, 2 hidden). HausdorffRelative and
# Report stay for macros and in the file, hidden: the editor shows a float with 2 decimals (0.0028
# as 0.00) and a many-line JSON text as hundreds of rows.
QUALITY_PROPERTIES = {
    "KappaMin": ("App::PropertyFloat", lambda r: _lookup(r, ("output", "kappa_min")),
                 "how well shaped the worst triangle is: 1 for an equilateral triangle, near 0 for a sliver", 1),
    "KappaMean": ("App::PropertyFloat", lambda r: _lookup(r, ("output", "kappa_mean")),
                  "how well shaped the triangles are on average: 1 for equilateral triangles", 1),
    "MinAngle": ("App::PropertyFloat", lambda r: _lookup(r, ("output", "min_angle_deg")),
                 "smallest angle of any triangle (degrees)", 1),
    "HausdorffDistance": ("App::PropertyLength", lambda r: _scaled(r, "bbox_diagonal"),
                          "largest distance between the new mesh and the source (mm)", 1),
    "HausdorffPercent": ("App::PropertyFloat", lambda r: _scaled(r, 100.0),
                         "largest distance between the new mesh and the source, in percent of the "
                         "source's bounding-box diagonal", 1),
    "HausdorffRelative": ("App::PropertyFloat", _relative,
                          "two-sided Hausdorff distance to the source / its bounding-box diagonal", 2),
    "SelfIntersections": ("App::PropertyInteger", lambda r: _lookup(r, ("output", "self_intersections")),
                          "pairs of triangles passing through each other or touching: 0 for a surface to fill with "
                          "tetrahedra (-1: not counted, a result saved before the count)", 1),
    "Report": ("App::PropertyString", None, "the full quality report (JSON, as the command-line tool writes it)", 2),
}
# Parameters whose default changed, with what a document saved before their property existed
# was remeshed with: restored so, it recomputes as it did (the creases held by default since
# issue 35's sites held on them became the default).
EARLIER_DEFAULTS = {"hold_creases": False}
SIZE_BY = "SizeBy"  # which of the two target sizes is used (an enumeration of their labels)
_adding = set()  # _key() of the features whose SizeBy is being added: its first values convert nothing


def _key(obj):
    """A feature's identity across Python wrappers: (document name, object name)."""
    return obj.Document.Name, obj.Name


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


# In the GUI the remesh of a recompute runs with a progress dialog and Cancel (gui/recompute.py sets
# this hook: hook(obj, params) -> meshing.Result, or None when it failed or was cancelled, which the
# hook has said in one line). Either way the recompute has its result before execute() returns, as
# without the GUI: dependent objects recompute on the new mesh and a macro sees it. A feature
# without a mesh yet (being created) has none to keep: its errors are raised (create_feature).
_recompute_hook = None


def set_recompute_hook(hook):
    """Sets the callable hook(feature, params) that remeshes a feature's source in the GUI."""
    global _recompute_hook
    _recompute_hook = hook


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


def size_choices():
    """The SizeBy choices: the labels of the two target sizes ("Vertex count", "Edge length")."""
    return [parameters.label(name) for name in parameters.size_names()]


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
        constrained one) gets the table's type, keeping its value when it is in range. Sets the
        descriptions and editor modes (not all of them are saved)."""
        defaults = parameters.defaults(mode)
        if "Source" not in obj.PropertiesList:
            obj.addProperty("App::PropertyLink", "Source", "Base", "the Part shape or mesh that is remeshed")
        for name, (prop, kind, group) in parameters.properties().items():
            value = defaults[name]
            if prop in obj.PropertiesList:
                if obj.getTypeIdOfProperty(prop) == kind:
                    _describe(obj, prop, parameters.gui_help(name))
                    continue
                value = _stored_value(obj, name, defaults[name])
                obj.removeProperty(prop)
            row = parameters.row(name)
            obj.addProperty(kind, prop, group, parameters.gui_help(name))
            if kind == "App::PropertyEnumeration":
                setattr(obj, prop, list(row["choices"]))
            _store(obj, name, value)
        if SIZE_BY not in obj.PropertiesList:
            # "EdgeLength 0 mm" meant "not set": the choice is said instead (as FreeCAD's Pad says
            # Type = Length / Up to face), and only the size in use is shown.
            by_length = getattr(obj, parameters.properties()[parameters.size_names()[1]][0]).Value > 0
            obj.addProperty("App::PropertyEnumeration", SIZE_BY, "Size",
                            "which target size sets how fine the mesh is: the vertex count, or the edge length (mm)")
            _adding.add(_key(obj))  # the stored sizes stay as they are (see onChanged)
            try:
                setattr(obj, SIZE_BY, size_choices())
                setattr(obj, SIZE_BY, size_choices()[1 if by_length else 0])
            finally:
                _adding.discard(_key(obj))
        _show_size(obj)
        for prop, (kind, _, doc, mode_) in QUALITY_PROPERTIES.items():
            if prop not in obj.PropertiesList:
                obj.addProperty(kind, prop, "Quality", doc)
                obj.setPropertyStatus(prop, "Output")  # setting it asks for no recompute
            _describe(obj, prop, doc)
            obj.setEditorMode(prop, mode_)

    def onDocumentRestored(self, obj):
        # A document saved by an earlier version lacks the properties added since: they are added
        # and, for a quality figure, read from the stored report (-1 where it lacks the figure too).
        # The constraints of the parameters' properties and the editor modes are not saved: they
        # are set again.
        missing = [prop for prop in QUALITY_PROPERTIES if prop not in obj.PropertiesList]
        earlier = [name for name in EARLIER_DEFAULTS if parameters.properties()[name][0] not in obj.PropertiesList]
        touched = "Touched" in obj.State
        self.add_properties(obj, obj.Mode if "Mode" in obj.PropertiesList else "isotropic")
        for name in earlier:  # a recompute gives what the version that saved it gave
            _store(obj, name, EARLIER_DEFAULTS[name])
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
            kind, value_of, _, _ = QUALITY_PROPERTIES[prop]
            if value_of is not None:
                _set_quality(obj, prop, kind, value_of(report), missing=-1)

    def onChanged(self, obj, prop):
        if "Restore" in obj.State:
            return
        properties = parameters.properties()
        if prop == SIZE_BY:
            if _key(obj) not in _adding:
                _size_by_changed(obj)
            return
        # A new mode brings its own nu and delta (Section 6.1), as --mode does on the command line.
        if prop != properties[parameters.MODE][0]:
            return
        defaults = parameters.defaults(getattr(obj, prop))
        for name in parameters.mode_dependent():
            if properties[name][0] in obj.PropertiesList and getattr(obj, properties[name][0]) != defaults[name]:
                _store(obj, name, defaults[name])

    def execute(self, obj):
        if obj.Source is None:
            raise ValueError("%s has no source to remesh" % obj.Label)
        params = params_of(obj)
        if _recompute_hook is not None and FreeCAD.GuiUp and obj.Mesh.CountFacets:
            result = _recompute_hook(obj, params)
            if result is None:
                return  # failed or cancelled: the previous mesh stays (the hook said why)
        else:
            result = meshing.remesh_source(obj.Source, **params)
        apply_result(obj, result)


def _describe(obj, prop, text):
    """Sets a property's description (a document saved earlier keeps the words of its version)."""
    if hasattr(obj, "setDocumentationOfProperty") and obj.getDocumentationOfProperty(prop) != text:
        obj.setDocumentationOfProperty(prop, text)


def _size_by_length(obj):
    """True when the feature's target size is the edge length."""
    return SIZE_BY in obj.PropertiesList and getattr(obj, SIZE_BY) == size_choices()[1]


def _show_size(obj):
    """Shows the size property SizeBy chooses and hides the other."""
    by_length = _size_by_length(obj)
    for name, shown in zip(parameters.size_names(), (not by_length, by_length)):
        prop = parameters.properties()[name][0]
        if prop in obj.PropertiesList:
            obj.setEditorMode(prop, 0 if shown else 2)


def _size_by_changed(obj):
    """SizeBy switched: the size now used starts from the equivalent of the other on the source's
    area (as the panel's radio buttons do), within its range; the other one is hidden."""
    replaced, replacing = parameters.size_names()
    vertices_prop, length_prop = (parameters.properties()[n][0] for n in (replaced, replacing))
    if vertices_prop not in obj.PropertiesList or length_prop not in obj.PropertiesList:
        return
    area = meshing.source_area(getattr(obj, "Source", None))
    if _size_by_length(obj):
        if not getattr(obj, length_prop).Value > 0:
            length = parameters.edge_length_for(area, getattr(obj, vertices_prop))
            _store(obj, replacing, parameters.clamp(replacing, length) if length else 1.0)
    elif getattr(obj, length_prop).Value > 0:
        vertices = parameters.vertices_for(area, getattr(obj, length_prop).Value)
        if vertices:
            _store(obj, replaced, parameters.clamp(replaced, vertices))
        _store(obj, replacing, None)
    _show_size(obj)


def params_of(obj):
    """The parameter dict stored in a feature's properties (SizeBy chooses the size in use; a
    feature without it uses the edge length when that is set)."""
    values = {}
    for name, (prop, kind, _) in parameters.properties().items():
        value = getattr(obj, prop)
        if hasattr(value, "Value"):  # Quantity (Length, Angle)
            value = value.Value
        values[name] = value
    replaced, replacing = parameters.size_names()
    by_length = _size_by_length(obj) if SIZE_BY in obj.PropertiesList else values[replacing] > 0
    if by_length:
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
    if SIZE_BY in obj.PropertiesList:
        by_length = values[parameters.size_names()[1]] is not None
        if getattr(obj, SIZE_BY) != size_choices()[1 if by_length else 0]:
            setattr(obj, SIZE_BY, size_choices()[1 if by_length else 0])
        _show_size(obj)


def apply_result(obj, result):
    """Sets a feature's mesh and quality properties from a Result."""
    obj.Mesh = result.mesh
    for prop, (kind, value_of, _, _) in QUALITY_PROPERTIES.items():
        if prop == "Report":
            obj.Report = json.dumps(result.report, indent=2)
        else:
            _set_quality(obj, prop, kind, value_of(result.report), missing=0)


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
    value = number(missing if value is None else value)
    if kind == "App::PropertyLength" and value < 0:
        value = 0.0  # a length cannot say "missing" by -1
    setattr(obj, prop, value)


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
