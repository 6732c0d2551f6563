"""FEM hand-off (LiftRemesh.fem): a remeshed plate with a hole as a shell FEM mesh of linear
triangles, checked with FreeCAD FEM's own tools and, when CalculiX is installed, solved.

The plate: a 100 x 60 mm planar face (a shell's midsurface) with a 20 mm hole, remeshed with
LiftRemesh.remesh_shape(face, vertices=1500), held by a Mesh::Feature whose Source links the plate
(as the add-on's remesh feature does), turned into a Fem::FemMeshObject by make_fem_shell.

FreeCAD FEM's own checks used here:
- the FemMesh counts (NodeCount, FaceCount, TriangleCount, EdgeCount, VolumeCount) and
  femmesh/meshtools.py: get_femmesh_eletype == "tria3", get_femelement_table,
  get_femnodes_ele_table, get_triangle_area, all through LiftRemesh.fem.check_fem_mesh;
- the node lookups the CalculiX writer makes for constraints (meshtools.get_femnodes_by_refshape,
  i.e. FemMesh.getNodesByVertex/Edge/Face), and its edge-load distribution
  (get_ref_edgenodes_table + get_ref_edgenodes_lengths), whose node lengths must add up to the
  edge length within the 1% the writer itself checks in get_force_obj_edge_nodeload_table;
- the CalculiX prerequisite check (femtools/ccxtools.py FemToolsCcx.check_prerequisites, i.e.
  femtools/checksanalysis.py check_member_for_solver_calculix: mesh, shell thickness, material,
  constraints) and the CalculiX input file FEM writes from it (S3 elements, fixed node set, loads);
- with `ccx` on PATH (calculix-ccx, scripts/install-deps.sh): a linear static analysis runs and
  its results are physically right: reactions balance the load, the largest displacement is on
  the loaded edge and close to the bar formula, the largest stress is at the hole.
"""
import math
import re
import shutil
import tempfile
import unittest
from unittest import mock

import FreeCAD
import ObjectsFem
import Part
from femmesh import meshtools
from femtools import ccxtools

import fem_compat
import LiftRemesh
from LiftRemesh import fem

LENGTH, WIDTH, HOLE_DIAMETER = 100.0, 60.0, 20.0   # mm
THICKNESS = 2.0                                      # mm
YOUNGS_MODULUS = 210000.0                            # MPa (N/mm^2), steel
FORCE = 10000.0                                      # N, along x on the right edge
VERTICES = 1500


def plate_with_hole():
    """100 x 60 planar face in z = 0 with a 20 mm hole in the middle."""
    v = FreeCAD.Vector
    outer = Part.Face(Part.Wire(Part.makePolygon(
        [v(0, 0, 0), v(LENGTH, 0, 0), v(LENGTH, WIDTH, 0), v(0, WIDTH, 0), v(0, 0, 0)])))
    hole = Part.Face(Part.Wire(Part.makeCircle(HOLE_DIAMETER / 2, v(LENGTH / 2, WIDTH / 2, 0))))
    return outer.cut(hole).Faces[0]


def edge_name(shape, test):
    """"EdgeN" of the one edge of `shape` for which test(edge) holds."""
    names = ["Edge%d" % i for i, e in enumerate(shape.Edges, 1) if test(e)]
    assert len(names) == 1, names
    return names[0]


def plate_edges(shape):
    """Names of the left (x = 0), right (x = LENGTH), bottom (y = 0) edges and the hole."""
    eps = 1e-6
    return {
        "left": edge_name(shape, lambda e: e.BoundBox.XMax < eps),
        "right": edge_name(shape, lambda e: e.BoundBox.XMin > LENGTH - eps),
        "bottom": edge_name(shape, lambda e: e.BoundBox.YMax < eps),
        "top": edge_name(shape, lambda e: e.BoundBox.YMin > WIDTH - eps),
        "hole": edge_name(shape, lambda e: hasattr(e.Curve, "Radius")),
    }


def mean_edge_lengths(points, facets):
    """Mean length of the mesh edges at each point."""
    incident = [[] for _ in points]
    for edge in {tuple(sorted(e)) for a, b, c in facets for e in ((a, b), (b, c), (c, a))}:
        length = (points[edge[0]] - points[edge[1]]).Length
        for i in edge:
            incident[i].append(length)
    return [sum(ls) / len(ls) for ls in incident]


