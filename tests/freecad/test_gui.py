"""The workbench in FreeCAD's GUI, run headless:

    LIFTREMESH_TESTS=test_gui QT_QPA_PLATFORM=offscreen freecadcmd tests/freecad/run_tests.py

The main window is shown offscreen; the workbench is registered by exec'ing InitGui.py as FreeCAD
does (no __file__, a namespace of its own), unless FreeCAD already loaded the add-on. There the
task dialog is not tracked by Gui.Control, so the tests drive the panel's accept() and reject()
and wait for the job with panel.wait(). Message boxes are recorded instead of shown.
"""
import os
import sys
import tempfile
import time
import unittest

if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")  # read when the GUI starts

import FreeCAD
import FreeCADGui
import Mesh
import Part

from LiftRemesh import native

WORKBENCH = "LiftRemeshWorkbench"
REMESH = "LiftRemesh_Remesh"
FEM_SHELL = "LiftRemesh_FemShell"
TIMEOUT = 300  # seconds a small remesh may take on a slow machine before the test fails


def setUpModule():
    if not FreeCAD.GuiUp:
        FreeCADGui.showMainWindow()
    if WORKBENCH not in FreeCADGui.listWorkbenches():
        path = os.path.join(native.ADDON_ROOT, "freecad_workbench", "InitGui.py")
        with open(path, encoding="utf-8") as f:
            code = compile(f.read(), path, "exec")
        exec(code, {"__builtins__": __builtins__}, {})  # as FreeCAD runs it: no __file__
    FreeCADGui.activateWorkbench(WORKBENCH)


def process_events():
    from PySide import QtGui

    QtGui.QApplication.processEvents()


class MessageBoxes:
    """Replaces QMessageBox's static functions by recorders, so no modal box blocks a test."""

    KINDS = ("critical", "warning", "information", "question")

    def __init__(self):
        from PySide import QtGui

        self.box = QtGui.QMessageBox
        self.shown = []  # (kind, title, text)
        self.saved = {kind: getattr(self.box, kind) for kind in self.KINDS}
        for kind in self.KINDS:
            setattr(self.box, kind, staticmethod(self._recorder(kind)))

    def _recorder(self, kind):
        def record(parent, title, text, *args, **kwargs):
            self.shown.append((kind, title, text))
            return self.box.Ok

        return record

    def restore(self):
        for kind, function in self.saved.items():
            setattr(self.box, kind, function)

    def texts(self, kind):
        return [text for k, _, text in self.shown if k == kind]


def add_box_with_hole(doc, name="Block"):
    """A Part::Feature: a 20 x 20 x 10 block with a through hole (genus 1)."""
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = Part.makeBox(20, 20, 10).cut(Part.makeCylinder(4, 10, FreeCAD.Vector(10, 10, 0)))
    doc.recompute()
    return obj


class GuiTestCase(unittest.TestCase):
    """A new document, active in the GUI, and recorded message boxes."""

    def setUp(self):
        # Hidden: no 3D view, whose deletion crashes Coin on the offscreen platform (no OpenGL).
        # FreeCAD makes one anyway when events are processed with a selection in the document:
        # tests clear their selection before they wait for a job (remesh()).
        self.doc = FreeCAD.newDocument("LiftRemeshGuiTest", hidden=True)
        FreeCAD.setActiveDocument(self.doc.Name)
        FreeCADGui.Selection.clearSelection()
        self.boxes = MessageBoxes()
        self.panel = None
        self.finished = False  # set when the test ends: its timers stop
        # exceptions raised in Qt slots (timers, signals) go to sys.excepthook: FreeCAD's report view
        self.uncaught = []
        self.saved_hook = sys.excepthook
        sys.excepthook = lambda kind, value, trace: self.uncaught.append(value)

    def tearDown(self):
        self.finished = True
        if self.panel is not None and self.panel.running():
            self.panel.cancel()
            self.panel.wait(TIMEOUT)
        sys.excepthook = self.saved_hook
        self.boxes.restore()
        FreeCADGui.Selection.clearSelection()
        FreeCAD.closeDocument(self.doc.Name)

    def names(self):
        return sorted(obj.Name for obj in self.doc.Objects)

    def select(self, *objects):
        FreeCADGui.Selection.clearSelection()
        for obj in objects:
            FreeCADGui.Selection.addSelection(obj)

    def make_panel(self, sources, vertices=800, **kwargs):
        from LiftRemesh.gui import task_panel

        self.panel = task_panel.RemeshTaskPanel(sources, **kwargs)
        self.panel.set_vertices(vertices)
        return self.panel

    def remesh(self, source, vertices=800):
        """Runs the panel on `source` to the end; returns the created feature."""
        FreeCADGui.Selection.clearSelection()  # see setUp
        panel = self.make_panel([source], vertices)
        self.assertFalse(panel.accept())  # the panel stays open while the job runs
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)
        self.assertEqual(len(panel.created), 1)
        return panel.created[0]


