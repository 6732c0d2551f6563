"""The compiled module `liftremesh`: round trip, bad arrays, cancel, one source of defaults."""
import unittest

import numpy as np

import liftremesh
import mesh_checks


def icosphere(subdivisions=2):
    """Unit icosphere: (n, 3) float64 points, (m, 3) int64 triangles, outward oriented."""
    t = (1.0 + 5.0 ** 0.5) / 2.0
    points = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
              [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    points = [list(np.array(p, float) / np.linalg.norm(p)) for p in points]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
             [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
             [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = np.add(points[a], points[b])
                points.append(list(m / np.linalg.norm(m)))
                middle[key] = len(points) - 1
            return middle[key]

        faces = [f for a, b, c in faces
                 for f in ([a, mid(a, b), mid(c, a)], [b, mid(b, c), mid(a, b)],
                           [c, mid(c, a), mid(b, c)], [mid(a, b), mid(b, c), mid(c, a)])]
    return np.array(points, dtype=np.float64), np.array(faces, dtype=np.int64)


class ModuleTest(unittest.TestCase):
    def setUp(self):
        self.points, self.triangles = icosphere(2)

    def test_round_trip_on_icosphere(self):
        points, triangles, report = liftremesh.remesh(self.points, self.triangles, vertices=300, seed=3)
        self.assertEqual(points.shape, (300, 3))
        self.assertEqual(points.dtype, np.float64)
        self.assertEqual(triangles.shape[1], 3)
        self.assertTrue(np.issubdtype(triangles.dtype, np.integer))
        # closed, oriented, chi 2; every vertex on the unit sphere within the chord error
        self.assertTrue(mesh_checks.is_closed_oriented_manifold(triangles))
        self.assertEqual(mesh_checks.euler_characteristic(points, triangles), 2)
        radii = np.linalg.norm(points, axis=1)
        self.assertLess(np.max(np.abs(radii - 1.0)), 0.02)
        # the report is the CLI's JSON, as a dict, and agrees with the arrays
        self.assertEqual(report["output"]["vertices"], 300)
        self.assertEqual(report["output"]["triangles"], len(triangles))
        self.assertEqual(report["output"]["euler_characteristic"], 2)
        self.assertGreater(report["output"]["kappa_min"], 0.3)
        self.assertEqual(len(report["output"]["kappa_histogram"]), 10)
        self.assertIn("timings", report)
        self.assertLess(report["hausdorff_relative"], 0.01)
        # the same seed gives the same mesh
        again, _, _ = liftremesh.remesh(self.points, self.triangles, vertices=300, seed=3)
        np.testing.assert_array_equal(points, again)

    def test_bad_arrays_raise_value_error_naming_the_problem(self):
        cases = [
            ((self.points[:, :2], self.triangles), "shape"),
            ((self.points, self.triangles.astype(float)), "integer"),
            ((self.points, self.triangles + len(self.points)), "refers to vertex"),
            ((self.points * np.nan, self.triangles), "not finite"),
            ((self.points, self.triangles[:, :2]), "shape"),
            (("not an array", self.triangles), "points"),
            ((self.points + 1j, self.triangles), "complex"),
            ((np.vstack([self.points, [[1e30, 0.0, 0.0]]]), np.vstack([self.triangles, [[0, 1, len(self.points)]]])),
             "far from the rest"),
        ]
        for args, words in cases:
            with self.subTest(words=words):
                with self.assertRaisesRegex(ValueError, words):
                    liftremesh.remesh(*args)
        with self.assertRaisesRegex(ValueError, "sigma"):
            liftremesh.remesh(self.points, self.triangles, sigma=0.5)
        with self.assertRaisesRegex(ValueError, "either"):
            liftremesh.remesh(self.points, self.triangles, vertices=100, edge_length=0.1)
        with self.assertRaisesRegex(ValueError, "mode"):
            liftremesh.remesh(self.points, self.triangles, mode="wobbly")

    def test_the_fuzz_corpus_of_bad_arrays_and_sizes_raises_invalid_input(self):
        """The bad inputs the readers are fuzzed with (tests/fuzz), as arrays: each is refused
        with liftremesh.InvalidInput naming the problem, never a crash, a hang or another error."""
        p, t = self.points, self.triangles
        one_bad = np.zeros(p.shape, bool)
        one_bad[5, 1] = True
        big = t.astype(np.uint64)
        big[3, 2] = np.uint64(2 ** 64 - 1)
        cases = [
            ((np.where(one_bad, np.nan, p), t), {}, "not finite"),
            ((np.where(one_bad, np.inf, p), t), {}, "not finite"),
            ((np.where(one_bad, -np.inf, p), t), {}, "not finite"),
            ((p, np.where(t == 7, len(p), t)), {}, "refers to vertex %d" % len(p)),
            ((p, np.where(t == 7, -3, t)), {}, "refers to vertex -3"),
            ((p, np.where(t == 7, 2 ** 31 + 7, t)), {}, "refers to vertex 2147483655"),  # int64 beyond int32
            ((p, np.where(t == 7, 2 ** 32 + 7, t)), {}, "refers to vertex 4294967303"),  # would wrap to 7
            ((p, big), {}, "refers to vertex"),
            ((np.zeros((0, 3)), np.zeros((0, 3), np.int64)), {}, "empty"),
            ((p, np.zeros((0, 3), np.int64)), {}, "empty"),
            ((np.array([]), np.array([], np.int64)), {}, "shape"),
            ((p.reshape(-1), t), {}, "shape"),
            ((p[None], t), {}, "shape"),
            ((p, t.reshape(-1, 1)), {}, "shape"),
            ((p.astype(str), t), {}, "numbers"),
            ((np.full(p.shape, None, object), t), {}, "numbers"),
            ((p.astype(bool), t), {}, "numbers"),
            ((p, t.astype(bool)), {}, "integer"),
            ((p, t.astype(np.float32)), {}, "integer"),
            ((p, np.array([[0, 0, 1], [2, 2, 2]])), {}, "no triangle of positive area: all 2 have a repeated"),
            ((np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]), np.array([[0, 1, 2]])), {}, "no triangle of positive area"),
            ((p * 1e-300, t), {}, "positive area"),
            ((p * 1e307, t), {}, "positive area"),
            ((p, t), {"vertices": 10 ** 12}, "vertices = 1000000000000 is out of range"),
            ((p, t), {"vertices": 1e12}, "vertices = 1000000000000.0 is out of range"),
            ((p, t), {"vertices": 10 ** 30}, "out of range"),
            ((p, t), {"edge_length": 1e-300}, "edge_length = 1e-300 gives inf vertices"),
            ((p, t), {"edge_length": 1e300}, "gives 0 vertices"),
            ((p, t), {"edge_length": float("nan")}, "out of range"),
            ((p, t), {"iterations": 10 ** 12}, "out of range"),
            ((p, t), {"threads": 10 ** 9}, "out of range"),
            ((p, t), {"seed": 2 ** 70}, "seed = %d is out of range" % 2 ** 70),
            ((p, t), {"seed": -1}, "out of range"),
        ]
        for args, options, words in cases:
            with self.subTest(words=words, options=options):
                with self.assertRaisesRegex(liftremesh.InvalidInput, words):
                    liftremesh.remesh(*args, **options)

    def test_progress_can_cancel(self):
        seen = []

        def progress(stage, iteration, total, energy):
            seen.append((stage, iteration, total, energy))
            return not (stage == "optimize" and iteration >= 5)

        with self.assertRaises(liftremesh.Cancelled):
            liftremesh.remesh(self.points, self.triangles, vertices=300, progress=progress)
        optimize = [s for s in seen if s[0] == "optimize"]
        self.assertEqual(optimize[-1][1], 5)  # stopped at the step that asked
        self.assertEqual(optimize[-1][2], 100)
        self.assertTrue(all(e > 0 for _, i, _, e in optimize if i > 0))
        self.assertTrue(issubclass(liftremesh.Cancelled, liftremesh.Error))

    def test_progress_exception_propagates_unchanged(self):
        def progress(*_):
            raise KeyError("from the callback")

        with self.assertRaises(KeyError):
            liftremesh.remesh(self.points, self.triangles, vertices=100, progress=progress)

    def test_defaults_follow_the_mode_and_match_the_parameter_table(self):
        iso, aniso = liftremesh.defaults("isotropic"), liftremesh.defaults("anisotropic")
        self.assertEqual((iso["nu"], iso["delta"]), (0.01, 0.4))       # Section 6.1
        self.assertEqual((aniso["nu"], aniso["delta"]), (0.05, 0.0))
        names = [row["name"] for row in liftremesh.parameters()]
        for name in names:
            self.assertIn(name, iso)
        self.assertIn("sigma", names)


    def test_parameters_give_kind_range_and_the_defaults_of_each_mode(self):
        rows = liftremesh.parameters()
        self.assertEqual([row["name"] for row in rows], list(liftremesh.defaults()))  # fill_holes too
        for row in rows:
            self.assertIn(row["kind"], ("integer", "real", "choice", "flag"), row["name"])
            for mode, value in row["defaults"].items():
                self.assertEqual(value, liftremesh.defaults(mode)[row["name"]], (row["name"], mode))
            if row["kind"] in ("integer", "real"):
                self.assertIsNotNone(row["min"], row["name"])
                if row["max"] is not None:
                    self.assertLess(row["min"], row["max"], row["name"])
        by_name = {row["name"]: row for row in rows}
        self.assertEqual((by_name["eta"]["min"], by_name["eta"]["min_open"], by_name["eta"]["max"]), (0.0, True, 0.5))
        self.assertEqual(by_name["mode"]["choices"], ["isotropic", "anisotropic"])
        self.assertEqual(by_name["edge_length"]["replaces"], "vertices")
        with self.assertRaises(TypeError):
            liftremesh.remesh(self.points, self.triangles, vertexes=100)
        with self.assertRaises(TypeError):
            liftremesh.remesh(self.points, self.triangles, vertices=100.5)


if __name__ == "__main__":
    unittest.main()
