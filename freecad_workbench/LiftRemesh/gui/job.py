"""A remesh job: prepared input meshes remeshed one after another in a worker thread.

No Qt and no document access here: the worker only calls meshing.remesh_mesh() (the compiled
module releases the GIL while it works) and records its progress; the task panel polls the job
from the main thread and is the one that touches the document.
"""
import threading

from .. import meshing
from .. import native

# Share of one source's progress bar given to each stage the module reports (start, end).
# The optimisation dominates; the quality report (Hausdorff distance) comes last.
STAGE_SPANS = {
    "prepare": (0.00, 0.03),
    "normals": (0.03, 0.08),
    "optimize": (0.08, 0.85),
    "rdt": (0.85, 0.90),
    "repair": (0.90, 0.91),
    "snap": (0.91, 0.92),
    "polish": (0.92, 0.925),
    "untangle": (0.925, 0.93),
    "quality": (0.93, 1.00),
}

STAGE_NAMES = {
    "prepare": "preparing the input",
    "normals": "vertex normals",
    "optimize": "optimising",
    "rdt": "extracting the triangles",
    "repair": "repairing",
    "snap": "snapping onto the input's boundary and creases",
    "polish": "polishing the triangles",
    "untangle": "untangling crossings",
    "quality": "measuring the quality",
}


class Progress:
    """What the worker last reported: source index, stage, iteration, total and energy."""

    def __init__(self, index=0, stage="prepare", iteration=0, total=0, energy=0.0):
        self.index = index
        self.stage = stage
        self.iteration = iteration
        self.total = total
        self.energy = energy

    def fraction(self, count):
        """Overall progress in [0, 1] for a job of `count` sources."""
        start, end = STAGE_SPANS.get(self.stage, (0.0, 0.0))
        within = self.iteration / self.total if self.total else 0.0
        part = start + (end - start) * min(max(within, 0.0), 1.0)
        return min((self.index + part) / max(count, 1), 1.0)

    def text(self, labels):
        """A status line such as 'Box: optimising, iteration 40 of 100' (the energy, a figure of the
        method, is not a user's business)."""
        label = labels[self.index] if self.index < len(labels) else ""
        prefix = "[%d/%d] " % (self.index + 1, len(labels)) if len(labels) > 1 else ""
        line = "%s%s: %s" % (prefix, label, STAGE_NAMES.get(self.stage, self.stage))
        if self.total:
            line += ", iteration %d of %d" % (self.iteration, self.total)
        return line


class RemeshJob:
    """Remeshes `meshes` (Mesh.Mesh, one per source) with `params` in a worker thread.

    start() starts it, cancel() asks it to stop at the module's next progress report, finished()
    says whether the thread is done. Afterwards exactly one of `results` (one Result per mesh)
    or `error` (the exception; liftremesh.Cancelled after a cancel) is set.
    """

    def __init__(self, meshes, params):
        self.meshes = list(meshes)
        self.params = dict(params)
        self.results = None
        self.error = None
        self.progress = Progress()
        self._cancel = threading.Event()
        self._thread = threading.Thread(target=self._run, name="LiftRemesh remesh", daemon=True)

    def start(self):
        """Starts the worker thread."""
        self._thread.start()

    def cancel(self):
        """Asks the worker to stop; the module raises Cancelled at its next progress report."""
        self._cancel.set()

    @property
    def cancel_requested(self):
        """True once cancel() was called."""
        return self._cancel.is_set()

    def finished(self):
        """True when the worker thread has ended (or never started)."""
        return not self._thread.is_alive()

    def join(self, timeout=None):
        """Waits for the worker thread (without processing GUI events)."""
        if self._thread.ident is not None:
            self._thread.join(timeout)

    def cancelled(self):
        """True when the job ended because it was cancelled."""
        return isinstance(self.error, native.load().Cancelled)

    def _report(self, stage, iteration, total, energy):
        """The module's progress callback (worker thread): records, and says whether to go on."""
        self.progress = Progress(self.progress.index, stage, iteration, total, energy)
        return not self._cancel.is_set()

    def _run(self):
        """The worker thread: every mesh in turn; any exception is kept for the main thread."""
        results = []
        try:
            for index, mesh in enumerate(self.meshes):
                if self._cancel.is_set():
                    raise native.load().Cancelled("cancelled before remeshing source %d" % (index + 1))
                self.progress = Progress(index)
                results.append(meshing.remesh_mesh(mesh, progress=self._report, **self.params))
        except BaseException as error:  # handed to the main thread, which reports it
            self.error = error
            return
        self.results = results
