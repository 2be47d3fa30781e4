#!/usr/bin/env bash
# Set-up (if needed) and build. Usage: scripts/build.sh [--target NAME ...] [extra cmake -D options]
# Without --target: everything (libraries, plugins, tests, benchmarks, the private prefix);
# with it, only the named targets and what they need (scripts/main-job.sh builds `prefix` alone).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
targets=()
options=()
while [ $# -gt 0 ]; do
  case "$1" in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) options+=("$1"); shift ;;
  esac
done
bash "$here/scripts/setup.sh"
build="${RELIEFKIT_BUILD_DIR:-$here/build}"
# RELIEFKIT_UNITY=ON: unity builds (a third less compiling from scratch; CI's cold builds use them).
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD="${RELIEFKIT_UNITY:-OFF}" \
  "${options[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
