#!/usr/bin/env bash
# How often one filter run computes the per-run geometry (vertex-face adjacency, scale, noise
# estimate, cotangent Laplacian, noise-floor simulation, repair): every example script through the
# real meshlabserver with RELIEFKIT_WORK_COUNTS=1 (the adapter logs the counts after each filter).
# Usage: scripts/work-counts.sh [mesh.ply]   (default: the bundled coin). Needs a build (scripts/build.sh).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mesh="${1:-$here/examples/data/penny.ply}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$here"/examples/data/*.png "$work"/
export RELIEFKIT_WORK_COUNTS=1
counts() {  # script [meshlabserver input args...]
  local script="$1"; shift
  sed "s|value=\"examples/data/|value=\"$work/|g" "$here/examples/$script" >"$work/s.mlx"
  "$here/scripts/meshlabserver" "$@" -s "$work/s.mlx" 2>&1 |
    sed -nE 's/^LOG: [0-9]+ Work counts of ([^:]*): (.*)/  \1|\2/p' | awk -F'|' '{ printf "  %-34s %s\n", $1, $2 }'
}
for s in curvature.mlx demarcating_shading.mlx relief_edges.mlx multiscale.mlx prominent.mlx; do
  echo "## $s on $(basename "$mesh")"
  counts "$s" -i "$mesh"
done
for s in drawing_relief.mlx base_and_relief.mlx; do
  echo "## $s"
  counts "$s"
done
