"""Tetrahedral meshes as numpy arrays, in FreeCAD's (SMESH's) node order: corners with the fourth on
the negative side of the first three, then for tet10 the middles of the edges 12, 23, 31, 14, 24,
34. Orientation, boundary faces, middle nodes, Jacobians of curved tet10 elements, and the shapes
FEM users judge a mesh by (dihedral angles, radius ratio). No FreeCAD: numpy only.
"""
import numpy as np

# Edges of a tetrahedron (corner indices) in the order of its middle nodes (module doc).
TET_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
# Faces of a tetrahedron (corner indices), each opposite one corner.
TET_FACES = ((1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1))


def edge_uses(triangles):
    """(edges (k, 2) with a < b, number of triangles using each)."""
    all_edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    return np.unique(all_edges, axis=0, return_counts=True)


def local_edge_lengths(points, triangles):
    """Mean length of the surface edges at each point: the size TetGen grades the interior from."""
    edges, _ = edge_uses(np.asarray(triangles, dtype=np.int64))
    lengths = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1)
    total = np.bincount(edges.ravel(), weights=np.repeat(lengths, 2), minlength=len(points))
    count = np.bincount(edges.ravel(), minlength=len(points))
    return total / np.maximum(count, 1)


def oriented(nodes, tets):
    """The tetrahedra with the first two corners swapped where the fourth is on the positive side
    of the first three (FreeCAD's order has it on the negative side)."""
    tets = np.array(tets, dtype=np.int64)
    positive = signed_volumes(nodes, tets) > 0.0
    tets[positive, 0], tets[positive, 1] = tets[positive, 1], tets[positive, 0].copy()
    return tets


def signed_volumes(nodes, tets):
    """Six times the signed volume of each tetrahedron (corners 0..3): negative in FreeCAD's order."""
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)


def boundary_faces(tets):
    """The faces of the tetrahedra (corners 0..3) that belong to one tetrahedron only, as sorted
    index triples (k, 3)."""
    faces = np.sort(tets[:, np.array(TET_FACES)].reshape(-1, 3), axis=1)
    unique, counts = np.unique(faces, axis=0, return_counts=True)
    return unique[counts == 1]


def boundary_mismatch(tets, triangles):
    """'' when the boundary faces of the tetrahedra are exactly the triangles, else what differs."""
    boundary = {tuple(f) for f in boundary_faces(tets).tolist()}
    surface = {tuple(sorted(t)) for t in np.asarray(triangles).tolist()}
    if boundary == surface:
        return ""
    return "%d surface triangles are not boundary faces, %d boundary faces are no surface triangle" % (
        len(surface - boundary), len(boundary - surface))


def quadratic(nodes, tets):
    """Tet10 from tet4: one new node at the middle of every edge, shared by the tetrahedra around it.
    Returns (nodes with the middles appended, (M, 10) elements)."""
    edges = np.sort(tets[:, np.array(TET_EDGES)].reshape(-1, 2), axis=1)
    unique, index = np.unique(edges, axis=0, return_inverse=True)
    middles = (nodes[unique[:, 0]] + nodes[unique[:, 1]]) / 2.0
    elements = np.hstack([tets, len(nodes) + index.reshape(-1, 6)])
    return np.vstack([nodes, middles]), elements


# Where the Jacobian of a tet10 element is checked: its ten nodes, in barycentric (xi, eta, zeta).
CHECK_POINTS = ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (.5, 0, 0), (.5, .5, 0), (0, .5, 0),
                (0, 0, .5), (.5, 0, .5), (0, .5, .5), (.25, .25, .25))


def _shape_derivatives(xi, eta, zeta):
    """(10, 3) derivatives of the quadratic tetrahedron's shape functions at (xi, eta, zeta), nodes
    in FreeCAD's order: corners N_i = L_i (2 L_i - 1), middles N_ab = 4 L_a L_b."""
    barycentric = (1.0 - xi - eta - zeta, xi, eta, zeta)
    gradients = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    d = np.zeros((10, 3))
    for i in range(4):
        d[i] = (4.0 * barycentric[i] - 1.0) * gradients[i]
    for k, (a, b) in enumerate(TET_EDGES):
        d[4 + k] = 4.0 * (barycentric[a] * gradients[b] + barycentric[b] * gradients[a])
    return d


