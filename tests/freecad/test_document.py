"""Document behaviour of the macro API: features created named after their sources, one undo
removes them, a failure of any kind leaves the document exactly as it was, and the feature is
parametric (recomputes when its source or parameters change, survives save and reload)."""
import json
import os
import tempfile
import unittest

import FreeCAD
import Part

import LiftRemesh
from LiftRemesh import feature
from LiftRemesh import native


def snapshot(doc):
    """What must not change when an operation fails: objects, their labels, types, states and
    shapes/meshes, and the undo stack."""
    objects = []
    for obj in doc.Objects:
        geometry = None
        if hasattr(obj, "Shape"):
            geometry = ("shape", obj.Shape.hashCode() if not obj.Shape.isNull() else None)
        if hasattr(obj, "Mesh"):
            geometry = ("mesh", obj.Mesh.CountPoints, obj.Mesh.CountFacets, round(obj.Mesh.Area, 9))
        objects.append((obj.Name, obj.Label, obj.TypeId, tuple(obj.State), geometry))
    return objects, doc.UndoNames, doc.RedoNames


def block_with_hole(doc, name="Block"):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = Part.makeBox(40, 30, 10).cut(Part.makeCylinder(6, 10, FreeCAD.Vector(20, 15, 0)))
    return obj


def reopened(doc, objects):
    """(`doc` saved and opened again, its `objects` there, found by name)."""
    names = [obj.Name for obj in objects]
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "saved.FCStd")
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
    return doc, [doc.getObject(name) for name in names]


class DocumentTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("LiftRemeshDocumentTest")
        self.doc.UndoMode = 1
        self.block = block_with_hole(self.doc)
        self.doc.recompute()
        self.doc.clearUndos()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_objects_created_and_one_undo_removes_them(self):
        cylinder = self.doc.addObject("Part::Cylinder", "Rod")
        self.doc.recompute()
        self.doc.clearUndos()
        before = snapshot(self.doc)
        created = LiftRemesh.remesh_objects(self.doc, [self.block, cylinder], vertices=600)
        self.assertEqual([o.Name for o in created], ["Block_Remesh", "Rod_Remesh"])
        for obj, source in zip(created, (self.block, cylinder)):
            self.assertTrue(obj.isDerivedFrom("Mesh::Feature"))
            self.assertIs(obj.Source, source)
            self.assertEqual(obj.Vertices, 600)
            self.assertGreater(obj.Mesh.CountFacets, 1000)
            self.assertTrue(obj.Mesh.isSolid())
            self.assertGreater(obj.KappaMin, 0.3)
            # none by the report, and none by FreeCAD's own check (Mesh workbench's evaluation)
            self.assertEqual(obj.SelfIntersections, 0)
            self.assertFalse(obj.Mesh.hasSelfIntersections())
            self.assertFalse(obj.isValid() is False)
            self.assertNotIn("Touched", obj.State)  # computed once, not again on recompute
        self.assertEqual(self.doc.UndoNames, ["Remesh"])
        self.doc.undo()
        self.assertEqual(snapshot(self.doc)[0], before[0])
        self.doc.redo()
        self.assertEqual(len(self.doc.Objects), 4)

    def test_edge_length_target_is_stored_and_used(self):
        obj = LiftRemesh.remesh_objects(self.doc, [self.block], edge_length=2.0)[0]
        self.assertEqual(obj.EdgeLength.Value, 2.0)
        # the vertex count keeps a value in its range (issue 34) and is not used
        self.assertEqual((feature.params_of(obj)["vertices"], obj.Vertices), (None, 6000))
        expected = self.block.Shape.Area / (3 ** 0.5 / 2 * 2.0 ** 2)
        self.assertAlmostEqual(obj.Mesh.CountPoints / expected, 1.0, delta=0.05)
        obj.EdgeLength = 3.0
        self.doc.recompute()
        self.assertAlmostEqual(obj.Mesh.CountPoints / (expected * 4 / 9), 1.0, delta=0.05)

    def test_partdesign_body_and_link_sources(self):
        body = self.doc.addObject("PartDesign::Body", "Body")
        box = self.doc.addObject("PartDesign::AdditiveBox", "Box")
        body.addObject(box)
        link = self.doc.addObject("App::Link", "BlockLink")
        link.LinkedObject = self.block
        link.Placement.Base = FreeCAD.Vector(100, 0, 0)
        self.doc.recompute()
        from_body, from_link = LiftRemesh.remesh_objects(self.doc, [body, link], vertices=400)
        self.assertEqual(from_body.Name, "Body_Remesh")
        self.assertAlmostEqual(from_body.Mesh.Volume, 1000.0, delta=20.0)  # the 10 mm default box
        self.assertAlmostEqual(from_link.Mesh.BoundBox.XMin, 100.0, delta=0.05)  # the link's placement
        box.Length = 20
        self.doc.recompute()
        self.assertAlmostEqual(from_body.Mesh.Volume, 2000.0, delta=40.0)

    def test_mesh_source_is_remeshed(self):
        source = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=500)[0]
        again = LiftRemesh.remesh_objects(self.doc, [source], vertices=800)[0]
        self.assertEqual(again.Name, "Block_Remesh_Remesh")
        self.assertAlmostEqual(again.Mesh.CountPoints, 800, delta=20)
        self.assertAlmostEqual(again.Mesh.Volume / source.Mesh.Volume, 1.0, delta=0.02)

    def test_failures_leave_the_document_as_it_was(self):
        empty = self.doc.addObject("Part::Feature", "Empty")
        sheet = self.doc.addObject("App::FeaturePython", "NotAShape")
        self.doc.recompute()
        self.doc.clearUndos()
        before = snapshot(self.doc)
        failures = [
            ([], {}, ValueError, "nothing to remesh"),
            ([empty], {}, ValueError, "empty shape"),
            ([sheet], {}, ValueError, "neither a Part shape nor a mesh"),
            ([self.block, empty], {}, ValueError, "Empty"),             # the good one is not added
            ([self.block], {"sigma": 0.5}, ValueError, "sigma"),
            ([self.block], {"vertices": 2}, ValueError, "vertices"),
            ([self.block], {"mode": "wobbly"}, ValueError, "mode"),
            ([self.block], {"linear_deflection": -1}, ValueError, "linear_deflection"),
            ([self.block], {"progress": lambda stage, i, n, e: stage != "optimize" or i < 2},
             LiftRemesh.Cancelled, "cancel"),
        ]
        for objects, params, error, words in failures:
            with self.subTest(words=words):
                with self.assertRaisesRegex(error, words):
                    LiftRemesh.remesh_objects(self.doc, objects, vertices=params.pop("vertices", 300), **params)
                self.assertEqual(snapshot(self.doc), before)

    def test_failure_while_adding_aborts_the_transaction(self):
        import MeshPart

        result = LiftRemesh.remesh_mesh(MeshPart.meshFromShape(self.block.Shape, 0.1, 0.5), vertices=300)
        for undo_mode in (1, 0):  # with undo off (FreeCADCmd's default) the added objects are removed
            with self.subTest(undo_mode=undo_mode):
                self.doc.UndoMode = undo_mode
                before = snapshot(self.doc)
                with self.assertRaises(AttributeError):
                    # the second "result" has no mesh: adding fails after the first feature was added
                    feature.add_results(self.doc, [self.block, self.block], {"vertices": 300}, [result, object()])
                self.assertEqual(snapshot(self.doc), before)

    def test_feature_recomputes_when_source_or_parameters_change(self):
        obj = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=500)[0]
        self.assertAlmostEqual(obj.Mesh.BoundBox.ZMax, 10.0, delta=0.05)
        self.block.Shape = Part.makeBox(40, 30, 25)  # the source changes: no hole, taller
        self.doc.recompute()
        self.assertAlmostEqual(obj.Mesh.BoundBox.ZMax, 25.0, delta=0.05)
        self.assertTrue(obj.Mesh.isSolid())
        obj.Vertices = 900
        self.doc.recompute()
        self.assertAlmostEqual(obj.Mesh.CountPoints, 900, delta=20)
        obj.Mode = "anisotropic"  # brings the mode's nu and delta, as --mode does
        self.assertEqual((obj.Nu, obj.Delta), (0.05, 0.0))
        # a source that can no longer be remeshed: the feature reports an error, keeps its mesh
        points = obj.Mesh.CountPoints
        self.block.Shape = Part.Shape()
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertEqual(obj.Mesh.CountPoints, points)

    def test_feature_survives_save_and_reload(self):
        obj = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=400)[0]
        facets = obj.Mesh.CountFacets
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "remeshed.FCStd")
            self.doc.saveAs(path)
            name = self.doc.Name
            FreeCAD.closeDocument(name)
            self.doc = FreeCAD.openDocument(path)
            obj = self.doc.getObject("Block_Remesh")
            self.assertIsInstance(obj.Proxy, feature.RemeshFeature)
            self.assertEqual(obj.Mesh.CountFacets, facets)
            self.assertIs(obj.Source, self.doc.getObject("Block"))
            obj.Vertices = 700
            self.doc.recompute()
            self.assertAlmostEqual(obj.Mesh.CountPoints, 700, delta=20)

    def test_a_document_saved_before_a_quality_property_gains_it_on_reload(self):
        obj = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=400)[0]
        other = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=300)[0]
        # as an earlier version saved them: no SelfIntersections, and for `other` a report without it
        for saved in (obj, other):
            saved.removeProperty("SelfIntersections")
        report = json.loads(other.Report)
        del report["output"]["self_intersections"]
        other.Report = json.dumps(report)
        self.doc, (obj, other) = reopened(self.doc, (obj, other))
        for restored in (obj, other):
            self.assertNotIn("Touched", restored.State)  # opening a document does not ask for a recompute
        self.assertEqual(obj.SelfIntersections, 0)  # read from the stored report
        self.assertEqual(other.SelfIntersections, -1)  # not counted
        self.assertEqual(obj.getGroupOfProperty("SelfIntersections"), "Quality")
        self.assertIn("ReadOnly", obj.getEditorMode("SelfIntersections"))
        other.Vertices = 350
        self.doc.recompute()
        self.assertEqual(other.SelfIntersections, 0)  # counted by the new run

    def test_a_document_saved_before_the_creases_were_held_recomputes_as_it_did(self):
        """A feature saved before HoldCreases existed gets it off on reload (the default then),
        not the default now; one saved with it keeps its value."""
        old, new = (LiftRemesh.remesh_objects(self.doc, [self.block], vertices=300)[0] for _ in range(2))
        self.assertTrue(new.HoldCreases)  # the default
        old.removeProperty("HoldCreases")  # as an earlier version saved it
        names = old.Name, new.Name
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "older.FCStd")
            self.doc.saveAs(path)
            FreeCAD.closeDocument(self.doc.Name)
            self.doc = FreeCAD.openDocument(path)
        old, new = (self.doc.getObject(name) for name in names)
        self.assertFalse(old.HoldCreases)
        self.assertTrue(new.HoldCreases)
        self.assertNotIn("Touched", old.State)


