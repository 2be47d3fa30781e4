#!/usr/bin/env bash
# Re-makes the pictures of docs/pottery.md in the real MeshLab GUI under a virtual display: a
# synthetic rim sherd (a third of a jar's rim, rough breaks, irregular triangles, noise, random
# pose: rk_make_mesh sherd) as scanned | turned onto its axis with its profile layer (from the
# side) | coloured by its distance from the surface of revolution. Then the filter in the GUI:
# found by the Filters search, its dialog, Apply, the log.
# Output: docs/img/pottery_sherd.png, docs/img/gui_pottery_dialog.png, docs/img/gui_pottery_applied.png,
# docs/img/pottery_plates.png
# (working files in build/pottery-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/pottery-pictures"; rm -rf "$out"; mkdir -p "$out"
source "$here/scripts/picture-helpers.sh"  # view(), label()
"$here/build/tests/rk_make_mesh" sherd jar 108 0.7 1 0.1 1 "$out/sherd.ply"
cat >"$out/record.mlx" <<'EOF'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Vessel Axis and Profile">
  <Param type="RichEnum" name="axis_mode" value="0" enum_cardinality="2" enum_val0="Fitted" enum_val1="Given" description="Axis" tooltip=""/>
  <Param type="RichPoint3f" name="axis_point" x="0" y="0" z="0" description="Axis point (given)" tooltip=""/>
  <Param type="RichPoint3f" name="axis_direction" x="0" y="0" z="1" description="Axis direction (given)" tooltip=""/>
  <Param type="RichBool" name="flip" value="false" description="Turn over" tooltip=""/>
  <Param type="RichFloat" name="smoothing" value="3" description="Normal smoothing (edge lengths)" tooltip=""/>
 </filter>
 <filter name="Colorize by vertex Quality">
  <Param type="RichFloat" name="minVal" value="-0.6" description="Min" tooltip=""/>
  <Param type="RichFloat" name="maxVal" value="0.6" description="Max" tooltip=""/>
  <Param type="RichDynamicFloat" name="perc" value="0" min="0" max="100" description="Percentile Crop [0..100]" tooltip=""/>
  <Param type="RichBool" name="zeroSym" value="true" description="Zero Symmetric" tooltip=""/>
 </filter>
</FilterScript>
EOF
"$here/scripts/meshlabserver" -i "$out/sherd.ply" -s "$out/record.mlx" -o "$out/oriented.ply" -l 0 -m vc \
  -o "$out/profile.obj" -l 1 >"$out/record.log" 2>&1
grep -E "^LOG: 2 (Axis|Up|Rim)" "$out/record.log" | sed 's/^LOG: 2 //'
# The oriented sherd without its colours (to show the shape and the profile), then coloured.
head -9 "$out/record.mlx" >"$out/axis_only.mlx"; echo "</FilterScript>" >>"$out/axis_only.mlx"
"$here/scripts/meshlabserver" -i "$out/sherd.ply" -s "$out/axis_only.mlx" -o "$out/oriented_grey.ply" -l 0 >/dev/null 2>&1
view "$out/as_scanned.png" 0 0 "$out/sherd.ply"
view "$out/profile_view.png" 240 0 "$out/oriented_grey.ply" "$out/profile.obj"
view "$out/distance.png" 240 0 "$out/oriented.ply"
label "$out/as_scanned.png" "the sherd as scanned"
label "$out/profile_view.png" "on its axis (+Z, rim up), its profile"
label "$out/distance.png" "distance from the surface of revolution"
convert "$out/as_scanned.png" "$out/profile_view.png" "$out/distance.png" +append -resize 1500x "$here/docs/img/pottery_sherd.png"
cat >"$out/gui.txt" <<EOF
click 1258 46
sleep 1
type Vessel Axis
sleep 2
click 860 99
sleep 3
shot $out/gui_dialog.png
click 441 577
sleep 6
click 152 577
sleep 2
click 231 10
sleep 1
click 290 138
sleep 2
click 231 10
sleep 1
click 290 113
sleep 2
drag 430 560 430 320
sleep 4
shot $out/gui_applied.png
EOF
"$here/scripts/gui-shots.sh" "$out/gui.txt" -- "$out/sherd.ply" >/dev/null
convert "$out/gui_dialog.png" -crop 600x600+0+0 +repage "$here/docs/img/gui_pottery_dialog.png"
convert "$out/gui_applied.png" -resize 75% "$here/docs/img/gui_pottery_applied.png"
echo "pictures written to $here/docs/img: pottery_sherd.png, gui_pottery_dialog.png, gui_pottery_applied.png"
# The pottery plate of the same sherd, and of a whole jar (examples/pottery.mlx).
"$here/build/tests/rk_make_mesh" sherd jar 360 0 1 0.05 2 "$out/jar.ply" >/dev/null
for piece in sherd jar; do
  (cd "$out" && "$here/scripts/meshlabserver" -i "$out/$piece.ply" -s "$here/examples/pottery.mlx" >"$out/${piece}_plate.log" 2>&1)
  grep -o "Illustration plate: [^;]*" "$out/${piece}_plate.log" | head -1
  rsvg-convert -w 700 -b white "$out/$piece-plate.svg" -o "$out/${piece}_plate.png"
done
convert "$out/sherd_plate.png" "$out/jar_plate.png" -gravity center +append "$here/docs/img/pottery_plates.png"
echo "and docs/img/pottery_plates.png"
