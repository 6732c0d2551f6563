"""CAD parts built with FreeCAD's Part module for the crease check (crease_check.py): each one a
kind of crease a user's part has, sized in mm as a real part is (the STL export's 0.1 mm deflection
then tessellates it as it would a user's). `PARTS` maps a name to its builder.
"""
import math

import FreeCAD
import Part

V = FreeCAD.Vector


def thread():
    """An M10-like screw: a core cylinder and a thread of 60-degree flanks swept along
    Part.makeHelix (pitch 2.5 mm, crests flat over P/8 as ISO 68-1 cuts them), cut to flat ends:
    helical creases at the crests and roots."""
    pitch, height, radius = 2.5, 12.5, 4.0
    depth = 0.5 * 0.75 * pitch / math.tan(math.radians(30.0))  # flanks at 30 degrees to the radius
    helix = Part.makeHelix(pitch, height, radius)
    crest, root = pitch / 16.0, 0.5 * 0.75 * pitch + pitch / 16.0  # half-widths at the crest and core
    profile = Part.makePolygon([V(radius - 0.1, 0, -root), V(radius + depth, 0, -crest),
                                V(radius + depth, 0, crest), V(radius - 0.1, 0, root), V(radius - 0.1, 0, -root)])
    sweep = Part.Wire(helix).makePipeShell([profile], True, True)
    core = Part.makeCylinder(radius, height + 2 * pitch, V(0, 0, -pitch))
    screw = core.fuse(sweep).removeSplitter()
    # flat ends: cut to the middle part of the helix
    box = Part.makeBox(4 * radius, 4 * radius, height - pitch, V(-2 * radius, -2 * radius, 0.5 * pitch))
    return screw.common(box).removeSplitter()


def fillets_and_chamfers():
    """A 40 x 30 x 20 mm block with 4 mm fillets on two vertical edges and 3 mm chamfers round its
    top: the chamfer runs over the fillets' tops, and meets the sharp vertical edges at corners."""
    block = Part.makeBox(40, 30, 20)
    vertical = [e for e in block.Edges if abs(e.tangentAt(e.FirstParameter).z) > 0.9
                and e.Vertexes[0].Point.x > 1.0]
    block = block.makeFillet(4.0, vertical)
    top = [e for e in block.Edges if all(abs(v.Point.z - 20.0) < 1e-6 for v in e.Vertexes)]
    return block.makeChamfer(3.0, top)


def revolved_profile():
    """A turned part: a profile of cylinders, a cone, shoulders and a groove revolved about z."""
    r = [(0, 0), (12, 0), (12, 8), (9, 8), (9, 12), (10.5, 12), (10.5, 14), (6, 22), (6, 30), (0, 30)]
    profile = Part.makePolygon([V(x, 0, z) for x, z in r] + [V(0, 0, 0)])
    return Part.Face(profile).revolve(V(0, 0, 0), V(0, 0, 1), 360)


def _prism(turns_deg, sides, height):
    """A prism on a polygon whose sides turn by `turns_deg` (summing to 360) at its corners, the
    last two sides' lengths solved so that it closes: its vertical creases turn by those angles."""
    directions, heading = [], 0.0
    for turn in turns_deg:
        directions.append((math.cos(math.radians(heading)), math.sin(math.radians(heading))))
        heading += turn
    # sum length_i * direction_i = 0, with the first lengths given: solve for the last two
    known = [sum(l * d[k] for l, d in zip(sides, directions)) for k in (0, 1)]
    (a, b), (c, d) = directions[-2], directions[-1]
    det = a * d - b * c
    l1 = (-known[0] * d + known[1] * c) / det
    l2 = (-a * known[1] + b * known[0]) / det
    assert l1 > 0 and l2 > 0, "the polygon does not close with positive sides"
    lengths = list(sides) + [l1, l2]
    corner, points = V(0, 0, 0), [V(0, 0, 0)]
    for l, (dx, dy) in zip(lengths, directions):
        corner = corner + V(l * dx, l * dy, 0)
        points.append(corner)
    points[-1] = points[0]
    return Part.Face(Part.makePolygon(points)).extrude(V(0, 0, height))


