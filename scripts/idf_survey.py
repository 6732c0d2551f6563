#!/usr/bin/python3
"""Remeshes every STEP part FreeCAD's Debian package ships (Mod/Idf/Idflibs: chip resistors,
diodes, transistors, inductors, connectors), each tessellated as a FreeCAD user's STL export
would be (MeshPart.meshFromShape, 0.1 mm / 30 degrees, several solids fused into one shape), and
prints a markdown table of what the command-line tool reports: Euler characteristic in and out,
kappa min and mean, sharp-edge length out/in, Hausdorff distance, triangles through each other
in and out, boundary edges, warnings. A map of where real FreeCAD parts still break, not a test.

    /usr/bin/python3 scripts/idf_survey.py [--vertices N] [--cli build/bin/liftremesh] [--out out/idf]
"""

import argparse
import glob
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, "/usr/lib/freecad-python3/lib")  # Debian's freecad-python3 package
import FreeCAD  # noqa: E402,F401
import MeshPart  # noqa: E402
import Part  # noqa: E402

IDF_LIBS = os.path.join(FreeCAD.getResourceDir(), "Mod", "Idf", "Idflibs")


def tessellate(path, stl):
    """The part as one shape (solids fused), written as FreeCAD's STL export would write it."""
    shape = Part.read(path)
    solids = shape.Solids
    if len(solids) > 1:
        shape = solids[0].multiFuse(solids[1:]).removeSplitter()
    MeshPart.meshFromShape(Shape=shape, LinearDeflection=0.1, AngularDeflection=math.radians(30)).write(stl)
    return len(shape.Solids)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", type=int, default=6000)
    parser.add_argument("--cli", default=os.path.join("build", "bin", "liftremesh"))
    parser.add_argument("--out", default=os.path.join("out", "idf"))
    args = parser.parse_args()
    parts = sorted(glob.glob(os.path.join(IDF_LIBS, "*.stp")))
    if not parts:
        sys.exit("idf_survey: no STEP part in %s" % IDF_LIBS)
    os.makedirs(args.out, exist_ok=True)
    print("| part | solids | chi in/out | kappa min | kappa mean | sharp60 out/in | Hausdorff % "
          "| crossings in/out | boundary edges out | warnings |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in parts:
        name = os.path.splitext(os.path.basename(path))[0]
        stl = os.path.join(args.out, name + ".stl")
        report_path = os.path.join(args.out, name + "_report.json")
        try:
            solids = tessellate(path, stl)
        except Exception as error:  # a part FreeCAD cannot read or tessellate: say so, go on
            print("| %s | tessellation failed: %s |||||||||" % (name, error))
            continue
        run = subprocess.run([args.cli, stl, os.path.join(args.out, name + "_remeshed.stl"), "--vertices",
                              str(args.vertices), "--report", report_path, "--quiet"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            print("| %s | %d | failed: %s |||||||" % (name, solids, run.stderr.strip().splitlines()[-1]))
            continue
        with open(report_path) as f:
            r = json.load(f)
        i, o = r["input"], r["output"]
        sharp = "%.3f" % (o["sharp_edge_length"] / i["sharp_edge_length"]) if i["sharp_edge_length"] > 0 else "-"
        print("| %s | %d | %d / %d | %.3f | %.3f | %s | %.3f | %d / %d | %d | %d |" % (
            name, solids, i["euler_characteristic"], o["euler_characteristic"], o["kappa_min"], o["kappa_mean"],
            sharp, 100.0 * r["hausdorff_relative"], i["self_intersections"], o["self_intersections"],
            o["boundary_edges"], len(r["warnings"])))


if __name__ == "__main__":
    main()
