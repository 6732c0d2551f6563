"""FEM solid hand-off (LiftRemesh.fem_solid): the demo bracket remeshed and filled with tet10
elements by TetGen, checked with FreeCAD FEM's own tools and, with CalculiX, solved and compared
with the same analysis on FreeCAD FEM's own Gmsh mesh of the B-rep; then the STL-only path.

The analysis: steel, the walls of the two mounting holes fixed (bolted), FORCE downwards on the
boss's top face; the largest displacement is compared.
Without `ccx` (Debian 13 has no calculix-ccx) the analyses say they skipped; without `gmsh` the
comparison does. Figures (displacements, element quality) are printed.
"""
import math
import os
import re
import shutil
import sys
import tempfile
import time
import unittest
from unittest import mock

import numpy as np

import FreeCAD
import Mesh
import MeshPart
import ObjectsFem
import Part
from femmesh import meshtools
from femtools import ccxtools

import fem_compat
import LiftRemesh
from LiftRemesh import fem, fem_solid, native, tet_mesh, tetgen

sys.path.insert(0, os.path.join(native.ADDON_ROOT, "scripts"))
from demo_bracket import make_bracket  # noqa: E402

EDGE_LENGTH = 2.5          # mm, remesh target and Gmsh's CharacteristicLengthMax
FORCE = 2000.0             # N, downwards on the boss top
YOUNGS_MODULUS = 210000.0  # MPa
AGREEMENT = 0.05           # largest displacements within 5% of the B-rep Gmsh mesh's
RESULTS = {}               # largest displacement per mesh, shared by the tests of this module
HOLE_AXES = (12.0, 38.0)   # y of the mounting holes' axes (x = 14), scripts/demo_bracket.py


def planar_face(shape, test):
    """"FaceN" of the one planar face of `shape` for which test(face) holds."""
    names = ["Face%d" % i for i, f in enumerate(shape.Faces, 1)
             if f.Surface.TypeId == "Part::GeomPlane" and test(f)]
    assert len(names) == 1, names
    return names[0]


def hole_faces(shape):
    """"FaceN" of the faces of `shape` on the walls of the two mounting holes (radius 4 about the
    vertical axes through (14, 12) and (14, 38)): the B-rep's cylinders, or the faceted solid's
    triangles there (every vertex at that radius, a horizontal normal)."""
    names = []
    for i, face in enumerate(shape.Faces, 1):
        for y in HOLE_AXES:
            radii = [math.hypot(v.Point.x - 14.0, v.Point.y - y) for v in face.Vertexes]
            centre = face.CenterOfMass
            if all(abs(r - 4.0) < 0.15 for r in radii) and \
                    abs(face.normalAt(*face.Surface.parameter(centre)).z) < 0.5:
                names.append("Face%d" % i)
    return names


def bracket_faces(shape):
    """The fixed faces (the mounting holes' walls: bolted) and the loaded one (the boss's top,
    z = 22): faces bounded by creases, whose every element face the FEM mesh has (the test below)."""
    eps = 1e-4
    return {"fixed": hole_faces(shape),
            "loaded": ["Face%d" % i for i, f in enumerate(shape.Faces, 1)
                       if f.Surface.TypeId == "Part::GeomPlane" and f.BoundBox.ZMin > 22.0 - eps]}


def document_state(doc):
    return [(o.Name, o.Label, o.TypeId) for o in doc.Objects]


def mesh_feature(doc, mesh, source=None, name="Remesh"):
    """A Mesh::Feature holding `mesh`, its Source linking `source` as the remesh feature's does."""
    obj = doc.addObject("Mesh::Feature", name)
    obj.Mesh = mesh
    if source is not None:
        obj.addProperty("App::PropertyLink", "Source", "Base", "the remeshed shape")
        obj.Source = source
    doc.recompute()
    return obj


def element_table(fem_mesh):
    """(corners (m, 4), all nodes (m, k)) of the volume elements, node ids."""
    rows = np.array([fem_mesh.getElementNodes(v) for v in sorted(fem_mesh.Volumes)])
    return rows[:, :4], rows


def print_quality(what, quality):
    print("\n%s: minimum dihedral angle %.1f deg, radius ratio worst %.3f, mean %.3f"
          % (what, quality["min_dihedral_deg"], quality["radius_ratio_min"], quality["radius_ratio_mean"]))


