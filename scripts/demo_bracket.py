"""The demo CAD part, built with FreeCAD's Part module: a mounting bracket -- a plate with rounded
corners, a cylindrical boss with a fillet at its foot and a chamfer on top, a bore through boss and
plate, and two mounting holes (genus 3). Shared by `make demo` (make_demo_part.py) and the FreeCAD
tests; importing it runs nothing. Part and Vector are passed in, so this file needs no FreeCAD path.
"""

THROUGH_HOLES = 3


def circle_edges(shape, radius, z):
    """Edges of `shape` that are circles of `radius` centred at height `z`."""
    found = []
    for edge in shape.Edges:
        curve = edge.Curve
        if curve.TypeId == "Part::GeomCircle" and abs(curve.Radius - radius) < 1e-6 \
                and abs(curve.Center.z - z) < 1e-6:
            found.append(edge)
    return found


def vertical_corner_edges(shape, length, width):
    """The four vertical line edges at the corners of a length x width plate."""
    corners = {(0.0, 0.0), (length, 0.0), (0.0, width), (length, width)}
    found = []
    for edge in shape.Edges:
        if edge.Curve.TypeId != "Part::GeomLine":
            continue
        a, b = edge.Vertexes[0].Point, edge.Vertexes[1].Point
        if abs(a.x - b.x) < 1e-9 and abs(a.y - b.y) < 1e-9 and \
                any(abs(a.x - x) < 1e-9 and abs(a.y - y) < 1e-9 for x, y in corners):
            found.append(edge)
    return found


def make_bracket(Part, Vector):
    length, width, thickness = 80.0, 50.0, 10.0
    boss_centre, boss_radius, boss_height = Vector(55.0, 25.0, thickness), 13.0, 12.0
    top = thickness + boss_height

    plate = Part.makeBox(length, width, thickness)
    plate = plate.makeFillet(8.0, vertical_corner_edges(plate, length, width))

    boss = Part.makeCylinder(boss_radius, boss_height, boss_centre)
    body = plate.fuse(boss).removeSplitter()
    body = body.makeFillet(2.0, circle_edges(body, boss_radius, thickness))
    body = body.makeChamfer(1.5, circle_edges(body, boss_radius, top))

    cutters = [Part.makeCylinder(6.5, top + 2.0, Vector(boss_centre.x, boss_centre.y, -1.0))]
    cutters += [Part.makeCylinder(4.0, thickness + 2.0, Vector(14.0, y, -1.0)) for y in (12.0, 38.0)]
    for cutter in cutters:
        body = body.cut(cutter)
    return body.removeSplitter()
