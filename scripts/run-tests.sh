#!/usr/bin/env bash
# All tests, from a fresh machine: set-up, Release build with the MeshLab plugins, unit and
# integration tests (the real meshlabserver on one virtual X display), then one clang build with
# AddressSanitizer + UndefinedBehaviorSanitizer for both the bounded libFuzzer run over the cores
# and the unit tests. Compiles through ccache (scripts/setup.sh installs it; CMakeLists.txt sets it
# up so that a clone in another folder hits the same cache). Prints the time of each stage at the end.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"
source "$here/scripts/stages.sh"
source "$here/scripts/virtual-display.sh"
trap 'stop_virtual_display; print_stages' EXIT

stage "set-up and Release build" bash "$here/scripts/build.sh"
start_virtual_display
stage "unit and integration tests (Release, $jobs at a time)" \
  ctest --test-dir "$here/build" --output-on-failure -j"$jobs"

san="${RELIEFKIT_SANITIZE_BUILD_DIR:-$here/build-sanitize}"
build_sanitized() {
  cmake -S "$here" -B "$san" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DRELIEFKIT_FUZZ=ON \
    -DRELIEFKIT_PLUGINS=OFF -DRELIEFKIT_TESTS=ON -DRELIEFKIT_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$san" -j"$jobs" --target fuzz_cores reliefkit_unit_tests
}
stage "sanitizer build (clang, ASan + UBSan + libFuzzer coverage)" build_sanitized

fuzz_cores() {
  local work
  export OMP_NUM_THREADS=1  # one input at a time; threads only slow the sanitizers down
  "$san/tests/fuzz/fuzz_cores" "$here"/tests/fuzz/regressions/* >"$san/replay.log" 2>&1 || { tail -n 20 "$san/replay.log"; return 1; }
  tail -n 2 "$san/replay.log"
  work="$(mktemp -d)"
  cp "$here"/tests/fuzz/corpus/* "$work"/
  rm -f "$san"/crash-* "$san"/leak-* "$san"/timeout-* "$san"/oom-*
  "$san/tests/fuzz/fuzz_cores" -max_total_time="${RELIEFKIT_FUZZ_SECONDS:-60}" -rss_limit_mb=4096 -max_len=2048 \
    -print_final_stats=1 -artifact_prefix="$san/" "$work" 2>&1 |
    grep -E "DONE|^Done|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" || true
  rm -rf "$work"
  unset OMP_NUM_THREADS
  [ -z "$(ls "$san"/crash-* "$san"/leak-* "$san"/timeout-* "$san"/oom-* 2>/dev/null)" ] || {
    echo "fuzzing found a failing input (kept in $san): add it to tests/fuzz/regressions after fixing" >&2; return 1; }
}
stage "fuzzing the cores (replay of tests/fuzz/regressions, then ${RELIEFKIT_FUZZ_SECONDS:-60} s)" fuzz_cores

stage "unit tests with AddressSanitizer + UndefinedBehaviorSanitizer" \
  env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir "$san" --output-on-failure -L unit -j"$jobs"
