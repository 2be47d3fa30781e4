#!/usr/bin/env bash
# All tests, from a fresh machine: set-up; the MeshLab 2022.02 and 2025.07 Debian roots made in the
# background meanwhile (downloads and unpacking); the Release build with the MeshLab plugins; unit
# and integration tests (the real meshlabserver on one virtual X display); one clang build of the
# unit tests and the libFuzzer harness with AddressSanitizer + UndefinedBehaviorSanitizer, and those
# tests beside a bounded fuzzer run over the cores; last, the builds against MeshLab 2022.02 and
# 2025.07 in their roots, every filter's outputs compared with the 2020.09 build's, and MeshLab
# 2025.07 loading the plugins from a user's plugin folder. Compiles through ccache (scripts/setup.sh
# installs it; CMakeLists.txt sets it up so that a clone in another folder hits the same cache).
# Prints the time of each stage at the end; scripts/cold-ci.sh measures a new machine's run.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"
source "$here/scripts/stages.sh"
source "$here/scripts/virtual-display.sh"
trap 'stop_virtual_display; print_stages' EXIT
# Tests run two at a time, each with OpenMP on both cores: with the default policy, threads waiting
# at a barrier spin and take the core from the other test's threads. Passive waiting made
# ScaleSpace.GaussianBumpFlattensLikeAGaussianConvolution take 7.7 s instead of 117 s beside a
# second job (on this 2-core machine, before the test was made smaller: `time build/tests/reliefkit_unit_tests
# --gtest_filter=ScaleSpace.GaussianBump*` with and without OMP_WAIT_POLICY=passive; issue 21).
export OMP_WAIT_POLICY=PASSIVE
# The four builds (Release, sanitizers, MeshLab 2022.02 and 2025.07) compile in unity batches: from
# scratch the cores take a third less compiling (reliefkit_common, gcc -O3, 2 cores: 316 core-s
# one file at a time, 206 in batches).
export RELIEFKIT_UNITY="${RELIEFKIT_UNITY:-ON}"

# ctest starts the longest tests first when it knows their times: a fresh build directory gets the
# times of an earlier run (tests/costs/, copied from Testing/Temporary/CTestCostData.txt), so that
# the last minutes are not one long test alone on one core. Tests missing there start last.
seed_test_costs() {  # build-dir costs-file
  mkdir -p "$1/Testing/Temporary"
  [ -f "$1/Testing/Temporary/CTestCostData.txt" ] || cp "$2" "$1/Testing/Temporary/CTestCostData.txt"
}

# Work that waits more than it computes (downloads, a GUI's windows), or that may use only what
# the stage in front leaves of the cores, runs in the background: started here, awaited in its
# own stage (whose time is then only the wait that remained).
declare -A bg_pid bg_log
start_in_background() {  # NAME NICENESS COMMAND... (a command or a function of this script)
  local name="$1" niceness="$2"; shift 2
  bg_log[$name]="$(mktemp)"
  ( renice -n "$niceness" -p "$BASHPID" >/dev/null; "$@" ) >"${bg_log[$name]}" 2>&1 &
  bg_pid[$name]=$!
}
wait_in_background() {  # NAME: its end and its output
  local status=0
  wait "${bg_pid[$1]}" || status=$?
  cat "${bg_log[$1]}"
  rm -f "${bg_log[$1]}"
  return "$status"
}

stage "set-up (Debian's packages, MeshLab 2020.09's sources)" bash "$here/scripts/setup.sh"
# The MeshLab 2022.02 and 2025.07 roots (downloads and unpacking) are made or checked meanwhile, at
# the lowest priority: the builds in front keep the cores.
if [ "$(id -u)" -eq 0 ]; then
  for release in 2022 2025; do start_in_background "root-$release" 19 bash "$here/scripts/meshlab-root.sh" "$release"; done
fi
stage "Release build (libraries, plugins, tests, benchmarks)" bash "$here/scripts/build.sh"
start_virtual_display
seed_test_costs "$here/build" "$here/tests/costs/release.txt"
# Tests write only into temporary folders: the source tree's files (the build folders, third_party/
# and out/ aside) are the same after the tests as before them.
source_tree_state() {
  git -C "$here" -c core.quotepath=off status --porcelain --ignored --untracked-files=all 2>/dev/null |
    grep -vE '^(!!|\?\?) "?(build[^/]*/|third_party/|out/)' || true
}
tree_before="$(source_tree_state)"
# One clang tree for the sanitizer tests and the fuzzer: the unit tests and the libFuzzer harness
# over the same ASan + UBSan build of the cores (libFuzzer's edge counters only on the cores the
# harness reaches; CMakeLists.txt).
san="${RELIEFKIT_SANITIZE_BUILD_DIR:-$here/build-sanitize}"
build_sanitized() {
  cmake -S "$here" -B "$san" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DRELIEFKIT_FUZZ=ON \
    -DRELIEFKIT_PLUGINS=OFF -DRELIEFKIT_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_UNITY_BUILD="$RELIEFKIT_UNITY" >/dev/null
  cmake --build "$san" -j"$jobs" --target reliefkit_unit_tests fuzz_cores
}


# The sanitizer tree compiles at the lowest priority beside the Release tests: they keep the cores
# they ask for, the build takes what their waits and one-test tails leave.
start_in_background sanitizer-build 19 build_sanitized
stage "unit and integration tests (Release, $jobs at a time)" \
  ctest --test-dir "$here/build" --output-on-failure -j"$jobs"
