#!/usr/bin/env bash
# Are two builds' outputs byte-identical? Runs two CLIs with the defaults (6000 vertices) on every
# mesh of ../shared/meshes (the acceptance meshes among them) and on out/demo_part.stl when it is
# there, at seeds 1-3 and once anisotropic, and compares the output meshes and reports with cmp
# (the reports without their timings). For refactors that must change no output.
#
#   scripts/compare_outputs.sh OLD_CLI NEW_CLI
set -euo pipefail
old="$1"; new="$2"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
meshes="$repo/../shared/meshes"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
same=0; differ=0
# The report without its stage timings, which vary from run to run.
strip() { python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); d.pop("timings", None); print(json.dumps(d, sort_keys=True))' "$1" 2>/dev/null || true; }
for mesh in "$meshes"/*.stl "$meshes"/*.off "$meshes"/*.obj "$repo/out/demo_part.stl"; do
  [ -e "$mesh" ] || continue
  name="$(basename "$mesh")"
  for options in "--seed 1" "--seed 2" "--seed 3" "--seed 1 --mode anisotropic"; do
    # shellcheck disable=SC2086
    "$old" "$mesh" "$tmp/old.off" $options --quiet --report "$tmp/old.json" >/dev/null 2>&1 || echo "old failed: $name $options"
    # shellcheck disable=SC2086
    "$new" "$mesh" "$tmp/new.off" $options --quiet --report "$tmp/new.json" >/dev/null 2>&1 || echo "new failed: $name $options"
    if cmp -s "$tmp/old.off" "$tmp/new.off" && cmp -s <(strip "$tmp/old.json") <(strip "$tmp/new.json"); then
      same=$((same + 1))
    else
      differ=$((differ + 1)); echo "DIFFER: $name $options"
    fi
  done
done
echo "compare_outputs: $same identical, $differ different"
[ "$differ" -eq 0 ]