class WorkbenchTest(GuiTestCase):
    def test_workbench_registers_and_activates_with_its_commands(self):
        self.assertIn(WORKBENCH, FreeCADGui.listWorkbenches())
        workbench = FreeCADGui.getWorkbench(WORKBENCH)
        self.assertEqual(workbench.MenuText, "Remesh")
        self.assertTrue(os.path.isfile(workbench.Icon), workbench.Icon)
        FreeCADGui.activateWorkbench(WORKBENCH)
        self.assertEqual(FreeCADGui.activeWorkbench().name(), WORKBENCH)
        self.assertIn("Remesh", workbench.listToolbars())
        self.assertIn("Remesh", workbench.listMenus())
        commands = FreeCADGui.listCommands()
        for name in (REMESH, FEM_SHELL):
            self.assertIn(name, commands)
        from LiftRemesh.gui import commands as gui_commands

        for command in (gui_commands.CommandRemesh(), gui_commands.CommandFemShell()):
            self.assertTrue(os.path.isfile(command.GetResources()["Pixmap"]))

    def test_remesh_command_is_active_only_with_a_shape_or_mesh_selected(self):
        block = add_box_with_hole(self.doc)
        group = self.doc.addObject("App::DocumentObjectGroup", "Group")
        self.assertFalse(FreeCADGui.isCommandActive(REMESH))
        self.select(group)
        self.assertFalse(FreeCADGui.isCommandActive(REMESH))
        self.select(block)
        self.assertTrue(FreeCADGui.isCommandActive(REMESH))
        self.assertFalse(FreeCADGui.isCommandActive(FEM_SHELL))
        mesh = self.doc.addObject("Mesh::Feature", "Mesh")
        mesh.Mesh = Mesh.createSphere(5.0, 30)
        self.select(mesh)
        self.assertTrue(FreeCADGui.isCommandActive(REMESH))
        self.assertTrue(FreeCADGui.isCommandActive(FEM_SHELL))

    def test_unavailable_commands_explain_why(self):
        # What the workbench registers when the compiled module cannot be imported.
        name = "LiftRemeshTest_Unavailable"
        FreeCADGui.getWorkbench(WORKBENCH).register_unavailable([name], "no module liftremesh", "")
        self.assertIn(name, FreeCADGui.listCommands())
        FreeCADGui.runCommand(name)
        self.assertEqual(self.boxes.texts("critical"), ["no module liftremesh"])


