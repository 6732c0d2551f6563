#!/usr/bin/python3
"""Builds the demo CAD part with FreeCAD's Part module and writes it as an STL the way a FreeCAD
user's export would tessellate it (MeshPart.meshFromShape: coarse, with slivers).

The part: a mounting bracket -- a plate with rounded corners, a cylindrical boss with a fillet at
its foot and a chamfer on top, a bore through boss and plate, and two mounting holes.
Genus 3 (three through-holes), so a closed tessellation has Euler characteristic 2 - 2*3 = -4.

Run with Debian's Python, which finds FreeCAD through its library directory:
    /usr/bin/python3 scripts/make_demo_part.py [OUT.stl]        (default out/demo_part.stl)
        [--linear-deflection MM] [--angular-deflection DEG]   (default FreeCAD's standard mesher's)
It also runs as `freecadcmd scripts/make_demo_part.py`. freecadcmd exits 0 even when a script
raises, so every failure ends in an explicit os._exit(1).
"""

import math
import os
import sys
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from demo_bracket import THROUGH_HOLES, make_bracket  # noqa: E402

FREECAD_LIB = "/usr/lib/freecad-python3/lib"  # Debian's freecad-python3 package

LINEAR_DEFLECTION = 0.1  # mm: FreeCAD's standard mesher surface deviation
ANGULAR_DEFLECTION = math.radians(30.0)  # FreeCAD's standard mesher angular deviation


def fail(message):
    sys.stdout.flush()
    sys.stderr.write("make_demo_part: " + message + "\n")
    sys.stderr.flush()
    os._exit(1)


def output_path():
    # Under freecadcmd, sys.argv holds freecadcmd's own arguments: take the last .stl, if any.
    args = [a for a in sys.argv[1:] if a.lower().endswith(".stl")]
    return args[-1] if args else os.path.join("out", "demo_part.stl")


def option(name, default):
    """The number after `name` on the command line, or `default`."""
    args = sys.argv[1:]
    if name in args and args.index(name) + 1 < len(args):
        try:
            return float(args[args.index(name) + 1])
        except ValueError:
            fail("%s expects a number, got %r" % (name, args[args.index(name) + 1]))
    return default


def check_solid(shape):
    if not shape.isValid():
        fail("the part is not a valid shape")
    if len(shape.Solids) != 1:
        fail("expected one solid, got %d" % len(shape.Solids))
    solid = shape.Solids[0]
    if len(solid.Shells) != 1 or not solid.Shells[0].isClosed():
        fail("the solid's shell is not closed")
    if solid.Volume <= 0.0:
        fail("the solid has volume %g" % solid.Volume)
    return solid


def check_mesh(mesh, what):
    """Closed, manifold, consistently oriented; returns the Euler characteristic V - E + F."""
    if not mesh.isSolid():
        fail(what + " is not closed")
    if mesh.hasNonManifolds():
        fail(what + " has non-manifold edges")
    if mesh.hasNonUniformOrientedFacets():
        fail(what + " has inconsistently oriented triangles")
    if mesh.countComponents() != 1:
        fail("%s has %d components" % (what, mesh.countComponents()))
    return mesh.CountPoints - mesh.CountEdges + mesh.CountFacets


def main():
    if FREECAD_LIB not in sys.path:
        sys.path.append(FREECAD_LIB)
    import FreeCAD  # noqa: F401  (loads the application; Part needs it)
    import Mesh
    import MeshPart
    import Part

    solid = check_solid(make_bracket(Part, FreeCAD.Vector))
    linear = option("--linear-deflection", LINEAR_DEFLECTION)
    angular = math.radians(option("--angular-deflection", math.degrees(ANGULAR_DEFLECTION)))
    mesh = MeshPart.meshFromShape(Shape=solid, LinearDeflection=linear, AngularDeflection=angular)
    chi = check_mesh(mesh, "the tessellation")
    expected_chi = 2 - 2 * THROUGH_HOLES
    if chi != expected_chi:
        fail("Euler characteristic %d, expected %d (genus %d)" % (chi, expected_chi, THROUGH_HOLES))

    path = output_path()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    mesh.write(path)
    # Read it back: an STL stores no shared vertices, so this checks the welded file itself.
    written = Mesh.Mesh(path)
    if written.CountFacets != mesh.CountFacets:
        fail("%s has %d triangles, expected %d" % (path, written.CountFacets, mesh.CountFacets))
    if check_mesh(written, path) != chi:
        fail(path + " has a different Euler characteristic after welding")

    bb = solid.BoundBox
    print("demo part: bracket %.0f x %.0f x %.0f mm, valid closed solid, volume %.1f mm^3, "
          "%d faces, genus %d" % (bb.XLength, bb.YLength, bb.ZLength, solid.Volume,
                                  len(solid.Faces), THROUGH_HOLES))
    print("tessellation (LinearDeflection %.3g mm, AngularDeflection %.3g deg): %d vertices, "
          "%d triangles, closed, Euler characteristic %d -> %s"
          % (linear, math.degrees(angular), mesh.CountPoints,
             mesh.CountFacets, chi, path))


if __name__ in ("__main__", "make_demo_part"):
    try:
        main()
    except SystemExit:
        raise
    except BaseException:  # freecadcmd would swallow it and exit 0
        traceback.print_exc()
        fail("failed")
    sys.stdout.flush()
    sys.stderr.flush()
    if "freecadcmd" in os.path.basename(sys.executable).lower():
        os._exit(0)
