"""The crease check of issue 35, measured against the CAD model itself (its B-rep), not against the
tessellation LiftRemesh is given; used by tests/freecad/test_creases.py and scripts/crease_check.py.

Reference (`brep_creases`): every B-rep edge between two faces is sampled; at each sample the angle
between the two faces' normals (their outward normals, so 90 degrees for a box's edge and 150 for a
30-degree knife edge) is taken. Samples where it is `CREASE_DEG` or more are crease samples. A
corner is a B-rep vertex where `CORNER_CREASES` or more crease edges meet (an edge counts at a
vertex when its sample there is a crease sample). For a mesh with no B-rep, `mesh_creases` takes the
tessellation's own edges at `CREASE_DEG` or more instead, but for the edges of its slivers (a weaker
reference: its creases are the tessellation's, placed as well as the exporter placed them).

Figures (`measure`), h the target edge length:
- recall: the fraction of crease samples within `RECALL_H` h of an output edge whose dihedral angle
  (between its two triangles' normals) is `OUTPUT_CREASE_DEG` or more;
- corner distances: from each corner to the nearest output vertex, in units of h;
- spurious: the output edges over `SPURIOUS_DEG` whose midpoint lies farther than `SPURIOUS_H` h from
  every crease sample (sampled at most SAMPLE_H h apart), their length over the crease length.

Arrays: points (n, 3) float64, triangles (m, 3) int. numpy only; FreeCAD for the B-rep functions.
"""
import math
import typing

import numpy as np

import mesh_checks

CREASE_DEG = 30.0
CORNER_CREASES = 3
OUTPUT_CREASE_DEG = 15.0
RECALL_H = 0.1
SPURIOUS_DEG = 40.0
SPURIOUS_H = 0.5
SAMPLE_H = 0.05  # crease samples at most this many h apart
SLIVER_H = 0.01  # mesh_creases: the edges of triangles narrower than this many h do not count

# Issue 35's targets.
RECALL_TARGET = 0.99
CORNER_TARGET_H = 0.1
SPURIOUS_TARGET = 0.02


class Creases:
    """A reference: crease samples (n, 3) with their angles (n,) in degrees, the corners (k, 3),
    the crease length, and what it was taken from ("B-rep" or "tessellation")."""

    def __init__(self, samples, angles, corners, length, source):
        self.samples = np.asarray(samples, dtype=np.float64).reshape(-1, 3)
        self.angles = np.asarray(angles, dtype=np.float64).reshape(-1)
        self.corners = np.asarray(corners, dtype=np.float64).reshape(-1, 3)
        self.length = float(length)
        self.source = source


def edge_length_for(area, vertices):
    """The edge length h of an equilateral mesh with `vertices` vertices on `area`: the target edge
    length a vertex count stands for (area sqrt(3)/2 h^2 per vertex, as the pipeline counts)."""
    return math.sqrt(area / (math.sqrt(3.0) / 2.0 * vertices))


def triangle_normals(points, triangles):
    """Unit normals (m, 3); a degenerate triangle's is zero."""
    p = points[triangles]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    norm = np.linalg.norm(n, axis=1)
    return n / np.where(norm > 0.0, norm, 1.0)[:, None]


def surface_area(points, triangles):
    p = points[triangles]
    return 0.5 * float(np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum())


