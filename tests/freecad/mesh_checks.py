"""Independent measurements for the FreeCAD tests: they do not use LiftRemesh's own report, so a
wrong report cannot make a test pass. Arrays: points (n, 3) float64, triangles (m, 3) int.
"""
import math

import numpy as np


def arrays(mesh):
    """(points, triangles) of a Mesh.Mesh."""
    points, facets = mesh.Topology
    return (np.array([(p.x, p.y, p.z) for p in points], dtype=np.float64).reshape(-1, 3),
            np.array(facets, dtype=np.int64).reshape(-1, 3))


def directed_edges(triangles):
    """Counts of directed edges (a, b)."""
    counts = {}
    for a, b, c in triangles.tolist():
        for e in ((a, b), (b, c), (c, a)):
            counts[e] = counts.get(e, 0) + 1
    return counts


def is_closed_oriented_manifold(triangles):
    """Every edge used by exactly two triangles, once in each direction."""
    counts = directed_edges(triangles)
    return all(n == 1 and counts.get((b, a)) == 1 for (a, b), n in counts.items())


def euler_characteristic(points, triangles):
    used = np.unique(triangles)
    edges = {(min(a, b), max(a, b)) for a, b in directed_edges(triangles)}
    return len(used) - len(edges) + len(triangles)