def crease_angles():
    """Creases of 30 to 150 degrees: a prism whose vertical creases turn by 30, 60, 45, 75 and 150
    degrees (sides 40, 10, 10 mm, the last two closing it: 11.7 and 46.6), with its 90-degree top and
    bottom rims."""
    return _prism([30, 60, 45, 75, 150], [40, 10, 10], 15)


def filleted_boolean():
    """A 40 x 30 x 10 mm block fused with a boss of 8 mm radius, the circle where they meet filleted
    (2 mm), and an 8 mm hole through both: a boolean's edges rounded where they meet."""
    body = Part.makeBox(40, 30, 10).fuse(Part.makeCylinder(8, 15, V(20, 15, 5))).removeSplitter()
    rim = [e for e in body.Edges if abs(e.BoundBox.ZMin - 10) < 1e-6 and abs(e.BoundBox.ZMax - 10) < 1e-6 and
           isinstance(e.Curve, Part.Circle)]
    return body.makeFillet(2.0, rim).cut(Part.makeCylinder(4, 30, V(20, 15, -5))).removeSplitter()


def hollowed():
    """A 40 x 30 x 20 mm box with its vertical edges filleted (5 mm), shelled to 1.5 mm walls with
    its top open: walls about as thick as the edge length at 6000 vertices (1.18 mm)."""
    box = Part.makeBox(40, 30, 20)
    box = box.makeFillet(5.0, [e for e in box.Edges if abs(e.tangentAt(e.FirstParameter).z) > 0.9])
    return box.makeThickness([f for f in box.Faces if abs(f.CenterOfMass.z - 20) < 1e-6], -1.5, 1e-3)


def primitives():
    """Fifteen of the Part workbench's primitives in one compound, 25 mm apart, as a file of
    several solids is: a box, a cylinder and a 120-degree sector of one, a cone, a pointed cone
    and a 90-degree sector of a cone, a sphere, a 90-degree and a 30-degree wedge of a sphere
    (its poles acute corners), a torus, a wedge, an ellipsoid, a hexagonal prism, a tube and a
    plate 1 mm thick. Euler characteristic 26: 13 spheres and two tori."""
    hexagon = Part.makePolygon([V(5 * math.cos(i * math.pi / 3), 5 * math.sin(i * math.pi / 3), 0) for i in range(7)])
    solids = [
        Part.makeBox(10, 8, 6),
        Part.makeCylinder(4, 10),
        Part.makeCone(5, 2, 8),
        Part.makeCone(5, 0, 8),
        Part.makeSphere(5),
        Part.makeSphere(5, V(0, 0, 0), V(0, 0, 1), -90, 90, 90),
        Part.makeTorus(6, 2),
        Part.makeCylinder(4, 10, V(0, 0, 0), V(0, 0, 1), 120),
        Part.makeSphere(6, V(0, 0, 0), V(0, 0, 1), -90, 90, 30),
        Part.makeWedge(0, 0, 0, 2, 2, 10, 10, 10, 8, 8),
        Part.makeSphere(1).transformGeometry(FreeCAD.Matrix(6, 0, 0, 0, 0, 4, 0, 0, 0, 0, 3, 0)),
        Part.Face(hexagon).extrude(V(0, 0, 8)),
        Part.makeCone(5, 3, 8, V(0, 0, 0), V(0, 0, 1), 90),
        Part.makeCylinder(5, 8).cut(Part.makeCylinder(3.5, 8)),
        Part.makeBox(12, 12, 1),
    ]
    for i, solid in enumerate(solids):
        solid.translate(V(25 * (i % 5), 25 * (i // 5), 0))
    return Part.makeCompound(solids)


PARTS = {
    "thread": thread,
    "fillets_chamfers": fillets_and_chamfers,
    "revolved": revolved_profile,
    "crease_angles": crease_angles,
    "filleted_boolean": filleted_boolean,
    "hollowed": hollowed,
    "primitives": primitives,
}
