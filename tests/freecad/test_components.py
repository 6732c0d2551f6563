"""Components and orientation: `liftremesh.components` on surfaces built here, and the frame of the
issue, rebuilt with FreeCAD's Part module: a 300 x 200 x 12 mm plate cut into 3 mm members by a grid
of rectangular holes, with a round hole at every crossing, tessellated as FreeCAD's STL export does
and remeshed at 6000 vertices. Its remesh closes small bubbles between the thin members, most of
them inside-out; they must not reach the result unsaid: the core removes them, counts them and warns.
"""
import unittest

import numpy as np

import FreeCAD
import Part

import liftremesh
from LiftRemesh import meshing

V = FreeCAD.Vector


def frame(width=300.0, height=200.0, thickness=12.0, member=3.0, columns=8):
    """The plate with a grid of `columns` x 2/3 columns rectangular holes leaving members `member`
    wide, and a round hole of 0.6 member diameter at every crossing."""
    rows = columns * 2 // 3
    cw, ch = (width - member) / columns, (height - member) / rows
    cells = [Part.makeBox(cw - member, ch - member, thickness + 2, V(member + i * cw, member + j * ch, -1))
             for i in range(columns) for j in range(rows)]
    shape = Part.makeBox(width, height, thickness).cut(Part.makeCompound(cells))
    pins = [Part.makeCylinder(0.3 * member, thickness + 2, V(member / 2 + i * cw, member / 2 + j * ch, -1))
            for i in range(columns + 1) for j in range(rows + 1)]
    return shape.cut(Part.makeCompound(pins))


def box(lo, hi, inside_out=False):
    """(points (8, 3), triangles (12, 3)) of the box [lo, hi], facing outward (or inward)."""
    x = np.array([[hi[0] if c & 1 else lo[0], hi[1] if c & 2 else lo[1], hi[2] if c & 4 else lo[2]]
                  for c in range(8)], dtype=np.float64)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = np.array([tri for a, b, c, d in quads for tri in ((a, b, c), (a, c, d))], dtype=np.int64)
    return x, (t[:, [0, 2, 1]] if inside_out else t)


def joined(*parts):
    points, triangles, offset = [], [], 0
    for p, t in parts:
        points.append(p)
        triangles.append(t + offset)
        offset += len(p)
    return np.vstack(points), np.vstack(triangles)


class ComponentsBinding(unittest.TestCase):
    def test_two_boxes_one_inside_out_a_cavity_and_an_open_patch(self):
        points, triangles = joined(box((0, 0, 0), (4, 4, 4)), box((1, 1, 1), (2, 3, 2), inside_out=True),
                                   box((10, 0, 0), (11, 1, 1), inside_out=True))
        patch = np.array([[0, 1, 2]], dtype=np.int64) + len(points)
        points = np.vstack([points, [[20.0, 0, 0], [21.0, 0, 0], [20.0, 1.0, 0]]])
        found = liftremesh.components(points, np.vstack([triangles, patch]))
        np.testing.assert_array_equal(found["closed"], [True, True, True, False])
        np.testing.assert_allclose(found["signed_volume"][:3], [64.0, -2.0, -1.0], rtol=1e-12)
        self.assertTrue(np.isnan(found["signed_volume"][3]))
        np.testing.assert_array_equal(found["cavity"], [False, True, False, False])  # inside the first box
        np.testing.assert_allclose(found["area"], [96.0, 10.0, 6.0, 0.5], rtol=1e-12)
        np.testing.assert_array_equal(found["triangles"], [12, 12, 12, 1])
        np.testing.assert_array_equal(found["label"], [0] * 12 + [1] * 12 + [2] * 12 + [3])

    def test_bad_arrays_are_invalid_input(self):
        points, triangles = box((0, 0, 0), (1, 1, 1))
        with self.assertRaisesRegex(liftremesh.InvalidInput, "refers to vertex 8"):
            liftremesh.components(points, np.vstack([triangles, [[0, 1, 8]]]))
        with self.assertRaisesRegex(liftremesh.InvalidInput, r"shape \(n, 3\)"):
            liftremesh.components(points[:, :2], triangles)


