#!/usr/bin/python3
"""Issue 35's crease check on the FreeCAD-built parts (tests/freecad/cad_parts.py, measured against
their B-rep) and on the shared CAD meshes (measured against their own tessellation's creases at 30
degrees or more but its slivers' edges: they come without a B-rep). Each part is tessellated as a user's STL export is
(0.1 mm, 30 degrees), remeshed by the command-line tool with the defaults at --vertices, and
measured by tests/freecad/crease_check.py; prints a markdown table.

    /usr/bin/python3 scripts/crease_check.py [--vertices 6000] [--cli build/bin/liftremesh] [--out out/creases]
        [--only NAME,...] [--cli-args "--feature-angle 180"]
"""

import argparse
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
sys.path.insert(0, "/usr/lib/freecad-python3/lib")  # Debian's freecad-python3 package
sys.path.insert(0, os.path.join(SOURCE, "tests", "freecad"))
import FreeCAD  # noqa: E402,F401
import Mesh  # noqa: E402

import cad_parts  # noqa: E402
import crease_check  # noqa: E402
import mesh_checks  # noqa: E402

SHARED = ("gmsh_t13_data.stl", "netgen_hinge.stl", "gmsh_lever.stl", "pmp_fandisk.off", "gmsh_object.stl")


def read(path):
    return mesh_checks.arrays(Mesh.Mesh(path))


def write(points, triangles, path):
    mesh = Mesh.Mesh([[tuple(points[i]) for i in t] for t in triangles])
    mesh.write(path)


def remesh(cli, source, out_dir, name, vertices, extra):
    output = os.path.join(out_dir, name + ".out.stl")
    report = os.path.join(out_dir, name + ".report.json")
    subprocess.run([cli, source, output, "--vertices", str(vertices), "--report", report] + extra, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(report) as f:
        return read(output), json.load(f)


def row(name, creases, figures, report):
    missed = figures.missed_angles
    worst = "%.2f" % figures.worst_corner_h if len(figures.corner_h) else "-"
    return "| %s | %s | %d | %.4f | %s | %d | %s | %.4f | %.3f | %.3f | %.3f | %d / %d |" % (
        name, creases.source, figures.samples, figures.recall,
        ("%.0f-%.0f" % (missed.min(), missed.max())) if len(missed) else "-",
        len(figures.corner_h), worst, figures.spurious, report["output"]["kappa_min"],
        report["output"]["kappa_mean"], 100.0 * report["hausdorff_relative"],
        report["input"]["euler_characteristic"], report["output"]["euler_characteristic"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", type=int, default=6000)
    parser.add_argument("--cli", default=os.path.join(SOURCE, "build", "bin", "liftremesh"))
    parser.add_argument("--out", default=os.path.join(SOURCE, "out", "creases"))
    parser.add_argument("--meshes", default=os.path.join(os.path.dirname(SOURCE), "shared", "meshes"))
    parser.add_argument("--only", default="", help="comma-separated part or mesh names")
    parser.add_argument("--cli-args", default="", help="more options for the command-line tool")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    only = {n for n in args.only.split(",") if n}
    extra = shlex.split(args.cli_args)
    print("| part | reference | crease samples | recall | missed at (deg) | corners | worst corner (h) | "
          "spurious | kappa min | kappa mean | Hausdorff % | chi in/out |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, build in cad_parts.PARTS.items():
        if only and name not in only:
            continue
        shape = build()
        points, triangles = crease_check.tessellate(shape)
        source = os.path.join(args.out, name + ".stl")
        write(points, triangles, source)
        h = crease_check.edge_length_for(crease_check.surface_area(points, triangles), args.vertices)
        creases = crease_check.brep_creases(shape, h)
        (out_points, out_triangles), report = remesh(args.cli, source, args.out, name, args.vertices, extra)
        print(row(name, creases, crease_check.measure(out_points, out_triangles, creases, h), report), flush=True)
    for file_name in SHARED:
        name = os.path.splitext(file_name)[0]
        if only and name not in only:
            continue
        source = os.path.join(args.meshes, file_name)
        points, triangles = read(source)
        h = crease_check.edge_length_for(crease_check.surface_area(points, triangles), args.vertices)
        creases = crease_check.mesh_creases(points, triangles, h)
        (out_points, out_triangles), report = remesh(args.cli, source, args.out, name, args.vertices, extra)
        print(row(name, creases, crease_check.measure(out_points, out_triangles, creases, h), report), flush=True)


if __name__ == "__main__":
    main()
