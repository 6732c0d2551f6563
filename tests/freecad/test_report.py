"""The report's readers, `scripts/report_summary.py` and the task panel's `report_view`, on a real
report: a sphere with a crack (its seam left unwelded, as an STL export can leave one) comes out
closed, and both readers show what the core counted instead of counting it again. And the
report's self-intersections against FreeCAD's own check, on two spheres through each other."""
import json
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np

import liftremesh
import mesh_checks

SOURCE_DIR = os.environ.get("LIFTREMESH_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(mesh_checks.__file__)))))
# scripts/report_summary.py runs on Debian's Python, as `make demo` runs it
PYTHON = "/usr/bin/python3"


def seamed_sphere(rings=16, sectors=32):
    """Unit UV sphere whose seam (longitude 0 and 2 pi, pole to pole) is two rows of vertices a
    rounding error apart: one boundary loop, chi 1. Outward oriented."""
    points = [[0.0, 0.0, 1.0]]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(sectors + 1):  # j = sectors is j = 0 again, not welded
            phi = 2.0 * math.pi * j / sectors
            points.append([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)])
    points.append([0.0, 0.0, -1.0])
    south = len(points) - 1

    def at(i, j):
        return 1 + (i - 1) * (sectors + 1) + j

    triangles = []
    for j in range(sectors):
        triangles.append([0, at(1, j), at(1, j + 1)])
        triangles.append([south, at(rings - 1, j + 1), at(rings - 1, j)])
        for i in range(1, rings - 1):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            triangles += [[a, b, c], [a, c, d]]
    return np.array(points, dtype=np.float64), np.array(triangles, dtype=np.int64)


class CrackedSphereReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        points, triangles = seamed_sphere()
        cls.input_chi = mesh_checks.euler_characteristic(points, triangles)
        cls.points, cls.triangles, cls.report = liftremesh.remesh(points, triangles, vertices=500, seed=1)

    def test_the_core_counts_the_crack_it_closes(self):
        self.assertEqual(self.input_chi, 1)
        self.assertTrue(mesh_checks.is_closed_oriented_manifold(self.triangles))
        self.assertEqual(mesh_checks.euler_characteristic(self.points, self.triangles), 2)
        self.assertEqual(self.report["input"]["boundary_loops"], 1)
        self.assertEqual(self.report["cracks_closed"], 1)
        self.assertEqual(self.report["vertex_fans_split"], 0)
        self.assertEqual(self.report["expected_euler_characteristic"], 2)
        self.assertEqual(self.report["warnings"], [])

    def summary(self, report):
        """(exit code, stdout) of report_summary.py --check on this report."""
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "report.json")
            with open(path, "w") as f:
                json.dump(report, f)
            run = subprocess.run([PYTHON, os.path.join(SOURCE_DIR, "scripts", "report_summary.py"), path, "--check"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=60)
        return run.returncode, run.stdout + run.stderr

    def test_report_summary_reads_the_counts(self):
        status, text = self.summary(self.report)
        self.assertEqual(status, 0, text)
        self.assertIn("closed 2-manifold with the input's topology, 1 crack(s) of the input closed", text)
        # The seam's duplicated vertices: corners of one side on triangles of the other (touches).
        self.assertIn("self-intersections %d -> 0" % self.report["input"]["self_intersections"], text)
        # It checks the output against the core's expected chi, not against a rule of its own:
        # the same report expecting another chi fails the check.
        other = dict(self.report, expected_euler_characteristic=1)
        status, text = self.summary(other)
        self.assertEqual(status, 1, text)
        self.assertIn("NOT the input's topology", text)
        # Triangles passing through each other fail the check where the input has none.
        crossing = dict(self.report, input=dict(self.report["input"], self_intersections=0),
                        output=dict(self.report["output"], self_intersections=3))
        status, text = self.summary(crossing)
        self.assertEqual(status, 1, text)
        self.assertIn("NOT free of self-intersections: 3 pairs of triangles pass through each other", text)
        crossing["input"] = dict(self.report["input"], self_intersections=5)
        status, text = self.summary(crossing)
        self.assertEqual(status, 0, text)
        self.assertIn("self-intersections 5 -> 3", text)
        # Several solids, one kept as it was: said, and no failure.
        status, text = self.summary(dict(self.report, parts=3, parts_kept=1))
        self.assertEqual(status, 0, text)
        self.assertIn("3 parts remeshed one by one (1 with the source's triangles)", text)
        self.assertNotIn("parts remeshed", self.summary(self.report)[1])
        # A report without the counts is refused, naming the key.
        lacking = dict(self.report)
        del lacking["cracks_closed"]
        status, text = self.summary(lacking)
        self.assertEqual(status, 2, text)
        self.assertIn("cracks_closed", text)

    def test_the_task_panel_shows_the_counts(self):
        from LiftRemesh.gui import report_view

        html = report_view.report_html(self.report)
        self.assertIn("1 crack(s) of the source closed", html)
        self.assertNotIn("fan(s)", html)
        self.assertNotIn("Warning", html)
        html = report_view.report_html(dict(self.report, cracks_closed=0, vertex_fans_split=2))
        self.assertNotIn("crack(s)", html)
        self.assertIn("2 fan(s) of the source's non-manifold vertices split", html)
        self.assertNotIn("parts remeshed", html)
        html = report_view.report_html(dict(self.report, parts=3))
        self.assertIn("3 parts remeshed one by one", html)
        self.assertNotIn("facet(s) of the source", html)
        html = report_view.report_html(dict(self.report, input_duplicates_removed=10, input_degenerate_removed=3,
                                            input_facets_turned=52))
        self.assertIn("10 repeated facet(s) of the source dropped, 3 degenerate facet(s) of the source dropped, "
                      "52 facet(s) of the source turned", html)


class SelfIntersectionReport(unittest.TestCase):
    """Two spheres through each other, as one mesh (an assembly exported as one STL): the report
    counts pairs of triangles passing through each other in the source and in the result, and so
    does FreeCAD's Mesh workbench (Mesh.hasSelfIntersections). The two agree on whether there are
    any, not on the count: FreeCAD's test (single-precision points, a tolerance) was measured to
    miss shallow crossings and to list pairs that do not meet in exact arithmetic (30 and 9 on
    the result at 4000 vertices, d = 1.5), and lists some pairs twice."""

    @classmethod
    def setUpClass(cls):
        import Mesh
        from LiftRemesh import meshing

        cls.source = Mesh.createSphere(1.0, 20)
        other = Mesh.createSphere(0.8, 24)
        other.translate(1.0, 0.1, 0.05)
        cls.source.addMesh(other)
        points, triangles = mesh_checks.arrays(cls.source)
        cls.points, cls.triangles, cls.report = liftremesh.remesh(points, triangles, vertices=1500, seed=1)
        cls.result = meshing.arrays_to_mesh(cls.points, cls.triangles)

    def test_the_report_and_freecads_check_agree(self):
        import Mesh
        from LiftRemesh import meshing

        self.assertTrue(self.source.hasSelfIntersections())
        self.assertGreater(self.report["input"]["self_intersections"], 0)
        self.assertTrue(self.result.hasSelfIntersections())
        self.assertGreater(self.report["output"]["self_intersections"], 0)
        warnings = [w for w in self.report["warnings"] if "passing through each other" in w]
        self.assertEqual(len(warnings), 1, self.report["warnings"])
        # one of the spheres alone: none, by either
        alone = Mesh.createSphere(1.0, 20)
        points, triangles, report = liftremesh.remesh(*mesh_checks.arrays(alone), vertices=800, seed=1)
        remeshed = meshing.arrays_to_mesh(points, triangles)
        self.assertFalse(alone.hasSelfIntersections())
        self.assertEqual(report["input"]["self_intersections"], 0)
        self.assertFalse(remeshed.hasSelfIntersections())
        self.assertEqual(report["output"]["self_intersections"], 0)

    def test_the_task_panel_shows_the_count(self):
        from LiftRemesh.gui import report_view

        html = report_view.report_html(self.report)
        row = "<tr><td>self-intersections</td><td align=\"right\">%d</td><td align=\"right\"><b>%d</b></td></tr>" % (
            self.report["input"]["self_intersections"], self.report["output"]["self_intersections"])
        self.assertIn(row, html)
        self.assertIn("passing through each other", html)


if __name__ == "__main__":
    unittest.main()
