#!/usr/bin/env bash
# All tests, from a fresh machine: set-up, Release build with the MeshLab plugins, unit and
# integration tests (the real meshlabserver under Xvfb), then the unit tests again built with
# AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"
bash "$here/scripts/build.sh"
echo "== unit and integration tests (Release) =="
ctest --test-dir "$here/build" --output-on-failure -j1
echo "== unit tests with AddressSanitizer + UndefinedBehaviorSanitizer =="
asan="${RELIEFKIT_ASAN_BUILD_DIR:-$here/build-asan}"
cmake -S "$here" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIEFKIT_SANITIZE=ON \
  -DRELIEFKIT_PLUGINS=OFF -DRELIEFKIT_BENCHMARKS=OFF >/dev/null
cmake --build "$asan" -j"$jobs" --target reliefkit_unit_tests
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir "$asan" --output-on-failure -L unit -j"$jobs"
