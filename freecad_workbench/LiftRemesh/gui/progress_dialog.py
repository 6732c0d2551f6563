"""Waiting for a worker job (gui/job.py) behind a window-modal progress dialog of the main window,
as FreeCAD's own long operations do (Gui::SequencerDialog): the main thread processes GUI events
while it waits, so the window repaints; the dialog's modality keeps the user from editing the
document meanwhile, and its Cancel asks the job to stop. Used by a feature's recompute
(gui/recompute.py) and by the FEM solid mesh command (gui/fem_solid_command.py).
"""
from PySide import QtCore, QtGui

from . import common

POLL_S = 0.05  # how long the wait blocks between two rounds of GUI events
STEPS = 1000  # the dialog's range


class ProgressDialog:
    """The modal progress dialog of one run, shown once it has lasted `min_duration_ms` (as
    QProgressDialog's minimumDuration); before, a wait processes no user input."""

    def __init__(self, title, label, min_duration_ms):
        self.dialog = QtGui.QProgressDialog(common.main_window())
        self.dialog.setWindowTitle(title)
        self.dialog.setWindowModality(QtCore.Qt.WindowModal)
        self.dialog.setLabelText(label)
        self.dialog.setCancelButtonText("Cancel")
        self.dialog.setRange(0, STEPS)
        self.dialog.setAutoClose(False)
        self.dialog.setAutoReset(False)
        self.dialog.setMinimumDuration(min_duration_ms)
        self.dialog.setValue(0)  # starts the minimum duration

    def canceled(self):
        """True once Cancel was pressed (or the dialog closed)."""
        return self.dialog.wasCanceled()

    def show(self, fraction, text):
        if self.canceled():
            return  # Cancel hid the dialog; setValue() would show it again
        self.dialog.setLabelText(text)
        self.dialog.setValue(max(1, int(round(STEPS * fraction))))

    def close(self):
        self.dialog.reset()  # stops the timer that would show it after the minimum duration
        self.dialog.hide()
        self.dialog.deleteLater()


def wait(job, dialog, progress):
    """Processes GUI events until the started `job` has ended, showing `progress()`, its
    (fraction in [0, 1], text) now. Cancel in the dialog cancels the job. User input goes only to
    the dialog once it is shown (modal); before, none is processed."""
    while not job.finished():
        job.join(POLL_S)
        if dialog.canceled() and not job.cancel_requested:
            job.cancel()
        dialog.show(*progress())
        flags = QtCore.QEventLoop.AllEvents
        if not dialog.dialog.isVisible():
            flags = QtCore.QEventLoop.ExcludeUserInputEvents
        QtGui.QApplication.processEvents(flags)
