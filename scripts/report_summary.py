#!/usr/bin/python3
"""Prints a short human-readable summary of a liftremesh --report JSON file.

    /usr/bin/python3 scripts/report_summary.py REPORT.json [--check]

With --check, exits 1 when the output is not an oriented 2-manifold with the input's Euler
characteristic (plus one per crack of the input it closes and per fan of a non-manifold vertex of
the input it splits) and, for a closed input, closed; or when it has triangles passing through
each other and the input has none.
Exits 2 when the report cannot be read or lacks a key.
"""

import json
import sys


def stage_times(timings):
    """The report's timings as (stage, seconds) pairs, from an object or a list of pairs."""
    if isinstance(timings, dict):
        return list(timings.items())
    return [(t["stage"], t["seconds"]) for t in timings or []]


def num(value, spec, scale=1.0):
    """A report number formatted; the report writes a non-finite value as null."""
    return "n/a" if value is None else format(scale * value, spec)


def quality_line(label, q):
    return ("%s: %s vertices, %s triangles, kappa min %s mean %s, min angle %s deg"
            % (label, q["vertices"], q["triangles"], num(q["kappa_min"], ".4f"),
               num(q["kappa_mean"], ".3f"), num(q["min_angle_deg"], ".2f")))


def summarise(report):
    inp, out = report["input"], report["output"]
    lines = [quality_line("input ", inp), quality_line("output", out)]
    lines.append("topology: Euler characteristic %d -> %d, boundary loops %d -> %d (%d edges), "
                 "%d non-manifold edges, self-intersections %d -> %d"
                 % (inp["euler_characteristic"], out["euler_characteristic"],
                    inp.get("boundary_loops", 0), out.get("boundary_loops", 0),
                    out["boundary_edges"], out["nonmanifold_edges"],
                    inp["self_intersections"], out["self_intersections"]))
    lines.append("fidelity: Hausdorff %s%% of the bounding-box diagonal; sharp-edge length "
                 "%s -> %s" % (num(report["hausdorff_relative"], ".3f", 100.0),
                               num(inp["sharp_edge_length"], ".4g"),
                               num(out["sharp_edge_length"], ".4g")))
    times = stage_times(report.get("timings"))
    if times:
        lines.append("time  : %.2f s (%s); %d sites, %d iterations"
                     % (sum(s or 0.0 for _, s in times),
                        ", ".join("%s %s" % (n, num(s, ".2f")) for n, s in times),
                        report["sites"], report["iterations"]))
    return lines


def topology_problems(report):
    inp, out = report["input"], report["output"]
    problems = []
    if inp.get("boundary_edges", 0) == 0 and out["boundary_edges"] != 0:
        problems.append("%d boundary edges on a closed input" % out["boundary_edges"])
    if out["nonmanifold_edges"] != 0:
        problems.append("%d non-manifold edges" % out["nonmanifold_edges"])
    if out.get("oriented") is False:
        problems.append("inconsistently oriented triangles")
    # Cracks of the input that the output closes, and fans of its non-manifold vertices that the
    # output splits, raise chi by one each: the core counts them (report.h) and writes the chi it
    # expects.
    if out["euler_characteristic"] != report["expected_euler_characteristic"]:
        problems.append("Euler characteristic %d, input %d"
                        % (out["euler_characteristic"], inp["euler_characteristic"]))
    return problems


def crossing_problem(report):
    """A sentence when the output has triangles passing through each other and the input has
    none (a tetrahedral mesher refuses such a surface), else None."""
    inp, out = report["input"], report["output"]
    if out["self_intersections"] > 0 and inp["self_intersections"] == 0:
        return ("%d pairs of triangles pass through each other, the input's none"
                % out["self_intersections"])
    return None


def main(argv):
    args = [a for a in argv if a != "--check"]
    if len(args) != 1:
        sys.stderr.write("usage: report_summary.py REPORT.json [--check]\n")
        return 2
    try:
        with open(args[0]) as f:
            report = json.load(f)
        lines = summarise(report)
        problems = topology_problems(report)
        crossing = crossing_problem(report)
        closed, split = report["cracks_closed"], report["vertex_fans_split"]
        parts, kept = report.get("parts", 1), report.get("parts_kept", 0)  # reports before solid_parts.h lack them
    except (OSError, ValueError, KeyError, TypeError) as e:
        sys.stderr.write("report_summary: cannot read %s: %s: %s\n" % (args[0], type(e).__name__, e))
        return 2
    print("\n".join(lines))
    if problems:
        print("check : NOT the input's topology: " + "; ".join(problems))
    else:
        print("check : %s 2-manifold with the input's topology"
              % ("closed" if report["output"]["boundary_edges"] == 0 else "open")
              + (", %d crack(s) of the input closed" % closed if closed else "")
              + (", %d fan(s) of its non-manifold vertices split" % split if split else "")
              + (", %d parts remeshed one by one" % parts if parts > 1 else "")
              + (" (%d with the source's triangles)" % kept if kept else ""))
    if crossing:
        print("check : NOT free of self-intersections: " + crossing)
    return 1 if (problems or crossing) and "--check" in argv else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
