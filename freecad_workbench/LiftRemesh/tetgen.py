"""TetGen (Debian's `tetgen`, run as a program) filling a closed triangle surface with linear
tetrahedra: -p a surface, -Y no point added on it (the boundary faces are the triangles, checked),
-q a bound on every tetrahedron's radius-edge ratio, -m a size at each surface point (the mean
length of its edges) that TetGen interpolates inside, -z numbers from 0. Its stage lines are
reported as progress; a progress callback returning False kills it.
"""
import os
import shutil
import subprocess
import tempfile
import threading

import numpy as np

from . import native
from . import tet_mesh

QUALITY = 1.4              # default bound on the radius-edge ratio (TetGen -q); TetGen's own is 2.0
QUALITY_RANGE = (1.1, 2.0)  # TetGen may not end below 1.1 (the regular tetrahedron has 0.61)

# TetGen's stage lines (its default output) and the share of the filling they start at.
TETGEN_STAGES = (
    ("Delaunizing vertices", 0.05, "Delaunay tetrahedralisation"),
    ("Creating surface mesh", 0.15, "inserting the surface"),
    ("Recovering boundaries", 0.20, "recovering the surface"),
    ("Removing exterior tetrahedra", 0.30, "removing the outside"),
    ("Recovering Delaunayness", 0.35, "recovering Delaunayness"),
    ("Refining mesh", 0.40, "refining to size and quality"),
    ("Optimizing mesh", 0.80, "optimising"),
    ("Writing", 0.95, "writing"),
)


class MesherFailed(RuntimeError):
    """TetGen is missing, failed, or changed the surface."""


def tetgen_program():
    """The TetGen program, or MesherFailed saying how to install it."""
    program = shutil.which("tetgen")
    if program is None:
        raise MesherFailed("TetGen is not installed: install the Debian package 'tetgen' "
                           "(scripts/install-deps.sh does)")
    return program



def tetrahedralize(points, triangles, quality=QUALITY, progress=None):
    """Linear tetrahedra filling the closed surface (points (n, 3), triangles (m, 3)) by TetGen:
    (nodes (N, 3), tets (M, 4)), nodes[:n] == points, every tetrahedron in FreeCAD's orientation.
    `progress(stage, iteration, total, energy)` as for the remesh (stage "fill", iteration out of
    100), returning False kills TetGen and raises liftremesh.Cancelled. MesherFailed when TetGen
    fails or its boundary is not the surface."""
    points = np.asarray(points, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    check_quality(quality)
    program = tetgen_program()
    with tempfile.TemporaryDirectory(prefix="liftremesh_tetgen_") as folder:
        base = os.path.join(folder, "surface")
        _write_off(base + ".off", points, triangles)
        with open(base + ".mtr", "w") as f:  # one size per point, read with -m
            f.write("%d 1\n" % len(points))
            f.write("".join("%.17g\n" % h for h in tet_mesh.local_edge_lengths(points, triangles)))
        # -p: fill a surface; -Y: no point added on it; -q: radius-edge bound; -m: sizes; -z: from 0
        command = [program, "-pYzmq%g" % quality, base + ".off"]
        log = _run_tetgen(command, progress)
        try:
            nodes = _read_table(base + ".1.node", float)[:, 1:4]
            tets = _read_table(base + ".1.ele", int)[:, 1:5]
        except (OSError, ValueError, IndexError) as error:
            raise MesherFailed("TetGen wrote no mesh (%s); its last lines: %s" % (error, log[-300:])) from error
    if len(nodes) < len(points) or not np.array_equal(nodes[:len(points)], points):
        raise MesherFailed("TetGen moved or dropped surface points")
    tets = tet_mesh.oriented(nodes, tets)
    missing = tet_mesh.boundary_mismatch(tets, triangles)
    if missing:
        raise MesherFailed("the tetrahedra's boundary is not the surface: %s" % missing)
    return nodes, tets


def check_quality(quality):
    low, high = QUALITY_RANGE
    if not low <= float(quality) <= high:
        raise ValueError("quality (the radius-edge ratio bound) must be in [%g, %g], got %r" % (low, high, quality))


def _write_off(path, points, triangles):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(points), len(triangles)))
        f.write("".join("%.17g %.17g %.17g\n" % tuple(p) for p in points.tolist()))
        f.write("".join("3 %d %d %d\n" % tuple(t) for t in triangles.tolist()))


def _run_tetgen(command, progress):
    """Runs TetGen, reporting its stages; kills it when progress says stop. Returns its output."""
    cancelled = native.load().Cancelled
    if progress is not None and progress("fill", 0, 100, 0.0) is False:
        raise cancelled("cancelled before filling")
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = []  # read by a thread: TetGen must never block on a full pipe
    reader = threading.Thread(target=lambda: lines.extend(process.stdout), daemon=True)
    reader.start()
    while True:
        try:
            process.wait(timeout=0.1)
            break
        except subprocess.TimeoutExpired:
            if progress is not None and progress("fill", _tetgen_percent(lines), 100, 0.0) is False:
                process.kill()
                process.wait()
                reader.join()
                raise cancelled("cancelled while TetGen was filling the surface")
    reader.join()
    process.stdout.close()
    output = "".join(lines)
    if process.returncode != 0:
        raise MesherFailed("TetGen failed (exit status %d): %s" % (process.returncode, output.strip()[-500:]))
    return output


def _tetgen_percent(lines):
    """How far TetGen is, from the last stage line it printed (TETGEN_STAGES)."""
    percent = 0
    for line in list(lines):
        for start, share, _ in TETGEN_STAGES:
            if line.startswith(start):
                percent = int(100 * share)
    return percent


def _read_table(path, kind):
    """The rows of a TetGen .node or .ele file after its header line, without comments."""
    with open(path) as f:
        rows = [line.split("#", 1)[0].split() for line in f]
    rows = [r for r in rows if r]
    return np.array(rows[1:], dtype=np.float64).astype(kind)
