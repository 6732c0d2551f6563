"""Recomputing a remesh feature in the GUI: synchronous, as FreeCAD's own long operations are, with
a progress dialog and a Cancel button.

FreeCAD's recompute calls the feature's execute(), which calls remesh() here: the remesh runs in
the worker thread of a RemeshJob (gui/job.py) while remesh() waits, processing GUI events so the
window repaints. A window-modal QProgressDialog of the main window (the stage, the percentage,
Cancel) shows when the run lasts longer than MIN_DURATION_MS; its modality keeps the user from
editing the document meanwhile. execute() sets the new mesh before it returns, so the objects that
depend on the feature recompute on it in the same recompute and a macro sees it once
doc.recompute() has returned, as in FreeCADCmd.

A failure or a Cancel leaves the previous mesh, prints one line in the report view (an exception
raised in execute() would print a traceback), says it in the status bar and leaves the feature
touched, to be recomputed. A recompute asked for while a run goes on (a timer, another document)
starts no nested run: it is refused the same way.
"""
import time

import FreeCAD
from PySide import QtCore

from .. import meshing
from .. import parameters
from . import common
from . import job as remesh_job
from . import progress_dialog

MIN_DURATION_MS = 500  # a shorter run shows no dialog (as QProgressDialog's minimumDuration)


class AfterRecompute:
    """What waits for the end of the document recompute a feature's execute() ran in (a document
    observer's slotRecomputedDocument): FreeCAD purges the touched flag of every object whose
    execute() returned, so a failed feature is touched again then, and it clears the status bar
    when it ends, so a message is shown then. Outside a document recompute (obj.recompute()) both
    happen at once."""

    def __init__(self):
        self.keys = set()  # (document name, object name) to touch
        self.messages = []  # (document name, status bar message)
        FreeCAD.addDocumentObserver(self)

    def touch(self, obj):
        obj.touch()
        if obj.Document.Recomputing:
            self.keys.add((obj.Document.Name, obj.Name))

    def show_status(self, obj, message):
        if obj.Document.Recomputing:
            self.messages.append((obj.Document.Name, message))
        else:
            common.show_status(message)

    def slotRecomputedDocument(self, doc):
        for key in [key for key in self.keys if key[0] == doc.Name]:
            self.keys.discard(key)
            obj = doc.getObject(key[1])
            if obj is not None:
                obj.touch()
        for message in [m for name, m in self.messages if name == doc.Name]:
            QtCore.QTimer.singleShot(0, lambda text=message: common.show_status(text))
        self.messages = [(name, m) for name, m in self.messages if name != doc.Name]


class Recomputer:
    """Runs the remesh of one feature's recompute at a time, waiting for it with the GUI alive."""

    def __init__(self):
        self.run = None  # (label, job) of the running recompute: refuses a nested one
        self.after = AfterRecompute()

    def remesh(self, obj, params):
        """The new mesh of a feature (a meshing.Result), computed with progress and Cancel; None
        after a failure, a Cancel or a refused nested request (said in one line, obj touched)."""
        if self.run is not None:
            return self.fail(obj, "recompute refused: the recompute of %s is still running" % self.run[0])
        started = time.monotonic()
        try:
            values = parameters.resolve(params)
            parameters.check(values, meshing.source_area(obj.Source))
            job = remesh_job.RemeshJob([meshing.input_mesh(obj.Source, values)], params)
        except Exception as error:
            return self.fail(obj, "recompute failed, the mesh is the previous one: %s" % common.describe_error(error))
        self.run = (obj.Label, job)
        label = obj.Label
        dialog = progress_dialog.ProgressDialog(common.TITLE, "Recomputing %s" % label, MIN_DURATION_MS)
        try:
            job.start()
            progress_dialog.wait(job, dialog,
                                 lambda: (job.progress.fraction(1), "Recomputing " + job.progress.text([label])))
        finally:
            dialog.close()
            self.run = None
        if job.cancel_requested or job.cancelled():
            return self.fail(obj, "recompute cancelled, the mesh is the previous one", FreeCAD.Console.PrintWarning)
        if job.error is not None:
            return self.fail(obj, "recompute failed, the mesh is the previous one: %s" % common.describe_error(job.error))
        result = job.results[0]
        meshing.print_warnings(result, obj.Label)
        self.after.show_status(obj, "%s recomputed in %.1f s" % (obj.Label, time.monotonic() - started))
        return result

    def fail(self, obj, message, printer=None):
        """One line in the report view and the status bar; the feature keeps its mesh, touched."""
        line = "%s: %s" % (obj.Label, message)
        (printer or FreeCAD.Console.PrintError)("%s: %s\n" % (common.TITLE, line))
        self.after.show_status(obj, line)
        self.after.touch(obj)
        return None


_recomputer = None


def recomputer():
    """The one Recomputer of the session (made when first asked)."""
    global _recomputer
    if _recomputer is None:
        _recomputer = Recomputer()
    return _recomputer


def remesh(obj, params):
    """The feature's recompute hook (feature.set_recompute_hook): see Recomputer.remesh()."""
    return recomputer().remesh(obj, params)
