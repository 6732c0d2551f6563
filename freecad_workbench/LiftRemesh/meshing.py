"""From FreeCAD objects to the remesher and back: the input mesh of a source (a Part shape
tessellated as an STL export would be, or a mesh), conversion between Mesh.Mesh and numpy arrays,
and the remesh itself. Needs FreeCAD's App modules only (no GUI), so macros and tests call it.
"""
import math

import numpy as np

import FreeCAD
import Mesh

from . import native
from . import parameters


class Result:
    """A remeshed surface: `mesh` (Mesh.Mesh, in document coordinates), `report` (dict, the
    fields of the command-line tool's JSON report) and `warnings` (report_warnings())."""

    def __init__(self, mesh, report):
        self.mesh = mesh
        self.report = report
        self.warnings = report_warnings(report)


def report_warnings(report):
    """What a user should know about a result that is not a faithful copy of its source: another
    topology (parts thinner than the target edge length merge or break), holes the source does not
    have, or a large distance. Sentences, from the core's report (its "warnings"); empty when all is well."""
    return list(report.get("warnings") or [])


def mesh_to_arrays(mesh):
    """(points (n, 3) float64, triangles (m, 3) int64) of a Mesh.Mesh, in its placed coordinates."""
    points, facets = mesh.Topology
    p = np.array([(v.x, v.y, v.z) for v in points], dtype=np.float64).reshape(-1, 3)
    t = np.array(facets, dtype=np.int64).reshape(-1, 3)
    return p, t


def arrays_to_mesh(points, triangles):
    """A Mesh.Mesh with these vertices and triangles."""
    mesh = Mesh.Mesh()
    mesh.addFacets(([FreeCAD.Vector(*p) for p in np.asarray(points, dtype=float).tolist()],
                    [tuple(t) for t in np.asarray(triangles).tolist()]))
    return mesh


def source_kind(obj):
    """'mesh', 'shape' or None: what a document object offers to remesh."""
    if obj is None:
        return None
    if obj.isDerivedFrom("Mesh::Feature"):
        return "mesh"
    if hasattr(obj, "Shape") or obj.isDerivedFrom("App::Link"):
        return "shape"
    return None


def source_area(obj):
    """The area of a source (shape or mesh) in mm^2, 0 when it cannot be had: only a hint (the
    starting value of one target size from the other)."""
    try:
        if source_kind(obj) == "mesh":
            return obj.Mesh.Area
        if source_kind(obj) == "shape":
            return shape_of(obj).Area
    except Exception:  # a hint: a source without a usable shape has none
        pass
    return 0.0


def shape_of(obj):
    """The shape of a document object with its global placement (Part features, PartDesign
    bodies, links), or ValueError naming the object."""
    import Part

    try:
        shape = Part.getShape(obj)
    except Exception as error:  # getShape raises plain exceptions for objects without shapes
        raise ValueError("%s has no shape to remesh (%s)" % (obj.Label, error)) from error
    if shape.isNull() or not shape.Faces:
        raise ValueError("%s has an empty shape: no face to remesh" % obj.Label)
    return shape


def tessellate(shape, linear_deflection, angular_deflection, label="the shape"):
    """The shape's faces as FreeCAD's STL export makes them (MeshPart.meshFromShape, absolute
    linear deflection in mm, angular deflection in degrees). ValueError when nothing comes out."""
    import MeshPart

    if shape.isNull() or not shape.Faces:
        raise ValueError("%s has no face to remesh" % label)
    try:
        mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=float(linear_deflection),
                                      AngularDeflection=math.radians(float(angular_deflection)), Relative=False)
    except Exception as error:
        raise ValueError("%s cannot be tessellated: %s" % (label, error)) from error
    if mesh.CountFacets == 0:
        raise ValueError("%s cannot be tessellated: the tessellation has no triangle" % label)
    return mesh


def input_mesh(obj, values):
    """The triangle mesh LiftRemesh remeshes for a document object (see source_kind)."""
    kind = source_kind(obj)
    if kind == "mesh":
        if obj.Mesh.CountFacets == 0:
            raise ValueError("%s is an empty mesh" % obj.Label)
        return obj.Mesh.copy()
    if kind == "shape":
        return tessellate(shape_of(obj), values["linear_deflection"], values["angular_deflection"], obj.Label)
    raise ValueError("%s is neither a Part shape nor a mesh" % (obj.Label if obj is not None else "nothing"))


def remesh_mesh(mesh, progress=None, **params):
    """Remeshes a Mesh.Mesh; returns a Result. `params`: see parameters.resolve(); `progress`:
    see liftremesh.remesh(). Raises ValueError (bad input) or liftremesh.Error (Cancelled, ...).
    Touches no document and prints nothing: safe in a worker thread."""
    values = parameters.resolve(params)
    if mesh.CountFacets == 0:
        raise ValueError("the mesh to remesh is empty")
    points, triangles = mesh_to_arrays(mesh)
    out_points, out_triangles, report = native.load().remesh(
        points, triangles, progress=progress, **parameters.module_arguments(values))
    return Result(arrays_to_mesh(out_points, out_triangles), report)


def print_warnings(result, label):
    """The result's warnings on FreeCAD's console (call from the main thread)."""
    for warning in result.warnings:
        FreeCAD.Console.PrintWarning("LiftRemesh: %s: %s\n" % (label, warning))


def remesh_source(obj, progress=None, **params):
    """Remeshes a document object (Part shape or mesh); returns a Result."""
    values = parameters.resolve(params)
    result = remesh_mesh(input_mesh(obj, values), progress=progress, **params)
    print_warnings(result, obj.Label)
    return result
