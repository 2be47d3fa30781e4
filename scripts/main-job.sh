#!/usr/bin/env bash
# The main job on the bundled sample: demarcating curves and curvature shading of a real coin
# scan (examples/data/penny.ply), through the real meshlabserver with ReliefKit's plugins
# (examples/demarcating_shading.mlx). Sets everything up on a fresh machine (scripts/build.sh)
# and writes
#   out/penny_shaded.ply        the coin, grey mean-curvature shading with the curves drawn in
#   out/penny_demarcating.obj   the demarcating curves as an edge layer (OBJ 'l' records)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/build.sh" --target prefix  # the plugins and the private prefix, no tests
mkdir -p "$here/out"
"$here/scripts/meshlabserver" -i "$here/examples/data/penny.ply" \
  -o "$here/out/penny_shaded.ply" -l 0 -m vc vq \
  -o "$here/out/penny_demarcating.obj" -l 1 \
  -s "$here/examples/demarcating_shading.mlx" | grep -E "^LOG|saved|Problem|rror" || true
test -s "$here/out/penny_shaded.ply" && grep -q "^l " "$here/out/penny_demarcating.obj"
echo "main-job: wrote out/penny_shaded.ply and out/penny_demarcating.obj"
echo "          view them: scripts/meshlab out/penny_shaded.ply out/penny_demarcating.obj"
