"""LiftRemesh for FreeCAD: the macro API (works in FreeCADCmd, no GUI needed).

    import LiftRemesh
    mesh = LiftRemesh.remesh_shape(shape, vertices=4000)          # -> Mesh.Mesh
    features = LiftRemesh.remesh_objects(doc, [doc.Box], edge_length=2.0)

Parameters (all optional, by keyword): vertices or edge_length, mode ("isotropic" or
"anisotropic"), sigma, feature_angle, hold_creases, local_sizing, gradation, min_edge, max_edge, delta, nu, eta,
iterations, seed, threads, fill_holes, and for
Part shapes linear_deflection (mm) and angular_deflection (degrees) of the tessellation. `defaults(mode)`
lists them with their values; the command-line tool has the same names and defaults.
Errors: ValueError for bad input (liftremesh.InvalidInput is one), LiftRemesh.Cancelled when a
progress callback returns False, LiftRemesh.Error as the base of the remesher's errors.
"""
from . import native as _native
from .meshing import Result, remesh_mesh
from .parameters import defaults
from .feature import remesh_objects

_module = _native.load()
Error = _module.Error
Cancelled = _module.Cancelled
InvalidInput = _module.InvalidInput

__all__ = ["remesh_shape", "remesh_mesh", "remesh_objects", "make_fem_shell", "make_fem_solid", "defaults",
           "Result", "Error", "Cancelled", "InvalidInput"]


def remesh_shape(shape, progress=None, **params):
    """Remeshes a Part shape: tessellated as FreeCAD's STL export does (linear_deflection,
    angular_deflection), then remeshed. Returns a Mesh.Mesh. See the module doc for `params`."""
    from . import meshing, parameters

    values = parameters.resolve(params)
    mesh = meshing.tessellate(shape, values["linear_deflection"], values["angular_deflection"])
    result = meshing.remesh_mesh(mesh, progress=progress, **params)
    meshing.print_warnings(result, "the shape")
    return result.mesh


def make_fem_shell(doc, mesh_obj, **kwargs):
    """A Fem::FemMeshObject of linear triangles (shell elements) from a mesh object; see fem.py."""
    from . import fem

    return fem.make_fem_shell(doc, mesh_obj, **kwargs)


def make_fem_solid(doc, mesh_obj, order=2, **kwargs):
    """A Fem::FemMeshObject of tetrahedra (tet10; tet4 with order=1) filling a closed mesh object;
    see fem_solid.py."""
    from . import fem_solid

    return fem_solid.make_fem_solid(doc, mesh_obj, order=order, **kwargs)


# The package is the macro API's facade, as FEM's ObjectsFem is FEM's: with the GUI up it brings in
# the GUI half, whose import sets feature.py's view-provider hook, so that a feature a macro makes
# gets its view provider even before the workbench is first activated. The App modules (feature,
# meshing, fem, parameters, document, native) never import gui/.
import FreeCAD as _FreeCAD  # noqa: E402

if _FreeCAD.GuiUp:
    from . import gui as _gui  # noqa: E402,F401
