"""The Remesh task panel: parameters, then OK runs the remesh in a worker thread with a progress
bar (Cancel stops it), then the quality report.

Life of a panel (FreeCAD's task dialog protocol: accept() and reject() return True to close):
  - OK: the parameters are checked, the sources tessellated (main thread), a RemeshJob started;
    the panel stays open, OK is disabled and refused while the job runs.
  - Cancel while it runs: the job is asked to stop; when it has, the panel says so (console and
    message box) and closes. The document is unchanged.
  - Job done: the features are added in one transaction (main thread), the quality report and the
    kappa histogram are shown, and the only button left is Close.
  - Job failed: console and message box; the document is unchanged and the panel stays open so
    the parameters can be changed and OK pressed again.
With `feature` (editing an existing remesh feature, opened by a double click) the result replaces
that feature's mesh and parameters in one transaction instead of adding a new feature.
"""
import math
import time

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from .. import document
from .. import feature as remesh_feature
from .. import meshing
from .. import parameters
from . import common
from . import job as remesh_job
from . import report_view

UI_FILE = "remesh_task.ui"
POLL_MS = 100


def number_fields():
    """The parameters with a spin box of the same name in the form, the target size apart (its two
    fields go with the radio buttons that choose between them)."""
    return tuple(row["name"] for row in parameters.rows()
                 if row["kind"] in ("integer", "real") and row["name"] not in parameters.size_names())


def button_flags(value):
    """A Qt flag combination as the int FreeCAD 0.20 wants (PySide6 enums have .value instead)."""
    try:
        return int(value)
    except TypeError:
        return value.value


def check_selection(doc, objects):
    """ValueError unless every object is a shape with faces or a non-empty mesh of `doc`."""
    remesh_feature.check_sources(doc, objects)
    for obj in objects:
        if meshing.source_kind(obj) == "mesh":
            if obj.Mesh.CountFacets == 0:
                raise ValueError("%s is an empty mesh" % obj.Label)
        else:
            meshing.shape_of(obj)


def source_area(obj):
    """The area of a source (shape or mesh), 0 when it cannot be had."""
    try:
        if meshing.source_kind(obj) == "mesh":
            return obj.Mesh.Area
        return meshing.shape_of(obj).Area
    except Exception:  # only a hint for the size fields
        return 0.0


def edge_length_for(area, vertices):
    """The edge length of an ideal mesh with `vertices` vertices on `area` (equilateral triangles,
    about 2 per vertex): only a starting value when the user switches the kind of target size."""
    if area <= 0 or vertices <= 0:
        return 0.0
    return math.sqrt(2.0 * area / (math.sqrt(3.0) * vertices))


def vertices_for(area, edge_length):
    """The inverse of edge_length_for()."""
    if area <= 0 or edge_length <= 0:
        return 0
    return int(round(2.0 * area / (math.sqrt(3.0) * edge_length ** 2)))


def scroll_into_view(widget):
    """Scrolls the task view (the QScrollArea holding the panel, if any) to show `widget`."""
    area = widget.parentWidget()
    while area is not None and not isinstance(area, QtGui.QScrollArea):
        area = area.parentWidget()
    if area is not None:
        QtCore.QTimer.singleShot(0, lambda: area.ensureWidgetVisible(widget))