def solve(test, doc, fem_obj, part, faces, name):
    """A CalculiX static analysis of fem_obj (steel, faces["fixed"] fixed, FORCE down on
    faces["loaded"]); returns (largest displacement in mm, reaction force along z in N)."""
    if not shutil.which("ccx"):
        test.skipTest("calculix-ccx not installed: the meshing is checked, the analysis skipped")
    analysis = ObjectsFem.makeAnalysis(doc, "Analysis" + name)
    solver = fem_compat.make_solver_ccx_tools(doc, "Solver" + name)
    solver.AnalysisType = "static"
    solver.GeometricalNonlinearity = "linear"
    analysis.addObject(solver)
    material = ObjectsFem.makeMaterialSolid(doc, "Steel" + name)
    values = material.Material
    values.update({"Name": "Steel", "YoungsModulus": "%g MPa" % YOUNGS_MODULUS, "PoissonRatio": "0.30"})
    material.Material = values
    analysis.addObject(material)
    fixed = ObjectsFem.makeConstraintFixed(doc, "Fixed" + name)
    fixed.References = [(part, tuple(faces["fixed"]))]
    analysis.addObject(fixed)
    force = ObjectsFem.makeConstraintForce(doc, "Force" + name)
    force.References = [(part, tuple(faces["loaded"]))]
    fem_compat.set_force(force, FORCE)
    force.Direction = (part, faces["loaded"][:1])
    doc.recompute()
    if force.DirectionVector.z > 0:
        force.Reversed = True
        doc.recompute()
    test.assertAlmostEqual(force.DirectionVector.z, -1.0, places=9)
    analysis.addObject(force)
    analysis.addObject(fem_obj)
    doc.recompute()

    work_dir = tempfile.mkdtemp(prefix="liftremesh_solid_")
    test.addCleanup(shutil.rmtree, work_dir, True)
    tools = ccxtools.FemToolsCcx(analysis, solver, test_mode=False)
    tools.update_objects()
    tools.setup_working_dir(work_dir)
    test.assertEqual(tools.check_prerequisites(), "")
    tools.write_inp_file()
    test.assertEqual(tools.ccx_run(), 0, tools.ccx_stdout[-2000:] if tools.ccx_stdout else "")
    tools.load_results()
    result = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")][0]
    displacements = list(result.DisplacementLengths)
    test.assertTrue(all(math.isfinite(d) for d in displacements))
    dat = [o for o in analysis.Group if o.TypeId == "App::TextDocument"][0].Text
    totals = re.search(r"total force \(fx,fy,fz\) for set FIXED\S*.*\n\s*\n\s*(\S+)\s+(\S+)\s+(\S+)", dat)
    test.assertIsNotNone(totals, dat)
    return max(displacements), float(totals.group(3))


