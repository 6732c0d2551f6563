"""Recomputing a remesh feature in the GUI after a property edit, as the task panel runs a remesh:
in a worker thread (gui/job.py), with a progress bar and a Cancel button in the main window's
status bar, so FreeCAD stays responsive during a long run.

FreeCAD's recompute calls the feature's execute(), which hands the work to request() and returns
at once: the feature keeps its previous mesh until the new one is there. Then (main thread) the
mesh and quality properties are set and the feature is clean. A failure or a Cancel leaves the
previous mesh, prints one line in the report view (no traceback), says it in the status bar and
marks the feature touched, as a failed recompute does. A new edit while a run goes on cancels it
and starts again. Without the GUI (FreeCADCmd) no hook is set and a recompute computes in place.
Macros and tests call wait() to have the result before they go on.
"""
import time

import FreeCAD
from PySide import QtCore, QtGui

from .. import feature as remesh_feature
from .. import meshing
from .. import parameters
from . import common
from . import job as remesh_job

POLL_MS = 100


class Run:
    """One feature's background recompute: which feature, its job, when it started."""

    def __init__(self, obj, job):
        self.doc_name = obj.Document.Name
        self.name = obj.Name
        self.label = obj.Label
        self.job = job
        self.started = time.monotonic()

    def feature(self):
        """The feature, or None when it or its document is gone."""
        doc = FreeCAD.listDocuments().get(self.doc_name)
        return doc.getObject(self.name) if doc is not None else None


class StatusProgress:
    """A progress bar, a status text and a Cancel button in the main window's status bar, shown
    while a recompute runs. Keeps the status bar's Python wrapper alive as long as its widgets:
    when a parent's wrapper goes, PySide invalidates the wrappers of the children it knows."""

    def __init__(self, on_cancel):
        self.status_bar = common.main_window().statusBar()
        self.widget = QtGui.QWidget()
        layout = QtGui.QHBoxLayout(self.widget)
        layout.setContentsMargins(0, 0, 0, 0)
        self.text = QtGui.QLabel()
        self.bar = QtGui.QProgressBar()
        self.bar.setRange(0, 1000)
        self.bar.setMaximumWidth(200)
        self.bar.setFormat("%p%")
        self.cancel = QtGui.QToolButton()
        self.cancel.setText("Cancel")
        self.cancel.setToolTip("Stop the remesh: the mesh keeps its previous triangles")
        self.cancel.clicked.connect(on_cancel)
        for widget in (self.text, self.bar, self.cancel):
            layout.addWidget(widget)
        self.status_bar.addPermanentWidget(self.widget)
        self.widget.hide()

    def show(self, fraction, text):
        self.bar.setValue(int(round(self.bar.maximum() * fraction)))
        self.text.setText(text)
        self.widget.show()

    def hide(self, message=None):
        self.widget.hide()
        if message:
            common.show_status(message)


class Recomputer:
    """The background recomputes of remesh features (one at a time per feature)."""

    def __init__(self):
        self.runs = {}  # (document name, feature name) -> Run
        self.progress = None
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self.poll)

    def request(self, obj, params):
        """The feature's execute() asks for a new mesh with `params`: started once the recompute
        has returned (the source's tessellation must not run inside it)."""
        key = (obj.Document.Name, obj.Name)
        QtCore.QTimer.singleShot(0, lambda: self.start(key, params))

    def start(self, key, params):
        """Starts the job for a feature (cancelling its running one). Errors: see fail()."""
        doc = FreeCAD.listDocuments().get(key[0])
        obj = doc.getObject(key[1]) if doc is not None else None
        if obj is None:
            return
        previous = self.runs.pop(key, None)
        if previous is not None:
            previous.job.cancel()  # its result is dropped: this run replaces it
        try:
            values = parameters.resolve(params)
            parameters.check(values, meshing.source_area(obj.Source))
            mesh = meshing.input_mesh(obj.Source, values)
        except Exception as error:
            self.fail(obj, error)
            return
        run = Run(obj, remesh_job.RemeshJob([mesh], params))
        self.runs[key] = run
        run.job.start()
        self.poll()
        self.timer.start()

    def running(self):
        """True while a background recompute runs."""
        return bool(self.runs)

    def cancel(self):
        """Asks every running recompute to stop."""
        for run in self.runs.values():
            run.job.cancel()

    def wait(self, timeout=None):
        """Processes GUI events until no recompute runs, including the ones a recompute in the
        event queue is about to start (for macros and tests)."""
        deadline = None if timeout is None else time.monotonic() + timeout
        QtGui.QApplication.processEvents()  # starts the requested runs
        while self.runs:
            if deadline is not None and time.monotonic() > deadline:
                raise TimeoutError("LiftRemesh: the recompute did not end within %s s" % timeout)
            for run in list(self.runs.values()):
                run.job.join(POLL_MS / 1000.0)
            QtGui.QApplication.processEvents()
            self.poll()

    def poll(self):
        """Timer slot: shows the progress of the latest run; ends the runs that have finished."""
        for key, run in list(self.runs.items()):
            if run.job.finished():
                del self.runs[key]
                self.ended(run)
        if not self.runs:
            self.timer.stop()
            return
        run = list(self.runs.values())[-1]
        progress = run.job.progress
        text = "%s  (%.0f s)" % (progress.text([run.label]), time.monotonic() - run.started)
        self.status().show(progress.fraction(1), "Recomputing " + text)

    def status(self):
        if self.progress is None:
            self.progress = StatusProgress(self.cancel)
        return self.progress

    def ended(self, run):
        """A finished run: the new mesh, or the failure or cancel reported."""
        obj = run.feature()
        if obj is None:
            self.status().hide()
            return
        job = run.job
        if job.cancel_requested or job.cancelled():
            message = "%s: recompute cancelled, the mesh is the previous one" % obj.Label
            FreeCAD.Console.PrintWarning("%s: %s\n" % (common.TITLE, message))
            obj.touch()
            self.status().hide(message)
        elif job.error is not None:
            self.fail(obj, job.error)
        else:
            result = job.results[0]
            remesh_feature.apply_result(obj, result)
            obj.purgeTouched()
            meshing.print_warnings(result, obj.Label)
            self.status().hide("%s recomputed in %.1f s" % (obj.Label, time.monotonic() - run.started))

    def fail(self, obj, error):
        """One line in the report view and the status bar; the feature keeps its mesh, touched."""
        message = "%s: recompute failed, the mesh is the previous one: %s" % (obj.Label, common.describe_error(error))
        FreeCAD.Console.PrintError("%s: %s\n" % (common.TITLE, message))
        obj.touch()
        self.status().hide(message)


_recomputer = None


def recomputer():
    """The one Recomputer of the session (made when first asked)."""
    global _recomputer
    if _recomputer is None:
        _recomputer = Recomputer()
    return _recomputer


def request(obj, params):
    """The feature's recompute hook (feature.set_recompute_hook)."""
    recomputer().request(obj, params)


def wait(timeout=None):
    """Waits (processing GUI events) until every background recompute has ended."""
    recomputer().wait(timeout)