def connected_components(triangles):
    """Number of pieces the triangles make, joined through shared vertices."""
    parent = {int(v): int(v) for v in np.unique(triangles)}

    def find(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for a, b, c in triangles.tolist():
        parent[find(b)] = find(a)
        parent[find(c)] = find(a)
    return len({find(v) for v in parent})


def shape_euler_characteristic(shape):
    """chi of the boundary surface from the BRep: V - E + sum over faces of (2 - wires), a face with
    k wires being a disk with k - 1 holes (a periodic face is cut open along its seam edge)."""
    return len(shape.Vertexes) - len(shape.Edges) + sum(2 - len(f.Wires) for f in shape.Faces)


def kappa(points, triangles):
    """Eq. 26 per triangle: 16 A^2 / (l1 l2 l3 (l1 + l2 + l3)); 1 equilateral, 0 degenerate."""
    a, b, c = (points[triangles[:, i]] for i in range(3))
    l1, l2, l3 = (np.linalg.norm(u - v, axis=1) for u, v in ((b, c), (c, a), (a, b)))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    denom = l1 * l2 * l3 * (l1 + l2 + l3)
    # A triangle with a zero-length edge is degenerate: 0, as measure/quality.cpp gives it.
    return np.clip(np.divide(16.0 * area ** 2, denom, out=np.zeros_like(denom), where=denom > 0), 0.0, 1.0)


def sharp_edge_length(points, triangles, angle_deg=60.0):
    """Total length of mesh edges whose two face normals differ by more than angle_deg."""
    a, b, c = (points[triangles[:, i]] for i in range(3))
    normals = np.cross(b - a, c - a)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    faces_of = {}
    for f, (i, j, k) in enumerate(triangles.tolist()):
        for e in ((i, j), (j, k), (k, i)):
            faces_of.setdefault((min(e), max(e)), []).append(f)
    limit = math.cos(math.radians(angle_deg))
    total = 0.0
    for (i, j), faces in faces_of.items():
        if len(faces) == 2 and np.dot(normals[faces[0]], normals[faces[1]]) < limit:
            total += np.linalg.norm(points[i] - points[j])
    return total


def shape_sharp_edge_length(shape, angle_deg=60.0, samples=9):
    """Total length of BRep edges along which the two faces' normals differ by more than angle_deg
    (tested at a few points of each edge; a fillet's tangent edges count as smooth)."""
    limit = math.cos(math.radians(angle_deg))
    total = 0.0
    for edge in shape.Edges:
        faces = _unique(shape.ancestorsOfType(edge, type(shape.Faces[0])))
        if len(faces) != 2:
            continue
        first, last = edge.FirstParameter, edge.LastParameter
        sharp = 0
        for t in np.linspace(first, last, samples + 2)[1:-1]:
            p = edge.valueAt(t)
            n = [_face_normal(f, p) for f in faces]
            if n[0].dot(n[1]) < limit:
                sharp += 1
        if sharp > samples // 2:
            total += edge.Length
    return total


def _unique(faces):
    out = []
    for f in faces:
        if not any(f.isSame(g) for g in out):
            out.append(f)
    return out


def _face_normal(face, point):
    u, v = face.Surface.parameter(point)
    n = face.normalAt(u, v)
    return n


def point_triangle_distances(queries, points, triangles):
    """Exact distance from each query point to the triangle mesh (closest point on a triangle,
    Ericson 5.1.5). Candidates are pruned without losing the answer: u = distance to the nearest
    mesh vertex bounds the result, and a triangle whose vertices lie within R of its centroid can
    only be closer than u if its centroid is within u + R; triangles are bucketed by R (powers of
    two) with one kd-tree of centroids per bucket."""
    from scipy.spatial import cKDTree

    queries = np.asarray(queries, dtype=np.float64)
    a, b, c = (points[triangles[:, i]] for i in range(3))
    centroid = (a + b + c) / 3.0
    radius = np.max([np.linalg.norm(v - centroid, axis=1) for v in (a, b, c)], axis=0)
    upper, _ = cKDTree(points[np.unique(triangles)]).query(queries)
    best = upper ** 2
    bucket = np.floor(np.log2(np.maximum(radius, 1e-300))).astype(int)
    for level in np.unique(bucket):
        members = np.nonzero(bucket == level)[0]
        reach = upper + radius[members].max() + 1e-12
        hits = cKDTree(centroid[members]).query_ball_point(queries, reach)
        q_index = np.repeat(np.arange(len(queries)), [len(h) for h in hits])
        if len(q_index) == 0:
            continue
        t_index = members[np.concatenate([np.asarray(h, dtype=np.int64) for h in hits])]
        for s in range(0, len(q_index), 1 << 20):
            qi, ti = q_index[s:s + (1 << 20)], t_index[s:s + (1 << 20)]
            d2 = _squared_distance(queries[qi], a[ti], b[ti], c[ti], b[ti] - a[ti], c[ti] - a[ti])
            np.minimum.at(best, qi, d2)
    return np.sqrt(best)


def _squared_distance(p, a, b, c, ab, ac):
    ap = p - a
    d1, d2 = np.sum(ab * ap, -1), np.sum(ac * ap, -1)
    bp = p - b
    d3, d4 = np.sum(ab * bp, -1), np.sum(ac * bp, -1)
    cp = p - c
    d5, d6 = np.sum(ab * cp, -1), np.sum(ac * cp, -1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    denom = va + vb + vc
    with np.errstate(divide="ignore", invalid="ignore"):
        v = vb / denom
        w = vc / denom
        closest = a + ab * v[..., None] + ac * w[..., None]  # inside the face
        # vertex and edge regions, in the order of Ericson's tests (last assignment wins: reverse)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        closest = np.where(((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0))[..., None],
                           b + (c - b) * t_bc[..., None], closest)
        t_ac = d2 / (d2 - d6)
        closest = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[..., None], a + ac * t_ac[..., None], closest)
        closest = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c, closest)
        t_ab = d1 / (d1 - d3)
        closest = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[..., None], a + ab * t_ab[..., None], closest)
        closest = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b, closest)
        closest = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a, closest)
    return np.sum((p - closest) ** 2, -1)


def hausdorff(points_a, triangles_a, points_b, triangles_b, samples=4000, seed=0):
    """Two-sided Hausdorff distance between two triangle meshes, from their vertices plus random
    points on their triangles (a lower bound that converges with samples)."""
    def sample(points, triangles):
        rng = np.random.default_rng(seed)
        a, b, c = (points[triangles[:, i]] for i in range(3))
        area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
        f = rng.choice(len(triangles), size=samples, p=area / area.sum())
        r1, r2 = rng.random(samples), rng.random(samples)
        s = np.sqrt(r1)
        inner = (1 - s)[:, None] * a[f] + (s * (1 - r2))[:, None] * b[f] + (s * r2)[:, None] * c[f]
        return np.vstack([points[np.unique(triangles)], inner])

    ab = point_triangle_distances(sample(points_a, triangles_a), points_b, triangles_b).max()
    ba = point_triangle_distances(sample(points_b, triangles_b), points_a, triangles_a).max()
    return max(ab, ba)
