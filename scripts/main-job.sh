#!/usr/bin/env bash
# The main job on the bundled sample: curvature of a real coin scan (examples/data/penny.ply),
# through the real meshlabserver with ReliefKit's plugins. Sets everything up on a fresh
# machine (scripts/build.sh) and writes out/penny_curvature.ply: per-vertex mean curvature in
# vertex quality and as colours (convex red, concave blue).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/build.sh"
mkdir -p "$here/out"
"$here/scripts/meshlabserver" -i "$here/examples/data/penny.ply" -o "$here/out/penny_curvature.ply" -m vq vc \
  -s "$here/examples/curvature_colors.mlx" | grep -E "^LOG|saved|Problem|rror" || true
test -s "$here/out/penny_curvature.ply"
echo "main-job: wrote out/penny_curvature.ply (open it in MeshLab: scripts/meshlab out/penny_curvature.ply)"