# The property types of the parameters before they carried the table's ranges (issue 34).
PLAIN_TYPES = {"integer": "App::PropertyInteger", "real": "App::PropertyFloat"}


def constrained_rows():
    """The module's rows whose property is a constraint one (numbers other than lengths)."""
    return [row for row in native.load().parameters() if row["kind"] in PLAIN_TYPES and row["unit"] != "length"]


def property_of(row):
    return "".join(word.capitalize() for word in row["name"].split("_"))


class PropertyRangeTest(unittest.TestCase):
    """The parameters' properties refuse what the core refuses: their constraints (what FreeCAD's
    property editor lets through, and what a value set from Python is clamped to) are the ranges
    of the core's parameter table, also after a save and a reload."""

    def setUp(self):
        self.doc = FreeCAD.newDocument("LiftRemeshPropertyTest")
        self.block = block_with_hole(self.doc)
        self.doc.recompute()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def reload(self):
        self.doc, objects = reopened(self.doc, self.doc.Objects)
        return objects

    def assert_constraints_are_the_table_ranges(self, obj):
        for row in constrained_rows():
            prop = property_of(row)
            kind = "App::Property%sConstraint" % ("Integer" if row["kind"] == "integer" else "Float")
            self.assertEqual(obj.getTypeIdOfProperty(prop), kind, prop)
            saved = getattr(obj, prop)
            setattr(obj, prop, -1e12 if row["kind"] == "real" else -2 ** 31)
            low = getattr(obj, prop)
            setattr(obj, prop, 1e12 if row["kind"] == "real" else 2 ** 31 - 1)
            high = getattr(obj, prop)
            setattr(obj, prop, saved)
            for bound, end, is_open, inward in ((low, row["min"], row["min_open"], 1),
                                               (high, row["max"], row["max_open"], -1)):
                if end is None:  # unbounded: as far as the editor goes
                    self.assertGreaterEqual(abs(bound), 1e9, prop)
                elif not is_open:
                    self.assertEqual(bound, end, prop)
                else:  # one unit of the last digit shown inside the open end
                    self.assertAlmostEqual(bound, end + inward * 10.0 ** -row["decimals"], 12, prop)
            # both ends are values the core accepts
            for value in (low, high if row["max"] is not None else low):
                self.assertTrue(self.core_accepts(row["name"], value), (prop, value))

    @staticmethod
    def tetrahedron():
        import numpy as np

        return (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
                np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))

    def core_accepts(self, name, value):
        """True unless the module refuses `value` for `name` as out of range."""
        liftremesh = native.load()
        try:
            liftremesh.remesh(*self.tetrahedron(), **{name: value, "progress": lambda *_: False})
        except liftremesh.Cancelled:
            return True
        except ValueError as error:
            return "out of range" not in str(error)
        return True

    def test_constraints_are_the_table_ranges(self):
        obj = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=300, iterations=10)[0]
        self.assert_constraints_are_the_table_ranges(obj)
        obj.Vertices = 3  # typed in the property editor: refused, the recompute does not fail
        self.assertEqual(obj.Vertices, 4)
        [_, obj] = self.reload()
        self.assert_constraints_are_the_table_ranges(obj)

    def test_a_document_saved_with_plain_property_types_opens(self):
        by_count = LiftRemesh.remesh_objects(self.doc, [self.block], vertices=300, iterations=10)[0]
        by_length = LiftRemesh.remesh_objects(self.doc, [self.block], edge_length=3.0, iterations=10)[0]
        expected = {}
        for obj in (by_count, by_length):  # as an earlier version saved them
            for prop in ("SizeBy", "HausdorffDistance", "HausdorffPercent"):  # issue 34
                obj.removeProperty(prop)
            obj.setEditorMode("Report", 0)
            for row in constrained_rows():
                prop = property_of(row)
                value, group = getattr(obj, prop), obj.getGroupOfProperty(prop)
                obj.removeProperty(prop)
                obj.addProperty(PLAIN_TYPES[row["kind"]], prop, group, row["help"])
                setattr(obj, prop, value)
            expected[obj.Name] = feature.params_of(obj)
        by_length.Vertices = 0  # an earlier version's "no vertex count"
        for obj in (by_count, by_length):
            obj.purgeTouched()
        counts = {obj.Name: obj.Mesh.CountPoints for obj in (by_count, by_length)}
        [_, by_count, by_length] = self.reload()
        for obj in (by_count, by_length):
            self.assertNotIn("Touched", obj.State)  # opening a document does not ask for a recompute
            self.assertEqual(feature.params_of(obj), expected[obj.Name])
            self.assertEqual(obj.Mesh.CountPoints, counts[obj.Name])
            self.assert_constraints_are_the_table_ranges(obj)
        self.assertEqual(by_length.Vertices, 6000)  # the default count, unused beside the length
        # the size in use is said by SizeBy and only that one is shown; Report is hidden; the
        # Hausdorff distance is read from the stored report in mm and in percent
        self.assertEqual((by_count.SizeBy, by_length.SizeBy), ("Vertex count", "Edge length"))
        self.assertEqual((by_count.getEditorMode("EdgeLength"), by_length.getEditorMode("Vertices")),
                         (["Hidden"], ["Hidden"]))
        self.assertEqual(by_length.getEditorMode("EdgeLength"), [])
        for obj in (by_count, by_length):
            self.assertIn("Hidden", obj.getEditorMode("Report"))
            report = json.loads(obj.Report)
            self.assertAlmostEqual(obj.HausdorffPercent, 100 * report["hausdorff_relative"], 9)
            self.assertAlmostEqual(obj.HausdorffDistance.Value,
                                   report["hausdorff_relative"] * report["bbox_diagonal"], 6)
            self.assertGreater(obj.HausdorffPercent, 0.0)
        by_length.Iterations = 12
        self.doc.recompute()
        self.assertTrue(by_length.isValid())
        self.assertEqual(feature.params_of(by_length)["iterations"], 12)


if __name__ == "__main__":
    unittest.main()
