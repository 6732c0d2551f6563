"""The "FEM solid mesh" command in FreeCAD's GUI, run headless (as test_gui.py, whose set-up it
shares): active on closed meshes only, progress dialog with Cancel, one undo step, the active
analysis, refusals in a message box.

The command's work is driven through CommandFemSolid.fill() with the selection cleared first:
processing events with a selection makes FreeCAD create a 3D view, which the offscreen platform
cannot draw (test_gui.py's GuiTestCase).
"""
import unittest
from unittest import mock

import FreeCADGui
import Mesh
import ObjectsFem

import LiftRemesh
from test_gui import GuiTestCase, add_box_with_hole, setUpModule  # noqa: F401  (the module's set-up)

FEM_SOLID = "LiftRemesh_FemSolid"


class FemSolidCommandTest(GuiTestCase):
    def add_mesh(self, mesh, name, source=None):
        obj = self.doc.addObject("Mesh::Feature", name)
        obj.Mesh = mesh
        if source is not None:
            obj.addProperty("App::PropertyLink", "Source", "Base", "the remeshed shape")
            obj.Source = source
        self.doc.recompute()
        return obj

    def command(self):
        from LiftRemesh.gui import fem_solid_command

        return fem_solid_command.CommandFemSolid()

    def run_command(self, *objects):
        """What Activated does for the selected `objects`, with the selection cleared (module doc)."""
        self.select(*objects)
        self.assertTrue(FreeCADGui.isCommandActive(FEM_SOLID))
        FreeCADGui.Selection.clearSelection()
        self.command().fill(self.doc, list(objects))

    def test_registered_in_the_workbench_and_active_on_closed_meshes_only(self):
        from LiftRemesh.gui import commands

        self.assertIn(FEM_SOLID, commands.NAMES)
        self.assertIn(FEM_SOLID, FreeCADGui.listCommands())
        import os

        self.assertTrue(os.path.isfile(self.command().GetResources()["Pixmap"]))
        block = add_box_with_hole(self.doc)
        closed = self.add_mesh(Mesh.createSphere(5.0, 30), "Closed")
        points, facets = Mesh.createSphere(5.0, 30).Topology
        open_mesh = Mesh.Mesh()
        open_mesh.addFacets((points, facets[1:]))
        opened = self.add_mesh(open_mesh, "Open")
        for obj, active in ((block, False), (opened, False), (closed, True)):
            with self.subTest(obj=obj.Name):
                self.select(obj)
                self.assertEqual(FreeCADGui.isCommandActive(FEM_SOLID), active)
        FreeCADGui.Selection.clearSelection()

    def test_fills_into_the_active_analysis_in_one_undo_step(self):
        import FemGui

        block = add_box_with_hole(self.doc)
        remeshed = self.add_mesh(LiftRemesh.remesh_shape(block.Shape, edge_length=2.0), "Remesh", block)
        analysis = ObjectsFem.makeAnalysis(self.doc, "Analysis")
        self.doc.recompute()
        FemGui.setActiveAnalysis(analysis)
        before = set(self.names())
        undo_count = self.doc.UndoCount
        self.run_command(remeshed)
        self.assertEqual(self.boxes.shown, [])
        added = [self.doc.getObject(name) for name in set(self.names()) - before]
        self.assertEqual([obj.TypeId for obj in added], ["Fem::FemMeshObject"])
        self.assertEqual(added[0].FemMesh.VolumeCount, added[0].FemMesh.TetraCount)
        self.assertGreater(added[0].FemMesh.VolumeCount, 0)
        self.assertIn(added[0], analysis.Group)
        self.assertFalse(remeshed.ViewObject.Visibility)
        self.assertEqual(self.doc.UndoCount, undo_count + 1)
        self.doc.undo()
        self.assertEqual(set(self.names()), before)
        self.assertTrue(remeshed.ViewObject.Visibility)

    def test_cancel_leaves_the_document_unchanged(self):
        from PySide import QtGui

        remeshed = self.add_mesh(LiftRemesh.remesh_shape(add_box_with_hole(self.doc).Shape, edge_length=1.0), "Remesh")
        before = self.names()
        with mock.patch.object(QtGui.QProgressDialog, "wasCanceled", return_value=True):
            self.run_command(remeshed)
        self.assertEqual(self.boxes.texts("warning"), ["FEM solid mesh cancelled; the document is unchanged."])
        self.assertEqual(self.names(), before)

    def test_crossing_triangles_are_refused_in_a_message_box(self):
        first = Mesh.createSphere(5.0, 30)
        second = Mesh.createSphere(4.0, 30)
        second.translate(6.0, 0.0, 0.0)
        first.addMesh(second)
        crossing = self.add_mesh(first, "Crossing")
        before = self.names()
        self.run_command(crossing)
        [error] = self.boxes.texts("critical")
        self.assertIn("Crossing cannot be filled with tetrahedra", error)
        self.assertIn("pass through each other, e.g. triangles centred at (", error)
        self.assertEqual(self.names(), before)


if __name__ == "__main__":
    unittest.main()
