#!/usr/bin/env bash
# All tests, from a fresh machine: set-up, Release build with the MeshLab plugins, unit and
# integration tests (the real meshlabserver under Xvfb), a bounded libFuzzer run over the cores,
# then the unit tests again built with AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"
bash "$here/scripts/build.sh"
echo "== unit and integration tests (Release) =="
ctest --test-dir "$here/build" --output-on-failure -j1
echo "== fuzzing the cores (libFuzzer + ASan + UBSan: replay of tests/fuzz/regressions, then ${RELIEFKIT_FUZZ_SECONDS:-60} s) =="
fuzz="${RELIEFKIT_FUZZ_BUILD_DIR:-$here/build-fuzz}"
cmake -S "$here" -B "$fuzz" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DRELIEFKIT_FUZZ=ON \
  -DRELIEFKIT_PLUGINS=OFF -DRELIEFKIT_TESTS=OFF -DRELIEFKIT_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$fuzz" -j"$jobs" --target fuzz_cores
export OMP_NUM_THREADS=1  # one input at a time; threads only slow the sanitizers down
"$fuzz/tests/fuzz/fuzz_cores" "$here"/tests/fuzz/regressions/* 2>&1 | tail -n 2
work="$(mktemp -d)"
cp "$here"/tests/fuzz/corpus/* "$work"/
rm -f "$fuzz"/crash-* "$fuzz"/leak-* "$fuzz"/timeout-* "$fuzz"/oom-*
"$fuzz/tests/fuzz/fuzz_cores" -max_total_time="${RELIEFKIT_FUZZ_SECONDS:-60}" -rss_limit_mb=4096 -max_len=2048 \
  -print_final_stats=1 -artifact_prefix="$fuzz/" "$work" 2>&1 | grep -E "DONE|^Done|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" \
  || true
[ -z "$(ls "$fuzz"/crash-* "$fuzz"/leak-* "$fuzz"/timeout-* "$fuzz"/oom-* 2>/dev/null)" ] || {
  echo "fuzzing found a failing input (kept in $fuzz): add it to tests/fuzz/regressions after fixing" >&2; exit 1; }
rm -rf "$work"
unset OMP_NUM_THREADS
echo "== unit tests with AddressSanitizer + UndefinedBehaviorSanitizer =="
asan="${RELIEFKIT_ASAN_BUILD_DIR:-$here/build-asan}"
cmake -S "$here" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIEFKIT_SANITIZE=ON \
  -DRELIEFKIT_PLUGINS=OFF -DRELIEFKIT_BENCHMARKS=OFF >/dev/null
cmake --build "$asan" -j"$jobs" --target reliefkit_unit_tests
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir "$asan" --output-on-failure -L unit -j"$jobs"
