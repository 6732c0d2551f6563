"""The benchmark's tables beyond the shared meshes (scripts/bench.py runs them):
- scale: the cost of the optimiser against sites and input triangles, on the shared bunny split
  into four once and twice (280k and 1.1M triangles): 10k, 30k and 100k sites on 1.1M triangles,
  and 100k sites on 70k, 280k and 1.1M;
- threads: the optimize stage on one thread and on two, for t13 at 6000 vertices and for the
  large case (1.1M triangles to 100k vertices), with the outputs compared byte for byte; and
  t13 with another process keeping one core busy, beside Gmsh on the same busy host;
- fig9: the paper's Fig. 9 job, a CAD part of about 40k triangles (the demo bracket tessellated
  finely by FreeCAD) to 50k vertices, beside Gmsh.
Each run is made once (but t13's on one thread and on two: see threads()): these are long, and
the shared table's repeats show the noise. targets_table() sets the figures beside issue 36's
targets.
"""

import filecmp
import os
import subprocess
import sys

import bench_gmsh
import bench_inputs

LARGE_SITES = 100000
SCALE_RUNS = [(2, 10000), (2, 30000), (2, 100000), (0, 100000), (1, 100000)]  # (splits, sites)


def fmt(value, spec, scale=1.0):
    """A number formatted; "-" for a missing value (the report writes non-finite ones as null)."""
    return "-" if value is None else format(scale * value, spec)


def markdown(head, rows):
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(str(c).replace("|", "/") for c in row) + " |" for row in rows]
    return "\n".join(lines)


def large_inputs(mesh_dir, out_dir):
    """{splits: path} for the bunny as it is (0), split once (1) and twice (2)."""
    bunny = os.path.join(mesh_dir, "pmp_bunny.off")
    return {0: bunny, 1: bench_inputs.subdivided(bunny, out_dir, 1), 2: bench_inputs.subdivided(bunny, out_dir, 2)}


def stage(row, name):
    return row.get("report", {}).get("timings", {}).get(name)


def scale(run_cli, cli, mesh_dir, out_dir):
    """Rows of the scale table; the large case (1.1M triangles, 100k sites) is also returned."""
    inputs = large_inputs(mesh_dir, out_dir)
    runs, large = [], None
    for splits, sites in SCALE_RUNS:
        row = run_cli(cli, inputs[splits], out_dir, "scale_split%d_%d" % (splits, sites), sites)
        runs.append(row)
        if splits == 2 and sites == LARGE_SITES:
            large = row
    return runs, large


def scale_table(runs):
    head = ["input triangles", "sites", "evaluations", "normals s", "optimize s", "ms per evaluation",
            "ns per evaluation per (site + triangle)", "wall s", "peak MiB", "kappa min", "kappa mean",
            "Hausdorff %"]
    rows = []
    for row in runs:
        report = row.get("report")
        if report is None:
            rows.append([row["name"], row["target"], "failed: " + row["error"]] + ["-"] * (len(head) - 3))
            continue
        triangles, sites, evaluations = report["input"]["triangles"], report["sites"], report["evaluations"]
        per_eval = stage(row, "optimize") / max(1, evaluations)
        rows.append(["%d" % triangles, sites, evaluations, fmt(stage(row, "normals"), ".2f"),
                     fmt(stage(row, "optimize"), ".2f"), fmt(per_eval, ".1f", 1e3),
                     fmt(per_eval / (sites + triangles), ".0f", 1e9), fmt(row["wall"], ".1f"),
                     fmt(row.get("rss"), ".0f"), fmt(report["output"]["kappa_min"], ".3f"),
                     fmt(report["output"]["kappa_mean"], ".3f"), fmt(report["hausdorff_relative"], ".3f", 100.0)])
    return markdown(head, rows)


class BusyCore:
    """Another process keeping one core busy while the block runs."""

    def __enter__(self):
        self.proc = subprocess.Popen([sys.executable, "-c", "while True: pass"])
        return self

    def __exit__(self, *exc):
        self.proc.kill()
        self.proc.wait()


T13_PAIRS = 5  # alternating runs on one thread and on two for t13, the fastest of each kept


def fastest_alternating(run_cli, cli, source, out_dir, vertices, repeat):
    """The runs on one thread and on two, alternating `repeat` times: the row of each with the
    fastest optimize stage (a failed run's row if one fails). A run only slows down when other
    work shares the host, and alternating spreads that over both."""
    best = {}
    for _ in range(repeat):
        for threads in (1, 2):
            row = run_cli(cli, source, out_dir, "threads%d_t13" % threads, vertices, ["--threads", str(threads)])
            if "report" not in row:
                return row, row
            if threads not in best or stage(row, "optimize") < stage(best[threads], "optimize"):
                best[threads] = row
    return best[1], best[2]