source_tree_untouched() {
  local written
  written="$(diff <(echo "$tree_before") <(source_tree_state) | grep '^>' || true)"
  [ -z "$written" ] || { echo "the tests wrote into the source tree:"; echo "$written"; return 1; }
  echo "the source tree is as it was before the tests"
}
stage "the source tree untouched by the tests" source_tree_untouched

# A fixed number of fuzzer runs (about what one core does in a minute), not a fixed time: it runs
# beside the sanitizer tests, and its strength must not depend on how busy the machine is.
fuzz_cores() {
  local work fuzzer="$san/tests/fuzz/fuzz_cores"
  export OMP_NUM_THREADS=1  # one input at a time; threads only slow the sanitizers down
  "$fuzzer" "$here"/tests/fuzz/regressions/* >"$san/replay.log" 2>&1 || { tail -n 20 "$san/replay.log"; return 1; }
  tail -n 2 "$san/replay.log"
  work="$(mktemp -d)"
  cp "$here"/tests/fuzz/corpus/* "$work"/
  rm -f "$san"/crash-* "$san"/leak-* "$san"/timeout-* "$san"/oom-*
  "$fuzzer" -runs="${RELIEFKIT_FUZZ_RUNS:-2000}" -max_total_time=600 -rss_limit_mb=4096 \
    -max_len=2048 -print_final_stats=1 -artifact_prefix="$san/" "$work" 2>&1 |
    grep -E "DONE|^Done|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" || true
  rm -rf "$work"
  unset OMP_NUM_THREADS
  [ -z "$(ls "$san"/crash-* "$san"/leak-* "$san"/timeout-* "$san"/oom-* 2>/dev/null)" ] || {
    echo "fuzzing found a failing input (kept in $san): add it to tests/fuzz/regressions after fixing" >&2; return 1; }
}
stage "sanitizer build: unit tests and fuzzer (clang, ASan + UBSan, libFuzzer's edge counters; begun beside the tests)" \
  wait_in_background sanitizer-build
seed_test_costs "$san" "$here/tests/costs/sanitized.txt"
# The fuzzer (one process) runs beside the sanitizer tests (two at a time): the cores stay busy to
# the end instead of one waiting for the other's last long test.
# Left to the Release run: the accuracy figures measured on large noisy meshes (30-100 s each under
# the sanitizers, 5-9 s in Release). The code they run runs under the sanitizers in the smaller tests
# of the same cores (Multiscale.*, OptimalScale.*, ProminentEnhancement.StepOne*).
sanitizer_skips='^(Multiscale\.(ReliefEdgesFollowTheStepsOfNoisyDiscReliefs|ReliefEdgesOfASharpNarrowBandAndAWideSoftStep|RidgesAndValleysOfWidthsFourteenTimesApartOnANoisyCylinder|NoEchoesBesideFineLinesWhereTheScaleRisesToTheBackground)|OptimalScale\.EachGrooveGetsItsOwnWidthTimesRootTwo|ProminentEnhancement\.(RestoresAnErodedStepBetterThanBilateralAndTaubin|SharpensNoMoreThanTheCleanSurface))$'
sanitized_tests_beside_fuzzing() {
  local log="$san/fuzzing.log" fuzzing status=0
  fuzz_cores >"$log" 2>&1 &
  fuzzing=$!
  env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$san" --output-on-failure -L unit -E "$sanitizer_skips" -j"$jobs" || status=$?
  wait "$fuzzing" || status=$?
  echo "-- fuzzing the cores (regressions, then ${RELIEFKIT_FUZZ_RUNS:-2000} runs):"
  cat "$log"
  return "$status"
}
stage "unit tests with AddressSanitizer + UndefinedBehaviorSanitizer, beside fuzzing the cores" \
  sanitized_tests_beside_fuzzing

# MeshLab 2022.02 (Debian 13's) and 2025.07 (Debian testing's), each in a root made by debootstrap
# once and kept in /var/cache/reliefkit: the builds against their FilterPlugin API, every filter at
# its defaults through reliefkit-batch on all three releases, the outputs compared with 2020.09's
# (docs/meshlab-releases.md), and MeshLab 2025.07's GUI loading the plugins from the user's folder.
if [ "$(id -u)" -eq 0 ]; then
  # 2025.07 first: its GUI check (mostly waiting for MeshLab's windows) runs beside the 2022.02
  # build, which compiles at the lowest priority meanwhile (the two use different roots).
  for release in 2025 2022; do
    stage "MeshLab $release: its Debian root (made once, then kept; in the background since the set-up)" wait_in_background "root-$release"
    [ "$release" = 2022 ] && niceness=19 || niceness=0
    stage "MeshLab $release: build (FilterPlugin adapter, plugins, reliefkit-batch)" \
      nice -n "$niceness" bash "$here/scripts/build-release.sh" "$release"
    [ "$release" = 2025 ] || continue
    start_in_background gui-check 0 bash "$here/tests/releases/user-plugins-gui.sh"
  done
  stage "MeshLab 2025.07's GUI: the plugins from the user's MeshLabExtraPlugins folder, a filter run (beside the 2022.02 build)" \
    wait_in_background gui-check
  stage "MeshLab 2022.02 and 2025.07 against 2020.09: every filter's outputs compared" \
    bash "$here/tests/releases/compare-releases.sh" 2022 2025
fi