class BracketSolidTest(unittest.TestCase):
    """The demo bracket: remeshed, filled with tet10 elements tied to the B-rep, and solved."""

    @classmethod
    def setUpClass(cls):
        cls.shape = make_bracket(Part, FreeCAD.Vector)
        cls.mesh = LiftRemesh.remesh_shape(cls.shape, edge_length=EDGE_LENGTH)
        cls.doc = FreeCAD.newDocument("LiftRemeshSolidTest")
        cls.part = cls.doc.addObject("Part::Feature", "Bracket")
        cls.part.Shape = cls.shape
        cls.remeshed = mesh_feature(cls.doc, cls.mesh, cls.part)
        cls.fem_obj = LiftRemesh.make_fem_solid(cls.doc, cls.remeshed)
        cls.faces = bracket_faces(cls.shape)

    @classmethod
    def tearDownClass(cls):
        FreeCAD.closeDocument(cls.doc.Name)

    def test_all_elements_are_tet10_and_the_boundary_is_the_remeshed_surface(self):
        fem_mesh = self.fem_obj.FemMesh
        self.assertEqual((self.fem_obj.Name, self.fem_obj.Label), ("Remesh_Solid", "Remesh_Solid"))
        self.assertEqual(self.fem_obj.Part, self.part)  # FEM's link to the shape (meshsetsgetter.py)
        self.assertGreater(fem_mesh.VolumeCount, self.mesh.CountFacets)
        self.assertEqual(fem_mesh.TetraCount, fem_mesh.VolumeCount)
        self.assertEqual((fem_mesh.FaceCount, fem_mesh.EdgeCount), (0, 0))
        table = meshtools.get_femelement_table(fem_mesh)
        self.assertEqual(meshtools.get_femmesh_eletype(fem_mesh, table), "tetra10")
        self.assertEqual(sorted(fem_mesh.Nodes), list(range(1, fem_mesh.NodeCount + 1)))

        # the faces of one tetrahedron only are the remeshed triangles, nodes 1..n its points
        corners, _ = element_table(fem_mesh)
        points, facets = self.mesh.Topology
        boundary = {tuple(f) for f in tet_mesh.boundary_faces(corners - 1).tolist()}
        self.assertEqual(boundary, {tuple(sorted(f)) for f in facets})
        nodes = fem_mesh.Nodes
        lengths = tet_mesh.local_edge_lengths(np.array([tuple(p) for p in points]), np.array(facets))
        moves = [(nodes[i + 1] - p).Length / lengths[i] for i, p in enumerate(points)]
        # put on the B-rep, not moved further: fem.FACE_SNAP, then fem_solid.CREASE_SNAP
        self.assertLess(max(moves), fem_solid.fem.FACE_SNAP + fem_solid.CREASE_SNAP)

        # FreeCAD's orientation: the fourth corner on the negative side, no element inverted
        xyz = np.array([tuple(nodes[n]) for n in range(1, fem_mesh.NodeCount + 1)])
        self.assertTrue(np.all(tet_mesh.signed_volumes(xyz, corners - 1) < 0.0))
        quality = tet_mesh.element_quality(xyz, corners - 1)
        print_quality("bracket, %d tet10 elements" % fem_mesh.VolumeCount, quality)
        self.assertGreater(quality["min_dihedral_deg"], 3.0)
        self.assertGreater(quality["radius_ratio_mean"], 0.7)

    def test_middle_nodes_of_the_boundary_are_on_the_edges_or_on_the_shape(self):
        fem_mesh = self.fem_obj.FemMesh
        _, rows = element_table(fem_mesh)
        nodes = fem_mesh.Nodes
        xyz = {n: np.array(tuple(p)) for n, p in nodes.items()}
        middles = tet_mesh.boundary_middles(rows - 1, np.array(self.mesh.Topology[1]))
        self.assertEqual(len(middles), self.mesh.CountEdges)
        top = self.shape.getElement(self.faces["loaded"][0])
        on_top = set(fem_mesh.getNodesByFace(top))
        for (a, b), m in middles.items():
            chord = xyz[a + 1] - xyz[b + 1]
            off = np.linalg.norm(xyz[m + 1] - (xyz[a + 1] + xyz[b + 1]) / 2)
            # a chord's sagitta on the curved faces: at most fem.FACE_SNAP, fem_solid.CREASE_SNAP
            # times the split surface's edge lengths (about half the chord)
            self.assertLess(off, 0.25 * np.linalg.norm(chord))
            if a + 1 in on_top and b + 1 in on_top:  # on a planar face (a chord of its rim: on the rim)
                self.assertLess(abs(xyz[m + 1][2] - 22.0), 1e-9)
        self.assertEqual(len(tet_mesh.inverted_elements(np.array([xyz[n] for n in sorted(xyz)]), rows - 1)), 0)

    def test_constraints_on_the_shape_find_every_node_of_their_faces(self):
        """The faces bounded by creases (the plate's bottom, the boss's top, the bore, the holes)
        get all six nodes of every element face on them, and those element faces cover their area
        (the CalculiX writer's face table): a load on them is applied in full. The faces that meet
        their neighbours tangentially (fillets) are covered in part only (docs/known-gaps.md)."""
        fem_mesh = self.fem_obj.FemMesh
        table = meshtools.get_femelement_table(fem_mesh)
        bottom = planar_face(self.shape, lambda f: f.BoundBox.ZMax < 1e-4)
        bore = [n for n in ("Face%d" % i for i in range(1, len(self.shape.Faces) + 1))
                if getattr(self.shape.getElement(n).Surface, "Radius", None) == 6.5]
        self.assertEqual(len(bore), 1)
        names = self.faces["fixed"] + self.faces["loaded"] + [bottom] + bore
        self.assertEqual(len(names), 5)
        for name in names:
            face = self.shape.getElement(name)
            with self.subTest(face=name, surface=face.Surface.TypeId):
                face_table = meshtools.get_ref_facenodes_table(fem_mesh, table, face)
                self.assertTrue(all(len(ns) == 6 for ns in face_table.values()))
                areas = meshtools.get_ref_facenodes_areas(fem_mesh.Nodes, face_table)
                total = sum(area for _, area in areas)
                self.assertAlmostEqual(total / face.Area, 1.0, delta=0.01)

    @unittest.skip("known gap (docs/known-gaps.md): faces meeting their neighbours tangentially, such "
                   "as the 2 mm foot fillet (about 20% covered), have no crease for the remesher to follow")
    def test_every_face_of_the_shape_is_covered_by_element_faces(self):
        """The literal aim: a load on any face of the part, fillets included, is applied in full."""
        fem_mesh = self.fem_obj.FemMesh
        table = meshtools.get_femelement_table(fem_mesh)
        for i, face in enumerate(self.shape.Faces, 1):
            with self.subTest(face="Face%d" % i, surface=face.Surface.TypeId):
                face_table = meshtools.get_ref_facenodes_table(fem_mesh, table, face)
                areas = meshtools.get_ref_facenodes_areas(fem_mesh.Nodes, face_table)
                self.assertAlmostEqual(sum(area for _, area in areas) / face.Area, 1.0, delta=0.01)

    def test_static_analysis_matches_fems_own_gmsh_mesh(self):
        displacement, reaction = solve(self, self.doc, self.fem_obj, self.part, self.faces, "Solid")
        RESULTS["remeshed B-rep"] = displacement
        # the load on the element faces found on the boss top, which cover 99.7% of it
        self.assertAlmostEqual(reaction, FORCE, delta=0.01 * FORCE)
        if not shutil.which("gmsh"):
            self.skipTest("gmsh not installed: LiftRemesh's largest displacement %.5f mm not compared" % displacement)
        from femmesh.gmshtools import GmshTools

        gmsh_obj = ObjectsFem.makeMeshGmsh(self.doc, "GmshMesh")
        fem_compat.set_gmsh_shape(gmsh_obj, self.part)
        gmsh_obj.CharacteristicLengthMax = EDGE_LENGTH
        gmsh_obj.ElementOrder = "2nd"
        self.doc.recompute()
        error = GmshTools(gmsh_obj).create_mesh()
        self.assertFalse(error, error)
        reference, _ = solve(self, self.doc, gmsh_obj, self.part, self.faces, "Gmsh")
        RESULTS["Gmsh B-rep"] = reference
        print("\nlargest displacement: LiftRemesh + TetGen %.5f mm (%d nodes), FEM's Gmsh %.5f mm "
              "(%d nodes): %+.2f%%" % (displacement, self.fem_obj.FemMesh.NodeCount, reference,
                                       gmsh_obj.FemMesh.NodeCount, 100 * (displacement / reference - 1)))
        self.assertAlmostEqual(displacement / reference, 1.0, delta=AGREEMENT)