class RemeshTaskPanel:
    """Task panel remeshing `sources` (Part shapes or meshes of one document). Raises ValueError
    for a bad selection before any widget is shown. See the module doc for its behaviour."""

    def __init__(self, sources, feature=None):
        self.sources = list(sources)
        self.doc = self.sources[0].Document if self.sources else FreeCAD.ActiveDocument
        check_selection(self.doc, self.sources)
        self.feature = feature
        self.job = None
        self.outcome = None  # None, "done", "failed" or "cancelled"
        self.created = []
        self.results = []
        self._buttons = None
        self._close_when_stopped = False
        self._started = 0.0
        self.form = FreeCADGui.PySideUic.loadUi(common.ui_path(UI_FILE))
        self.form.setWindowTitle("Edit remesh" if feature is not None else "Remesh")
        self.form.setWindowIcon(QtGui.QIcon(common.icon_path("LiftRemesh_Remesh.svg")))
        self.histogram = report_view.KappaHistogram()
        self._widget("histogram_box").layout().addWidget(self.histogram)
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self._setup()
        initial = remesh_feature.params_of(feature) if feature is not None else parameters.defaults()
        self.set_params(initial)

    # --- FreeCAD task dialog protocol -------------------------------------------------------

    def getStandardButtons(self):
        return button_flags(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def modifyStandardButtons(self, buttons):
        """Called by FreeCAD with the dialog's button box: kept to disable OK while running."""
        self._buttons = buttons

    def accept(self):
        """OK: starts the remesh (the panel stays open); after a result, closes."""
        if self.running():
            FreeCAD.Console.PrintWarning("LiftRemesh: the remesh is still running: wait, or Cancel it\n")
            return False
        if self.outcome == "done":
            return self._leave()
        self.start()
        return False

    def reject(self):
        """Cancel: stops a running remesh (the panel closes once it has stopped), else closes."""
        if self.running():
            self.cancel(close=True)
            return False
        return self._leave()

    # --- the job ------------------------------------------------------------------------------

    def running(self):
        """True from OK until the job's outcome has been handled."""
        return self.job is not None

    def start(self):
        """Checks the parameters, tessellates the sources and starts the worker. False (and the
        error reported) when something is wrong; the document is not changed either way."""
        try:
            params = self.params()
            values = parameters.resolve(params)
            check_selection(self.doc, self.sources)
            meshes = self._input_meshes(values)
        except Exception as error:
            self._failed(error)
            return False
        self.outcome = None
        self.job = remesh_job.RemeshJob(meshes, params)
        self._started = time.monotonic()
        self._set_running(True)
        self.job.start()
        self.timer.start()
        scroll_into_view(self._widget("progress_group"))
        return True

    def cancel(self, close=False):
        """Asks a running job to stop; with `close`, the panel closes once it has."""
        if self.job is None:
            return
        self._close_when_stopped = self._close_when_stopped or close
        self.job.cancel()
        self._widget("status").setText("Cancelling...")

    def wait(self, timeout=None):
        """Processes GUI events until the running job's outcome has been handled (for tests and
        macros; the panel polls the job by itself in the GUI). Returns the outcome."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while self.job is not None:
            if deadline is not None and time.monotonic() > deadline:
                raise TimeoutError("LiftRemesh: the remesh did not end within %s s" % timeout)
            self.job.join(POLL_MS / 1000.0)
            QtGui.QApplication.processEvents()  # may run _poll() from the timer
            self._poll()
        return self.outcome

    def _input_meshes(self, values):
        """The meshes to remesh, one per source (tessellation of shapes), in the main thread."""
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            return [meshing.input_mesh(obj, values) for obj in self.sources]
        finally:
            QtGui.QApplication.restoreOverrideCursor()

    def _poll(self):
        """Timer slot (main thread): shows the progress; handles the outcome once the job ended."""
        current = self.job
        if current is None:
            self.timer.stop()
            return
        self._show_progress(current.progress)
        if current.finished():
            self.timer.stop()
            self.job = None
            self._ended(current)

    def _ended(self, finished):
        """Handles a job that has ended: cancelled, failed or done."""
        self._set_running(False)
        if finished.cancel_requested or finished.cancelled():
            self._cancelled()
        elif finished.error is not None:
            self._failed(finished.error)
        else:
            self._store(finished)

    def _store(self, finished):
        """Adds the results to the document (one transaction) and shows the report."""
        try:
            if self.feature is not None:
                self.created = self._replace_feature(finished.params, finished.results[0])
            else:
                self.created = remesh_feature.add_results(self.doc, self.sources, finished.params, finished.results)
        except Exception as error:
            self._failed(error)
            return
        self.results = finished.results
        self.outcome = "done"
        self._show_done()

    def _replace_feature(self, params, result):
        """Edit mode: the feature takes the new parameters and mesh, in one transaction."""
        obj = self.feature
        with document.document_change(self.doc, "Edit remesh"):
            remesh_feature.set_params(obj, params)
            remesh_feature.apply_result(obj, result)
            obj.purgeTouched()
        return [obj]

    def _cancelled(self):
        """The job was cancelled: nothing was added; say so, and close if Cancel asked to."""
        self.outcome = "cancelled"
        self._reset_progress("Cancelled: the document is unchanged.")
        common.report_warning("Remesh cancelled: the document is unchanged.")
        if self._close_when_stopped:
            self._close()

    def _failed(self, error):
        """Reports a failure (console, message box, status line); the panel stays open."""
        self.outcome = "failed"
        message = common.describe_error(error)
        self._reset_progress("Failed: %s" % message)
        common.report_error("Remesh failed, the document is unchanged: %s" % message)

    # --- closing --------------------------------------------------------------------------------

    def _leave(self):
        """Ends the panel's life from accept()/reject() (their True return closes the dialog):
        stops polling and, when editing a feature, leaves edit mode. Returns True."""
        self.timer.stop()
        if self.feature is not None and FreeCADGui.ActiveDocument is not None:
            FreeCADGui.ActiveDocument.resetEdit()
        return True

    def _close(self):
        """Closes the panel from outside accept()/reject() (after a cancel has taken effect)."""
        self.timer.stop()
        if self.feature is not None and FreeCADGui.ActiveDocument is not None:
            FreeCADGui.ActiveDocument.resetEdit()  # unsetEdit closes the dialog
        else:
            FreeCADGui.Control.closeDialog()

    # --- parameters <-> widgets -----------------------------------------------------------------

    def _widget(self, name):
        """The form's child widget of that object name."""
        widget = getattr(self.form, name, None)
        if widget is None:
            widget = self.form.findChild(QtCore.QObject, name)
        return widget

    def _setup(self):
        """Mode items, tooltips, signals, the sources line; hides the report until there is one."""
        mode = self._widget(parameters.MODE)
        for name in parameters.modes():
            mode.addItem(name.capitalize(), name)
        for row in parameters.rows():
            for widget_name in (row["name"], row["name"] + "_label", row["name"] + "_radio"):
                widget = self._widget(widget_name)
                if widget is not None:
                    widget.setToolTip(row["help"])
            if row["kind"] in ("integer", "real"):
                self._set_range(self._widget(row["name"]), row)
        mode.currentIndexChanged.connect(self._mode_changed)
        self._widget("vertices_radio").toggled.connect(self._size_kind_changed)
        self._widget("report_source").currentIndexChanged.connect(self._show_report)
        kinds = [meshing.source_kind(obj) for obj in self.sources]
        self._widget("tessellation_group").setEnabled("shape" in kinds)
        self._widget("sources_label").setText(", ".join(
            "%s (%s)" % (obj.Label, "Part shape" if kind == "shape" else "mesh")
            for obj, kind in zip(self.sources, kinds)))
        self._widget("report_group").hide()
        self._widget("progress").setValue(0)

    @staticmethod
    def _set_range(spin_box, row):
        """A spin box takes the range, step and decimals of its parameter's row."""
        low, high, step = parameters.editor_range(row)
        if row["kind"] == "real":
            spin_box.setDecimals(row["decimals"])
        spin_box.setRange(low, high)
        spin_box.setSingleStep(step)

    def set_params(self, values):
        """Shows a parameter dict (as defaults() or params_of() give it) in the widgets."""
        values = dict(values)
        mode = self._widget(parameters.MODE)
        mode.blockSignals(True)
        mode.setCurrentIndex(max(0, mode.findData(values.get(parameters.MODE) or parameters.modes()[0])))
        mode.blockSignals(False)
        for name in number_fields():
            if values.get(name) is not None:
                self._widget(name).setValue(values[name])
        for row in parameters.rows():
            if row["kind"] == "flag" and values.get(row["name"]) is not None:
                self._widget(row["name"]).setChecked(bool(values[row["name"]]))
        by_length = bool(values.get("edge_length"))
        self._widget("vertices_radio").blockSignals(True)
        self._widget("vertices_radio" if not by_length else "edge_length_radio").setChecked(True)
        self._widget("vertices_radio").blockSignals(False)
        area = source_area(self.sources[0])
        vertices = values.get("vertices") or vertices_for(area, values.get("edge_length") or 0.0)
        if vertices:
            self._widget("vertices").setValue(vertices)
        length = values.get("edge_length") or edge_length_for(area, self._widget("vertices").value())
        if length:
            self._widget("edge_length").setValue(length)
        self._update_size_fields()

    def params(self):
        """The parameter dict the widgets show (vertices or edge_length, the other None)."""
        values = {parameters.MODE: self._widget(parameters.MODE).currentData() or parameters.modes()[0]}
        for row in parameters.rows():
            if row["kind"] == "flag":
                values[row["name"]] = self._widget(row["name"]).isChecked()
        for name in number_fields():
            values[name] = self._widget(name).value()
        if self._widget("edge_length_radio").isChecked():
            values["vertices"], values["edge_length"] = None, self._widget("edge_length").value()
        else:
            values["vertices"], values["edge_length"] = self._widget("vertices").value(), None
        return values

    def set_vertices(self, count):
        """Asks for `count` output vertices (convenience for macros and tests)."""
        self._widget("vertices_radio").setChecked(True)
        self._widget("vertices").setValue(count)

    def _mode_changed(self, index):
        """A new mode brings its own nu and delta, as --mode does on the command line."""
        mode = self._widget(parameters.MODE).itemData(index)
        defaults = parameters.defaults(mode)
        for name in parameters.mode_dependent():
            self._widget(name).setValue(defaults[name])

    def _size_kind_changed(self, by_vertices):
        """Vertex count <-> edge length: the other field gets the equivalent value."""
        area = source_area(self.sources[0])
        if by_vertices:
            vertices = vertices_for(area, self._widget("edge_length").value())
            if vertices:
                self._widget("vertices").setValue(vertices)
        else:
            length = edge_length_for(area, self._widget("vertices").value())
            if length:
                self._widget("edge_length").setValue(length)
        self._update_size_fields()

    def _update_size_fields(self):
        by_vertices = self._widget("vertices_radio").isChecked()
        self._widget("vertices").setEnabled(by_vertices)
        self._widget("edge_length").setEnabled(not by_vertices)

    # --- display --------------------------------------------------------------------------------

    def _set_running(self, running):
        """Parameters frozen and OK disabled while the job runs."""
        for name in ("size_group", "method_group", "advanced_group"):
            self._widget(name).setEnabled(not running)
        kinds = [meshing.source_kind(obj) for obj in self.sources]
        self._widget("tessellation_group").setEnabled(not running and "shape" in kinds)
        self._set_button_enabled(QtGui.QDialogButtonBox.Ok, not running)
        if running:
            self._widget("report_group").hide()
            self._show_progress(self.job.progress)

    def _set_button_enabled(self, which, enabled):
        if self._buttons is not None and self._buttons.button(which) is not None:
            self._buttons.button(which).setEnabled(enabled)

    def _show_progress(self, progress):
        bar = self._widget("progress")
        bar.setValue(int(round(bar.maximum() * progress.fraction(len(self.sources)))))
        if self.job is not None and self.job.cancel_requested:
            return
        labels = [obj.Label for obj in self.sources]
        self._widget("status").setText("%s  (%.0f s)" % (progress.text(labels), time.monotonic() - self._started))

    def _reset_progress(self, text):
        self._widget("progress").setValue(0)
        self._widget("status").setText(text)

    def _show_done(self):
        """The result: full progress bar, report of each source, Close as the only button."""
        bar = self._widget("progress")
        bar.setValue(bar.maximum())
        self._widget("status").setText("Done in %.1f s: %s %s." % (
            time.monotonic() - self._started, ", ".join(obj.Label for obj in self.created),
            "updated" if self.feature is not None else "added"))
        for name in ("size_group", "method_group"):
            self._widget(name).setEnabled(False)  # shown as used; the feature's properties keep them
        for name in ("advanced_group", "tessellation_group"):
            self._widget(name).hide()  # room for the report
        chooser = self._widget("report_source")
        chooser.blockSignals(True)
        chooser.clear()
        chooser.addItems([obj.Label for obj in self.sources])
        chooser.blockSignals(False)
        chooser.setVisible(len(self.sources) > 1)
        self._widget("report_group").show()
        self._show_report(0)
        scroll_into_view(self._widget("report_group"))
        for obj, result in zip(self.sources, self.results):
            FreeCAD.Console.PrintMessage("LiftRemesh: %s\n" % report_view.summary(obj.Label, result.report))
            meshing.print_warnings(result, obj.Label)
        if self._buttons is not None:
            self._buttons.setStandardButtons(QtGui.QDialogButtonBox.Close)

    def _show_report(self, index):
        if not 0 <= index < len(self.results):
            return
        report = self.results[index].report
        self._widget("report_text").setText(report_view.report_html(report))
        self.histogram.set_report(report)
