#!/usr/bin/python3
"""Gmsh's remeshing of an STL, timed: the recipe of Gmsh's tutorial t13 (classifySurfaces at 40
degrees, createGeometry, generate(2)), the one ../shared/PEERS.md measured, with the mesh size
of an equilateral mesh of the same area with the vertices asked for. Prints one line of JSON:
wall seconds from reading the file to the end of generate(2), the output's vertices and
triangles, and its kappa (Eq. 26) min and mean; or {"error": ...} when Gmsh fails.

    /usr/bin/python3 scripts/bench_gmsh.py MESH.stl VERTICES

bench.py calls timed(), which runs this file in a process of its own.
Gmsh runs single-threaded (General.NumThreads 1), as in PEERS.md. Needs the Debian packages
gmsh and python3-gmsh (scripts/install-deps.sh, optional).
"""

import json
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "freecad"))
from mesh_checks import kappa  # noqa: E402  (Eq. 26, measured independently of LiftRemesh)


def mesh_arrays(gmsh):
    """The current model's nodes and triangles as arrays (triangles as row numbers of the nodes)."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    points = np.asarray(coords).reshape(-1, 3)
    row = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    row[tags.astype(np.int64)] = np.arange(len(tags))
    _, node_tags = gmsh.model.mesh.getElementsByType(2)
    return points, row[np.asarray(node_tags, dtype=np.int64)].reshape(-1, 3)


def timed(source, vertices, out_dir, repeat=1):
    """Gmsh on `source` (an OFF file is converted to STL first) in a process of its own, the
    fastest of `repeat` runs: the dict main() prints, or {"error": ...}."""
    import subprocess
    import bench_inputs
    try:
        import gmsh  # noqa: F401
    except ImportError:
        return {"error": "Gmsh not installed (python3-gmsh)"}
    path = bench_inputs.as_stl(source, out_dir)
    best = None
    for _ in range(max(1, repeat)):
        sys.stderr.write("bench: gmsh %s %d\n" % (path, vertices))
        proc = subprocess.run([sys.executable, os.path.abspath(__file__), path, str(vertices)],
                              capture_output=True, text=True, timeout=1800)
        lines = proc.stdout.strip().splitlines()
        result = json.loads(lines[-1]) if lines else {"error": "Gmsh exited %d" % proc.returncode}
        if "error" in result:
            return result
        if best is None or result["wall"] < best["wall"]:
            best = result
    return best


def main():
    path, vertices = sys.argv[1], int(sys.argv[2])
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    try:
        start = time.monotonic()
        gmsh.merge(path)
        points, triangles = mesh_arrays(gmsh)
        a, b, c = (points[triangles[:, i]] for i in range(3))
        area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
        # An equilateral mesh of V vertices has about 2 V triangles of area sqrt(3)/4 h^2.
        size = math.sqrt(2.0 * area / (math.sqrt(3.0) * vertices))
        gmsh.model.mesh.classifySurfaces(math.radians(40.0), True, True, math.radians(180.0))
        gmsh.model.mesh.createGeometry()
        gmsh.option.setNumber("Mesh.MeshSizeMin", size)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.model.mesh.generate(2)
        wall = time.monotonic() - start
        points, triangles = mesh_arrays(gmsh)
        used = np.unique(triangles)
        k = kappa(points, triangles)
        print(json.dumps({"wall": wall, "vertices": int(len(used)), "triangles": int(len(triangles)),
                          "kappa_min": float(k.min()), "kappa_mean": float(k.mean())}))
    except Exception as e:  # Gmsh raises Exception with its own message
        print(json.dumps({"error": str(e).splitlines()[0] if str(e) else type(e).__name__}))
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
