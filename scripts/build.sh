#!/usr/bin/env bash
# Set-up (if needed) and build: libraries, plugins, tests, benchmarks, and the private prefix.
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/setup.sh"
build="${RELIEFKIT_BUILD_DIR:-$here/build}"
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