class StlOnlyTest(unittest.TestCase):
    """A bracket that exists only as an STL: imported as a mesh, remeshed, filled; the faceted
    solid that comes with the FEM mesh carries the constraints."""

    @classmethod
    def setUpClass(cls):
        shape = make_bracket(Part, FreeCAD.Vector)
        cls.folder = tempfile.mkdtemp(prefix="liftremesh_stl_")
        cls.stl = os.path.join(cls.folder, "bracket.stl")
        MeshPart.meshFromShape(Shape=shape, LinearDeflection=0.1, AngularDeflection=math.radians(30)).write(cls.stl)
        cls.doc = FreeCAD.newDocument("LiftRemeshStlTest")
        Mesh.insert(cls.stl, cls.doc.Name)
        [cls.imported] = cls.doc.Objects
        [cls.remeshed] = LiftRemesh.remesh_objects(cls.doc, [cls.imported], edge_length=EDGE_LENGTH)
        cls.fem_obj = LiftRemesh.make_fem_solid(cls.doc, cls.remeshed)
        cls.faces_obj = cls.doc.getObject(fem_solid.faces_name(cls.remeshed))

    @classmethod
    def tearDownClass(cls):
        FreeCAD.closeDocument(cls.doc.Name)
        shutil.rmtree(cls.folder, True)

    def test_the_faceted_solid_has_the_planar_regions_as_faces(self):
        self.assertIsNotNone(self.faces_obj)
        self.assertEqual(self.faces_obj.Label, self.remeshed.Label + "_Faces")
        self.assertEqual(self.fem_obj.Part, self.faces_obj)
        solid = self.faces_obj.Shape
        self.assertEqual((solid.ShapeType, solid.isValid()), ("Solid", True))
        self.assertLess(len(solid.Faces), self.remeshed.Mesh.CountFacets)
        self.assertAlmostEqual(solid.Volume / self.remeshed.Mesh.Volume, 1.0, places=2)  # put on the STL
        faces = bracket_faces(solid)
        # a planar region is one face, as on the CAD part (with a few triangles at its rim)
        areas = [solid.getElement(n).Area for n in faces["loaded"]]
        self.assertGreater(max(areas), 0.9 * sum(areas))
        print("\nSTL only: faceted solid of %d faces; boss top %d faces, the holes' walls %d"
              % (len(solid.Faces), len(faces["loaded"]), len(faces["fixed"])))
        self.assertGreater(len(faces["fixed"]), 20)  # a curved one a face per triangle
        bottom = planar_face(solid, lambda f: f.BoundBox.ZMax < 1e-4)
        fem_mesh = self.fem_obj.FemMesh
        table = meshtools.get_femelement_table(fem_mesh)
        for name in faces["fixed"]:  # its element faces' corners and middles, no other's, covering it
            face = solid.getElement(name)
            face_table = meshtools.get_ref_facenodes_table(fem_mesh, table, face)
            self.assertTrue(face_table and all(len(ns) == 6 for ns in face_table.values()), name)
            self.assertEqual(set(fem_mesh.getNodesByFace(face)), {n for ns in face_table.values() for n in ns}, name)
            covered = sum(a for _, a in meshtools.get_ref_facenodes_areas(fem_mesh.Nodes, face_table))
            self.assertAlmostEqual(covered / face.Area, 1.0, places=6, msg=name)
        for names in (faces["loaded"], [bottom]):
            covered = total = 0.0
            for name in names:
                face = solid.getElement(name)
                self.assertGreaterEqual(len(fem_mesh.getNodesByFace(face)), 3)
                face_table = meshtools.get_ref_facenodes_table(fem_mesh, table, face)
                self.assertTrue(all(len(ns) == 6 for ns in face_table.values()))
                covered += sum(a for _, a in meshtools.get_ref_facenodes_areas(fem_mesh.Nodes, face_table))
                total += face.Area
            self.assertAlmostEqual(covered / total, 1.0, places=6)

    def test_static_analysis_on_the_faceted_faces(self):
        faces = bracket_faces(self.faces_obj.Shape)
        displacement, reaction = solve(self, self.doc, self.fem_obj, self.faces_obj, faces, "Stl")
        self.assertAlmostEqual(reaction, FORCE, delta=1e-3 * FORCE)
        print("\nSTL only: largest displacement %.5f mm" % displacement)
        reference = RESULTS.get("Gmsh B-rep") or RESULTS.get("remeshed B-rep")
        if reference is not None:
            self.assertAlmostEqual(displacement / reference, 1.0, delta=AGREEMENT)