def threads(run_cli, cli, mesh_dir, out_dir, large):
    """Rows of the threads table: (case, one-thread row, two-thread row) pairs, then the busy-core
    rows (what, wall s)."""
    t13 = os.path.join(mesh_dir, "gmsh_t13_data.stl")
    pairs = [("t13, 6000 vertices",) + fastest_alternating(run_cli, cli, t13, out_dir, 6000, T13_PAIRS)]
    if large is not None:
        big = large_inputs(mesh_dir, out_dir)[2]
        pairs.append(("1.1M triangles, 100k vertices",
                      run_cli(cli, big, out_dir, "threads1_large", LARGE_SITES, ["--threads", "1"]),
                      large))
    busy = []
    with BusyCore():
        row = run_cli(cli, t13, out_dir, "busy_t13", 6000, ["--threads", "2"])
        busy.append(("LiftRemesh, 2 threads (waiting threads sleep: the CLI's default)", row["wall"]))
        row = run_cli(cli, t13, out_dir, "busy_t13_active", 6000, ["--threads", "2"],
                      env={"OMP_WAIT_POLICY": "ACTIVE"})
        busy.append(("LiftRemesh, 2 threads, OMP_WAIT_POLICY=ACTIVE (waiting threads spin)", row["wall"]))
        row = run_cli(cli, t13, out_dir, "busy_t13_1", 6000, ["--threads", "1"])
        busy.append(("LiftRemesh, 1 thread", row["wall"]))
        gmsh = bench_gmsh.timed(t13, 6000, out_dir)
        busy.append(("Gmsh (single-threaded)", gmsh.get("wall")))
    return pairs, busy


def threads_tables(pairs, busy):
    head = ["case", "optimize s, 1 thread", "optimize s, 2 threads", "speed-up", "wall s, 1 thread",
            "wall s, 2 threads", "outputs identical"]
    rows = []
    for name, one, two in pairs:
        t1, t2 = stage(one, "optimize"), stage(two, "optimize")
        same = ("report" in one and "report" in two and filecmp.cmp(one["output"], two["output"], shallow=False))
        rows.append([name, fmt(t1, ".2f"), fmt(t2, ".2f"), fmt(t1 / t2 if t1 and t2 else None, ".2f"),
                     fmt(one["wall"], ".2f"), fmt(two["wall"], ".2f"), "yes" if same else "NO"])
    busy_rows = [[what, fmt(wall, ".2f")] for what, wall in busy]
    return markdown(head, rows) + "\n\nt13 at 6000 vertices with another process busy on one core:\n\n" + \
        markdown(["run", "wall s"], busy_rows)


def fig9(run_cli, cli, out_dir):
    part = bench_inputs.fine_bracket(out_dir)
    row = run_cli(cli, part, out_dir, "fig9_bracket", 50000)
    return row, bench_gmsh.timed(part, 50000, out_dir)


def fig9_table(row, gmsh):
    report = row.get("report", {})
    out = report.get("output", {})
    head = ["input triangles", "sites", "output triangles", "wall s", "optimize s", "peak MiB", "kappa min",
            "kappa mean", "Hausdorff %", "Gmsh wall s", "Gmsh kappa min"]
    cells = [report.get("input", {}).get("triangles", "-"), report.get("sites", "-"), out.get("triangles", "-"),
             fmt(row["wall"], ".2f"), fmt(stage(row, "optimize"), ".2f"), fmt(row.get("rss"), ".0f"),
             fmt(out.get("kappa_min"), ".3f"), fmt(out.get("kappa_mean"), ".3f"),
             fmt(report.get("hausdorff_relative"), ".3f", 100.0), fmt(gmsh.get("wall"), ".2f"),
             fmt(gmsh.get("kappa_min"), ".3f") if "error" not in gmsh else gmsh["error"]]
    return markdown(head, [cells])


def _marginal(rows, key_axis):
    """Per step along one axis of the scale table (rows sorted along it, the other axis fixed),
    the optimize stage's added seconds per evaluation over the sites or triangles added."""
    out = []
    for a, b in zip(rows, rows[1:]):
        ea = stage(a, "optimize") / a["report"]["evaluations"]
        eb = stage(b, "optimize") / b["report"]["evaluations"]
        out.append((eb - ea) / (key_axis(b) - key_axis(a)))
    return out


# For each target of issue 36 that cannot be met on this kind of host (docs/known-gaps.md gives the
# floors that prove it), the bar it keeps instead, checked as the target is: (bar, limit). Each
# is the figure the benches have read on this kind of host, with room for its noise.
ADOPTED = {
    "wall": ("under 55 s", 55.0),
    "normals": ("under 7 s", 7.0),
    "threads": ("1.5 times, outputs identical", 1.5),
    "fig9": ("under 9 s", 9.0),
    "gmsh": ("at most 3.5 times its wall, better kappa min", 3.5),
}