class TaskPanelTest(GuiTestCase):
    def test_panel_shows_the_module_defaults_and_mode_sets_nu_and_delta(self):
        from LiftRemesh import parameters

        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block])
        iso, aniso = parameters.defaults("isotropic"), parameters.defaults("anisotropic")
        values = panel.params()
        for name in ("sigma", "delta", "nu", "iterations", "linear_deflection", "angular_deflection"):
            self.assertAlmostEqual(values[name], iso[name], msg=name)
        self.assertEqual((values["vertices"], values["edge_length"]), (800, None))
        mode = panel._widget("mode")
        mode.setCurrentIndex(mode.findData("anisotropic"))
        values = panel.params()
        self.assertEqual(values["mode"], "anisotropic")
        self.assertAlmostEqual(values["nu"], aniso["nu"])
        self.assertAlmostEqual(values["delta"], aniso["delta"])
        panel._widget("edge_length_radio").setChecked(True)
        values = panel.params()
        self.assertIsNone(values["vertices"])
        self.assertGreater(values["edge_length"], 0.0)
        self.assertTrue(panel._widget("mode").toolTip())

    def test_spin_boxes_take_the_table_ranges(self):
        """Every number of the module's table has its spin box, bounded as the core bounds it (an
        open end one unit of the last shown digit inside), as are the feature's properties."""
        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block])
        for row in native.load().parameters():
            if row["kind"] not in ("integer", "real"):
                continue
            box = panel._widget(row["name"])
            self.assertIsNotNone(box, row["name"])
            unit = 1 if row["kind"] == "integer" else 10.0 ** -row["decimals"]
            if row["kind"] == "real":
                self.assertEqual(box.decimals(), row["decimals"], row["name"])
            for shown, end, is_open, inward in ((box.minimum(), row["min"], row["min_open"], 1),
                                                (box.maximum(), row["max"], row["max_open"], -1)):
                if end is None:
                    self.assertGreaterEqual(abs(shown), 1e9, row["name"])  # as far as the box goes
                else:
                    self.assertAlmostEqual(shown, end + (inward * unit if is_open else 0), 12, row["name"])

    def test_accept_inserts_one_mesh_feature_and_one_undo_removes_it(self):
        block = add_box_with_hole(self.doc)
        shape, volume, area = block.Shape, block.Shape.Volume, block.Shape.Area
        before = self.names()
        undo_count = self.doc.UndoCount
        feature = self.remesh(block)

        added = sorted(set(self.names()) - set(before))
        self.assertEqual(added, [feature.Name])
        self.assertTrue(feature.isDerivedFrom("Mesh::Feature"))
        self.assertEqual(feature.Mesh.CountPoints, self.panel.results[0].report["output"]["vertices"])
        self.assertGreater(feature.Mesh.CountFacets, 1000)
        self.assertIs(feature.Source, block)
        self.assertTrue(block.Shape.isEqual(shape))  # the source is untouched
        self.assertAlmostEqual(block.Shape.Volume, volume)
        self.assertAlmostEqual(block.Shape.Area, area)
        self.assertNotIn("Touched", block.State)
        self.assertEqual(self.doc.UndoCount, undo_count + 1)
        self.assertEqual(self.boxes.shown, [])
        # what the user sees: the report, the triangles, the source hidden, Close only
        self.assertFalse(self.panel._widget("report_group").isHidden())
        self.assertIn("κ min", self.panel._widget("report_text").text())
        self.assertEqual(len(self.panel.histogram.output_counts), 10)
        self.assertEqual(feature.ViewObject.DisplayMode, "Flat Lines")
        self.assertEqual(type(feature.ViewObject.Proxy).__name__, "ViewProviderRemesh")
        self.assertTrue(os.path.isfile(feature.ViewObject.Proxy.getIcon()))
        self.assertFalse(block.ViewObject.Visibility)
        self.assertTrue(self.panel.accept())  # OK again closes the panel

        self.doc.undo()
        self.assertEqual(self.names(), before)
        self.assertTrue(block.ViewObject.Visibility)

    def test_edge_length_as_the_target_size(self):
        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block])
        panel._widget("edge_length_radio").setChecked(True)
        panel._widget("edge_length").setValue(1.5)
        panel.accept()
        outcome = panel.wait(TIMEOUT)
        self.assertEqual(outcome, "done", self.boxes.shown)
        feature = panel.created[0]
        self.assertAlmostEqual(feature.EdgeLength.Value, 1.5)
        from LiftRemesh import feature as remesh_feature

        self.assertIsNone(remesh_feature.params_of(feature)["vertices"])  # Vertices is not used
        self.assertGreater(feature.Mesh.CountPoints, 100)

    def test_a_remeshed_mesh_saves_and_reloads(self):
        sphere = self.doc.addObject("Mesh::Feature", "Sphere")
        sphere.Mesh = Mesh.createSphere(5.0, 40)
        feature = self.remesh(sphere, vertices=500)
        self.assertEqual(feature.Mesh.CountPoints, 500)
        path = os.path.join(tempfile.mkdtemp(prefix="liftremesh_gui_"), "remeshed.FCStd")
        self.doc.saveAs(path)
        name = feature.Name
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path, True)  # hidden, as in setUp
        restored = self.doc.getObject(name)
        self.assertEqual(restored.Mesh.CountPoints, 500)
        self.assertEqual(type(restored.ViewObject.Proxy).__name__, "ViewProviderRemesh")
        self.assertEqual(restored.Source.Name, "Sphere")

    def test_editing_a_feature_replaces_its_mesh_in_one_undo_step(self):
        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=800)
        names = self.names()
        panel = self.make_panel([block], vertices=500, feature=feature)
        self.assertFalse(panel.accept())
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)
        self.assertEqual(self.names(), names)  # no new object
        self.assertEqual(feature.Mesh.CountPoints, 500)
        self.assertEqual(feature.Vertices, 500)
        self.doc.undo()
        self.assertEqual(feature.Mesh.CountPoints, 800)

    def test_cancel_during_a_run_leaves_the_document_unchanged(self):
        block = add_box_with_hole(self.doc)
        before, undo_count = self.names(), self.doc.UndoCount
        panel = self.make_panel([block], vertices=3000)
        panel._widget("iterations").setValue(100000)  # long enough to cancel in the middle
        panel.accept()
        deadline = time.monotonic() + TIMEOUT
        while panel.job.progress.stage != "optimize" or panel.job.progress.iteration < 2:
            self.assertLess(time.monotonic(), deadline, "the optimisation did not start")
            process_events()
            time.sleep(0.02)
        self.assertFalse(panel.accept())  # OK is refused while it runs
        self.assertFalse(panel.reject())  # Cancel stops the job; the panel closes when it has
        self.assertEqual(panel.wait(TIMEOUT), "cancelled")
        self.assertEqual(self.names(), before)
        self.assertEqual(self.doc.UndoCount, undo_count)
        self.assertEqual(len(self.boxes.texts("warning")), 1)
        self.assertIn("unchanged", self.boxes.texts("warning")[0])


