#!/usr/bin/env bash
# Re-makes the pictures of docs/multiscale.md: single-scale against multi-scale ridges & valleys
# and relief edges on the bundled coin (the example scripts at their defaults), shown in the real
# MeshLab GUI under a virtual display (scripts/screenshot.sh). Run scripts/make-doc-pictures.sh
# first (it makes the shaded coin and the single-scale layers).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/doc-pictures"; mkdir -p "$out"
coin="$here/examples/data/penny.ply"
"$here/scripts/meshlabserver" -i "$coin" -o "$out/penny_scale.ply" -l 0 -m vq \
  -o "$out/penny_ms_ridges.obj" -l 1 -o "$out/penny_ms_valleys.obj" -l 2 -o "$out/penny_ms_relief.obj" -l 3 \
  -s "$here/examples/multiscale.mlx" >"$out/penny_multiscale.log" 2>&1
"$here/scripts/screenshot.sh" "$out/penny_ms_ridges_full.png" -- "$out/penny_shaded.ply" "$out/penny_ms_ridges.obj" "$out/penny_ms_valleys.obj"
"$here/scripts/screenshot.sh" "$out/penny_ms_relief_full.png" -- "$out/penny_shaded.ply" "$out/penny_ms_relief.obj"
for what in ms_ridges ms_relief; do
  convert "$out/penny_${what}_full.png" -crop 700x640+75+140 +repage "$here/docs/img/scan_penny_${what}.png"
done
# The statuette and the bunny (made by make-doc-pictures.sh): multi-scale relief edges at defaults.
for m in fertility bunny; do
  src="$out/$m.ply"; [ "$m" = bunny ] && src="$out/stanford-bunny.ply"
  "$here/scripts/meshlabserver" -i "$src" -o "$out/${m}_ms_relief.obj" -l 3 -s "$here/examples/multiscale.mlx" \
    >"$out/${m}_multiscale.log" 2>&1
  "$here/scripts/screenshot.sh" "$out/${m}_ms_relief_full.png" -- "$out/${m}_shaded.ply" "$out/${m}_ms_relief.obj"
  convert "$out/${m}_ms_relief_full.png" -crop 700x640+75+140 +repage "$here/docs/img/scan_${m}_ms_relief.png"
done
grep -E "Optimal scale|Multi-scale" "$out/penny_multiscale.log" | sed 's/^LOG: [0-9]* //' || true
echo "pictures in docs/img/scan_penny_ms_*.png"