def targets_table(shared, runs, pairs, busy, fig9_row):
    """Issue 36's targets beside the figures this bench measured: (target, asked, measured, met,
    closest bar kept) rows. A target not met is the known gap docs/known-gaps.md explains, with
    the bar (ADOPTED) that the bench checks in its place."""
    rows = []

    def add(target, asked, measured, met, adopted=None, value=None, higher_is_better=False):
        if met:
            rows.append([target, asked, measured, "yes", "-"])
            return
        bar, limit = ADOPTED[adopted] if adopted else ("-", None)
        kept = limit is not None and value is not None and (value >= limit if higher_is_better else value < limit)
        rows.append([target, asked, measured, "no: known gap",
                     bar + (": kept" if kept else ": NOT kept") if limit is not None else "-"])

    large = next((r for r in runs if "report" in r and r["report"]["input"]["triangles"] > 1000000
                  and r["report"]["sites"] == LARGE_SITES), None)
    if large:
        out = large["report"]["output"]
        add("1. the large case, wall", "under 25 s", fmt(large["wall"], ".1f") + " s", large["wall"] < 25.0,
            "wall", large["wall"])
        add("1. the large case, peak memory", "under 1024 MiB", fmt(large.get("rss"), ".0f") + " MiB",
            (large.get("rss") or 1e9) < 1024.0)
        quality = (out["kappa_min"] >= 0.3 and out["kappa_mean"] >= 0.95 and
                   large["report"]["hausdorff_relative"] <= 0.001)
        add("1. the large case, quality", "kappa min 0.3, mean 0.95, Hausdorff 0.1%",
            "%.3f, %.3f, %.3f%%" % (out["kappa_min"], out["kappa_mean"], 100.0 * large["report"]["hausdorff_relative"]),
            quality)
        normals = stage(large, "normals")
        add("2. normals at 1.1M triangles", "under 2 s", fmt(normals, ".2f") + " s",
            normals is not None and normals < 2.0, "normals", normals)
    good = [r for r in runs if "report" in r]

    def sites(r):
        return r["report"]["sites"]

    def triangles(r):
        return r["report"]["input"]["triangles"]
    by_sites = sorted((r for r in good if triangles(r) > 1000000), key=sites)
    by_tris = sorted((r for r in good if sites(r) == LARGE_SITES), key=triangles)
    if len(by_sites) > 2 and len(by_tris) > 2:
        per_site = _marginal(by_sites, sites)
        per_tri = _marginal(by_tris, triangles)
        linear = all(b <= a * 1.1 for a, b in zip(per_site, per_site[1:])) and \
            all(b <= a * 1.1 for a, b in zip(per_tri, per_tri[1:]))
        add("3. an evaluation's cost in proportion to sites plus triangles",
            "no step costs more per site or triangle added than the step before",
            "per site added " + ", ".join("%.2f" % (1e6 * v) for v in per_site) + " us; per triangle " +
            ", ".join("%.3f" % (1e6 * v) for v in per_tri) + " us", linear)
    for name, one, two in pairs:
        t1, t2 = stage(one, "optimize"), stage(two, "optimize")
        same = ("report" in one and "report" in two and filecmp.cmp(one["output"], two["output"], shallow=False))
        speedup = t1 / t2 if t1 and t2 else None
        add("4. two threads against one: " + name, "1.7 times, outputs identical",
            fmt(speedup, ".2f") + (", identical" if same else ", DIFFERENT"), bool(speedup and speedup >= 1.7 and same),
            "threads", speedup if same else None, higher_is_better=True)
    walls = dict(busy)
    two = walls.get("LiftRemesh, 2 threads (waiting threads sleep: the CLI's default)")
    one = walls.get("LiftRemesh, 1 thread")
    if two and one:
        add("4. a busy core does not stall the run", "2 threads no slower than 1 beside a busy core (5% noise)",
            "%.2f s against %.2f s" % (two, one), two <= 1.05 * one)
    if fig9_row is not None and "report" in fig9_row:
        add("5. the Fig. 9 job", "under 5 s", fmt(fig9_row["wall"], ".2f") + " s", fig9_row["wall"] < 5.0,
            "fig9", fig9_row["wall"])
    compared = [r for r in shared if "report" in r and r.get("gmsh", {}).get("wall")]
    if compared:
        ratios = [r["wall"] / r["gmsh"]["wall"] for r in compared]
        better = all(r["report"]["output"]["kappa_min"] > r["gmsh"].get("kappa_min", 1.0) for r in compared)
        add("6. beside Gmsh, each shared mesh", "at most 0.5 times its wall, better kappa min",
            "%.2f to %.2f times; kappa min %s" % (min(ratios), max(ratios),
                                                  "better on each" if better else "NOT better on each"),
            max(ratios) <= 0.5 and better, "gmsh", max(ratios) if better else None)
    return markdown(["target (issue 36)", "asked", "measured", "met", "closest bar kept (known gap)"], rows)
