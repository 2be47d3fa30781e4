#!/usr/bin/env bash
# Re-makes the pictures of docs/rollout.md: a synthetic cylinder seal and a decorated vessel
# (rk_make_mesh turned: irregular triangles, random pose, a frieze of known design) run through
# examples/seal_impression.mlx and examples/vessel_rollout.mlx; each as scanned and unrolled in
# the real MeshLab 2020.09 GUI under a virtual display, and its plate; then the filter's dialog in
# the GUI (found by the Filters search).
# Output: docs/img/rollout_seal.png, rollout_vessel.png, rollout_seal_plate.png,
# rollout_vessel_plate.png, gui_rollout_dialog.png (working files in build/rollout-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/rollout-pictures"; rm -rf "$out"; mkdir -p "$out"
source "$here/scripts/picture-helpers.sh"  # view(), label()
# The seal: a frieze carved 0.6 mm deep (as cylinder seals are cut), radius 15 mm; the vessel: a
# rounded belly (radius 20 mm at its widest) with the frieze in relief 0.5 mm high.
"$here/build/tests/rk_make_mesh" turned cylinder -0.6 2 1 "$out/seal.ply"
"$here/build/tests/rk_make_mesh" turned globe 0.5 2 7 "$out/vessel.ply"
# Each through its example script (unroll, demarcating curves, prominent coloring, plate); the
# layers saved for the pictures with the same filter alone.
run_example() {  # $1: mesh name, $2: example script
  (cd "$out" && "$here/scripts/meshlabserver" -i "$out/$1.ply" -s "$here/examples/$2.mlx" >"$out/$1.log" 2>&1)
  grep -E "^LOG: 2 (Axis|Base|Seam|Development|Seal|Repeat|Illustration)" "$out/$1.log" | sed 's/^LOG: 2 //'
}
run_example seal seal_impression
run_example vessel vessel_rollout
unroll_only() {  # $1: example script, $2: output: its Unroll Around Axis filter alone
  sed -n '1,/<\/filter>/p' "$here/examples/$1.mlx" | sed '/^ <!--/,/-->$/d' >"$out/$2.mlx"
  echo "</FilterScript>" >>"$out/$2.mlx"
}
unroll_only seal_impression impression_only
unroll_only vessel_rollout rollout_only
"$here/scripts/meshlabserver" -i "$out/seal.ply" -s "$out/impression_only.mlx" -o "$out/impression.ply" -l 1 >/dev/null 2>&1
"$here/scripts/meshlabserver" -i "$out/vessel.ply" -s "$out/rollout_only.mlx" -o "$out/rollout.ply" -l 1 >/dev/null 2>&1
view "$out/seal_view.png" 0 0 "$out/seal.ply"
view "$out/impression_view.png" 0 0 "$out/impression.ply"
view "$out/vessel_view.png" 0 0 "$out/vessel.ply"
view "$out/rollout_view.png" 0 0 "$out/rollout.ply"
label "$out/seal_view.png" "the seal as scanned (a carved frieze)"
label "$out/impression_view.png" "its impression, a quarter turn repeated"
label "$out/vessel_view.png" "a decorated vessel as scanned"
label "$out/rollout_view.png" "its rollout (conformal)"
convert "$out/seal_view.png" "$out/impression_view.png" +append -resize 1200x "$here/docs/img/rollout_seal.png"
convert "$out/vessel_view.png" "$out/rollout_view.png" +append -resize 1200x "$here/docs/img/rollout_vessel.png"
rsvg-convert -w 1400 -b white "$out/seal-seal_impression-plate.svg" -o "$here/docs/img/rollout_seal_plate.png"
rsvg-convert -w 1400 -b white "$out/vessel-rollout-plate.svg" -o "$here/docs/img/rollout_vessel_plate.png"
cat >"$out/gui.txt" <<EOS
click 1258 46
sleep 1
type Unroll
sleep 2
click 860 99
sleep 3
shot $out/gui_dialog.png
EOS
"$here/scripts/gui-shots.sh" "$out/gui.txt" -- "$out/seal.ply" >/dev/null
convert "$out/gui_dialog.png" -crop 640x700+0+0 +repage "$here/docs/img/gui_rollout_dialog.png"
echo "pictures written to $here/docs/img: rollout_seal.png, rollout_vessel.png, rollout_seal_plate.png, rollout_vessel_plate.png, gui_rollout_dialog.png"
