#!/usr/bin/env bash
# Re-makes the pictures of docs/rollout.md in the real MeshLab GUI under a virtual display: a
# synthetic cylinder seal (five round figures 1 mm high on a 15 mm radius, irregular triangles,
# random pose: rk_make_mesh turned) as scanned | its rollout | its impression; then the filter in
# the GUI (found by the Filters search, its dialog); the rollout's plate (examples/illustration_plate.mlx:
# demarcating curves over the prominent shading, facing the relief, to scale).
# Output: docs/img/rollout_seal.png, docs/img/gui_rollout_dialog.png, docs/img/rollout_plate.png
# (working files in build/rollout-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/rollout-pictures"; rm -rf "$out"; mkdir -p "$out"
source "$here/scripts/picture-helpers.sh"  # view(), label()
"$here/build/tests/rk_make_mesh" turned cylinder 1.0 0 1 "$out/seal.ply"
unroll_script() {  # $1: impression (true/false)
  cat <<EOS
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Unroll Around Axis">
  <Param type="RichEnum" name="axis_mode" value="0" enum_val0="Fitted" enum_val1="+Z" enum_val2="Given" enum_cardinality="3" description="Axis" tooltip=""/>
  <Param type="RichPoint3f" name="axis_point" x="0" y="0" z="0" description="Axis point (given)" tooltip=""/>
  <Param type="RichPoint3f" name="axis_direction" x="0" y="0" z="1" description="Axis direction (given)" tooltip=""/>
  <Param type="RichEnum" name="base" value="1" enum_val0="Smooth profile" enum_val1="Cylinder or cone" enum_cardinality="2" description="Base" tooltip=""/>
  <Param type="RichFloat" name="base_window" value="0" description="Base window (edge lengths)" tooltip=""/>
  <Param type="RichBool" name="seam_auto" value="true" description="Seam automatic" tooltip=""/>
  <Param type="RichFloat" name="seam_angle" value="0" description="Seam angle (degrees)" tooltip=""/>
  <Param type="RichBool" name="impression" value="$1" description="Seal impression" tooltip=""/>
  <Param type="RichFloat" name="smoothing" value="3" description="Normal smoothing (edge lengths)" tooltip=""/>
 </filter>
</FilterScript>
EOS
}
unroll_script false >"$out/unroll.mlx"
unroll_script true >"$out/impression.mlx"
"$here/scripts/meshlabserver" -i "$out/seal.ply" -s "$out/unroll.mlx" -o "$out/rollout.ply" -l 1 >"$out/unroll.log" 2>&1
"$here/scripts/meshlabserver" -i "$out/seal.ply" -s "$out/impression.mlx" -o "$out/impression.ply" -l 1 >"$out/impression.log" 2>&1
grep -E "^LOG: 2 (Axis|Base|Seam|Stretch|Seal)" "$out/unroll.log" "$out/impression.log" | sed 's/^.*LOG: 2 //'
view "$out/as_scanned.png" 0 0 "$out/seal.ply"
view "$out/rollout.png" 0 0 "$out/rollout.ply"
view "$out/impression_view.png" 0 0 "$out/impression.ply"
label "$out/as_scanned.png" "the seal as scanned"
label "$out/rollout.png" "its rollout (the figures raised)"
label "$out/impression_view.png" "its impression (mirrored, sunk)"
convert "$out/as_scanned.png" "$out/rollout.png" "$out/impression_view.png" +append -resize 1500x "$here/docs/img/rollout_seal.png"
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
(cd "$out" && "$here/scripts/meshlabserver" -i "$out/rollout.ply" -s "$here/examples/illustration_plate.mlx" >"$out/plate.log" 2>&1)
rsvg-convert -w 1200 -b white "$out/rollout-plate.svg" -o "$here/docs/img/rollout_plate.png"
echo "pictures written to $here/docs/img: rollout_seal.png, gui_rollout_dialog.png, rollout_plate.png"
