# The Remesh panel in FreeCAD's real main window, driven as a user drives it: clicks and typing sent
# through QTest to the toolbar button, the radio buttons, the fields and the dialog's buttons. Run
# by ctest (freecad.gui_window) in a virtual X server:
#
#   xvfb-run -a -s "-screen 0 1280x900x24" freecad tests/freecad/gui_window.py
#
# Environment: LIFTREMESH_SOURCE_DIR, LIFTREMESH_MODULE_DIR (as run_tests.py), LIFTREMESH_SCREENSHOTS
# (default build/gui-screenshots): the window before, during and after a run is saved there as PNG
# files for a person to look at, with log.txt. Exits 0 only when every check passed.
import os
import sys
import time
import traceback

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

try:
    from PySide import QtTest
except ImportError:  # FreeCAD's PySide shim without QtTest
    try:
        from PySide2 import QtTest
    except ImportError:  # python3-pyside2.qttest missing: main() says so and fails
        QtTest = None

HERE = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else None
SOURCE = os.environ.get("LIFTREMESH_SOURCE_DIR") or os.path.dirname(os.path.dirname(HERE))
MODULE_DIR = os.environ.get("LIFTREMESH_MODULE_DIR") or os.path.join(SOURCE, "build", "python")
SHOTS = os.environ.get("LIFTREMESH_SCREENSHOTS") or os.path.join(SOURCE, "build", "gui-screenshots")
TIMEOUT = 300
os.environ["LIFTREMESH_MODULE_DIR"] = MODULE_DIR
for path in (os.path.join(SOURCE, "freecad_workbench"), MODULE_DIR):
    if path not in sys.path:
        sys.path.insert(0, path)
os.makedirs(SHOTS, exist_ok=True)
LOG = open(os.path.join(SHOTS, "log.txt"), "w")
failures = []
uncaught = []
sys.excepthook = lambda kind, value, trace: uncaught.append("".join(traceback.format_exception(kind, value, trace)))


def say(text):
    LOG.write(text + "\n")
    LOG.flush()
    sys.__stdout__.write(text + "\n")
    sys.__stdout__.flush()


def check(condition, what):
    say(("ok    " if condition else "FAIL  ") + what)
    if not condition:
        failures.append(what)


def pump(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.02)


def wait_until(condition, what, timeout=TIMEOUT):
    end = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > end:
            raise AssertionError("timed out waiting for " + what)
        pump(0.05)


def shot(name):
    path = os.path.join(SHOTS, name)
    FreeCADGui.getMainWindow().grab().save(path)
    say("screenshot " + path)


def click(widget):
    QtTest.QTest.mouseClick(widget, QtCore.Qt.LeftButton)
    pump(0.2)


def type_into(spin_box, text):
    spin_box.setFocus()
    spin_box.selectAll()
    QtTest.QTest.keyClicks(spin_box, text)
    QtTest.QTest.keyClick(spin_box, QtCore.Qt.Key_Tab)
    pump(0.2)


def dialog_button(which):
    """The task dialog's standard button (OK, Apply, Cancel, Close) that is shown, or None."""
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QDialogButtonBox):
        button = box.button(which)
        if button is not None and button.isVisible():
            return button
    return None


def near(count, target):
    """The core meets a vertex count to within a few vertices (not exactly on every part)."""
    return abs(count - target) <= 0.01 * target


def fully_visible(widget):
    """True when the whole widget is on screen: not scrolled away nor clipped by the task view."""
    return widget.isVisible() and widget.visibleRegion().boundingRect().size() == widget.size()


def answer_message_box(name, seen):
    """Saves the modal message box and presses its button (scheduled before the click opening it)."""
    box = QtGui.QApplication.activeModalWidget()
    if box is None:
        QtCore.QTimer.singleShot(200, lambda: answer_message_box(name, seen))
        return
    seen.append(box.text() if hasattr(box, "text") else box.windowTitle())
    shot(name)
    box.grab().save(os.path.join(SHOTS, name.replace(".png", "-box.png")))  # a window of its own
    buttons = box.findChildren(QtGui.QPushButton)
    click(buttons[0]) if buttons else box.close()


def while_recomputing(action, period_ms=50):
    """Calls action(dialog) from a timer while doc.recompute() waits, each time the progress dialog
    is shown, until it returns True."""
    def poll():
        shown = [d for d in FreeCADGui.getMainWindow().findChildren(QtGui.QProgressDialog) if d.isVisible()]
        if not (shown and action(shown[0])):
            QtCore.QTimer.singleShot(period_ms, poll)

    QtCore.QTimer.singleShot(period_ms, poll)