class JobStagesTest(unittest.TestCase):
    def test_every_stage_the_module_reports_has_a_span_and_a_name(self):
        """The progress bar and status line know each stage the core reports (pipeline.cpp's
        StageClock), so none falls back to the bar's start or a raw name."""
        import MeshPart
        import numpy as np
        from LiftRemesh.gui import job

        box = Part.makeBox(20, 12, 6).cut(Part.makeCylinder(3, 6, FreeCAD.Vector(10, 6, 0)))
        mesh = MeshPart.meshFromShape(Shape=box, LinearDeflection=0.1, AngularDeflection=0.5)
        points = np.array([tuple(p) for p in mesh.Topology[0]], dtype=np.float64)
        triangles = np.array(mesh.Topology[1], dtype=np.int64)
        stages = []

        def progress(stage, iteration, total, energy):
            if stage not in stages:
                stages.append(stage)
            return True

        native.load().remesh(points, triangles, vertices=500, progress=progress)
        self.assertIn("snap", stages)  # the stages after the triangulation are reported too
        self.assertIn("polish", stages)
        for stage in stages:
            self.assertIn(stage, job.STAGE_SPANS)
            self.assertIn(stage, job.STAGE_NAMES)
        spans = [job.STAGE_SPANS[stage] for stage in stages]
        self.assertEqual(spans, sorted(spans), "the bar goes forward through the stages: %s" % stages)


class FailureTest(GuiTestCase):
    def assert_remesh_refused(self, culprit, *selection):
        """Running Remesh on `selection` shows one error naming `culprit` and adds nothing."""
        before = self.names()
        self.select(*selection)
        self.assertTrue(FreeCADGui.isCommandActive(REMESH))
        FreeCADGui.runCommand(REMESH)
        errors = self.boxes.texts("critical")
        self.assertEqual(len(errors), 1, self.boxes.shown)
        self.assertIn(culprit, errors[0])
        self.assertEqual(self.names(), before)

    def test_a_non_shape_in_the_selection_is_refused(self):
        block = add_box_with_hole(self.doc)
        group = self.doc.addObject("App::DocumentObjectGroup", "Folder")
        self.assert_remesh_refused("Folder", block, group)

    def test_an_empty_shape_is_refused(self):
        empty = self.doc.addObject("Part::Feature", "Wire")
        empty.Shape = Part.makeLine(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(10, 0, 0))
        self.doc.recompute()
        self.assert_remesh_refused("Wire", empty)

    def test_a_shape_emptied_before_ok_fails_and_the_panel_stays_open(self):
        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block])
        block.Shape = Part.Shape()
        before = self.names()
        self.assertFalse(panel.accept())
        self.assertEqual(panel.outcome, "failed")
        self.assertFalse(panel.running())
        self.assertEqual(len(self.boxes.texts("critical")), 1)
        self.assertEqual(self.names(), before)

    def test_a_remesh_error_in_the_worker_is_reported_and_nothing_added(self):
        flat = self.doc.addObject("Mesh::Feature", "Flat")
        flat.Mesh = Mesh.Mesh([[FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 0, 0), FreeCAD.Vector(2, 0, 0)]])
        self.assertEqual(flat.Mesh.CountFacets, 1)
        before, undo_count = self.names(), self.doc.UndoCount
        panel = self.make_panel([flat])
        panel.accept()
        self.assertEqual(panel.wait(TIMEOUT), "failed")
        errors = self.boxes.texts("critical")
        self.assertEqual(len(errors), 1, self.boxes.shown)
        self.assertIn("positive area", errors[0])
        self.assertEqual(self.names(), before)
        self.assertEqual(self.doc.UndoCount, undo_count)