class StrayPiecesOfAFrame(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.shape = frame()
        cls.assertTrue(cls, cls.shape.isValid())
        mesh = meshing.tessellate(cls.shape, 0.1, 30.0)  # degrees: the STL export's defaults
        points, triangles = meshing.mesh_to_arrays(mesh)
        cls.points, cls.triangles, cls.report = liftremesh.remesh(points, triangles, vertices=6000)

    def test_stray_pieces_are_removed_counted_and_warned(self):
        report = self.report
        self.assertEqual((report["input"]["components"], report["input"]["inward_components"]), (1, 0))
        self.assertGreater(report["stray_components_removed"], 0)
        self.assertGreater(report["stray_inward_removed"], 0)
        self.assertTrue(any("small closed pieces standing for no part of the source" in w or
                            "small closed piece standing" in w for w in report["warnings"]), report["warnings"])

    def test_the_result_is_one_closed_piece_facing_outward(self):
        """As the input is, and as the report says (its volume is the frame's less the members the
        remesh merged or thinned: the size field's matter, not this one's)."""
        found = liftremesh.components(self.points, self.triangles)
        self.assertEqual(len(found["closed"]), 1, found["signed_volume"])
        self.assertTrue(found["closed"][0])
        self.assertGreater(found["signed_volume"][0], 0.5 * self.shape.Volume)
        output = self.report["output"]
        self.assertEqual((output["components"], output["inward_components"]), (1, 0))
        self.assertAlmostEqual(output["component_list"][0]["signed_volume"], found["signed_volume"][0],
                               delta=1e-6 * self.shape.Volume)

    @unittest.skip("known gap (docs/known-gaps.md, thin parts): issue 35 asks the frame kept at 6000 "
                   "vertices, where its edges would be about 4.5 mm, wider than its 3 mm members; a ring of "
                   "well-shaped triangles round each member takes about 13,000 vertices, where "
                   "FrameAtTheSizeItsMembersNeed asserts it (-78 for -186 here, kappa min 0.05)")
    def test_the_frame_keeps_its_topology(self):
        assert_frame_kept(self, self.report["output"])


def assert_frame_kept(test, output):
    """The frame's topology kept (one closed piece facing outward, Euler characteristic -186),
    nothing folded shut or crossing, no triangle under kappa 0.3: `output` is a report's."""
    test.assertEqual(output["euler_characteristic"], -186)
    test.assertEqual((output["components"], output["inward_components"]), (1, 0))
    test.assertEqual((output["folded_edges"], output["self_intersections"]), (0, 0))
    test.assertGreaterEqual(output["kappa_min"], 0.3)


class FrameAtTheSizeItsMembersNeed(unittest.TestCase):
    """The frame at 13,000 vertices, about the count its 3 mm members need for a ring of well-shaped
    triangles round them (at 6000 its edges would be wider than its members). The default eta-ball,
    3.6 mm here, is wider than its 1.8 mm pin holes and the 0.6 mm walls round them: the normals of
    a hole's wall and of the faces beside it are averaged together, and the remesh merged members
    (Euler characteristic -180 for -186). The part is lifted again with normals over balls a
    quarter of the edge length wide, and that run, which keeps the topology, is the one kept."""

    @classmethod
    def setUpClass(cls):
        mesh = meshing.tessellate(frame(), 0.1, 30.0)
        points, triangles = meshing.mesh_to_arrays(mesh)
        cls.points, cls.triangles, cls.report = liftremesh.remesh(points, triangles, vertices=13000)

    def test_the_topology_is_kept_and_the_warning_says_how(self):
        report = self.report
        self.assertEqual(report["input"]["euler_characteristic"], -186)
        self.assertEqual(report["output"]["euler_characteristic"], -186)
        self.assertEqual(report["parts_eta_reduced"], 1)
        self.assertTrue(any("averaged over balls a quarter of the target edge length" in w
                            for w in report["warnings"]), report["warnings"])
        self.assertFalse(any("topology" in w for w in report["warnings"]), report["warnings"])

    def test_a_closed_piece_near_the_part(self):
        found = liftremesh.components(self.points, self.triangles)
        self.assertEqual(list(found["closed"]), [True])
        self.assertEqual(self.report["output"]["folded_edges"], 0)
        # 0.45% when the members merged.
        self.assertLess(self.report["hausdorff_relative"], 0.0025)

    def test_no_triangle_under_kappa_0_3(self):
        # 0.299 when a triangle across a 0.6 mm wall round a pin hole, standing on the outer
        # crease, kept it: a split of its crease edge alone made a worse one (edge_collapse.h).
        self.assertGreaterEqual(self.report["output"]["kappa_min"], 0.3)
        self.assertEqual(self.report["output"]["self_intersections"], 0)


class FrameAtTheSizeItsMembersNeedOnOtherSeeds(unittest.TestCase):
    """The same on seeds 2 and 3: the topology kept with no triangle under kappa 0.3. Seed 2 had
    0.150 where the untangling took out a tent standing through the 0.6 mm wall between a pin
    hole of the outer member (x = 261.4) and the outer face: the triangle of its rim is mended
    now as the polish's are (pipeline.cpp)."""

    @classmethod
    def setUpClass(cls):
        mesh = meshing.tessellate(frame(), 0.1, 30.0)
        cls.input = meshing.mesh_to_arrays(mesh)

    def test_seeds_2_and_3(self):
        for seed in (2, 3):
            with self.subTest(seed=seed):
                _, _, report = liftremesh.remesh(*self.input, vertices=13000, seed=seed)
                assert_frame_kept(self, report["output"])


class FrameAtTwentyThousandVertices(unittest.TestCase):
    """The frame at 20,000 vertices, seed 1: the topology kept with no triangle under kappa 0.3.
    A crease's point inserted beside triangles that crossed others (a pin hole's 0.6 mm wall,
    thinner than the edges) was one more vertex for the untangling to move, under kappa 0.2,
    and it made a needle of 0.246 there: the creases the output's pass far from get no vertex
    within 2 h of such triangles (pipeline.cpp)."""

    def test_seed_1(self):
        mesh = meshing.tessellate(frame(), 0.1, 30.0)
        _, _, report = liftremesh.remesh(*meshing.mesh_to_arrays(mesh), vertices=20000, seed=1)
        assert_frame_kept(self, report["output"])


class FrameAtThirtyThousandVertices(unittest.TestCase):
    """The frame finer, at 30,000 vertices (edges of about 2 mm) on seeds 1-3: the topology kept
    with no triangle under kappa 0.3. Seed 3 had 0.223 on the wall of a 1.8 mm pin hole, whose
    bottom rim the output had cut: a vertex of the part's face 0.35 mm beside it, joined up the
    wall. The crease snap could not move it onto the rim while the triangle to the next rim vertex
    would have spanned the bore (a chord 0.45 mm inside it); it can once the mending has split a
    vertex onto the rim beside it, with the flip that mends the triangle up the wall, whose new
    diagonal is a deeper chord of the bore (pipeline.cpp, crease_snap.h)."""

    @classmethod
    def setUpClass(cls):
        mesh = meshing.tessellate(frame(), 0.1, 30.0)
        cls.input = meshing.mesh_to_arrays(mesh)

    def test_seeds_1_to_3(self):
        for seed in (1, 2, 3):
            with self.subTest(seed=seed):
                _, _, report = liftremesh.remesh(*self.input, vertices=30000, seed=seed)
                assert_frame_kept(self, report["output"])


if __name__ == "__main__":
    unittest.main()
