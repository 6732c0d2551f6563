"""FEM preprocessing: a closed remeshed surface filled with tetrahedra, as a solid FEM mesh for
FreeCAD FEM (CalculiX C3D10, or C3D4 with order=1).

    import LiftRemesh.fem_solid as fem_solid
    fem_obj = fem_solid.make_fem_solid(doc, remesh_feature)     # -> Fem::FemMeshObject, tet10

The mesher is TetGen (tetgen.py): it fills the surface without adding a point to it, so the
boundary faces are exactly the remeshed triangles; `quality` bounds every tetrahedron's
radius-edge ratio, and the interior sizes grade from the surface's edge lengths. Gmsh and Netgen
would remesh or re-optimise the surface, which is what the remesher has just made well; TetGen is
also what the project's tests already fill surfaces with.

Steps, the document touched only at the end (one undo step, nothing left behind on a failure):
1. the surface is refused, in words saying where, when it is open or non-manifold (edges not shared
   by exactly two triangles) or when triangles pass through each other (liftremesh's
   crossing_triangles): a tetrahedral mesher cannot fill either;
2. given the shape the mesh was made from (a remesh feature's Source), the surface points are put
   on it (onto_shape: its faces, as for the shell mesh, then the edges between faces near which
   they lie), so that constraints on its faces find their nodes (FemMesh.getNodesByFace: within
   the face's tolerance, about 1e-7 mm). Given instead the STL a mesh was remeshed from, the
   points are put on that (on_surface), and a faceted solid of the result carries the faces for
   the constraints (faceted_solid);
3. TetGen fills the surface; its first points are the surface points, in order;
4. order 2: a node at the middle of every edge (tet10). A boundary edge's middle node lies on the
   straight edge, so each boundary face is a remeshed triangle; given a shape, those middle nodes
   then go onto it as the corners did (a chord's middle lies h^2/(8R) off a surface of radius R),
   unless that would invert an element: a constraint on a curved face of the shape finds all six
   nodes of its element faces, as on FreeCAD's own second-order meshes of the B-rep.
Nodes are numbered from 1 (surface points first), elements from 1, in FreeCAD's order
(tet_mesh.py).

Needs FreeCAD's App modules only (Fem, Part, Mesh), numpy and the compiled module: macros, tests
and the GUI's worker thread call it.
"""
import numpy as np

import FreeCAD

from . import document
from . import fem
from . import native
from . import tet_mesh
from . import tetgen
from .tetgen import MesherFailed, QUALITY, QUALITY_RANGE  # noqa: F401  (part of this module's API)

ORDERS = (1, 2)
TRANSACTION = "FEM solid mesh"
SHOWN = 3  # places named in a refusal
CREASE_SNAP = 0.25  # largest move onto an edge between two faces, in local edge lengths (onto_shape)


SurfaceRefused = fem.SurfaceRefused  # the surface cannot be filled: the message says why and where


class SolidMesh:
    """A filled surface: `nodes` (n, 3) float64, `elements` (m, 4 or 10) int64 0-based node indices
    in FreeCAD's order (module doc), `surface_count` (nodes 0 .. surface_count - 1 are the surface
    points, in their order), `triangles` (the surface's, as filled), `quality`
    (tet_mesh.element_quality() of the corner tetrahedra) and `snapped` (fem.snap_points_to_shape's counts of
    the surface points, or None without a shape), `faces` (faceted_solid() of the surface when it
    had no shape to be put on, else None)."""

    def __init__(self, nodes, elements, surface_count, triangles, quality, snapped=None, faces=None):
        self.faces = faces
        self.nodes = nodes
        self.elements = elements
        self.surface_count = surface_count
        self.triangles = triangles
        self.quality = quality
        self.snapped = snapped

    @property
    def order(self):
        return 2 if self.elements.shape[1] == 10 else 1

    def fem_mesh(self):
        """The Fem.FemMesh: node i + 1 is nodes[i], element j + 1 is elements[j]."""
        import Fem

        fem_mesh = Fem.FemMesh()
        for node_id, (x, y, z) in enumerate(self.nodes.tolist(), 1):
            fem_mesh.addNode(x, y, z, node_id)
        for element_id, element in enumerate((self.elements + 1).tolist(), 1):
            fem_mesh.addVolume(element, element_id)
        return fem_mesh


# ----- refusal ------------------------------------------------------------------------------------