class FemShellTest(GuiTestCase):
    def test_fem_shell_command_on_a_remeshed_mesh(self):
        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        before = set(self.names())
        self.select(feature)
        self.assertTrue(FreeCADGui.isCommandActive(FEM_SHELL))
        FreeCADGui.runCommand(FEM_SHELL)
        FreeCADGui.Selection.clearSelection()
        self.assertEqual(self.boxes.shown, [])
        added = [self.doc.getObject(name) for name in set(self.names()) - before]
        self.assertEqual([obj.TypeId for obj in added], ["Fem::FemMeshObject"])
        self.assertEqual(added[0].FemMesh.FaceCount, feature.Mesh.CountFacets)
        self.assertEqual(added[0].Label, "Block_ShellMesh")  # named after the part, as FEM's FEMMeshGmsh
        # a confirmation the user sees without the report view
        self.assertIn("Block_ShellMesh", FreeCADGui.getMainWindow().statusBar().currentMessage())
        self.assertFalse(feature.ViewObject.Visibility)  # the FEM mesh lies on it
        self.doc.undo()  # one step
        self.assertEqual(set(self.names()), before)
        self.assertTrue(feature.ViewObject.Visibility)

    def test_fem_shell_goes_into_the_active_analysis_with_a_thickness(self):
        import FemGui
        import ObjectsFem

        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        analysis = ObjectsFem.makeAnalysis(self.doc, "Analysis")
        FemGui.setActiveAnalysis(analysis)
        before = set(self.names())
        self.select(feature)
        FreeCADGui.runCommand(FEM_SHELL)
        FreeCADGui.Selection.clearSelection()
        self.assertEqual(self.boxes.shown, [])
        added = {self.doc.getObject(name) for name in set(self.names()) - before}
        self.assertEqual(set(analysis.Group), added)
        [mesh] = [obj for obj in added if obj.TypeId == "Fem::FemMeshObject"]
        [thickness] = [obj for obj in added if obj is not mesh]
        self.assertEqual(thickness.Proxy.Type, "Fem::ElementGeometry2D")
        volume, area = block.Shape.Volume, block.Shape.Area
        self.assertAlmostEqual(thickness.Thickness.Value, float("%.2g" % (2 * volume / area)))
        self.assertIn("Analysis", FreeCADGui.getMainWindow().statusBar().currentMessage())
        # a second shell mesh joins the analysis and its thickness, which is not repeated
        self.select(feature)
        FreeCADGui.runCommand(FEM_SHELL)
        FreeCADGui.Selection.clearSelection()
        self.assertEqual(len(analysis.Group), 3)
        self.doc.undo()
        self.assertEqual(len(analysis.Group), 2)
        self.doc.undo()
        self.assertEqual(set(self.names()), before)


