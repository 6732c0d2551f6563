"""The "FEM solid mesh" command: the selected closed meshes filled with tet10 elements
(LiftRemesh.fem_solid), in a worker thread behind a progress dialog with Cancel, then added in one
undo step (into FEM's active analysis when there is one).

The worker (a job.RemeshJob whose work is fem_solid.solid_mesh) touches no document; the main
thread polls it, shows its stage, and is the one that changes the document.
"""
import FreeCAD
import FreeCADGui

from .. import document
from .. import fem
from .. import fem_solid
from . import common
from . import job
from . import progress_dialog

FEM_SOLID = "LiftRemesh_FemSolid"

# Share of one mesh's progress bar at the start of each stage solid_mesh reports, and its words.
STAGES = {
    "check": (0.00, "checking the surface"),
    "snap": (0.02, "putting the nodes on the shape"),
    "fill": (0.15, "filling with tetrahedra (TetGen)"),
    "quadratic": (0.75, "mid-edge nodes"),
    "faces": (0.85, "faces for the constraints"),
}


def closed_meshes():
    """The selected mesh objects whose mesh is closed (a solid's surface)."""
    return [obj for obj in common.selected_objects()
            if obj.isDerivedFrom("Mesh::Feature") and obj.Mesh.CountFacets and obj.Mesh.isSolid()]


class SolidJob(job.RemeshJob):
    """Fills the meshes of the mesh objects `objects` one after another with fem_solid.solid_mesh
    (nodes on their source shape or source mesh, as make_fem_solid puts them), with `params`.
    `results`: one SolidMesh per object. The objects are read here, in the main thread."""

    def __init__(self, objects, params):
        super().__init__([fem.mesh_of(obj) for obj in objects], params)
        self.shapes = [fem.source_shape(obj) for obj in objects]
        self.surfaces = [fem_solid.source_mesh(obj) for obj in objects]
        self.expected = [fem.expected_components(obj) for obj in objects]
        self.labels = [obj.Label for obj in objects]

    def fraction(self):
        """Overall progress in [0, 1]."""
        p = self.progress
        order = sorted(STAGES, key=lambda s: STAGES[s][0]) + [None]
        start = STAGES.get(p.stage, (0.0, ""))[0]
        following = order[order.index(p.stage) + 1] if p.stage in STAGES else None
        end = STAGES[following][0] if following else 1.0
        within = p.iteration / p.total if p.total else 0.0
        return min((p.index + start + (end - start) * within) / max(len(self.meshes), 1), 1.0)

    def text(self):
        p = self.progress
        label = self.labels[p.index] if p.index < len(self.labels) else ""
        return "%s: %s" % (label, STAGES.get(p.stage, (0.0, p.stage))[1])

    def _run(self):
        results = []
        try:
            for index, mesh in enumerate(self.meshes):
                self.progress = job.Progress(index, "check")
                results.append(fem_solid.solid_mesh(mesh, self.shapes[index], progress=self._report,
                                                    label=self.labels[index], surface=self.surfaces[index],
                                                    expected=self.expected[index],
                                                    **self.params))
        except BaseException as error:  # handed to the main thread, which reports it
            self.error = error
            return
        self.results = results


class CommandFemSolid:
    """Fills each selected closed mesh with tet10 elements: a Fem::FemMeshObject each."""

    def GetResources(self):
        return {
            "Pixmap": common.icon_path("LiftRemesh_FemSolid.svg"),
            "MenuText": "FEM solid mesh from remeshed mesh",
            "ToolTip": "Fill each selected closed mesh (e.g. a remeshed solid) with second-order "
                       "tetrahedra (TetGen), its triangles kept as the boundary faces: a FEM mesh for "
                       "CalculiX, in one undo step and in the active analysis. A mesh without a Part "
                       "shape also gets a faceted solid whose faces take the constraints.",
        }

    def IsActive(self):
        return (not FreeCADGui.Control.activeDialog() and common.active_document() is not None
                and bool(closed_meshes()))

    def Activated(self):
        doc = common.active_document()
        meshes = closed_meshes()
        if doc is None or not meshes:
            common.report_error("Select one or more closed meshes to fill with tetrahedra.")
            return
        self.fill(doc, meshes)

    def fill(self, doc, meshes):
        """Fills the mesh objects `meshes` of `doc` (the work of Activated)."""
        try:
            solid_job = SolidJob(meshes, {})
        except Exception as error:
            common.report_error("FEM solid mesh failed: %s" % common.describe_error(error))
            return
        dialog = progress_dialog.ProgressDialog("FEM solid mesh", "Filling with tetrahedra...", 0)
        try:
            solid_job.start()
            progress_dialog.wait(solid_job, dialog, lambda: (solid_job.fraction(), solid_job.text()))
        finally:
            dialog.close()
        if solid_job.cancelled():
            common.report_warning("FEM solid mesh cancelled; the document is unchanged.")
            return
        if solid_job.error is not None:
            common.report_error("FEM solid mesh failed, the document is unchanged: %s"
                                % common.describe_error(solid_job.error))
            return
        try:
            with document.document_change(doc, fem_solid.TRANSACTION):
                created = [fem_solid.add_fem_solid(doc, obj, result, shape_obj=fem_solid.shape_object(obj))
                           for obj, result in zip(meshes, solid_job.results)]
                for obj in meshes:  # the FEM mesh fills it; undoing shows it again
                    if obj.ViewObject is not None:
                        obj.ViewObject.hide()
            doc.recompute()
        except Exception as error:
            common.report_error("FEM solid mesh failed, the document is unchanged: %s" % common.describe_error(error))
            return
        for obj in created:
            FreeCAD.Console.PrintMessage("LiftRemesh: FEM solid mesh %s added\n" % obj.Label)


FreeCADGui.addCommand(FEM_SOLID, CommandFemSolid())