def surface_problems(points, triangles, expected=None):
    """Why a tetrahedral mesher cannot fill this surface, in sentences that say where (coordinates):
    edges used by one triangle (a hole) or by more than two, closed components facing inward that
    are no cavity of another or, given `expected` (fem.expected_components), components its source
    does not have (fem.component_problems), triangles passing through each other.
    [] when it can. points (n, 3), triangles (m, 3) 0-based."""
    points = np.asarray(points, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    problems = []
    edges, uses = tet_mesh.edge_uses(triangles)
    for count, what in ((1, "open: %d edges belong to one triangle only (a hole in the surface)"),
                        (3, "not manifold: %d edges are shared by more than two triangles")):
        bad = edges[uses == 1] if count == 1 else edges[uses >= 3]
        if len(bad):
            places = [_point_text((points[a] + points[b]) / 2) for a, b in bad[:SHOWN]]
            problems.append((what % len(bad)) + ", e.g. at " + ", ".join(places))
    if not problems:
        problems = fem.component_problems(points, triangles, expected)
    if not problems:
        pairs = np.asarray(native.load().crossing_triangles(points, triangles)).reshape(-1, 2)
        if len(pairs):
            places = [_point_text(points[triangles[s]].mean(axis=0)) + " / " +
                      _point_text(points[triangles[t]].mean(axis=0)) for s, t in pairs[:SHOWN]]
            problems.append("%d pairs of triangles pass through each other, e.g. triangles centred at %s"
                            % (len(pairs), "; ".join(places)))
    return problems



_point_text = fem._point_text


# ----- filling ------------------------------------------------------------------------------------

# ----- the whole computation (no document) --------------------------------------------------------

def solid_mesh(mesh, shape=None, order=2, quality=QUALITY, progress=None, label="the mesh", faces=True,
               surface=None, expected=None):
    """A SolidMesh filling the closed Mesh.Mesh `mesh`; nodes put on `shape` when given (module doc).
    Without a shape, the points are put on `surface` when given (a Mesh.Mesh, the STL the mesh was
    remeshed from: its closest points, so that a planar region is exactly planar), and with `faces`
    the SolidMesh's `faces` is faceted_solid() of the result. `expected`: (components, inward
    components) of what the mesh was made from (fem.expected_components), or None.
    Touches no document: safe in a worker thread. SurfaceRefused (a ValueError) for a surface that
    cannot be filled, ValueError for bad settings, MesherFailed, liftremesh.Cancelled."""
    if order not in ORDERS:
        raise ValueError("order must be 1 (tet4) or 2 (tet10), got %r" % (order,))
    tetgen.check_quality(quality)
    vectors, triangle_list = fem.mesh_arrays(mesh)
    triangles = np.array(triangle_list, dtype=np.int64).reshape(-1, 3)
    _report_stage(progress, "check")
    problems = surface_problems(_array(vectors), triangles, expected)
    if problems:
        raise SurfaceRefused("%s cannot be filled with tetrahedra: it is %s" % (label, "; ".join(problems)))
    snapped = None
    if shape is None and surface is not None:
        _report_stage(progress, "snap")
        vectors = on_surface(vectors, surface)
        problems = surface_problems(_array(vectors), triangles)
        if problems:
            raise SurfaceRefused("%s, put on its source, cannot be filled: it is %s"
                                 % (label, "; ".join(problems)))
    if shape is not None:
        _report_stage(progress, "snap")
        vectors, snapped, on_creases = onto_shape(vectors, triangle_list, shape)
        problems = surface_problems(_array(vectors), triangles)
        if problems:
            raise SurfaceRefused("%s, put on its shape, cannot be filled: it is %s"
                                 % (label, "; ".join(problems)))
    points = _array(vectors)
    nodes, tets = tetgen.tetrahedralize(points, triangles, quality, progress)
    quality_figures = tet_mesh.element_quality(nodes, tets)
    if order == 2:
        _report_stage(progress, "quadratic")
        nodes, elements = tet_mesh.quadratic(nodes, tets)
        if shape is not None:
            curved = _middles_onto_shape(nodes, elements, triangles, len(points), shape, on_creases)
            nodes = tet_mesh.keep_jacobians_positive(nodes, curved, elements)
    else:
        elements = tets
    faceted = None
    if shape is None and faces:
        _report_stage(progress, "faces")
        faceted = faceted_solid(vectors, triangle_list)
    return SolidMesh(nodes, elements, len(points), triangles, quality_figures, snapped, faceted)


# How far, relative to the largest coordinate, a closest point may be from its STL triangle's
# corner or edge to be put on it: about 17 times the rounding of a Mesh.Mesh's float32 points.
RIM_ROUNDING = 1e-6


def on_surface(vectors, surface):
    """The closest points of the Mesh.Mesh `surface` to the FreeCAD vectors `vectors`. A Mesh.Mesh
    holds float32 points, so a vertex on a crease of the STL comes a rounding off it, and its
    closest point would be on one facet only, a rounding below the other's plane: a planar region
    would no longer be one face. A closest point within that rounding of its triangle's corner or
    edge is put on it, on both facets' planes."""
    from . import meshing

    surface_points, surface_triangles = meshing.mesh_to_arrays(surface)
    rim = RIM_ROUNDING * float(np.abs(surface_points).max(initial=0.0))
    closest = native.load().closest_points(_array(vectors), surface_points, surface_triangles, rim=rim)
    return [FreeCAD.Vector(*p) for p in np.asarray(closest).tolist()]


def _array(vectors):
    return np.array([(v.x, v.y, v.z) for v in vectors], dtype=np.float64).reshape(-1, 3)


def _report_stage(progress, stage):
    if progress is not None and progress(stage, 0, 0, 0.0) is False:
        raise native.load().Cancelled("cancelled at %s" % stage)


def onto_shape(points, triangles, shape, along=None):
    """fem.snap_points_to_shape (points: FreeCAD vectors; triangles: index triples), then the points
    within CREASE_SNAP of their local edge length from an edge between two faces of the shape onto
    the nearest such edge: the remesher puts vertices on creases only as well as the tessellation
    it started from has them, and a point a hair off the crease lies on one face only, so that the
    element faces along the crease would belong to neither. With `along` ({point: set of edge
    indices}) a point may go only onto those edges. Returns (points, counts with "crease",
    {point: set of the indices in shape.Edges of the edges it was put on})."""
    moved, counts = fem.snap_points_to_shape(points, triangles, shape)
    free_edges, _ = fem.free_edges_and_corners(shape)
    lengths = fem.local_lengths(moved, fem.edge_use(triangles))
    candidates = {}  # point -> [(position, edge index)]
    for index, edge in enumerate(shape.Edges):
        if edge.Degenerated or any(edge.isSame(f) for f in free_edges):
            continue
        nodes = range(len(moved)) if along is None else [n for n, edges in along.items() if index in edges]
        found = {}
        fem.snap_to(edge, nodes, moved, lengths, CREASE_SNAP, index, found)
        for node, (position, _) in found.items():
            candidates.setdefault(node, []).append((position, index))
    targets = {}
    for node, options in candidates.items():
        nearest = min(options, key=lambda o: (o[0] - moved[node]).Length)[0]
        targets[node] = (nearest, "crease")
    fem.undo_folding_moves(moved, triangles, targets)
    moved = list(moved)
    on_edges = {}
    for node, (position, _) in targets.items():
        moved[node] = position
        on_edges[node] = {i for p, i in candidates[node] if (p - position).Length <= 1e-9}
    return moved, dict(counts, crease=len(targets)), on_edges


def _middles_onto_shape(nodes, elements, triangles, surface_count, shape, on_creases):
    """The middle nodes of the boundary edges put on `shape` as the corners were: the surface split
    into four triangles per triangle (corners and middles) goes through onto_shape, and only the
    middles take their new positions (the corners are there already). A middle goes onto an edge
    between two faces only when both its corners are on that edge (`on_creases`, onto_shape's
    third result): the middle of an edge that merely ends on creases belongs on the face."""
    middle_of = tet_mesh.boundary_middles(elements, triangles)
    local = {}  # node -> index in the split surface
    for node in list(range(surface_count)) + sorted(middle_of.values()):
        local[node] = len(local)
    split = []
    for a, b, c in np.asarray(triangles).tolist():
        ab, bc, ca = (middle_of[tuple(sorted(e))] for e in ((a, b), (b, c), (c, a)))
        split += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    split = [tuple(local[n] for n in t) for t in split]
    order = sorted(local, key=local.get)
    vectors = [FreeCAD.Vector(*nodes[n]) for n in order]
    along = {local[m]: on_creases[a] & on_creases[b] for (a, b), m in middle_of.items()
             if a in on_creases and b in on_creases}
    moved, _, _ = onto_shape(vectors, split, shape, {m: e for m, e in along.items() if e})
    nodes = nodes.copy()
    for node in middle_of.values():
        v = moved[local[node]]
        nodes[node] = (v.x, v.y, v.z)
    return nodes


# ----- faces to put constraints on, for a mesh without a shape --------------------------------------

def faceted_solid(points, triangles):
    """The closed surface (points: FreeCAD vectors, triangles: index triples) as a Part solid whose
    faces are its triangles, adjacent coplanar ones merged (Part's "Refine shape",
    ShapeUpgrade_UnifySameDomain): a planar region bounded by creases is one face, as on the CAD
    part; a curved region (a bore, a fillet) stays a face per triangle. Its vertices are the
    points, in double precision, so nodes made from them lie on its faces exactly (a middle node
    on a planar face too): FEM constraints on these faces find their nodes.
    MesherFailed when the triangles do not close into a valid solid."""
    import Part

    triangulated = Part.Shape()
    triangulated.makeShapeFromMesh((list(points), [tuple(t) for t in triangles]), 1e-7)
    solid = Part.Solid(Part.Shell(triangulated.Faces)).removeSplitter()
    if not solid.isValid() or solid.ShapeType != "Solid" or solid.Volume <= 0.0:
        raise MesherFailed("the surface does not make a valid solid for its faces")
    return solid


# ----- document -----------------------------------------------------------------------------------

def make_fem_solid(doc, mesh_obj, order=2, quality=QUALITY, name=None, shape=None, analysis=None,
                   progress=None, faces=True):
    """Adds a Fem::FemMeshObject of tetrahedra (tet10, tet4 with order=1) filling the closed mesh of
    `mesh_obj` (a remesh feature, any Mesh::Feature) to `doc` and returns it; into `analysis`, or
    FEM's active analysis when there is one. Name: `name` or mesh_obj.Name + "_Solid"; Label:
    mesh_obj.Label + "_Solid". Nodes on `shape`, or on the Shape of mesh_obj's Source (a remesh
    feature's source) when there is one. `quality`: bound on the radius-edge ratio, in QUALITY_RANGE.
    Everything is computed before the document changes, in one transaction ("FEM solid mesh"):
    a failure leaves the document as it was. Raises as solid_mesh()."""
    if doc is None:
        raise ValueError("no document")
    mesh = fem.mesh_of(mesh_obj)
    shape_obj = None
    if shape is None:
        shape, shape_obj = fem.source_shape(mesh_obj), shape_object(mesh_obj)
    result = solid_mesh(mesh, shape, order, quality, progress, mesh_obj.Label, faces, source_mesh(mesh_obj),
                        fem.expected_components(mesh_obj))
    return add_fem_solid(doc, mesh_obj, result, name, analysis, shape_obj)


def add_fem_solid(doc, mesh_obj, result, name=None, analysis=None, shape_obj=None):
    """Puts a SolidMesh made from mesh_obj into the document (make_fem_solid's last step, which the
    GUI runs in the main thread after the worker made `result`). With result.faces, a Part::Feature
    holding them is added too: name mesh_obj.Name + "_Faces", label mesh_obj.Label + "_Faces".
    The FEM mesh object's property Part links that, or `shape_obj` (the object whose shape the
    nodes were put on): FEM reads a mesh's shape from it (femmesh/meshsetsgetter.py, as for its
    own Gmsh mesh objects), e.g. to tell the solids of several materials apart."""
    if analysis is None:
        analysis = fem.active_analysis(doc)
    fem_mesh = result.fem_mesh()
    _report(mesh_obj.Label, fem_mesh, result)
    with document.document_change(doc, TRANSACTION):
        if result.faces is not None:
            faces_obj = doc.addObject("Part::Feature", faces_name(mesh_obj))
            faces_obj.Shape = result.faces
            faces_obj.Label = mesh_obj.Label + "_Faces"
            shape_obj = faces_obj
        fem_obj = doc.addObject("Fem::FemMeshObject", name or mesh_obj.Name + "_Solid")
        if shape_obj is not None:
            fem_obj.addProperty("App::PropertyLink", "Part", "FEM Mesh", "the Part shape the nodes lie on, "
                                "whose faces the constraints reference")
            fem_obj.Part = shape_obj
        fem.fill_fem_mesh_object(fem_obj, fem_mesh, mesh_obj.Label + "_Solid")
        if analysis is not None:
            analysis.addObject(fem_obj)
    return fem_obj


def shape_object(mesh_obj):
    """mesh_obj.Source when it holds the shape the nodes go on (fem.source_shape), else None."""
    return mesh_obj.Source if fem.source_shape(mesh_obj) is not None else None


source_mesh = fem.source_mesh  # the mesh mesh_obj.Source links (an imported STL), or None


def faces_name(mesh_obj):
    """Name of the faceted solid add_fem_solid makes for a mesh without a shape."""
    return mesh_obj.Name + "_Faces"


def _report(label, fem_mesh, result):
    q = result.quality
    FreeCAD.Console.PrintLog(
        "LiftRemesh: %s filled: %d nodes, %d tet%d elements; minimum dihedral angle %.1f deg, "
        "radius ratio worst %.3f, mean %.3f%s\n" % (
            label, fem_mesh.NodeCount, fem_mesh.VolumeCount, 10 if result.order == 2 else 4,
            q["min_dihedral_deg"], q["radius_ratio_min"], q["radius_ratio_mean"],
            "" if result.snapped is None else "; surface nodes put on faces %(face)d, then on edges "
                                              "between faces %(crease)d" % result.snapped))