class OnSurfaceTest(unittest.TestCase):
    """Points put on an STL keep its planar regions planar."""

    def test_points_rounded_off_a_crease_stay_on_both_planes(self):
        # A flat facet at z = 22 and one sloping down from it along a crease that no axis follows,
        # as where the bracket's boss top meets its chamfer. Points on the crease, rounded to
        # float32 as a Mesh.Mesh holds them, fall a rounding to either side: the closest point on
        # the sloping facet was a rounding below z = 22, and the boss top came out in 22 faces.
        a, b = (0.0, 0.0, 22.0), (10.0, 7.0, 22.0)
        surface = Mesh.Mesh([[a, b, (0.0, 10.0, 22.0)], [b, a, (10.0, 0.0, 19.0)]])
        along = np.linspace(0.01, 0.99, 200)[:, None]
        rounded = (np.array(a) + along * (np.array(b) - np.array(a))).astype(np.float32).astype(np.float64)
        moved = fem_solid.on_surface([FreeCAD.Vector(*p) for p in rounded.tolist()], surface)
        self.assertEqual([v.z for v in moved], [22.0] * len(moved))
        off = [(v - FreeCAD.Vector(*p)).Length for v, p in zip(moved, rounded.tolist())]
        self.assertLess(max(off), 1e-5)


