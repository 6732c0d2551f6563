"""The FEM API calls the tests make that differ between FreeCAD 0.20 and 1.x, in one place."""
import FreeCAD
import ObjectsFem


def make_solver_ccx_tools(doc, name):
    """The CalculiX solver object driven by femtools.ccxtools: makeSolverCalculixCcxTools in 0.20,
    makeSolverCalculiXCcxTools (capital X) in 1.0."""
    make = getattr(ObjectsFem, "makeSolverCalculiXCcxTools", None) or ObjectsFem.makeSolverCalculixCcxTools
    return make(doc, name)


def set_force(constraint, newtons):
    """A force constraint's magnitude in newtons. 0.20's Force is a float read in N; 1.0's is an
    App::PropertyForce, where a bare float is read in the base unit, mN."""
    if isinstance(constraint.Force, FreeCAD.Units.Quantity):
        constraint.Force = FreeCAD.Units.Quantity("%r N" % float(newtons))
    else:
        constraint.Force = float(newtons)


def set_gmsh_shape(mesh_obj, part):
    """The shape a FEM Gmsh mesh object meshes: its Part property in 0.20, Shape in 1.x."""
    setattr(mesh_obj, "Shape" if "Shape" in mesh_obj.PropertiesList else "Part", part)