def wait_until(condition, what, timeout=TIMEOUT):
    """Processes GUI events until condition() is true; fails the test after `timeout` seconds."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError("timed out waiting for " + what)
        process_events()
        time.sleep(0.02)


class RetryAndCloseTest(GuiTestCase):
    """Issue 34, items 1 and 2: an error keeps the panel usable, and a closed panel leaves nothing
    running behind it."""

    def test_a_retry_after_an_error_succeeds_and_adds_the_result(self):
        block = add_box_with_hole(self.doc)
        before = self.names()
        panel = self.make_panel([block])
        panel._widget("edge_length_radio").setChecked(True)
        panel._widget("edge_length").setValue(0.001)  # billions of vertices on a 20 mm block
        self.assertFalse(panel.accept())
        panel.wait(TIMEOUT)
        self.assertEqual(panel.outcome, "failed")
        [error] = self.boxes.texts("critical")
        # the setting named as the panel names it, with units, and what would be accepted
        self.assertIn("Edge length 0.001 mm", error)
        self.assertIn("mm\u00b2", error)
        self.assertNotIn("edge_length", error)
        # back to the vertex count: clamped to the core's largest count, radio and field in step
        panel._widget("vertices_radio").setChecked(True)
        self.assertEqual(panel._widget("vertices").value(), native.load().parameters()[0]["max"])
        self.assertTrue(panel._widget("vertices").isEnabled())
        self.assertFalse(panel._widget("edge_length").isEnabled())
        panel.set_vertices(600)
        self.assertFalse(panel.accept())
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)
        self.assertEqual(len(set(self.names()) - set(before)), 1)
        self.assertAlmostEqual(panel.created[0].Mesh.CountPoints, 600, delta=6)
        self.assertEqual(self.uncaught, [])

    def test_no_timer_runs_and_no_exception_after_the_panel_is_gone(self):
        import shiboken2

        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block], vertices=3000)
        panel._widget("iterations").setValue(100000)  # still running when the panel goes
        self.assertFalse(panel.accept())
        wait_until(lambda: panel.job.progress.stage == "optimize", "the optimisation")
        job, timer = panel.job, panel.timer
        self.assertTrue(timer.isActive())
        shiboken2.delete(panel.form)  # FreeCAD deletes the task box and the form in it
        self.assertFalse(shiboken2.isValid(timer))  # the poll timer went with the form
        self.assertTrue(job.cancel_requested)  # and the job was asked to stop
        self.assertFalse(panel.running())
        end = time.monotonic() + 1.0
        while time.monotonic() < end:
            process_events()
            time.sleep(0.02)
        self.assertEqual(self.uncaught, [])
        errors = []
        with ConsoleErrors(errors):  # a late call on a dead panel is refused without a word
            self.assertFalse(panel.accept())
            self.assertFalse(panel.apply())
        self.assertEqual(errors, [])
        self.assertEqual(self.uncaught, [])
        job.cancel()
        job.join(TIMEOUT)

    def test_closing_the_panel_stops_its_timer(self):
        block = add_box_with_hole(self.doc)
        panel = self.make_panel([block])
        self.remesh_in(panel)
        self.assertTrue(panel.accept())  # OK after the result closes
        self.assertFalse(panel.timer.isActive())
        self.assertEqual(self.uncaught, [])

    def remesh_in(self, panel):
        FreeCADGui.Selection.clearSelection()
        self.assertFalse(panel.accept())
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)


class ApplyTest(GuiTestCase):
    """Issue 34, item 8: Apply runs again with the new values and replaces its previous result."""

    def test_apply_replaces_the_previous_result_and_one_undo_removes_it(self):
        block = add_box_with_hole(self.doc)
        before = self.names()
        panel = self.make_panel([block], vertices=500)
        self.assertTrue(panel.apply())
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)
        [first] = panel.created
        count = first.Mesh.CountPoints
        self.assertAlmostEqual(count, 500, delta=5)
        undo_count = self.doc.UndoCount
        self.assertFalse(panel._widget("report_group").isHidden())  # the report stays
        self.assertTrue(panel._widget("size_group").isEnabled())  # the panel stays editable
        panel.set_vertices(700)
        self.assertTrue(panel.apply())
        self.assertEqual(panel.wait(TIMEOUT), "done", self.boxes.shown)
        self.assertEqual(panel.created, [first])  # replaced, not added
        self.assertEqual(sorted(set(self.names()) - set(before)), [first.Name])
        self.assertEqual(first.Vertices, 700)
        self.assertAlmostEqual(first.Mesh.CountPoints, 700, delta=7)
        self.assertEqual(self.doc.UndoCount, undo_count + 1)
        self.assertEqual(len(self.panel.histogram.output_counts), 10)
        self.assertTrue(panel.accept())  # OK with the applied values closes
        self.doc.undo()  # one step back: the first result
        self.assertEqual((first.Mesh.CountPoints, first.Vertices), (count, 500))
        self.doc.undo()
        self.assertEqual(self.names(), before)
        self.assertEqual(self.uncaught, [])


def while_recomputing(test, action, period_ms=50):
    """Calls action(dialog) from a timer, while doc.recompute() waits, each time LiftRemesh's
    progress dialog is shown, until it returns True or the test ends (the test's hand during a
    modal run)."""
    from PySide import QtCore, QtGui

    def poll():
        if test.finished:
            return
        shown = [d for d in FreeCADGui.getMainWindow().findChildren(QtGui.QProgressDialog) if d.isVisible()]
        if shown and action(shown[0]):
            return
        QtCore.QTimer.singleShot(period_ms, poll)

    QtCore.QTimer.singleShot(period_ms, poll)


class Follower:
    """Proxy of a test object that depends on a remesh feature: its execute() records the point
    count of the feature's mesh at the time (Points)."""

    @staticmethod
    def add(doc, feature):
        obj = doc.addObject("App::FeaturePython", "Follower")
        obj.addProperty("App::PropertyLink", "Feature")
        obj.addProperty("App::PropertyInteger", "Points")
        obj.Proxy = Follower()
        obj.Feature = feature
        doc.recompute()
        return obj

    def execute(self, obj):
        obj.Points = obj.Feature.Mesh.CountPoints