class ModuleHelpersTest(unittest.TestCase):
    """The compiled module's helpers fem_solid uses: crossing_triangles, closest_points."""

    def test_crossing_triangles_pairs_the_two_spheres(self):
        first = Mesh.createSphere(5.0, 30)
        count = first.CountFacets
        second = Mesh.createSphere(4.0, 30)
        second.translate(6.0, 0.0, 0.0)
        first.addMesh(second)
        points, triangles = (np.array(a) for a in first.Topology)
        pairs = native.load().crossing_triangles(points, triangles)
        self.assertEqual(pairs.shape[1], 2)
        self.assertGreater(len(pairs), 10)
        self.assertTrue(np.all(pairs[:, 0] < count) and np.all(pairs[:, 1] >= count))  # one of each
        alone = [np.array(a) for a in Mesh.createSphere(5.0, 30).Topology]
        self.assertEqual(native.load().crossing_triangles(*alone).shape, (0, 2))
        with self.assertRaisesRegex(ValueError, "refers to vertex 7"):
            native.load().crossing_triangles(np.zeros((3, 3)), np.array([[0, 1, 7]]))

    def test_closest_points_on_a_square(self):
        square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
        triangles = np.array([[0, 1, 2], [0, 2, 3]])
        queries = np.array([[0.25, 0.5, 3.0], [2.0, 0.5, -1.0], [-1.0, -1.0, 0.5]])
        closest = native.load().closest_points(queries, square, triangles)
        np.testing.assert_allclose(closest, [[0.25, 0.5, 0.0], [1.0, 0.5, 0.0], [0.0, 0.0, 0.0]], atol=1e-15)
        with self.assertRaisesRegex(ValueError, "no triangle"):
            native.load().closest_points(queries, square, np.zeros((0, 3), dtype=int))
        # within `rim` of a corner or an edge: on it
        near = np.array([[0.999999, 0.5, 1e-9], [1e-7, 1e-7, 0.0], [0.5, 0.4, 0.0]])
        on_rim = native.load().closest_points(near, square, triangles, rim=1e-5)
        self.assertEqual(on_rim.tolist(), [[1.0, 0.5, 0.0], [0.0, 0.0, 0.0], [0.5, 0.4, 0.0]])
        with self.assertRaisesRegex(ValueError, "rim"):
            native.load().closest_points(queries, square, triangles, rim=-1.0)