def edge_load_length(fem_mesh, edge):
    """The length over which FEM's CalculiX writer spreads a load on `edge`: the sum of its node
    lengths (meshtools.get_ref_edgenodes_table + get_ref_edgenodes_lengths)."""
    table = meshtools.get_femelement_table(fem_mesh)
    edge_table = meshtools.get_ref_edgenodes_table(fem_mesh, table, edge)
    return sum(length for _, length in meshtools.get_ref_edgenodes_lengths(fem_mesh.Nodes, edge_table))


def inp_sections(text):
    """{keyword line without its "*": [data lines]} of a CalculiX input file; comments ("**") and
    blank lines left out (a keyword that comes twice keeps its last block)."""
    sections, current = {}, None
    for line in text.splitlines():
        if not line.strip() or line.startswith("**"):
            continue
        if line.startswith("*"):
            current = sections[line[1:].strip()] = []
        elif current is not None:
            current.append(line.strip())
    return sections


def document_state(doc):
    """What must not change when make_fem_shell fails: the objects, their labels, their order."""
    return [(o.Name, o.Label, o.TypeId) for o in doc.Objects]


class FemShellTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.face = plate_with_hole()
        cls.mesh = LiftRemesh.remesh_shape(cls.face, vertices=VERTICES)

    def setUp(self):
        if FreeCAD.getActiveTransaction() is not None:
            FreeCAD.closeActiveTransaction()  # FreeCADCmd keeps one an earlier test committed open
        self.doc = FreeCAD.newDocument("LiftRemeshFemTest")
        self.plate = self.doc.addObject("Part::Feature", "Plate")
        self.plate.Shape = self.face
        self.remeshed = self.doc.addObject("Mesh::Feature", "Remesh")
        self.remeshed.Mesh = self.mesh
        self.remeshed.addProperty("App::PropertyLink", "Source", "Base", "the remeshed shape")
        self.remeshed.Source = self.plate
        self.doc.recompute()
        self.edges = plate_edges(self.plate.Shape)

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    # ----- the FEM mesh ---------------------------------------------------------------------------

    def test_shell_mesh_is_the_remeshed_mesh_in_linear_triangles(self):
        fem_obj = fem.make_fem_shell(self.doc, self.remeshed)
        self.assertTrue(fem_obj.isDerivedFrom("Fem::FemMeshObject"))
        self.assertEqual((fem_obj.Name, fem_obj.Label), ("Remesh_FEM", "Plate_ShellMesh"))
        fem_mesh = fem_obj.FemMesh
        points, facets = self.mesh.Topology
        self.assertEqual(fem_mesh.NodeCount, len(points))
        self.assertEqual(fem_mesh.FaceCount, len(facets))
        self.assertEqual(fem_mesh.TriangleCount, len(facets))
        self.assertEqual((fem_mesh.EdgeCount, fem_mesh.VolumeCount, fem_mesh.QuadrangleCount), (0, 0, 0))
        table = meshtools.get_femelement_table(fem_mesh)
        self.assertEqual(meshtools.get_femmesh_eletype(fem_mesh, table), "tria3")
        self.assertEqual(fem.check_fem_mesh(fem_mesh), [])
        # element j + 1 is facet j with the same node order (orientation), node i + 1 is point i
        self.assertEqual(sorted(fem_mesh.Faces), list(range(1, len(facets) + 1)))
        for j in (0, len(facets) // 2, len(facets) - 1):
            self.assertEqual(fem_mesh.getElementNodes(j + 1), tuple(i + 1 for i in facets[j]))
        # nodes moved onto the geometry by at most their local edge length, none off the plane
        nodes = fem_mesh.Nodes
        lengths = mean_edge_lengths(points, facets)
        moves = [(nodes[i + 1] - p).Length / lengths[i] for i, p in enumerate(points)]
        self.assertLessEqual(max(moves), fem.VERTEX_SNAP)
        self.assertEqual(max(abs(n.z) for n in nodes.values()), 0.0)

    def test_constraints_on_the_plate_find_their_nodes(self):
        fem_mesh = fem.make_fem_shell(self.doc, self.remeshed).FemMesh
        shape = self.plate.Shape
        for side, name in self.edges.items():
            with self.subTest(edge=side):
                edge = shape.getElement(name)
                nodes = meshtools.get_femnodes_by_refshape(fem_mesh, (self.plate, (name,)))
                self.assertGreater(len(nodes), 10)
                # the writer spreads an edge load over the whole edge (its own check: within 1%);
                # a straight edge's chain of nodes runs corner to corner exactly
                ratio = edge_load_length(fem_mesh, edge) / edge.Length
                self.assertAlmostEqual(ratio, 1.0, delta=0.01 if side == "hole" else 1e-9)
        corners = [v for v in shape.Vertexes if v.Point.x in (0, LENGTH) and v.Point.y in (0, WIDTH)]
        self.assertEqual(len(corners), 4)
        for vertex in corners:
            self.assertEqual(len(fem_mesh.getNodesByVertex(vertex)), 1, vertex.Point)
        self.assertEqual(len(fem_mesh.getNodesByFace(shape.Faces[0])), fem_mesh.NodeCount)

    def test_nodes_go_onto_a_curved_placed_shell(self):
        """An open tube (cylinder face with a seam), moved and turned: single-precision mesh points
        are on no face; the FEM mesh's nodes are all on it, and its two rims (the free edges; the
        seam is not one) carry edge loads in full."""
        tube = Part.makeCylinder(20, 40).Faces[0]
        tube.Placement = FreeCAD.Placement(FreeCAD.Vector(3.3, -7.1, 5.3),
                                           FreeCAD.Rotation(FreeCAD.Vector(1, 1, 0.3), 37))
        mesh = LiftRemesh.remesh_shape(tube, vertices=VERTICES)
        bare = fem.fem_mesh_from_mesh(mesh)
        self.assertLess(len(bare.getNodesByFace(tube)), bare.NodeCount // 10)
        fem_mesh = fem.fem_mesh_from_mesh(mesh, tube)
        self.assertEqual(fem.check_fem_mesh(fem_mesh), [])
        self.assertEqual(len(fem_mesh.getNodesByFace(tube)), fem_mesh.NodeCount)
        rims, corners = fem.free_edges_and_corners(tube)
        self.assertEqual((len(rims), len(corners)), (2, 0))
        self.assertFalse(any(rim.isSeam(tube) for rim in rims))
        for rim in rims:
            self.assertAlmostEqual(edge_load_length(fem_mesh, rim) / rim.Length, 1.0, delta=0.01)

    def test_check_fem_mesh_reports_problems(self):
        import Fem

        bad = Fem.FemMesh()
        for i, p in enumerate([(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (5, 5, 5)], 1):
            bad.addNode(*p, i)
        bad.addFace([1, 2, 3], 1)   # collinear: degenerate
        bad.addFace([1, 2, 4], 2)   # node 5 is used by nothing
        problems = " / ".join(fem.check_fem_mesh(bad))
        self.assertIn("degenerate", problems)
        self.assertIn("belong to no element", problems)
        self.assertEqual(fem.check_fem_mesh(Fem.FemMesh()), ["the FEM mesh has no face (shell) elements"])

    # ----- analysis ---------------------------------------------------------------------------------

    def make_analysis(self, fem_obj):
        """Static shell analysis: steel, THICKNESS, left edge fixed, FORCE along +x on the right."""
        doc = self.doc
        analysis = ObjectsFem.makeAnalysis(doc, "Analysis")
        solver = fem_compat.make_solver_ccx_tools(doc, "CalculiXccxTools")
        solver.AnalysisType = "static"
        solver.GeometricalNonlinearity = "linear"
        analysis.addObject(solver)
        analysis.addObject(ObjectsFem.makeElementGeometry2D(doc, THICKNESS, "Thickness"))
        material = ObjectsFem.makeMaterialSolid(doc, "Steel")
        values = material.Material
        values.update({"Name": "Steel", "YoungsModulus": "%g MPa" % YOUNGS_MODULUS, "PoissonRatio": "0.30"})
        material.Material = values
        analysis.addObject(material)
        fixed = ObjectsFem.makeConstraintFixed(doc, "Fixed")
        fixed.References = [(self.plate, self.edges["left"])]
        analysis.addObject(fixed)
        force = ObjectsFem.makeConstraintForce(doc, "Force")
        force.References = [(self.plate, self.edges["right"])]
        fem_compat.set_force(force, FORCE)
        force.Direction = (self.plate, [self.edges["bottom"]])
        force.Reversed = False
        analysis.addObject(force)
        analysis.addObject(fem_obj)
        doc.recompute()
        self.assertEqual(force.DirectionVector, FreeCAD.Vector(1, 0, 0))
        return analysis, solver

    def prepared_ccx_tools(self, analysis, solver, test_mode):
        """FemToolsCcx with a temporary working directory; asserts FEM's prerequisite check passes."""
        work_dir = tempfile.mkdtemp(prefix="liftremesh_fem_")
        self.addCleanup(shutil.rmtree, work_dir, True)
        tools = ccxtools.FemToolsCcx(analysis, solver, test_mode=test_mode)
        tools.update_objects()
        tools.setup_working_dir(work_dir)
        self.assertEqual(tools.working_dir, work_dir)
        self.assertEqual(tools.check_prerequisites(), "")
        return tools

    def test_calculix_prerequisites_and_input_file(self):
        fem_obj = fem.make_fem_shell(self.doc, self.remeshed)
        analysis, solver = self.make_analysis(fem_obj)
        tools = self.prepared_ccx_tools(analysis, solver, test_mode=True)
        tools.write_inp_file()
        with open(tools.inp_file_name) as f:
            inp = f.read()
        sections = inp_sections(inp)
        self.assertEqual(len(sections["Element, TYPE=S3, ELSET=Efaces"]), fem_obj.FemMesh.FaceCount)
        fixed = {int(n.rstrip(",")) for n in sections["NSET,NSET=Fixed"]}
        left = self.plate.Shape.getElement(self.edges["left"])
        self.assertEqual(fixed, set(fem_obj.FemMesh.getNodesByEdge(left)))
        loads = [line.split(",") for line in sections["CLOAD"]]
        self.assertEqual({dof for _, dof, _ in loads}, {"1"})
        self.assertAlmostEqual(sum(float(value) for _, _, value in loads), FORCE, delta=1e-6 * FORCE)

    def test_static_shell_analysis_with_calculix(self):
        if not shutil.which("ccx"):
            self.skipTest("calculix-ccx not installed")
        fem_obj = fem.make_fem_shell(self.doc, self.remeshed)
        analysis, solver = self.make_analysis(fem_obj)
        tools = self.prepared_ccx_tools(analysis, solver, test_mode=False)
        tools.write_inp_file()
        self.assertEqual(tools.ccx_run(), 0, tools.ccx_stdout[-2000:] if tools.ccx_stdout else "")
        tools.load_results()
        self.assertTrue(tools.results_present)
        result = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")][0]
        nodes = fem_obj.FemMesh.Nodes  # exact; the result mesh has the .frd file's rounded copy
        where = [nodes[n] for n in result.NodeNumbers]
        self.assertEqual(len(where), fem_obj.FemMesh.NodeCount)
        displacements = list(result.DisplacementLengths)
        stresses = list(result.vonMises)
        self.assertTrue(all(math.isfinite(x) for x in displacements + stresses))

        # equilibrium: the reactions of the fixed edge (the .dat file) balance the load
        dat = [o for o in analysis.Group if o.TypeId == "App::TextDocument"][0].Text
        totals = re.search(r"total force \(fx,fy,fz\) for set FIXED.*\n\s*\n\s*(\S+)\s+(\S+)\s+(\S+)", dat)
        self.assertIsNotNone(totals, dat)
        reaction = [float(x) for x in totals.groups()]
        self.assertAlmostEqual(reaction[0], -FORCE, delta=1e-3 * FORCE)
        self.assertLess(abs(reaction[1]) + abs(reaction[2]), 1e-3 * FORCE)

        # the fixed edge stays, the loaded edge moves most: along +x, as much as a bar of the
        # plate's cross-section stretches (F L / (E W t)), somewhat more because of the hole
        largest = max(range(len(displacements)), key=displacements.__getitem__)
        self.assertAlmostEqual(where[largest].x, LENGTH, places=9)
        self.assertEqual(max(d for d, p in zip(displacements, where) if p.x == 0.0), 0.0)
        bar = FORCE * LENGTH / (YOUNGS_MODULUS * WIDTH * THICKNESS)
        ux = result.DisplacementVectors[largest].x
        self.assertGreater(ux / bar, 1.0)
        self.assertLess(ux / bar, 1.5)

        # the largest von Mises stress is at the hole, a stress concentration over the nominal stress
        peak = max(range(len(stresses)), key=stresses.__getitem__)
        centre = FreeCAD.Vector(LENGTH / 2, WIDTH / 2, 0)
        self.assertLess((where[peak] - centre).Length, HOLE_DIAMETER / 2 + 1e-6)
        nominal = FORCE / (WIDTH * THICKNESS)
        self.assertGreater(stresses[peak] / nominal, 1.5)
        self.assertLess(stresses[peak] / nominal, 4.0)

    # ----- failures -----------------------------------------------------------------------------

    def test_empty_mesh_raises_and_leaves_the_document_unchanged(self):
        empty = self.doc.addObject("Mesh::Feature", "Empty")
        self.doc.recompute()
        before = document_state(self.doc)
        with self.assertRaisesRegex(ValueError, "Empty has an empty mesh"):
            fem.make_fem_shell(self.doc, empty)
        self.assertEqual(document_state(self.doc), before)
        with self.assertRaisesRegex(ValueError, "Plate has no mesh"):
            LiftRemesh.make_fem_shell(self.doc, self.plate)
        self.assertEqual(document_state(self.doc), before)

    def test_an_inside_out_piece_is_refused_and_the_document_left_as_it_was(self):
        """A small closed piece facing inward beside the plate (as the remesh of a thin part may
        make): FEM would take shell elements with normals and mass from a piece standing for
        nothing. Refused, saying which and where, nothing added."""
        import Mesh

        surface = Mesh.Mesh(self.mesh)
        bubble = Mesh.createBox(2.0, 2.0, 2.0)
        bubble.flipNormals()
        bubble.translate(120.0, 10.0, 0.0)
        surface.addMesh(bubble)
        self.remeshed.Mesh = surface
        self.doc.recompute()
        before = document_state(self.doc)
        with self.assertRaisesRegex(fem.SurfaceRefused, r"Remesh cannot be made a shell FEM mesh: it is 1 closed "
                                                        r"components face inward .* at \((119|120|121)\.\d+, (9|10|11)\.\d+, "
                                                        r"-?[01]\.\d+\) \(signed volume -8\)"):
            fem.make_fem_shell(self.doc, self.remeshed)
        self.assertEqual(document_state(self.doc), before)
        # facing outward, it is a piece the remesh report's input does not have
        bubble.flipNormals()
        surface = Mesh.Mesh(self.mesh)
        surface.addMesh(bubble)
        self.remeshed.Mesh = surface
        self.remeshed.addProperty("App::PropertyString", "Report", "Base", "a remesh report")
        self.remeshed.Report = '{"input": {"components": 1, "inward_components": 0}}'
        self.doc.recompute()
        before = document_state(self.doc)
        with self.assertRaisesRegex(fem.SurfaceRefused, "made of 2 components where its source has 1"):
            fem.make_fem_shell(self.doc, self.remeshed)
        self.assertEqual(document_state(self.doc), before)

    def test_failure_inside_the_transaction_leaves_the_document_unchanged(self):
        # undo off (FreeCADCmd's default: aborting the transaction alone keeps the new object) and
        # on (the GUI's: aborting removes it)
        for undo_mode in (0, 1):
            with self.subTest(undo_mode=undo_mode):
                self.doc.UndoMode = undo_mode
                before = document_state(self.doc)
                failure = RuntimeError("setting the mesh failed")
                with mock.patch.object(fem, "fill_fem_mesh_object", side_effect=failure):
                    with self.assertRaisesRegex(RuntimeError, "setting the mesh failed"):
                        fem.make_fem_shell(self.doc, self.remeshed)
                self.assertEqual(document_state(self.doc), before)
                self.assertIsNone(self.doc.getObject("Remesh_FEM"))
                self.assertEqual(self.doc.UndoNames, [])  # no undo step left behind

    def test_one_undo_step(self):
        self.doc.UndoMode = 1
        before = document_state(self.doc)
        fem.make_fem_shell(self.doc, self.remeshed)
        self.assertEqual(self.doc.UndoNames, [fem.TRANSACTION])
        self.doc.undo()
        self.assertEqual(document_state(self.doc), before)

    def test_a_callers_open_transaction_is_joined_not_committed(self):
        """A command that makes several FEM meshes in its own transaction (undo on, as in the GUI)
        can still undo all of them at once when a later one fails."""
        self.doc.UndoMode = 1
        before = document_state(self.doc)
        self.doc.openTransaction("FEM shell meshes")
        fem.make_fem_shell(self.doc, self.remeshed)
        self.assertTrue(self.doc.HasPendingTransaction)
        with self.assertRaises(ValueError):
            fem.make_fem_shell(self.doc, self.doc.addObject("Mesh::Feature", "Empty"))
        self.doc.abortTransaction()
        self.assertEqual(document_state(self.doc), before)


if __name__ == "__main__":
    unittest.main()
