"""An installed `liftremesh` (a wheel, `pip install .`) loads and remeshes: no FreeCAD needed.

    python tests/python/check_wheel.py [--not-under DIR]

Remeshes an octahedron subdivided onto the unit sphere to 200 vertices and checks the output is
a closed, consistently oriented surface of Euler characteristic 2 on the sphere. With
--not-under DIR it also checks the module was not loaded from DIR (a source or build tree).
cibuildwheel runs it as its test-command. Exits non-zero on any failure.
"""
import os
import sys
from collections import Counter

import numpy as np


def sphere(levels=3):
    points = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    faces = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    for _ in range(levels):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = np.add(points[a], points[b]) / 2.0
                points.append(list(m / np.linalg.norm(m)))
                middle[key] = len(points) - 1
            return middle[key]

        faces = [f for a, b, c in faces
                 for f in ([a, mid(a, b), mid(c, a)], [b, mid(b, c), mid(a, b)],
                           [c, mid(c, a), mid(b, c)], [mid(a, b), mid(b, c), mid(c, a)])]
    return np.array(points, dtype=np.float64), np.array(faces, dtype=np.int64)


def main(argv):
    import liftremesh

    where = os.path.realpath(liftremesh.__file__)
    if "--not-under" in argv:
        tree = os.path.realpath(argv[argv.index("--not-under") + 1])
        assert not where.startswith(tree + os.sep), "liftremesh loaded from %s, inside %s" % (where, tree)
    points, triangles = sphere()
    out_points, out_triangles, report = liftremesh.remesh(points, triangles, vertices=200, seed=1)
    assert out_points.shape == (200, 3), out_points.shape
    # closed and oriented: every directed edge once, and its reverse once
    directed = Counter((int(t[i]), int(t[(i + 1) % 3])) for t in out_triangles for i in range(3))
    assert all(n == 1 for n in directed.values()), "an edge is used twice the same way"
    assert all((b, a) in directed for a, b in directed), "an edge has one triangle"
    chi = len(out_points) - len(directed) // 2 + len(out_triangles)
    assert chi == 2, chi
    radii = np.linalg.norm(out_points, axis=1)
    assert np.max(np.abs(radii - 1.0)) < 0.05, np.max(np.abs(radii - 1.0))
    print("check_wheel: liftremesh %s from %s: 200 vertices, %d triangles, chi 2, kappa min %.3f"
          % (getattr(liftremesh, "__version__", "?"), where, len(out_triangles),
             report["output"]["kappa_min"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