def dihedral_edges(points, triangles, with_triangles=False):
    """(edges (e, 2), angles (e,) in degrees) of the edges with exactly two triangles: the angle
    between their normals, 0 where flat; and with_triangles, the two triangles (e, 2) as well."""
    tris = np.asarray(triangles, dtype=np.int64)
    ends = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    owner = np.tile(np.arange(len(tris)), 3)
    key = np.sort(ends, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, owner = key[order], owner[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    starts = np.flatnonzero(same)
    # an edge used exactly twice: the pair (i, i + 1) equal, not equal to its neighbours beyond
    before = np.concatenate([[False], same])[starts]
    after = np.concatenate([same, [False]])[starts + 1]
    pairs = starts[~before & ~after]
    normals = triangle_normals(points, tris)
    cosine = np.clip(np.einsum("ij,ij->i", normals[owner[pairs]], normals[owner[pairs + 1]]), -1.0, 1.0)
    angles = np.degrees(np.arccos(cosine))
    if with_triangles:
        return key[pairs], angles, np.stack([owner[pairs], owner[pairs + 1]], axis=1)
    return key[pairs], angles


def triangle_widths(points, triangles):
    """Each triangle's smallest altitude: twice its area over its longest edge (m,)."""
    p = np.asarray(points, dtype=np.float64)[np.asarray(triangles, dtype=np.int64)]
    twice = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    longest = np.max(np.linalg.norm(p - np.roll(p, 1, axis=1), axis=2), axis=1)
    return twice / np.where(longest > 0.0, longest, 1.0)


def _segment_distances(queries, starts, ends, chunk=256):
    """Distance from each query point to the nearest of the segments (starts[i], ends[i])."""
    queries = np.asarray(queries, dtype=np.float64).reshape(-1, 3)
    if len(starts) == 0:
        return np.full(len(queries), np.inf)
    d = ends - starts
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    out = np.empty(len(queries))
    for i in range(0, len(queries), chunk):
        q = queries[i:i + chunk]
        t = np.clip(np.einsum("qsj,sj->qs", q[:, None, :] - starts[None], d) / dd, 0.0, 1.0)
        closest = starts[None] + t[..., None] * d[None]
        out[i:i + chunk] = np.sqrt(np.min(np.sum((q[:, None, :] - closest) ** 2, axis=2), axis=1))
    return out


def _sample_segments(starts, ends, step):
    """Points along segments at most `step` apart (both ends included), and their lengths."""
    points, lengths = [], []
    for a, b in zip(starts, ends):
        length = float(np.linalg.norm(b - a))
        n = max(1, int(math.ceil(length / step)))
        t = np.linspace(0.0, 1.0, n + 1)[:, None]
        points.append(a + t * (b - a))
        lengths.append(length)
    return (np.concatenate(points) if points else np.zeros((0, 3))), np.asarray(lengths)


def mesh_creases(points, triangles, h, crease_deg=CREASE_DEG, min_width_h=SLIVER_H):
    """The reference of a mesh without a B-rep: its own edges at `crease_deg` or more, sampled at
    most SAMPLE_H h apart; a corner where CORNER_CREASES or more of them meet. An edge of a
    triangle narrower than `min_width_h` h does not count: where a tessellation joins two
    differently faceted patches of one smooth surface through a ring of slivers, the ring's rims
    turn by 90 degrees across a few thousandths of h, and are no crease of the part (the rule
    SharpEdgeCriterion in tests/native/end_to_end/pipeline_test.cpp applies, at 0.01 h)."""
    points = np.asarray(points, dtype=np.float64)
    edges, angles, sides = dihedral_edges(points, triangles, with_triangles=True)
    keep = angles >= crease_deg
    if min_width_h > 0.0:
        keep &= np.all(triangle_widths(points, triangles)[sides] >= min_width_h * h, axis=1)
    edges, angles = edges[keep], angles[keep]
    samples, per_edge = [], []
    for (a, b), angle in zip(edges, angles):
        s, _ = _sample_segments(points[[a]], points[[b]], SAMPLE_H * h)
        samples.append(s)
        per_edge.append(np.full(len(s), angle))
    degree = np.bincount(edges.reshape(-1), minlength=len(points)) if len(edges) else np.zeros(len(points), int)
    length = float(np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1).sum()) if len(edges) else 0.0
    return Creases(np.concatenate(samples) if samples else np.zeros((0, 3)),
                   np.concatenate(per_edge) if per_edge else np.zeros(0),
                   points[degree >= CORNER_CREASES], length, "tessellation")


def brep_creases(shape, h, crease_deg=CREASE_DEG):
    """The reference of a Part shape's B-rep (see the module's text), sampled at most SAMPLE_H h
    apart along each edge."""
    import Part

    samples, angles, length = [], [], 0.0
    crease_ends = {}  # vertex index -> number of crease edges ending there
    vertices = shape.Vertexes

    def vertex_index(point):
        for i, v in enumerate(vertices):
            if v.Point.distanceToPoint(point) <= 1e-6 * max(1.0, h):
                return i
        return None

    def uv_of(face, edge):
        """The (u, v) on `face` of a point of `edge` at the edge's parameter t: its curve on the
        face (the pcurve, sharing the edge's parameter; curveOnSurface gives (curve2d, ..., first,
        last) in 0.20 and 1.0), else the surface's projection (Surface.parameter, slower)."""
        try:
            curve2d = face.curveOnSurface(edge)[0]
        except Exception:  # no pcurve stored for it
            curve2d = None

        def uv(t, point):
            if curve2d is not None:
                q = curve2d.value(t)
                if face.Surface.value(q.x, q.y).distanceToPoint(point) <= 1e-3 * h:
                    return q.x, q.y
            return face.Surface.parameter(point)
        return uv

    def normal(face, uv):
        n = face.normalAt(*uv)  # the face's orientation included: outward on a solid
        return np.array([n.x, n.y, n.z])

    for edge in shape.Edges:
        if edge.Length <= 0.0:  # a degenerate edge (a cone's apex)
            continue
        faces = shape.ancestorsOfType(edge, Part.Face)
        if len(faces) != 2 or faces[0].isSame(faces[1]):  # a boundary or a seam
            continue
        n = max(2, int(math.ceil(edge.Length / (SAMPLE_H * h))) + 1)
        ts = [edge.getParameterByLength(s) for s in np.linspace(0.0, edge.Length, n)]
        points = [edge.valueAt(t) for t in ts]
        uv0, uv1 = uv_of(faces[0], edge), uv_of(faces[1], edge)
        turn = []
        for t, p in zip(ts, points):
            a, b = normal(faces[0], uv0(t, p)), normal(faces[1], uv1(t, p))
            turn.append(math.degrees(math.acos(max(-1.0, min(1.0, float(a.dot(b)))))))
        turn = np.array(turn)
        xyz = np.array([(p.x, p.y, p.z) for p in points])
        crease = turn >= crease_deg
        samples.append(xyz[crease])
        angles.append(turn[crease])
        step = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
        length += float(np.sum(step * 0.5 * (crease[1:].astype(float) + crease[:-1])))
        for end, is_crease in ((points[0], crease[0]), (points[-1], crease[-1])):
            i = vertex_index(end)
            if is_crease and i is not None:
                crease_ends[i] = crease_ends.get(i, 0) + 1
    corners = [tuple(vertices[i].Point) for i, k in sorted(crease_ends.items()) if k >= CORNER_CREASES]
    return Creases(np.concatenate(samples) if samples else np.zeros((0, 3)),
                   np.concatenate(angles) if angles else np.zeros(0), corners, length, "B-rep")


class Figures(typing.NamedTuple):
    """What `measure` gives."""
    recall: float
    missed_angles: np.ndarray  # the angles of the crease samples missed, in degrees
    corner_h: np.ndarray  # each corner's distance to the nearest output vertex, in h
    spurious: float
    samples: int  # crease samples

    @property
    def worst_corner_h(self):
        return float(np.max(self.corner_h)) if len(self.corner_h) else 0.0

    def meets_targets(self):
        return (self.recall >= RECALL_TARGET and self.worst_corner_h <= CORNER_TARGET_H and
                self.spurious <= SPURIOUS_TARGET)


def measure(points, triangles, creases, h):
    """The figures of an output mesh against a reference (see the module's text)."""
    points = np.asarray(points, dtype=np.float64)
    edges, angles = dihedral_edges(points, triangles)
    sharp = edges[angles >= OUTPUT_CREASE_DEG]
    distance = _segment_distances(creases.samples, points[sharp[:, 0]], points[sharp[:, 1]])
    found = distance <= RECALL_H * h
    recall = float(np.mean(found)) if len(found) else 1.0
    corner_h = np.array([np.min(np.linalg.norm(points - c, axis=1)) / h for c in creases.corners])
    spurious_edges = edges[angles > SPURIOUS_DEG]
    mid = 0.5 * (points[spurious_edges[:, 0]] + points[spurious_edges[:, 1]])
    if len(creases.samples):
        far = _nearest_point_distances(mid, creases.samples) > SPURIOUS_H * h
    else:
        far = np.ones(len(mid), dtype=bool)
    spurious_length = float(np.linalg.norm(points[spurious_edges[far, 1]] - points[spurious_edges[far, 0]], axis=1).sum())
    spurious = spurious_length / creases.length if creases.length > 0.0 else (0.0 if spurious_length == 0.0 else np.inf)
    return Figures(recall, creases.angles[~found], corner_h, spurious, len(found))


def _nearest_point_distances(queries, points, chunk=256):
    out = np.empty(len(queries))
    for i in range(0, len(queries), chunk):
        q = queries[i:i + chunk]
        out[i:i + chunk] = np.sqrt(np.min(np.sum((q[:, None, :] - points[None]) ** 2, axis=2), axis=1))
    return out


def tessellate(shape, linear_deflection=0.1, angular_deflection_deg=30.0):
    """(points, triangles) of a Part shape as FreeCAD's STL export makes them (Preferences >
    Import-Export > Mesh formats: 0.1 mm and 30 degrees, the add-on's tessellation defaults)."""
    import MeshPart

    return mesh_checks.arrays(MeshPart.meshFromShape(Shape=shape, LinearDeflection=linear_deflection,
                                                     AngularDeflection=math.radians(angular_deflection_deg),
                                                     Relative=False))
