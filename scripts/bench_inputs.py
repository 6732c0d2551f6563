"""The benchmark's made inputs, written under its output folder and never stored in the tree:
- the shared bunny with every triangle split into four at its edge midpoints, once (280k
  triangles) or twice (1.1M): the large inputs of the scale table. A split leaves the surface as
  it was, so every row remeshes the same shape;
- the demo bracket tessellated finely by FreeCAD (about 40k triangles): the paper's Fig. 9 job;
- an OFF mesh as a binary STL, for Gmsh, which reads no OFF.
"""

import os
import subprocess
import sys

import numpy as np

SCRIPTS = os.path.dirname(os.path.abspath(__file__))


def read_off(path):
    """Points (n x 3) and triangles (m x 3) of an OFF file of triangles."""
    with open(path) as f:
        tokens = [t for line in f for t in line.split("#", 1)[0].split()]
    i = 1 if tokens[0] == "OFF" else 0
    nv, nf = int(tokens[i]), int(tokens[i + 1])
    i += 3
    points = np.array(tokens[i:i + 3 * nv], dtype=float).reshape(nv, 3)
    i += 3 * nv
    faces = np.array(tokens[i:i + 4 * nf], dtype=np.int64).reshape(nf, 4)
    if (faces[:, 0] != 3).any():
        raise ValueError("%s: only triangles are read" % path)
    return points, faces[:, 1:]


def write_off(path, points, triangles):
    with open(path, "w") as out:
        out.write("OFF\n%d %d 0\n" % (len(points), len(triangles)))
        np.savetxt(out, points, "%.17g")
        np.savetxt(out, np.column_stack([np.full(len(triangles), 3), triangles]), "%d")


def write_binary_stl(path, points, triangles):
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(triangles), dtype=record)
    data["corners"] = points[triangles]
    with open(path, "wb") as out:
        out.write(b"binary STL written by scripts/bench_inputs.py".ljust(80, b" "))
        out.write(np.uint32(len(triangles)).tobytes())
        out.write(data.tobytes())


def split_in_four(points, triangles):
    """Every triangle split into four at its edge midpoints (one new point per edge)."""
    n = len(triangles)
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    unique, which = np.unique(edges, axis=0, return_inverse=True)
    which = which.reshape(-1)
    mid = len(points) + np.arange(len(unique))
    points = np.concatenate([points, 0.5 * (points[unique[:, 0]] + points[unique[:, 1]])])
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    ab, bc, ca = mid[which[:n]], mid[which[n:2 * n]], mid[which[2 * n:]]
    triangles = np.concatenate([np.stack([a, ab, ca], 1), np.stack([ab, b, bc], 1),
                                np.stack([ca, bc, c], 1), np.stack([ab, bc, ca], 1)])
    return points, triangles


def subdivided(source, out_dir, times):
    """`source` (OFF) with every triangle split into four `times` times, written once under
    out_dir and reused; returns its path."""
    stem = os.path.splitext(os.path.basename(source))[0]
    path = os.path.join(out_dir, "%s_split%d.off" % (stem, times))
    if not os.path.exists(path):
        points, triangles = read_off(source)
        for _ in range(times):
            points, triangles = split_in_four(points, triangles)
        write_off(path + ".tmp", points, triangles)
        os.replace(path + ".tmp", path)
    return path


def as_stl(source, out_dir):
    """`source` itself if it is an STL, else an STL copy of it (OFF) written under out_dir."""
    if source.lower().endswith(".stl"):
        return source
    path = os.path.join(out_dir, os.path.splitext(os.path.basename(source))[0] + "_for_gmsh.stl")
    if not os.path.exists(path):
        write_binary_stl(path, *read_off(source))
    return path


# FreeCAD's mesher at a fine setting: the bracket of `make demo` in about 40k triangles.
FINE_LINEAR_DEFLECTION = 0.004  # mm
FINE_ANGULAR_DEFLECTION = 2.75  # degrees


def fine_bracket(out_dir):
    """The demo bracket tessellated finely (make_demo_part.py), written once under out_dir."""
    path = os.path.join(out_dir, "bracket_fine.stl")
    if not os.path.exists(path):
        subprocess.run([sys.executable, os.path.join(SCRIPTS, "make_demo_part.py"), path,
                        "--linear-deflection", str(FINE_LINEAR_DEFLECTION),
                        "--angular-deflection", str(FINE_ANGULAR_DEFLECTION)],
                       check=True, stdout=subprocess.DEVNULL)
    return path