class PropertyEditTest(GuiTestCase):
    """Issue 34, items 3 to 5: the property view and a recompute after a property edit. The
    recompute is synchronous, as FreeCAD's own are: a modal progress dialog with Cancel while it
    runs, the new mesh when doc.recompute() returns.

    The dialog is shown from the first progress step here, not after half a second: on a quiet
    host these runs may end sooner, and the test's hand acts through the dialog."""

    def setUp(self):
        super().setUp()
        from LiftRemesh.gui import recompute

        self.min_duration_ms = recompute.MIN_DURATION_MS
        recompute.MIN_DURATION_MS = 0
        self.addCleanup(setattr, recompute, "MIN_DURATION_MS", self.min_duration_ms)

    def test_a_recompute_shows_progress_and_gives_the_new_mesh(self):
        from PySide import QtCore, QtGui

        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        follower = Follower.add(self.doc, feature)
        feature.Vertices = 3000
        feature.Iterations = 300  # a run of about a second or more: long enough for the dialog
        seen = []

        def record(dialog):
            seen.append((dialog.value(), dialog.labelText(), dialog.windowModality(), dialog.parent()))
            return False

        while_recomputing(self, record)
        self.doc.recompute()
        self.assertAlmostEqual(feature.Mesh.CountPoints, 3000, delta=30)  # the new mesh, at once
        self.assertEqual(follower.Points, feature.Mesh.CountPoints)  # a dependent saw it in the same pass
        self.assertNotIn("Touched", feature.State)
        self.assertTrue(seen, "no progress dialog shown")
        value, label, modality, parent = seen[-1]
        self.assertGreater(value, 0)
        self.assertIn(feature.Label, label)
        self.assertEqual(modality, QtCore.Qt.WindowModal)  # the document cannot be edited meanwhile
        self.assertIs(parent, FreeCADGui.getMainWindow())
        self.assertFalse([d for d in FreeCADGui.getMainWindow().findChildren(QtGui.QProgressDialog) if d.isVisible()])
        process_events()
        self.assertIn("recomputed", FreeCADGui.getMainWindow().statusBar().currentMessage())
        self.assertEqual(self.uncaught, [])

    def test_a_recompute_can_be_cancelled_and_keeps_the_mesh(self):
        from PySide import QtGui

        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        count = feature.Mesh.CountPoints
        feature.Iterations = 100000
        feature.Vertices = 3000
        warnings = []
        clicked = []

        def cancel(dialog):
            if dialog.value() <= 0:
                return False
            clicked.append(dialog.value())
            dialog.findChild(QtGui.QPushButton).click()  # its Cancel button
            return True

        while_recomputing(self, cancel)
        started = time.monotonic()
        with ConsoleErrors(warnings, "PrintWarning"):
            self.doc.recompute()
        self.assertTrue(clicked)
        self.assertLess(time.monotonic() - started, 60)  # 100000 iterations were not run
        self.assertEqual(feature.Mesh.CountPoints, count)
        self.assertIn("Touched", feature.State)  # still to be recomputed
        cancelled = [w for w in warnings if "cancelled" in w]
        self.assertEqual(len(cancelled), 1, warnings)
        self.assertEqual(cancelled[0].count("\n"), 1)
        process_events()
        self.assertIn("cancelled", FreeCADGui.getMainWindow().statusBar().currentMessage())
        self.assertEqual(self.uncaught, [])

    def test_a_recompute_asked_for_during_one_starts_no_nested_run(self):
        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        other = self.remesh(block, vertices=400)
        feature.Vertices = 1500
        feature.Iterations = 300
        other.Vertices = 450
        counts = (feature.Mesh.CountPoints, other.Mesh.CountPoints)
        nested = []

        def ask_again(dialog):
            for call in (self.doc.recompute, other.recompute):  # FreeCAD refuses the first, we the second
                try:
                    nested.append(call())
                except Exception as error:
                    nested.append(error)
            return True

        while_recomputing(self, ask_again)
        errors = []
        with ConsoleErrors(errors):
            self.doc.recompute()
        self.assertEqual(len(nested), 2, nested)  # whatever FreeCAD says to the nested doc.recompute()
        refused = [e for e in errors if "refused" in e]
        self.assertEqual(len(refused), 1, errors)
        self.assertIn(other.Label, refused[0])
        self.assertAlmostEqual(feature.Mesh.CountPoints, 1500, delta=15)
        self.assertNotEqual(feature.Mesh.CountPoints, counts[0])
        self.assertAlmostEqual(other.Mesh.CountPoints, 450, delta=5)  # the outer recompute reached it too
        self.assertEqual(self.uncaught, [])

    def test_a_recompute_error_is_one_line_and_keeps_the_mesh(self):
        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        count = feature.Mesh.CountPoints
        errors = []
        observer = ConsoleErrors(errors)
        feature.SizeBy = "Edge length"
        feature.EdgeLength = 0.001
        with observer:
            self.doc.recompute()
        self.assertEqual(feature.Mesh.CountPoints, count)
        self.assertEqual(len(errors), 1, errors)
        self.assertEqual(errors[0].count("\n"), 1)  # one line, no traceback
        self.assertIn("Edge length 0.001 mm", errors[0])
        self.assertIn("Touched", feature.State)
        self.assertEqual(self.uncaught, [])

    def test_the_property_view_shows_what_a_user_needs(self):
        block = add_box_with_hole(self.doc)
        feature = self.remesh(block, vertices=500)
        self.assertIn("Hidden", feature.getEditorMode("Report"))
        self.assertTrue(feature.Report.startswith("{"))  # still there for macros and the file
        self.assertEqual(feature.SizeBy, "Vertex count")
        self.assertIn("Hidden", feature.getEditorMode("EdgeLength"))  # not set: not shown
        feature.SizeBy = "Edge length"  # the equivalent length on the block's area
        area = block.Shape.Area
        self.assertAlmostEqual(feature.EdgeLength.Value, (2 * area / (3 ** 0.5 * 500)) ** 0.5, 3)
        self.assertIn("Hidden", feature.getEditorMode("Vertices"))
        self.assertEqual(feature.getEditorMode("EdgeLength"), [])
        for prop in ("Sigma", "Nu", "Eta", "Iterations", "Vertices", "EdgeLength"):
            doc = feature.getDocumentationOfProperty(prop)
            for jargon in ("unit-ball", "rho^", "L-BFGS", "sites", "--"):
                self.assertNotIn(jargon, doc, prop)
        self.assertIn("mm", feature.getDocumentationOfProperty("EdgeLength"))


class ConsoleErrors:
    """Records FreeCAD's console errors (the report view's red lines), or the lines of another
    Console printer (`kind`), while in a with block."""

    def __init__(self, errors, kind="PrintError"):
        self.errors = errors
        self.kind = kind

    def __enter__(self):
        self.saved = getattr(FreeCAD.Console, self.kind)
        setattr(FreeCAD.Console, self.kind, lambda text: (self.errors.append(text), self.saved(text)))
        return self

    def __exit__(self, *exc):
        setattr(FreeCAD.Console, self.kind, self.saved)
        return False