def inverted_elements(nodes, elements):
    """Indices of the tet10 elements whose Jacobian determinant, at any of CHECK_POINTS, does not
    have the sign of their straight-sided tetrahedron (CalculiX refuses them: "nonpositive
    jacobian")."""
    corners = nodes[elements]
    straight = np.sign(signed_volumes(nodes, elements[:, :4]))
    bad = np.zeros(len(elements), dtype=bool)
    for point in CHECK_POINTS:
        jacobian = np.einsum("mki,kj->mij", corners, _shape_derivatives(*point))
        bad |= np.linalg.det(jacobian) * straight <= 0.0
    return np.nonzero(bad)[0]


def keep_jacobians_positive(straight, curved, elements):
    """`curved` (middle nodes moved onto the shape) with the middles of every element that the
    move would invert put back where `straight` has them, until none is inverted."""
    nodes = curved.copy()
    for _ in range(10):
        bad = inverted_elements(nodes, elements)
        if not len(bad):
            return nodes
        middles = np.unique(elements[bad, 4:])
        nodes[middles] = straight[middles]
    return straight


def element_quality(nodes, tets):
    """Shape of the tetrahedra (corners 0..3): {"min_dihedral_deg", "max_dihedral_deg",
    "radius_ratio_min", "radius_ratio_mean"}; the radius ratio is 3 r / R (inscribed over
    circumscribed radius), 1 for the regular tetrahedron, 0 for a flat one."""
    p = [nodes[tets[:, k]] for k in range(4)]
    volume6 = np.abs(signed_volumes(nodes, tets))
    # face areas (x2), opposite corners 0..3, and the outward normals' dihedral angles
    normals = [np.cross(p[b] - p[a], p[c] - p[a]) for a, b, c in TET_FACES]
    areas2 = [np.linalg.norm(n, axis=1) for n in normals]
    inradius = volume6 / np.sum(areas2, axis=0)  # r = 3 V / (sum of areas)
    # circumradius: R = |a^2 (b x c) + b^2 (c x a) + c^2 (a x b)| / (2 * 6V), edges from corner 0
    a, b, c = p[1] - p[0], p[2] - p[0], p[3] - p[0]
    sq = [np.einsum("ij,ij->i", v, v)[:, None] for v in (a, b, c)]
    circum = np.linalg.norm(sq[0] * np.cross(b, c) + sq[1] * np.cross(c, a) + sq[2] * np.cross(a, b), axis=1)
    circumradius = circum / (2.0 * np.maximum(volume6, 1e-300))
    ratio = 3.0 * inradius / circumradius
    dihedral = []
    for i in range(4):
        for j in range(i + 1, 4):
            ni = normals[i] / areas2[i][:, None]
            nj = normals[j] / areas2[j][:, None]
            # both oriented the same way round the tetrahedron: the angle inside is pi - angle(ni, nj)
            cosine = np.clip(np.einsum("ij,ij->i", ni, nj), -1.0, 1.0)
            dihedral.append(180.0 - np.degrees(np.arccos(cosine)))
    dihedral = np.array(dihedral)
    return {"min_dihedral_deg": float(dihedral.min()), "max_dihedral_deg": float(dihedral.max()),
            "radius_ratio_min": float(ratio.min()), "radius_ratio_mean": float(ratio.mean())}


def boundary_middles(elements, triangles):
    """{(a, b) boundary edge, a < b: its middle node} of tet10 elements whose surface is `triangles`."""
    corners = elements[:, :4]
    pairs = np.sort(corners[:, np.array(TET_EDGES)].reshape(-1, 2), axis=1)
    middles = elements[:, 4:].reshape(-1)
    surface_edges, _ = edge_uses(np.asarray(triangles, dtype=np.int64))
    wanted = {tuple(e) for e in surface_edges.tolist()}
    return {e: m for e, m in zip(map(tuple, pairs.tolist()), middles.tolist()) if e in wanted}
