"""The workbench's commands, registered when this module is imported (the workbench imports it
when it is activated):

  LiftRemesh_Remesh    remesh the selected Part shapes and meshes (task panel)
  LiftRemesh_FemShell  FEM mesh of linear triangles (shell elements) from the selected meshes
  LiftRemesh_FemSolid  FEM mesh of tet10 elements filling the selected closed meshes
                       (fem_solid_command.py)
"""
import FreeCAD
import FreeCADGui

from .. import document
from .. import meshing
from . import common
from . import fem_solid_command  # registers its command, LiftRemesh_FemSolid

REMESH = "LiftRemesh_Remesh"
FEM_SHELL = "LiftRemesh_FemShell"
NAMES = (REMESH, FEM_SHELL, fem_solid_command.FEM_SOLID)


def no_task_dialog():
    """False while a task dialog (ours or another) is open: one at a time."""
    return not FreeCADGui.Control.activeDialog()


def selected_sources():
    """The selected objects that can be remeshed (Part shapes, meshes)."""
    return [obj for obj in common.selected_objects() if meshing.source_kind(obj) is not None]


def selected_meshes():
    """The selected mesh objects (Mesh::Feature and derived)."""
    return [obj for obj in common.selected_objects() if obj.isDerivedFrom("Mesh::Feature")]


class CommandRemesh:
    """Opens the Remesh task panel for the selected Part shapes and meshes."""

    def GetResources(self):
        return {
            "Pixmap": common.icon_path("LiftRemesh_Remesh.svg"),
            "MenuText": "Remesh",
            "ToolTip": "Remesh the selected Part shapes (tessellated as the STL export does) and meshes "
                       "into well-shaped triangle meshes that keep the sharp edges. Adds one mesh per "
                       "source; the sources are not changed.",
        }

    def IsActive(self):
        return no_task_dialog() and common.active_document() is not None and bool(selected_sources())

    def Activated(self):
        from . import task_panel

        objects = common.selected_objects()
        try:
            panel = task_panel.RemeshTaskPanel(objects)
        except Exception as error:
            common.report_error("Cannot remesh the selection: %s" % common.describe_error(error))
            return
        try:
            FreeCADGui.Control.showDialog(panel)
        except Exception as error:  # another task dialog is open
            common.report_error("Cannot open the Remesh panel: %s" % common.describe_error(error))


class CommandFemShell:
    """Makes a Fem::FemMeshObject of linear triangles (shell elements) from each selected mesh."""

    def GetResources(self):
        return {
            "Pixmap": common.icon_path("LiftRemesh_FemShell.svg"),
            "MenuText": "FEM shell mesh from remeshed mesh",
            "ToolTip": "Make a FEM mesh of linear triangles (shell elements) from each selected mesh, "
                       "e.g. a remeshed one, in one undo step.",
        }

    def IsActive(self):
        return no_task_dialog() and common.active_document() is not None and bool(selected_meshes())

    def Activated(self):
        import LiftRemesh
        from .. import fem

        doc = common.active_document()
        meshes = selected_meshes()
        if doc is None or not meshes:
            common.report_error("Select one or more mesh objects to make FEM shell meshes of.")
            return
        analysis = fem.active_analysis(doc)
        added = []
        try:
            with document.document_change(doc, "FEM shell mesh"):
                created = [LiftRemesh.make_fem_shell(doc, obj) for obj in meshes]
                for obj in meshes:  # the FEM mesh lies on it; undoing shows it again
                    if obj.ViewObject is not None:
                        obj.ViewObject.hide()
                if analysis is not None:  # as FEM's own mesh commands do
                    for mesh_obj, fem_obj in zip(meshes, created):
                        added += fem.add_to_analysis(analysis, fem_obj, fem.plate_thickness(fem.source_shape(mesh_obj)))
            doc.recompute()
        except Exception as error:
            common.report_error("FEM shell mesh failed, the document is unchanged: %s"
                                % common.describe_error(error))
            return
        message = "FEM shell mesh %s added" % ", ".join(
            "%s (%d triangles)" % (obj.Label, obj.FemMesh.FaceCount) for obj in created)
        if analysis is not None:
            extra = [obj.Label for obj in added if obj not in created]
            message += " to %s%s" % (analysis.Label, " with the shell thickness %s" % ", ".join(extra) if extra else "")
        FreeCAD.Console.PrintMessage("LiftRemesh: %s\n" % message)
        common.show_status(message)


FreeCADGui.addCommand(REMESH, CommandRemesh())
FreeCADGui.addCommand(FEM_SHELL, CommandFemShell())
