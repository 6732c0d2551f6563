#!/usr/bin/env python3
"""The include rule of the core's folders (native/core/liftremesh/), checked as a ctest.

Each folder of the core is one stage of the pipeline, and each stage has a rank (RANKS below,
the one place that lists them). A file may include:
  - any header of a lower rank;
  - within its own folder: any header where the folder's files are parts of one tool (PARTS),
    else only its own header and the folder's internal/ headers: a repair step never includes
    another step of its own rank; what two steps share moves down (edit/flip_rules is that);
and nothing of its own rank in another folder, nor of a higher rank.

    tests/check_include_ranks.py native/core/liftremesh   # exit 1 and one line per broken include
    tests/check_include_ranks.py --self-test              # the rule rejects what it must
"""
import os
import re
import sys

# Folder (or, for the files at the top, file stem) -> rank. Lower ranks come first in the pipeline.
RANKS = {
    # Top-level headers that include nothing of the core, used at every rank.
    "exceptions": 0,
    "progress": 0,
    # The foundation: meshes and their geometry, then the search trees over them; threads, memory.
    "mesh": 1,
    "system": 1,
    "spatial": 2,
    # The tools: lifting (normals, density, thin walls), the CVT (sampling, RVD, energy,
    # optimiser, RDT), local edits (flip rules, edge collapse, acute creases).
    "lift": 3,
    "cvt": 3,
    "edit": 3,
    # The steps after the triangulation, in the pipeline's order.
    "repair": 4,
    "snap": 5,
    "polish": 6,
    "measure": 7,
    # The entry points: the parameters, the report, the steps' settings (steps.h), the pipeline.
    "params": 8,
    "report": 8,
    "steps": 8,
    "pipeline": 9,
}

# Folders whose files are parts of one tool and may include each other.
PARTS = {"mesh", "system", "spatial", "lift", "cvt", "edit"}

INCLUDE = re.compile(r'^\s*#\s*include\s+"liftremesh/([^"]+)"', re.MULTILINE)


def unit_of(path):
    """The rank table's key for a path relative to the core's folder ('snap/crease_snap.h')."""
    parts = path.split("/")
    return parts[0] if len(parts) > 1 else os.path.splitext(parts[0])[0]


def stem_of(path):
    return os.path.splitext(os.path.basename(path))[0]


def broken(path, included):
    """Why `path` may not include `included` (both relative to the core's folder), or None."""
    unit, target = unit_of(path), unit_of(included)
    for u in (unit, target):
        if u not in RANKS:
            return "'%s' is in no rank of the table in tests/check_include_ranks.py" % u
    rank, target_rank = RANKS[unit], RANKS[target]
    if target == unit:
        if unit in PARTS or stem_of(included) == stem_of(path) or "/internal/" in included:
            return None
        return "a step includes another step of its folder (rank %d): move what they share to a lower rank" % rank
    if target_rank < rank:
        return None
    if target_rank == rank:
        return "%s/ and %s/ share rank %d: a stage never includes one of its own rank" % (unit, target, rank)
    return "%s (rank %d) includes %s (rank %d): a stage includes lower ranks only" % (unit, rank, target, target_rank)


def check_tree(root):
    """One message per broken include under `root`; missing headers count as broken."""
    errors = []
    for folder, _, files in sorted(os.walk(root)):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")
            with open(os.path.join(folder, name), encoding="utf-8") as f:
                text = f.read()
            for included in INCLUDE.findall(text):
                if not os.path.exists(os.path.join(root, included)):
                    errors.append('%s: includes "liftremesh/%s", which does not exist' % (path, included))
                    continue
                why = broken(path, included)
                if why:
                    errors.append('%s: includes "liftremesh/%s": %s' % (path, included, why))
    return errors


def self_test():
    """The rule on made-up includes: each case (path, included, allowed)."""
    cases = [
        ("polish/hausdorff_refinement.cpp", "edit/flip_rules.h", True),
        ("polish/hausdorff_refinement.cpp", "snap/crease_snap.h", True),  # an earlier stage
        ("snap/crease_snap.cpp", "polish/quality_polish.h", False),  # a later one
        ("polish/hausdorff_refinement.cpp", "polish/quality_polish.h", False),  # a step of its rank
        ("polish/quality_polish.cpp", "polish/quality_polish.h", True),  # its own header
        ("polish/quality_polish.cpp", "polish/internal/passes.h", True),
        ("cvt/optimizer.cpp", "cvt/rvd.h", True),  # parts of one tool
        ("lift/normals.cpp", "cvt/rvd.h", False),  # another folder of its rank
        ("mesh/mesh.cpp", "spatial/aabb_tree.h", False),
        ("spatial/aabb_tree.h", "mesh/mesh.h", True),
        ("mesh/mesh.cpp", "exceptions.h", True),
        ("report.h", "measure/quality.h", True),
        ("measure/quality.cpp", "report.h", False),
        ("pipeline.cpp", "newstage/step.h", False),  # not in the table
    ]
    failures = 0
    for path, included, allowed in cases:
        if (broken(path, included) is None) != allowed:
            failures += 1
            print("self-test: %s including %s should be %s" % (path, included, "allowed" if allowed else "refused"))
    print("self-test: %d of %d cases as expected" % (len(cases) - failures, len(cases)))
    return failures == 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return 0 if self_test() else 1
    if len(argv) != 2:
        print(__doc__)
        return 2
    errors = check_tree(argv[1])
    for e in errors:
        print(e)
    print("include ranks: %s" % ("%d broken includes" % len(errors) if errors else "every include points to a lower rank"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
