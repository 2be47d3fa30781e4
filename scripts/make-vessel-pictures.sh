#!/usr/bin/env bash
# Re-makes the vessel pictures of docs/drawing_recon.md in the real MeshLab GUI under a virtual
# display: "Vessel from Profile Drawing" at its defaults on the shared bowl half-section and on the
# example jar (hatched section, base broken off): drawing | the vessel from below | from the side.
# Then the filter in the GUI: found by the Filters search, the bowl chosen with "...", Apply.
# Output: docs/img/drawing_vessels.png, docs/img/gui_vessel_dialog.png, docs/img/gui_vessel_applied.png
# (working files in build/vessel-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/vessel-pictures"; rm -rf "$out"; mkdir -p "$out"
source "$here/scripts/picture-helpers.sh"  # view(), label()
rows=()
for d in "$here/tests/data/drawings/pottery_bowl_half_section.jpg:1" "$here/examples/data/jar_half_section.png:2"; do
  IFS=: read -r drawing scale <<<"$d"
  name="$(basename "${drawing%.*}")"
  sed -e "s#value=\"examples/data/jar_half_section.png\"#value=\"$drawing\"#" -e "s#name=\"scale\" value=\"2\"#name=\"scale\" value=\"$scale\"#" \
    "$here/examples/vessel_from_profile.mlx" >"$out/$name.mlx"
  "$here/scripts/meshlabserver" -s "$out/$name.mlx" -o "$out/$name.ply" -l 1 -o "$out/${name}_profile.obj" -l 0 >"$out/$name.log" 2>&1
  grep -o 'Vessel from Profile Drawing: [^;]*;[^;]*' "$out/$name.log" | head -1
  convert "$drawing" -background white -alpha remove -alpha off -trim +repage -bordercolor white -border 20 -resize 700x600 \
    -gravity center -extent 760x660 "$out/${name}_d.png"
  view "$out/${name}_below.png" 150 0 "$out/$name.ply"
  view "$out/${name}_side.png" -60 0 "$out/$name.ply"
  label "$out/${name}_d.png" "$name"; label "$out/${name}_below.png" "vessel, from below"; label "$out/${name}_side.png" "from the side"
  convert "$out/${name}_d.png" "$out/${name}_below.png" "$out/${name}_side.png" +append "$out/${name}_row.png"
  rows+=("$out/${name}_row.png")
done
convert "${rows[@]}" -append -resize 1500x "$here/docs/img/drawing_vessels.png"
cat >"$out/gui.txt" <<EOF
click 1258 46
sleep 1
type Vessel from
sleep 2
click 860 99
sleep 3
click 466 343
sleep 3
type $here/tests/data/drawings/pottery_bowl_half_section.jpg
key Return
sleep 2
shot $out/gui_dialog.png
click 390 569
sleep 6
click 134 569
sleep 2
click 231 10
sleep 1
click 290 113
sleep 2
drag 430 560 430 440
sleep 4
shot $out/gui_applied.png
EOF
"$here/scripts/gui-shots.sh" "$out/gui.txt" -- >/dev/null
convert "$out/gui_dialog.png" -crop 530x600+0+0 +repage "$here/docs/img/gui_vessel_dialog.png"
convert "$out/gui_applied.png" -resize 75% "$here/docs/img/gui_vessel_applied.png"
echo "pictures written to $here/docs/img: drawing_vessels.png, gui_vessel_dialog.png, gui_vessel_applied.png"