def plate(doc):
    """A filleted plate with five holes, as the issue's user tried."""
    import Part

    shape = Part.makeBox(80, 50, 4)
    shape = shape.makeFillet(6, [e for e in shape.Edges if abs(e.Vertexes[0].Z - e.Vertexes[-1].Z) > 1])
    for x, y, r in ((15, 15, 4), (65, 15, 4), (15, 35, 4), (65, 35, 4), (40, 25, 8)):
        shape = shape.cut(Part.makeCylinder(r, 4, FreeCAD.Vector(x, y, 0)))
    obj = doc.addObject("Part::Feature", "Plate")
    obj.Shape = shape
    doc.recompute()
    return obj


def run():
    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/NotificationArea").SetBool(
        "NonIntrusiveNotificationsEnabled", False)
    window = FreeCADGui.getMainWindow()
    window.resize(1280, 880)
    if "LiftRemeshWorkbench" not in FreeCADGui.listWorkbenches():
        path = os.path.join(SOURCE, "freecad_workbench", "InitGui.py")
        with open(path, encoding="utf-8") as f:
            exec(compile(f.read(), path, "exec"), {"__builtins__": __builtins__}, {})
    FreeCADGui.activateWorkbench("LiftRemeshWorkbench")
    from LiftRemesh.gui import task_panel

    panels = []
    original_init = task_panel.RemeshTaskPanel.__init__

    def recording_init(self, *args, **kwargs):
        original_init(self, *args, **kwargs)
        panels.append(self)

    task_panel.RemeshTaskPanel.__init__ = recording_init
    doc = FreeCAD.newDocument("Window")
    source = plate(doc)
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.Selection.addSelection(source)
    pump(0.5)

    # the toolbar button opens the panel
    action = [a for a in window.findChildren(QtGui.QAction) if a.objectName() == "LiftRemesh_Remesh"]
    buttons = [w for a in action for w in a.associatedWidgets() if isinstance(w, QtGui.QToolButton)]
    check(bool(buttons), "the Remesh toolbar button is there")
    click(buttons[0])
    pump(0.5)
    check(len(panels) == 1 and FreeCADGui.Control.activeDialog(), "the toolbar button opens the panel")
    panel = panels[-1]
    form = panel.form
    widget = form.findChild
    check(not widget(QtGui.QGroupBox, "advanced_group").isVisible(), "Advanced starts collapsed")
    check("unit-ball" not in widget(QtGui.QDoubleSpinBox, "nu").toolTip(), "tooltips in plain words")
    shot("1-panel-before.png")
    say("form width %d, minimum %d, shown %d" % (form.width(), form.minimumSizeHint().width(),
                                                 form.visibleRegion().boundingRect().width()))
    check(form.visibleRegion().boundingRect().width() == form.width(),
          "the panel fits the task view's default width (nothing cut on the right)")

    # an error: an edge length far too small, then back to the vertex count, then a retry
    click(widget(QtGui.QRadioButton, "edge_length_radio"))
    type_into(widget(QtGui.QDoubleSpinBox, "edge_length"), "0.001")
    seen = []
    QtCore.QTimer.singleShot(300, lambda: answer_message_box("2-error-box.png", seen))
    click(dialog_button(QtGui.QDialogButtonBox.Ok))
    pump(1.0)
    check(seen and "Edge length 0.001 mm" in seen[0], "the error names the setting with its unit: %s" % seen)
    check(FreeCADGui.Control.activeDialog() and panel.outcome == "failed", "the panel stays open after the error")
    click(widget(QtGui.QRadioButton, "vertices_radio"))
    vertices = widget(QtGui.QSpinBox, "vertices")
    check(vertices.isEnabled() and vertices.value() == vertices.maximum(),
          "vertex count clamped to %d and enabled" % vertices.maximum())
    type_into(vertices, "3000")
    click(dialog_button(QtGui.QDialogButtonBox.Apply))
    check(panel.running(), "Apply after the error starts a run")
    wait_until(lambda: panel.job is None or panel.job.progress.stage == "optimize", "the optimisation")
    pump(0.5)
    shot("3-panel-running.png")
    status = widget(QtGui.QLabel, "status")
    for name, which in (("OK", QtGui.QDialogButtonBox.Ok), ("Cancel", QtGui.QDialogButtonBox.Cancel)):
        button = dialog_button(which)
        check(button is not None and fully_visible(button), "%s stays in view during the run" % name)
    # A new status text reaches the layout through posted events: deliver them (no timer runs in
    # between, so the text stays the one measured), else a text set just now is measured against
    # the height of the one before.
    for _ in range(3):
        QtCore.QCoreApplication.sendPostedEvents()
    right = status.mapTo(form, QtCore.QPoint(status.width(), 0)).x()
    check(status.isVisible() and status.height() >= status.heightForWidth(status.width()) and right <= form.width(),
          "the status line is not clipped: %r" % status.text())
    wait_until(lambda: not panel.running(), "the end of the run")
    pump(0.5)
    shot("4-panel-applied.png")
    check(panel.outcome == "done", "the retry succeeded")
    remeshed = [o for o in doc.Objects if o.Name.endswith("_Remesh")]
    check(len(remeshed) == 1 and near(remeshed[0].Mesh.CountPoints, 3000),
          "Apply added one mesh of about 3000 vertices: %s" % [o.Mesh.CountPoints for o in remeshed])
    check(widget(QtGui.QGroupBox, "report_group").isVisible(), "the report is shown")

    # Apply again with other values: the same feature takes them; OK then closes
    type_into(vertices, "2000")
    click(dialog_button(QtGui.QDialogButtonBox.Ok))
    wait_until(lambda: not panel.running(), "the end of the second run")
    pump(0.5)
    shot("5-panel-done.png")
    remeshed = [o for o in doc.Objects if o.Name.endswith("_Remesh")]
    check(len(remeshed) == 1 and near(remeshed[0].Mesh.CountPoints, 2000),
          "OK replaced the applied result: %s" % [o.Mesh.CountPoints for o in remeshed])
    click(dialog_button(QtGui.QDialogButtonBox.Close))
    pump(1.0)
    check(not FreeCADGui.Control.activeDialog(), "Close closes the panel")
    check(not uncaught, "no exception reached the report view")

    # a property edit recomputes as FreeCAD's own recomputes do: doc.recompute() returns with the new
    # mesh, after a modal progress dialog with Cancel
    feature = remeshed[0]
    feature.ViewObject.DisplayMode = "Flat Lines"
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(feature)  # its properties in the property view
    pump(0.3)
    feature.Vertices = 2500
    feature.Iterations = 300  # a run of a second or more on a quiet host: the dialog shows after 0.5 s
    seen = []

    def look(dialog):
        if dialog.value() <= 0:
            return False
        seen.append((dialog.value(), dialog.labelText(), dialog.isModal(), fully_visible(dialog)))
        shot("6-recompute-progress.png")
        dialog.grab().save(os.path.join(SHOTS, "6-recompute-progress-dialog.png"))  # a window of its own
        return True

    while_recomputing(look)
    doc.recompute()
    check(bool(seen) and seen[0][0] > 0 and feature.Label in seen[0][1] and seen[0][2] and seen[0][3],
          "the recompute shows a modal progress dialog: %s" % seen)
    check(near(feature.Mesh.CountPoints, 2500), "doc.recompute() gives the new mesh: %d" % feature.Mesh.CountPoints)
    check("Touched" not in feature.State, "the feature is up to date")

    # the dialog's Cancel button, clicked: the previous mesh stays, the feature stays touched
    count, iterations = feature.Mesh.CountPoints, feature.Iterations
    feature.Iterations = 100000
    feature.Vertices = 3500
    clicked = []

    def cancel(dialog):
        if dialog.value() <= 0:
            return False
        click(dialog.findChild(QtGui.QPushButton))
        clicked.append(True)
        return True

    while_recomputing(cancel)
    started = time.monotonic()
    doc.recompute()
    check(clicked and time.monotonic() - started < 60, "Cancel stops the recompute")
    check(feature.Mesh.CountPoints == count and "Touched" in feature.State,
          "after Cancel the mesh is the previous one and the feature is touched")
    feature.Iterations = iterations
    feature.Vertices = 2500
    doc.recompute()
    check("Touched" not in feature.State, "a recompute after the Cancel succeeds")
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.activeDocument().activeView().saveImage(os.path.join(SHOTS, "7-result-view.png"), 1000, 700, "White")
    pump(1.0)
    check(not uncaught, "no exception reached the report view: %s" % uncaught)
    FreeCAD.closeDocument(doc.Name)


def main():
    status = 1
    try:
        if QtTest is None:
            raise ImportError("no QtTest: install python3-pyside2.qttest (scripts/install-deps.sh)")
        run()
        status = 0 if not failures else 1
    except BaseException:
        say(traceback.format_exc())
        shot("error.png")
    for text in uncaught:
        say("uncaught: " + text)
    say("%d failed checks" % len(failures))
    LOG.close()
    os._exit(status)


QtCore.QTimer.singleShot(500, main)
