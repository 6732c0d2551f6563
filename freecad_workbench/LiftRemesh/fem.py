"""FEM preprocessing: a remeshed surface as a shell FEM mesh (linear triangles) for FreeCAD FEM.

    import LiftRemesh.fem as fem
    fem_obj = fem.make_fem_shell(doc, remesh_feature)      # -> Fem::FemMeshObject
    problems = fem.check_fem_mesh(fem_obj.FemMesh)         # [] when FEM can use it

Every triangle of the mesh becomes one tria3 face element (CalculiX S3 with a shell thickness,
ObjectsFem.makeElementGeometry2D); nodes are the mesh's points, numbered from 1 in the mesh's
order, elements its facets, numbered from 1, orientation kept.

Putting nodes on the geometry. FreeCAD 0.20's CalculiX writer finds the nodes of a constraint
from its reference shapes (femmesh/meshtools.py get_femnodes_by_refshape, and for edge and face
loads get_ref_edgenodes_table / get_ref_facenodes_table), through FemMesh.getNodesByVertex,
getNodesByEdge and getNodesByFace: a node belongs to a vertex, edge or face when its distance to
it is below the BRep tolerance of that vertex, edge or face, typically 1e-7 mm. A remeshed mesh
misses that by far: Mesh.Mesh stores single-precision points (1e-6 mm off at 50 mm), and the
remesher's vertices are centroids of Voronoi cells, so the vertices along an open boundary lie
about half an edge length inside the boundary (0.4 to 0.6 times the local edge length on a
plate). Given the shape the mesh was made from, the nodes are therefore moved onto it, in double
precision, each only when it is already close, measured in its local edge length h (the mean
length of the mesh edges at the node):

1. corners: each vertex of the shape where two or more free edges meet (edges of one face only,
   not seams) takes the nearest mesh boundary node, when closer than VERTEX_SNAP * h;
2. the other boundary nodes (on mesh edges used by one triangle) go to the nearest point of the
   shape's free edges, when closer than EDGE_SNAP * h;
3. every other node goes to the nearest point of the shape's faces, when closer than
   FACE_SNAP * h (this removes the single-precision error; a node near a crease between two faces
   may land on the crease).

So a constraint on a free edge gets the whole chain of boundary nodes along it, corner to corner,
and FEM's edge loads add up to the full edge length. A move that would fold or collapse a triangle
(its area, projected on its old normal, dropping below MIN_AREA_RATIO of what it was) is undone for
that triangle's nodes. Nodes near edges shared by two faces are not put on those edges.

Refusal. A surface with a closed component facing inward that is no cavity of another (an
inside-out piece: it bounds no solid), or with more components, or more facing inward, than what it
was made from (its remesh report's input, or its source mesh) is refused (SurfaceRefused, in words
saying which and where) before anything is made: FEM's shell elements would take their normals and
their mass from a piece that stands for nothing, and TetGen refuses such a surface
(fem_solid.py refuses it the same way).

Needs FreeCAD's App modules only (Fem, Part, Mesh): macros and tests call it without the GUI.
"""
import json

import numpy as np

import FreeCAD
from . import document
from . import native

# Largest move onto the geometry, as a fraction of the local mesh edge length (module doc).
VERTEX_SNAP = 1.0   # a 90-degree corner's nearest node is about 0.7 h away
EDGE_SNAP = 0.75    # boundary nodes lie 0.4 to 0.6 h inside the boundary
FACE_SNAP = 0.25    # nodes are on the tessellated surface: chord error, rounding
MIN_AREA_RATIO = 0.25
TRANSACTION = "FEM shell mesh"
SHOWN = 3  # places named in a refusal


class SurfaceRefused(ValueError):
    """The surface cannot be meshed for FEM: open, non-manifold, crossing itself (fem_solid.py), or
    with components facing inward or not in its source. The message says which and where."""


# ----- mesh -> FEM mesh ---------------------------------------------------------------------------

def fem_mesh_from_mesh(mesh, shape=None):
    """A Fem.FemMesh of linear triangles from a Mesh.Mesh: node i + 1 is the mesh's point i, element
    j + 1 its facet j (tria3, same orientation). With `shape` (a Part shape, usually the one the mesh
    was remeshed from) nodes close to it are moved onto it first (see the module doc), so FEM
    constraints that reference the shape's edges and faces find their nodes.
    Raises ValueError for something that is not a mesh or has no triangle."""
    points, triangles = mesh_arrays(mesh)
    if shape is not None:
        points, _ = snap_points_to_shape(points, triangles, shape)
    return build_fem_mesh(points, triangles)