class FillingTest(unittest.TestCase):
    """make_fem_solid's settings, refusals, undo, cancel, on small shapes."""

    @classmethod
    def setUpClass(cls):
        cls.box_shape = Part.makeBox(20, 10, 6)
        cls.box_mesh = LiftRemesh.remesh_shape(cls.box_shape, edge_length=2.0)

    def setUp(self):
        if FreeCAD.getActiveTransaction() is not None:
            FreeCAD.closeActiveTransaction()
        self.doc = FreeCAD.newDocument("LiftRemeshFillTest")
        self.box = self.doc.addObject("Part::Feature", "Box")
        self.box.Shape = self.box_shape
        self.remeshed = mesh_feature(self.doc, self.box_mesh, self.box)

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_order_one_makes_tet4_and_quality_bounds_the_radius_edge_ratio(self):
        fem_obj = LiftRemesh.make_fem_solid(self.doc, self.remeshed, order=1, quality=1.2)
        fem_mesh = fem_obj.FemMesh
        self.assertEqual(meshtools.get_femmesh_eletype(fem_mesh, meshtools.get_femelement_table(fem_mesh)),
                         "tetra4")
        self.assertEqual(fem_mesh.NodeCount, max(fem_mesh.Nodes))
        corners, _ = element_table(fem_mesh)
        xyz = np.array([tuple(fem_mesh.Nodes[n]) for n in range(1, fem_mesh.NodeCount + 1)])
        # the interior grades from the surface's edges: no edge much longer than the surface's
        edges = np.sort(corners[:, np.array(tet_mesh.TET_EDGES)].reshape(-1, 2), axis=1) - 1
        lengths = np.linalg.norm(xyz[edges[:, 0]] - xyz[edges[:, 1]], axis=1)
        surface = tet_mesh.local_edge_lengths(xyz[:self.box_mesh.CountPoints], np.array(self.box_mesh.Topology[1]))
        self.assertLess(lengths.max(), 2.0 * surface.max())

    def test_bad_settings_are_refused(self):
        before = document_state(self.doc)
        with self.assertRaisesRegex(ValueError, "order must be 1"):
            LiftRemesh.make_fem_solid(self.doc, self.remeshed, order=3)
        with self.assertRaisesRegex(ValueError, r"quality .* must be in \[1.1, 2\]"):
            LiftRemesh.make_fem_solid(self.doc, self.remeshed, quality=0.9)
        with self.assertRaisesRegex(ValueError, "Box has no mesh"):
            LiftRemesh.make_fem_solid(self.doc, self.box)
        self.assertEqual(document_state(self.doc), before)

    def test_an_open_surface_is_refused_with_where_before_the_mesher_runs(self):
        points, facets = self.box_mesh.Topology
        hole = Mesh.Mesh()
        hole.addFacets((points, facets[1:]))  # one triangle taken out
        gap = sum((points[i] for i in facets[0]), FreeCAD.Vector()) / 3
        obj = mesh_feature(self.doc, hole, name="Open")
        before = document_state(self.doc)
        with mock.patch.object(tetgen, "tetrahedralize") as mesher:
            with self.assertRaisesRegex(fem_solid.SurfaceRefused, r"open: 3 edges .* e\.g\. at \(") as caught:
                LiftRemesh.make_fem_solid(self.doc, obj)
            mesher.assert_not_called()
        places = [tuple(map(float, m)) for m in re.findall(r"\((-?[\d.]+), (-?[\d.]+), (-?[\d.]+)\)", str(caught.exception))]
        self.assertTrue(all((FreeCAD.Vector(*p) - gap).Length < 2.0 for p in places), (places, gap))
        self.assertEqual(document_state(self.doc), before)

    def test_crossing_triangles_are_refused_with_where(self):
        first = Mesh.createSphere(5.0, 30)
        second = Mesh.createSphere(4.0, 30)
        second.translate(6.0, 0.0, 0.0)
        first.addMesh(second)
        obj = mesh_feature(self.doc, first, name="Crossing")
        before = document_state(self.doc)
        with mock.patch.object(tetgen, "tetrahedralize") as mesher:
            with self.assertRaisesRegex(fem_solid.SurfaceRefused, "pass through each other, e.g. triangles centred at \\("):
                LiftRemesh.make_fem_solid(self.doc, obj)
            mesher.assert_not_called()
        self.assertEqual(document_state(self.doc), before)
        # where the two spheres meet: the circle x = (25 - 16 + 36) / 12 = 3.75
        self.assertEqual(fem_solid.surface_problems(*map(np.array, Mesh.createSphere(5.0, 30).Topology)), [])

    def test_an_inside_out_piece_is_refused_and_the_document_left_as_it_was(self):
        """The frame's case: the part beside a small closed piece facing inward, which bounds no
        solid (TetGen would fill around it or fail). Refused, saying where, before TetGen runs."""
        surface = Mesh.Mesh(self.box_mesh)
        bubble = Mesh.createBox(1.0, 1.0, 1.0)
        bubble.flipNormals()
        bubble.translate(30.0, 5.0, 3.0)
        surface.addMesh(bubble)
        obj = mesh_feature(self.doc, surface, self.box, name="InsideOut")
        before = document_state(self.doc)
        with mock.patch.object(tetgen, "tetrahedralize") as mesher:
            with self.assertRaisesRegex(fem_solid.SurfaceRefused,
                                        r"InsideOut cannot be filled .* 1 closed components face inward and are no "
                                        r"cavity of another .* e\.g\. at \((29|30)\.\d+, [45]\.\d+, [23]\.\d+\) "
                                        r"\(signed volume -1\)"):
                LiftRemesh.make_fem_solid(self.doc, obj)
            mesher.assert_not_called()
        self.assertEqual(document_state(self.doc), before)

    def test_pieces_the_source_does_not_have_are_refused(self):
        """A second closed piece, facing outward, where the remesh report's input (or the source
        mesh) has one: refused. The remesh report's counts come first, then the source mesh's."""
        surface = Mesh.Mesh(self.box_mesh)
        extra = Mesh.createBox(1.0, 1.0, 1.0)
        extra.translate(30.0, 5.0, 3.0)
        surface.addMesh(extra)
        source = mesh_feature(self.doc, self.box_mesh, name="SourceMesh")
        obj = mesh_feature(self.doc, surface, source, name="TwoPieces")
        before = document_state(self.doc)
        with mock.patch.object(tetgen, "tetrahedralize") as mesher:
            with self.assertRaisesRegex(fem_solid.SurfaceRefused, "made of 2 components where its source has 1"):
                LiftRemesh.make_fem_solid(self.doc, obj)
            obj.addProperty("App::PropertyString", "Report", "Base", "a remesh report")
            obj.Report = '{"input": {"components": 2, "inward_components": 0}}'
            self.assertEqual(fem.expected_components(obj), (2, 0))
            before = document_state(self.doc)
            mesher.side_effect = tetgen.MesherFailed("not run")  # the check passes: TetGen is reached
            # (with the points left where they are: put on the source, which has no second piece,
            # the extra box would lie flat on the first one's face, touching it)
            with mock.patch.object(fem_solid, "on_surface", side_effect=lambda vectors, surface: vectors):
                with self.assertRaisesRegex(tetgen.MesherFailed, "not run"):
                    LiftRemesh.make_fem_solid(self.doc, obj)
        self.assertEqual(document_state(self.doc), before)

    def test_a_hollowed_solids_cavity_is_no_problem(self):
        """A cavity faces inward as a hollowed solid's inner wall does: accepted, alone and beside its
        source's counts; the same two walls where the source has one component are refused."""
        outer = Mesh.createBox(10.0, 10.0, 10.0)
        inner = Mesh.createBox(4.0, 4.0, 4.0)  # both centred at the origin
        inner.flipNormals()
        hollow = Mesh.Mesh(outer)
        hollow.addMesh(inner)
        points, facets = hollow.Topology
        points = np.array([tuple(p) for p in points])
        self.assertEqual(fem.component_problems(points, facets), [])
        self.assertEqual(fem.component_problems(points, facets, (2, 1)), [])
        self.assertEqual(fem_solid.surface_problems(points, facets, (2, 1)), [])
        self.assertEqual(len(fem.component_problems(points, facets, (1, 0))), 2)  # a piece more, inward more

    def test_one_undo_step_into_the_given_analysis(self):
        self.doc.UndoMode = 1
        analysis = ObjectsFem.makeAnalysis(self.doc, "Analysis")
        self.doc.recompute()
        self.doc.clearUndos()
        before = document_state(self.doc)
        fem_obj = LiftRemesh.make_fem_solid(self.doc, self.remeshed, analysis=analysis)
        self.assertIn(fem_obj, analysis.Group)
        self.assertIsNone(self.doc.getObject(fem_solid.faces_name(self.remeshed)))  # it has a shape
        self.assertEqual(self.doc.UndoNames, [fem_solid.TRANSACTION])
        self.doc.undo()
        self.assertEqual(document_state(self.doc), before)
        self.assertEqual(analysis.Group, [])

    def test_failure_and_cancel_leave_the_document_unchanged(self):
        for undo_mode in (0, 1):
            with self.subTest(undo_mode=undo_mode):
                self.doc.UndoMode = undo_mode
                before = document_state(self.doc)
                with mock.patch.object(fem_solid.fem, "fill_fem_mesh_object", side_effect=RuntimeError("boom")):
                    with self.assertRaisesRegex(RuntimeError, "boom"):
                        LiftRemesh.make_fem_solid(self.doc, self.remeshed)
                self.assertEqual(document_state(self.doc), before)
                self.assertEqual(self.doc.UndoNames, [])

    def test_cancel_stops_the_mesher_and_leaves_the_document_unchanged(self):
        slow = os.path.join(tempfile.mkdtemp(prefix="liftremesh_slow_"), "tetgen")
        self.addCleanup(shutil.rmtree, os.path.dirname(slow), True)
        with open(slow, "w") as f:
            f.write("#!/bin/sh\necho Delaunizing vertices...\nexec sleep 60\n")
        os.chmod(slow, 0o755)
        stages = []

        def stop_while_filling(stage, iteration, total, energy):
            stages.append((stage, iteration))
            return stage != "fill" or iteration == 0

        before = document_state(self.doc)
        started = time.monotonic()
        with mock.patch.object(tetgen.shutil, "which", return_value=slow):
            with self.assertRaisesRegex(LiftRemesh.Cancelled, "while TetGen was filling"):
                LiftRemesh.make_fem_solid(self.doc, self.remeshed, progress=stop_while_filling)
        self.assertLess(time.monotonic() - started, 30.0)  # TetGen killed, not waited for
        self.assertEqual([s for s, _ in stages[:3]], ["check", "snap", "fill"])
        self.assertEqual(stages[-1], ("fill", 5))  # "Delaunizing vertices": tetgen.TETGEN_STAGES
        self.assertEqual(document_state(self.doc), before)

    def test_a_mesher_that_changes_the_surface_is_refused(self):
        points, facets = self.box_mesh.Topology
        p = np.array([tuple(v) for v in points])
        t = np.array(facets)
        nodes, tets = tetgen.tetrahedralize(p, t)
        self.assertEqual(tet_mesh.boundary_mismatch(tets, t), "")
        self.assertEqual(tet_mesh.boundary_mismatch(tets, t[2:]),
                         "0 surface triangles are not boundary faces, 2 boundary faces are no surface triangle")


if __name__ == "__main__":
    unittest.main()
