"""The Remesh task panel: parameters, then OK or Apply runs the remesh in a worker thread with a
progress bar (Cancel stops it), then the quality report.

Life of a panel (FreeCAD's task dialog protocol: accept() and reject() return True to close,
clicked() gets the other buttons):
  - OK or Apply: the parameters are checked, the sources tessellated (main thread), a RemeshJob
    started; the panel stays open, OK and Apply are disabled and refused while the job runs. The
    panel does not scroll: OK and Cancel stay where they are.
  - Cancel while it runs: the job is asked to stop; when it has, the panel says so (console and
    message box) and closes. The document is unchanged.
  - Job done: the features are added in one transaction (main thread), or, after an earlier Apply,
    the features that one added take the new parameters and mesh in one transaction; the quality
    report and the kappa histogram are shown. After OK the only button left is Close; after Apply
    the panel stays as it is, to change values and Apply again (as FreeCAD's "Remesh by Gmsh"
    does). OK with the values already applied closes; Cancel then closes and keeps the result.
  - Job failed: console and message box; the document is unchanged and the panel stays open so
    the parameters can be changed and OK pressed again.
With `feature` (editing an existing remesh feature, opened by a double click) the result replaces
that feature's mesh and parameters in one transaction instead of adding a new feature.
No exception leaves the panel's slots and the dialog protocol: FreeCAD would close the dialog and
print a traceback. Once the panel has closed, its timer is stopped and its job cancelled.
"""
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
        self._closed = False
        self._started = 0.0
        self._applying = False  # the running job was started by Apply (the panel stays editable)
        self._replaced = False  # the last result replaced an earlier one
        self._applied = None  # the parameters of the last result, when Apply made it
        self.form = FreeCADGui.PySideUic.loadUi(common.ui_path(UI_FILE))
        self.form.setWindowTitle("Edit remesh" if feature is not None else "Remesh")
        self.form.setWindowIcon(QtGui.QIcon(common.icon_path("LiftRemesh_Remesh.svg")))
        self.histogram = report_view.KappaHistogram()
        self._widget("histogram_box").layout().addWidget(self.histogram)
        self.timer = QtCore.QTimer(self.form)  # goes with the form
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self.form.destroyed.connect(lambda *_: self._stop())  # FreeCAD deletes it when the dialog closes
        self._setup()
        initial = remesh_feature.params_of(feature) if feature is not None else parameters.defaults()
        self.set_params(initial)

    # --- FreeCAD task dialog protocol -------------------------------------------------------

    def getStandardButtons(self):
        return button_flags(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Apply | QtGui.QDialogButtonBox.Cancel)

    def modifyStandardButtons(self, buttons):
        """Called by FreeCAD with the dialog's button box: kept to disable OK and Apply while running.
        Each button is made no wider than its icon and text: the style's minimum width (80 px) for
        three buttons is more than the task view's default width."""
        self._buttons = buttons
        for button in buttons.buttons():
            width = button.fontMetrics().boundingRect(button.text()).width()
            button.setMaximumWidth(width + button.iconSize().width() + 24)

    def accept(self):
        """OK: starts the remesh (the panel stays open); after a result, closes."""
        if self._gone():
            return False
        try:
            if self.running():
                FreeCAD.Console.PrintWarning("LiftRemesh: the remesh is still running: wait, or Cancel it\n")
                return False
            if self.outcome == "done" and (self._applied is None or self._applied == self.params()):
                return self._leave()
            self.start()
        except Exception as error:  # see the module doc
            self._failed(error)
        return False

    def reject(self):
        """Cancel: stops a running remesh (the panel closes once it has stopped), else closes."""
        try:
            if self.running():
                self.cancel(close=True)
                return False
        except Exception as error:  # see the module doc
            common.report_error("Cannot cancel the remesh: %s" % common.describe_error(error))
        return self._leave()

    def clicked(self, button):
        """The dialog's other buttons: Apply runs the remesh and keeps the panel open."""
        if button == button_flags(QtGui.QDialogButtonBox.Apply):
            self.apply()

    def apply(self):
        """Apply: remeshes with the values shown; the result replaces the previous one (one undo
        step) and the panel stays open. False when refused or it could not start."""
        if self._gone():
            return False
        try:
            if self.running():
                return False
            return self.start(applying=True)
        except Exception as error:  # see the module doc
            self._failed(error)
            return False

    # --- the job ------------------------------------------------------------------------------

    def running(self):
        """True from OK until the job's outcome has been handled."""
        return self.job is not None

    def start(self, applying=False):
        """Checks the parameters, tessellates the sources and starts the worker. False (and the
        error reported) when something is wrong; the document is not changed either way."""
        try:
            params = self.params()
            values = parameters.resolve(params)
            check_selection(self.doc, self.sources)
            for obj in self.sources:
                parameters.check(values, meshing.source_area(obj))
            meshes = self._input_meshes(values)
        except Exception as error:
            self._failed(error)
            return False
        self.outcome = None
        self._applying = applying
        self.job = remesh_job.RemeshJob(meshes, params)
        self._started = time.monotonic()
        self._set_running(True)
        self.job.start()
        self.timer.start()
        return True

    def cancel(self, close=False):
        """Asks a running job to stop; with `close`, the panel closes once it has."""
        if self.job is None:
            return
        self._close_when_stopped = self._close_when_stopped or close
        self.job.cancel()
        if common.widget_alive(self.form):
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
        """Timer slot (main thread): shows the progress; handles the outcome once the job ended.
        A panel whose form is gone (closed) stops polling and cancels its job."""
        current = self.job
        if self._gone():
            self._stop()
            return
        if current is None:
            self.timer.stop()
            return
        try:
            self._show_progress(current.progress)
            if current.finished():
                self.timer.stop()
                self.job = None
                self._ended(current)
        except Exception as error:  # see the module doc
            self.job = None
            self._failed(error)

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
        """Adds the results to the document, or replaces the previous ones (one transaction), and
        shows the report."""
        try:
            previous = self._previous_results()
            self._replaced = bool(previous)
            if previous:
                self.created = self._replace(previous, finished.params, finished.results)
            else:
                self.created = remesh_feature.add_results(self.doc, self.sources, finished.params, finished.results)
        except Exception as error:
            self._failed(error)
            return
        self.results = finished.results
        self.outcome = "done"
        self._applied = dict(finished.params) if self._applying else None
        self._show_done(final=not self._applying)

    def _previous_results(self):
        """The features a new result replaces: the edited feature, or what an earlier Apply of this
        panel added (while they all still exist); [] when the result is to be added."""
        if self.feature is not None:
            return [self.feature]
        alive = [obj for obj in self.created if self.doc.getObject(obj.Name) is obj]
        return alive if self.created and len(alive) == len(self.sources) else []

    def _replace(self, features, params, results):
        """The features take the new parameters and meshes, in one transaction."""
        with document.document_change(self.doc, "Edit remesh" if self.feature is not None else "Remesh"):
            for obj, result in zip(features, results):
                remesh_feature.set_params(obj, params)
                remesh_feature.apply_result(obj, result)
                obj.purgeTouched()
        return list(features)

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
        if common.widget_alive(self.form) and self.job is None:
            self._set_running(False)
        self._reset_progress("Failed: %s" % message)
        common.report_error("Remesh failed, the document is unchanged: %s" % message)

    # --- closing --------------------------------------------------------------------------------

    def _gone(self):
        """True once the panel has closed or FreeCAD has deleted its form: a late call (a queued
        click, a macro holding the panel) then does nothing and says nothing."""
        return self._closed or not common.widget_alive(self.form)

    def _stop(self):
        """The panel is closing or gone: no more polling, and no job left running."""
        self._closed = True
        if common.widget_alive(self.timer):  # a child of the form: gone with it
            self.timer.stop()
        if self.job is not None:
            self.job.cancel()
            self.job = None

    def _leave(self):
        """Ends the panel's life from accept()/reject() (their True return closes the dialog):
        stops polling and, when editing a feature, leaves edit mode. Returns True."""
        self._stop()
        if self.feature is not None and FreeCADGui.ActiveDocument is not None:
            FreeCADGui.ActiveDocument.resetEdit()
        return True

    def _close(self):
        """Closes the panel from outside accept()/reject() (after a cancel has taken effect)."""
        self._stop()
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
                    widget.setToolTip(parameters.gui_help(row["name"]))
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
        self._add_advanced_toggle()
        # Progress and then the report right below the sources, in view with the buttons while a
        # run goes on and after it (the panel does not scroll: OK and Cancel would leave the screen).
        layout = self.form.layout()
        for name in ("progress_group", "report_group"):
            layout.removeWidget(self._widget(name))
            layout.insertWidget(layout.indexOf(self._widget("size_group")), self._widget(name))

    def _add_advanced_toggle(self):
        """The Advanced group starts collapsed: an arrow button above it shows and hides it."""
        group = self._widget("advanced_group")
        toggle = QtGui.QToolButton()
        toggle.setObjectName("advanced_toggle")
        toggle.setText(group.title())
        toggle.setToolTip("Show or hide the settings a user rarely changes")
        toggle.setCheckable(True)
        toggle.setAutoRaise(True)
        toggle.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)
        toggle.setArrowType(QtCore.Qt.RightArrow)
        group.setTitle("")
        layout = self.form.layout()
        layout.insertWidget(layout.indexOf(group), toggle)
        toggle.toggled.connect(self._advanced_toggled)
        self._advanced_toggled(False)

    def _advanced_toggled(self, shown):
        self._widget("advanced_toggle").setArrowType(QtCore.Qt.DownArrow if shown else QtCore.Qt.RightArrow)
        self._widget("advanced_group").setVisible(shown)

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
        area = meshing.source_area(self.sources[0])
        vertices = values.get("vertices") or parameters.vertices_for(area, values.get("edge_length") or 0.0)
        if vertices:
            self._widget("vertices").setValue(parameters.clamp("vertices", vertices))
        length = values.get("edge_length") or parameters.edge_length_for(area, self._widget("vertices").value())
        if length:
            self._widget("edge_length").setValue(parameters.clamp("edge_length", length))
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
        """Vertex count <-> edge length: the field now used gets the equivalent of the other, moved
        into its range (a tiny edge length gives billions of vertices, more than the core takes)."""
        try:
            area = meshing.source_area(self.sources[0])
            if by_vertices:
                vertices = parameters.vertices_for(area, self._widget("edge_length").value())
                if vertices:
                    self._widget("vertices").setValue(parameters.clamp("vertices", vertices))
            else:
                length = parameters.edge_length_for(area, self._widget("vertices").value())
                if length:
                    self._widget("edge_length").setValue(parameters.clamp("edge_length", length))
        finally:
            self._update_size_fields()  # the radio buttons and the fields stay in step

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
        self._set_button_enabled(QtGui.QDialogButtonBox.Apply, not running)
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
        if not common.widget_alive(self.form):
            return
        self._widget("progress").setValue(0)
        self._widget("status").setText(text)

    def _show_done(self, final=True):
        """The result: full progress bar, report of each source; after OK (`final`) the values
        shown as used and Close as the only button, after Apply the panel left editable."""
        bar = self._widget("progress")
        bar.setValue(bar.maximum())
        replaced = self._replaced
        self._widget("status").setText("Done in %.1f s: %s %s." % (
            time.monotonic() - self._started, ", ".join(obj.Label for obj in self.created),
            "updated" if replaced else "added"))
        if final:
            for name in ("size_group", "method_group"):
                self._widget(name).setEnabled(False)  # shown as used; the feature's properties keep them
            for name in ("advanced_toggle", "advanced_group", "tessellation_group"):
                self._widget(name).hide()  # room for the report
        chooser = self._widget("report_source")
        chooser.blockSignals(True)
        chooser.clear()
        chooser.addItems([obj.Label for obj in self.sources])
        chooser.blockSignals(False)
        chooser.setVisible(len(self.sources) > 1)
        self._widget("report_group").show()
        self._show_report(0)
        for obj, result in zip(self.sources, self.results):
            FreeCAD.Console.PrintMessage("LiftRemesh: %s\n" % report_view.summary(obj.Label, result.report))
            meshing.print_warnings(result, obj.Label)
        if final and self._buttons is not None:
            self._buttons.setStandardButtons(QtGui.QDialogButtonBox.Close)

    def _show_report(self, index):
        if not 0 <= index < len(self.results):
            return
        report = self.results[index].report
        self._widget("report_text").setText(report_view.report_html(report))
        self.histogram.set_report(report)