def mesh_arrays(mesh):
    """(points: list of FreeCAD.Vector in placed coordinates, triangles: list of 0-based index
    triples) of a Mesh.Mesh; ValueError when it is not a mesh or has no triangle."""
    import Mesh

    if not isinstance(mesh, Mesh.Mesh):
        raise ValueError("expected a Mesh.Mesh, got %s" % type(mesh).__name__)
    if mesh.CountFacets == 0:
        raise ValueError("the mesh has no triangles")
    points, facets = mesh.Topology
    return [FreeCAD.Vector(p) for p in points], [tuple(f) for f in facets]


def build_fem_mesh(points, triangles):
    """A Fem.FemMesh with the nodes `points` (ids from 1) and one tria3 face element per triangle
    (ids from 1; node indices 0-based)."""
    import Fem

    fem_mesh = Fem.FemMesh()
    for node_id, p in enumerate(points, 1):
        fem_mesh.addNode(p.x, p.y, p.z, node_id)
    for element_id, (a, b, c) in enumerate(triangles, 1):
        fem_mesh.addFace([a + 1, b + 1, c + 1], element_id)
    return fem_mesh


# ----- components ---------------------------------------------------------------------------------

def component_problems(points, triangles, expected=None):
    """Why FEM and TetGen cannot take this surface's components, in sentences that say where
    ([] when they can): closed components facing inward (negative signed volume) that are no
    cavity of another one; given `expected` = (components, inward components) of what the surface
    was made from (expected_components), more components or more inward ones than that (a
    hollowed solid's cavity faces inward in both). points (n, 3), triangles (m, 3) 0-based."""
    points = np.asarray(points, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    found = native.load().components(points, triangles)
    closed, volume, cavity = found["closed"], found["signed_volume"], found["cavity"]
    inward = np.nonzero(closed & (np.nan_to_num(volume) < 0.0))[0]
    _, first = np.unique(found["label"], return_index=True)  # each component's first triangle

    def where(components):
        return ", ".join("%s (signed volume %.4g)" % (_point_text(points[triangles[first[c]]].mean(axis=0)), volume[c])
                         for c in components[:SHOWN])

    problems = []
    inside_out = [c for c in inward if not cavity[c]]
    if inside_out:
        problems.append("%d closed components face inward and are no cavity of another (inside-out pieces, "
                        "bounding no solid), e.g. at %s" % (len(inside_out), where(inside_out)))
    if expected is not None:
        pieces, inward_expected = expected
        if len(closed) > pieces:
            problems.append("made of %d components where its source has %d (pieces the source does not have)"
                            % (len(closed), pieces))
        if len(inward) > inward_expected and not inside_out:
            problems.append("%d closed components face inward where its source has %d, e.g. at %s"
                            % (len(inward), inward_expected, where(list(inward))))
    return problems


def expected_components(mesh_obj):
    """(components, inward components) of what mesh_obj was made from: the input counts of its
    remesh report (a remesh feature's Report), else those of the mesh its Source links (source_mesh),
    else None (nothing to compare with)."""
    try:
        counts = json.loads(getattr(mesh_obj, "Report", "") or "{}").get("input", {})
        return int(counts["components"]), int(counts["inward_components"])
    except (ValueError, KeyError, TypeError, AttributeError):
        pass
    source = source_mesh(mesh_obj)
    if source is None:
        return None
    points, facets = source.Topology
    found = native.load().components(np.array([tuple(p) for p in points], dtype=np.float64).reshape(-1, 3),
                                     np.array(facets, dtype=np.int64).reshape(-1, 3))
    volume = np.nan_to_num(found["signed_volume"])
    return len(found["closed"]), int(np.count_nonzero(found["closed"] & (volume < 0.0)))


def source_mesh(mesh_obj):
    """The Mesh of the object mesh_obj.Source links when that is a mesh (a remesh feature of an
    imported STL), or None."""
    source = getattr(mesh_obj, "Source", None)
    mesh = getattr(source, "Mesh", None) if source is not None else None
    return mesh if mesh is not None and mesh.CountFacets else None


def _point_text(p):
    return "(%.3f, %.3f, %.3f)" % tuple(p)


# ----- nodes onto the geometry --------------------------------------------------------------------

def snap_points_to_shape(points, triangles, shape):
    """Moves points onto the shape's corners, free edges and faces (module doc). Returns (new list
    of points, counts: {"vertex", "edge", "face", "undone", "boundary_missed"}); `points` itself
    is not changed."""
    uses = edge_use(triangles)
    lengths = local_lengths(points, uses)
    boundary = sorted({i for edge, n in uses.items() if n == 1 for i in edge})
    free_edges, corners = free_edges_and_corners(shape)

    targets = {}  # node -> (new position, kind)
    for corner in corners:
        node = _nearest_free_node(points, boundary, corner.Point, targets)
        if node is not None and (points[node] - corner.Point).Length <= VERTEX_SNAP * lengths[node]:
            targets[node] = (FreeCAD.Vector(corner.Point), "vertex")
    if free_edges:
        snap_to(_compound(free_edges), [i for i in boundary if i not in targets],
                points, lengths, EDGE_SNAP, "edge", targets)
    if shape.Faces:
        snap_to(_compound(shape.Faces), [i for i in range(len(points)) if i not in targets],
                points, lengths, FACE_SNAP, "face", targets)

    undone = undo_folding_moves(points, triangles, targets)
    moved = list(points)
    counts = {"vertex": 0, "edge": 0, "face": 0, "undone": len(undone)}
    for node, (position, kind) in targets.items():
        moved[node] = position
        counts[kind] += 1
    on_edges = {i for i, (_, kind) in targets.items() if kind in ("vertex", "edge")}
    counts["boundary_missed"] = len(boundary) - len(on_edges) if free_edges else 0
    return moved, counts


def free_edges_and_corners(shape):
    """(free edges, corners) of a shape: edges that belong to one face only and are not its seam
    (the boundary of an open shell; none on a solid), and the vertices where two or more of them
    meet (not the lone vertex of a closed edge such as a circle)."""
    import Part

    free_edges = []
    for edge in shape.Edges:
        if edge.Degenerated:
            continue
        faces = _unique(shape.ancestorsOfType(edge, Part.Face))
        if len(faces) == 1 and not edge.isSeam(faces[0]):
            free_edges.append(edge)
    vertices, uses = [], []
    for edge in free_edges:
        for vertex in _unique(edge.Vertexes):
            for k, known in enumerate(vertices):
                if known.isSame(vertex):
                    uses[k] += 1
                    break
            else:
                vertices.append(vertex)
                uses.append(1)
    corners = [v for v, n in zip(vertices, uses) if n >= 2]
    return free_edges, corners


def snap_to(target_shape, nodes, points, lengths, fraction, kind, targets):
    """Records in `targets` the nearest point of target_shape for each of `nodes` closer than
    fraction * its local edge length."""
    import Part

    box = target_shape.BoundBox
    box.enlarge(fraction * max(lengths))
    for node in nodes:
        p = points[node]
        if not box.isInside(p):
            continue
        distance, pairs, _ = target_shape.distToShape(Part.Vertex(p))
        if pairs and distance <= fraction * lengths[node]:
            targets[node] = (FreeCAD.Vector(pairs[0][0]), kind)


def undo_folding_moves(points, triangles, targets):
    """Drops from `targets` the moves of every triangle they would fold or collapse, until none
    does. Returns the dropped nodes."""
    undone = set()
    while True:
        bad = set()
        for tri in triangles:
            if not any(i in targets for i in tri):
                continue
            old = [points[i] for i in tri]
            new = [targets[i][0] if i in targets else points[i] for i in tri]
            n_old = (old[1] - old[0]).cross(old[2] - old[0])
            n_new = (new[1] - new[0]).cross(new[2] - new[0])
            area2 = n_old.dot(n_old)
            if area2 > 0.0 and n_new.dot(n_old) < MIN_AREA_RATIO * area2:
                bad.update(i for i in tri if i in targets)
        if not bad:
            return undone
        for i in bad:
            del targets[i]
        undone |= bad


def edge_use(triangles):
    """{(i, j) with i < j: number of triangles using that edge}."""
    use = {}
    for a, b, c in triangles:
        for i, j in ((a, b), (b, c), (c, a)):
            key = (i, j) if i < j else (j, i)
            use[key] = use.get(key, 0) + 1
    return use


def local_lengths(points, edge_use):
    """Mean length of the mesh edges at each point (0 for a point no triangle uses)."""
    total = [0.0] * len(points)
    count = [0] * len(points)
    for i, j in edge_use:
        length = (points[i] - points[j]).Length
        total[i] += length
        total[j] += length
        count[i] += 1
        count[j] += 1
    return [t / n if n else 0.0 for t, n in zip(total, count)]


def _nearest_free_node(points, nodes, position, taken):
    """The node of `nodes` nearest to `position` that is not in `taken`, or None."""
    best, best_distance = None, None
    for i in nodes:
        if i in taken:
            continue
        distance = (points[i] - position).Length
        if best is None or distance < best_distance:
            best, best_distance = i, distance
    return best


def _compound(shapes):
    import Part

    return Part.Compound(shapes)


def _unique(shapes):
    out = []
    for s in shapes:
        if not any(s.isSame(t) for t in out):
            out.append(s)
    return out


# ----- checks -------------------------------------------------------------------------------------

def check_fem_mesh(fem_mesh):
    """FreeCAD FEM's own view of a shell mesh, as its CalculiX tools would see it. Returns the list
    of problems found ([] when there is none):
    - the element counts CalculiX's prerequisite check (femtools/checksanalysis.py) looks at with a
      shell thickness: face elements, no volume elements; and no edge elements either;
    - femmesh/meshtools.py get_femmesh_eletype (the element type the writer uses) is "tria3", and
      every element of get_femelement_table has three distinct, existing nodes;
    - nodes are numbered 1..NodeCount and every node is used by an element
      (meshtools.get_femnodes_ele_table);
    - no element is degenerate (meshtools.get_triangle_area, relative to the mean area).
    """
    from femmesh import meshtools

    problems = []
    if fem_mesh.FaceCount == 0:
        return ["the FEM mesh has no face (shell) elements"]
    if fem_mesh.VolumeCount:
        problems.append("%d volume elements in a shell mesh" % fem_mesh.VolumeCount)
    if fem_mesh.EdgeCount:
        problems.append("%d edge elements in a shell mesh" % fem_mesh.EdgeCount)
    if fem_mesh.TriangleCount != fem_mesh.FaceCount:
        problems.append("%d of %d face elements are not triangles"
                        % (fem_mesh.FaceCount - fem_mesh.TriangleCount, fem_mesh.FaceCount))
    nodes = fem_mesh.Nodes
    if sorted(nodes) != list(range(1, len(nodes) + 1)):
        problems.append("nodes are not numbered 1..%d" % len(nodes))
    table = meshtools.get_femelement_table(fem_mesh)
    element_type = meshtools.get_femmesh_eletype(fem_mesh, table)
    if element_type != "tria3":
        problems.append("element type %s, not tria3 (linear triangles)" % element_type)
    bad = [e for e, ns in table.items() if len(set(ns)) != 3 or any(n not in nodes for n in ns)]
    if bad:
        problems.append("%d elements without three distinct existing nodes, e.g. %d" % (len(bad), bad[0]))
        return problems
    unused = [n for n, uses in meshtools.get_femnodes_ele_table(nodes, table).items() if not uses]
    if unused:
        problems.append("%d nodes belong to no element, e.g. %d" % (len(unused), unused[0]))
    areas = {e: meshtools.get_triangle_area(*(nodes[n] for n in ns)) for e, ns in table.items()}
    mean = sum(areas.values()) / len(areas)
    degenerate = [e for e, a in areas.items() if a <= 1e-6 * mean]
    if degenerate:
        problems.append("%d degenerate elements, e.g. %d" % (len(degenerate), degenerate[0]))
    return problems


# ----- document -----------------------------------------------------------------------------------

def make_fem_shell(doc, mesh_obj, name=None, shape=None):
    """Adds a Fem::FemMeshObject of linear triangles made from `mesh_obj` (any object with a Mesh
    property: Mesh::Feature, a LiftRemesh remesh feature) to `doc` and returns it. Name: `name` or
    mesh_obj.Name + "_FEM"; Label: shell_mesh_label(mesh_obj). Nodes are put on `shape`, or when it is
    None on the Shape of the object mesh_obj's Source property links (a remesh feature's source),
    when there is one (see the module doc).
    Everything is computed before the document changes, and the change is one transaction
    ("FEM shell mesh"): any failure leaves the document as it was. ValueError for an object without
    a mesh or with an empty mesh; SurfaceRefused (a ValueError) for components facing inward or not
    in its source (component_problems)."""
    if doc is None:
        raise ValueError("no document")
    mesh = mesh_of(mesh_obj)
    if shape is None:
        shape = source_shape(mesh_obj)
    points, triangles = mesh_arrays(mesh)
    problems = component_problems([tuple(p) for p in points], triangles, expected_components(mesh_obj))
    if problems:
        raise SurfaceRefused("%s cannot be made a shell FEM mesh: it is %s" % (mesh_obj.Label, "; ".join(problems)))
    counts = None
    if shape is not None:
        points, counts = snap_points_to_shape(points, triangles, shape)
    fem_mesh = build_fem_mesh(points, triangles)
    _report(mesh_obj.Label, fem_mesh, counts)

    with document.document_change(doc, TRANSACTION):
        fem_obj = doc.addObject("Fem::FemMeshObject", name or mesh_obj.Name + "_FEM")
        fill_fem_mesh_object(fem_obj, fem_mesh, shell_mesh_label(mesh_obj))
    return fem_obj


def shell_mesh_label(mesh_obj):
    """"Plate_ShellMesh": named after the part, as FEM names its meshes (FEMMeshGmsh): the source's
    label for a remesh feature, else the mesh's own."""
    source = getattr(mesh_obj, "Source", None)
    return "%s_ShellMesh" % (source.Label if source is not None else mesh_obj.Label)


def active_analysis(doc):
    """FEM's active analysis when it is in `doc` (FemGui.getActiveAnalysis, GUI only), else None."""
    if not FreeCAD.GuiUp:
        return None
    try:
        import FemGui

        analysis = FemGui.getActiveAnalysis()
    except Exception:  # FEM not installed or not loaded: no analysis
        return None
    if analysis is None or analysis.Document is not doc:
        return None
    return analysis


def add_to_analysis(analysis, fem_obj, thickness=None):
    """Puts a shell FEM mesh into a FEM analysis, with a shell thickness object
    (ObjectsFem.makeElementGeometry2D; `thickness` in mm, FEM's default when None) unless the
    analysis has one. Returns the objects added to it. No transaction of its own."""
    import ObjectsFem

    added = [fem_obj]
    analysis.addObject(fem_obj)
    if not any(_is_element_geometry_2d(obj) for obj in analysis.Group):
        geometry = (ObjectsFem.makeElementGeometry2D(fem_obj.Document) if thickness is None
                    else ObjectsFem.makeElementGeometry2D(fem_obj.Document, thickness))
        analysis.addObject(geometry)
        added.append(geometry)
    return added


def plate_thickness(shape):
    """The thickness of a plate-like solid, 2 * volume / area (its two large faces carry nearly all
    the area), to two significant digits; None for a shape without volume."""
    if shape is None or not shape.Solids or shape.Area <= 0 or shape.Volume <= 0:
        return None
    return float("%.2g" % (2.0 * shape.Volume / shape.Area))


def _is_element_geometry_2d(obj):
    """True for FEM's shell thickness object (Fem::FeaturePython of type Fem::ElementGeometry2D)."""
    proxy = getattr(obj, "Proxy", None)
    return getattr(proxy, "Type", None) == "Fem::ElementGeometry2D"


def fill_fem_mesh_object(fem_obj, fem_mesh, label):
    """Sets a new FEM mesh object's mesh and label and recomputes it."""
    fem_obj.FemMesh = fem_mesh
    fem_obj.Label = label
    fem_obj.recompute()


def mesh_of(mesh_obj):
    """The non-empty Mesh.Mesh of a document object, or ValueError saying what is wrong."""
    import Mesh

    label = getattr(mesh_obj, "Label", repr(mesh_obj))
    mesh = getattr(mesh_obj, "Mesh", None)
    if not isinstance(mesh, Mesh.Mesh):
        raise ValueError("%s has no mesh: select a mesh (e.g. a remeshed surface)" % label)
    if mesh.CountFacets == 0:
        raise ValueError("%s has an empty mesh: nothing to turn into a FEM mesh" % label)
    return mesh


def source_shape(mesh_obj):
    """The Shape of the object mesh_obj.Source links (a remesh feature's source), or None."""
    source = getattr(mesh_obj, "Source", None)
    shape = getattr(source, "Shape", None) if source is not None else None
    if shape is None or shape.isNull():
        return None
    return shape


def _report(label, fem_mesh, counts):
    """One log line on what was made; a warning when boundary nodes stayed off the shape's edges."""
    FreeCAD.Console.PrintLog("LiftRemesh: %s as a shell FEM mesh: %d nodes, %d tria3 elements%s\n" % (
        label, fem_mesh.NodeCount, fem_mesh.FaceCount,
        "" if counts is None else "; nodes put on corners %(vertex)d, edges %(edge)d, faces %(face)d, "
                                  "moves undone %(undone)d" % counts))
    if counts and counts["boundary_missed"]:
        FreeCAD.Console.PrintWarning(
            "LiftRemesh: %d boundary nodes of %s are not on an edge of its shape: constraints on those "
            "edges will not find them\n" % (counts["boundary_missed"], label))
