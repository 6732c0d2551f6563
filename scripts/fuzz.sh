#!/usr/bin/env bash
# make fuzz: builds the libFuzzer targets of tests/fuzz in build-fuzz/ (clang, ASan, UBSan) and
# runs each for FUZZ_SECONDS seconds (default 60), one after the other, on the corpus in the
# tree (tests/fuzz/corpus/<target>, read only) plus what earlier runs found
# (build-fuzz/corpus/<target>). A crash, a sanitizer report, a run slower than FUZZ_TIMEOUT
# seconds (default 10, a hang) or one over 2 GB stops the target and leaves its input in
# build-fuzz/artifacts/<target>/; the script then exits non-zero after the other targets.
#   FUZZ_SECONDS=900 make fuzz                   every target 15 minutes
#   FUZZ_TARGETS="obj off" FUZZ_SECONDS=60 make fuzz   some of them
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${FUZZ_SECONDS:-60}
timeout=${FUZZ_TIMEOUT:-30}
targets=${FUZZ_TARGETS:-"stl_ascii stl_binary obj off remesh"}
build=${FUZZ_BUILD_DIR:-build-fuzz}
jobs=${JOBS:-2}
cxx=$(command -v clang++ || command -v clang++-14 || true)
[ -n "$cxx" ] || { echo "fuzz: clang++ not found (scripts/install-deps.sh installs clang)" >&2; exit 1; }

# -O1 -g, assertions on: the usual build for fuzzing (fast enough, readable stacks).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_COMPILER="$cxx" \
      -DLIFTREMESH_BUILD_FUZZ=ON -DLIFTREMESH_BUILD_TESTS=OFF -DLIFTREMESH_BUILD_PYTHON=OFF >/dev/null
# shellcheck disable=SC2086
cmake --build "$build" --parallel "$jobs" --target $(printf 'fuzz_%s ' $targets)

status=0
for t in $targets; do
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t"
  echo "== fuzz_$t: $seconds s (log $build/fuzz_$t.log)"
  rc=0
  ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
    "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 \
    -report_slow_units="$timeout" -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/" \
    "$build/corpus/$t" "tests/fuzz/corpus/$t" >"$build/fuzz_$t.log" 2>&1 || rc=$?
  # The last progress line (executions, cov, ft, corpus) and the final statistics.
  grep -E '^#[0-9]+' "$build/fuzz_$t.log" | tail -1 || true
  grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb)|ERROR|SUMMARY|Test unit written' "$build/fuzz_$t.log" || true
  if [ "$rc" -ne 0 ] || [ -n "$(ls -A "$build/artifacts/$t")" ]; then
    echo "fuzz_$t: findings in $build/artifacts/$t/ (exit $rc)" >&2
    status=1
  fi
done
exit $status
