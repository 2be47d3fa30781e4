#!/usr/bin/env bash
# Re-makes the pictures of docs/multiscale.md: on the shared scans (the coin, the statuette, the
# bunny, the Cycladic torso, the oxhide ingot), the single-scale filters (examples/relief_edges.mlx) beside the multi-scale ones
# (examples/multiscale.mlx), all at their defaults, shown in the real MeshLab GUI under a virtual
# display (scripts/screenshot.sh). Run scripts/make-doc-pictures.sh first (it makes the shaded
# scans and the single-scale pictures docs/img/scan_<scan>_{relief,ridges}.png).
# Usage: scripts/make-multiscale-pictures.sh [NAME ...]  (default: all of them)
# Output: docs/img/scan_<scan>_ms_{relief,ridges}.png and the pairs scan_<scan>_pair_{relief,ridges}.png.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/doc-pictures"; mkdir -p "$out"
source "$here/scripts/picture-helpers.sh"
img="$here/docs/img"
names=("$@"); [ ${#names[@]} -gt 0 ] || names=(penny fertility bunny cycladic oxhide gargoyle)
for name in "${names[@]}"; do
  src="$out/$name.ply"
  case "$name" in
    penny) src="$here/examples/data/penny.ply" ;;
    bunny) src="$out/stanford-bunny.ply" ;;
    cycladic) src="$here/../shared/data/meshes/cycladic_figurine_torso.ply" ;;
    oxhide) src="$here/../shared/data/meshes/oxhide_ingot.ply" ;;
    gargoyle) src="$here/../shared/data/meshes/gargoyle.ply" ;;
  esac
  [ -f "$out/${name}_shaded.ply" ] || { echo "missing $out/${name}_shaded.ply: run scripts/make-doc-pictures.sh" >&2; exit 1; }
  "$here/scripts/meshlabserver" -i "$src" -o "$out/${name}_ms_ridges.obj" -l 1 -o "$out/${name}_ms_valleys.obj" -l 2 \
    -o "$out/${name}_ms_relief.obj" -l 3 -s "$here/examples/multiscale.mlx" >"$out/${name}_multiscale.log" 2>&1
  "$here/scripts/screenshot.sh" "$out/${name}_ms_ridges_full.png" -- "$out/${name}_shaded.ply" \
    "$out/${name}_ms_ridges.obj" "$out/${name}_ms_valleys.obj"
  "$here/scripts/screenshot.sh" "$out/${name}_ms_relief_full.png" -- "$out/${name}_shaded.ply" "$out/${name}_ms_relief.obj"
  for what in ms_ridges ms_relief; do
    convert "$out/${name}_${what}_full.png" -crop 700x640+75+140 +repage "$img/scan_${name}_${what}.png"
  done
  for what in relief ridges; do
    cp "$img/scan_${name}_${what}.png" "$out/single.png"; label "$out/single.png" "single scale (defaults)"
    cp "$img/scan_${name}_ms_${what}.png" "$out/multi.png"; label "$out/multi.png" "multi-scale (defaults)"
    convert "$out/single.png" "$out/multi.png" +append -resize 50% "$img/scan_${name}_pair_${what}.png"
  done
  grep -E "Optimal scale|Multi-scale" "$out/${name}_multiscale.log" | sed 's/^LOG: [0-9]* //' || true
done
echo "pictures in docs/img/scan_*_ms_*.png and scan_*_pair_*.png"
