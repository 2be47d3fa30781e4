#!/usr/bin/env bash
# Re-makes the pictures of docs/drawing_recon.md in the real MeshLab GUI under a virtual display:
# the pipeline on a real drawing (drawing, curves, levels, relief), the real drawings of
# ../shared/data/drawings (coloured by height and shaded), the bases (cylinder, a dome as the current layer), an edited
# interpretation (a disc sunk instead of raised), and the filter dialog and its result in the GUI.
# Output: docs/img/drawing_*.png, docs/img/gui_drawing_*.png (working files in build/drawing-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/drawing-pictures"; rm -rf "$out"; mkdir -p "$out"
img="$here/docs/img"
server="$here/scripts/meshlabserver"
shared="$here/tests/data/drawings"  # copies of ../shared/data/drawings

# The example script with another drawing, base, line scale and step width (and interpretation file).
script() {  # script(drawing, base, sigma, margin, [interpretation]) > file
  sed -e "s#value=\"examples/data/nested_drawing.png\"#value=\"$1\"#" -e "s#name=\"base\" value=\"0\"#name=\"base\" value=\"$2\"#" \
      -e "s#name=\"sigma\" value=\"0\"#name=\"sigma\" value=\"$3\"#" -e "s#name=\"margin\" value=\"4\"#name=\"margin\" value=\"$4\"#" \
      -e "s#name=\"interpretation\" value=\"\"#name=\"interpretation\" value=\"${5:-}\"#" "$here/examples/drawing_relief.mlx"
}
# Colours a relief by its height (vertex quality) from 0 to the top level its log reports.
colorize() {  # colorize(relief log) > mlx
  local top step
  top=$(grep -o 'levels 0 to [0-9]*' "$1" | head -1 | grep -o '[0-9]*$')
  step=$(grep -o 'step [0-9.e+-]* mesh units' "$1" | head -1 | cut -d' ' -f2)
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="Colorize by vertex Quality">\n'
  printf '  <Param type="RichFloat" name="minVal" value="0"/>\n'
  printf '  <Param type="RichFloat" name="maxVal" value="%s"/>\n' "$(python3 -c "print($top * $step)")"
  printf '  <Param type="RichDynamicFloat" name="perc" value="0" min="0" max="100"/>\n'
  printf '  <Param type="RichBool" name="zeroSym" value="false"/>\n </filter>\n</FilterScript>\n'
}
source "$here/scripts/picture-helpers.sh"  # view(), label()

# 1. The pipeline on the Qesem cave drawing.
cp "$shared/lithic_qesem_cave.png" "$out/qesem.png"
script "$out/qesem.png" 0 0 4 >"$out/qesem.mlx"
"$server" -s "$out/qesem.mlx" -o "$out/qesem_relief.ply" -l 0 -m vq -o "$out/qesem_curves.obj" -l 1 >"$out/qesem.log" 2>&1
colorize "$out/qesem.log" >"$out/colorize.mlx"
"$server" -i "$out/qesem_relief.ply" -s "$out/colorize.mlx" -o "$out/qesem_levels.ply" -m vc vq >"$out/qesem_levels.log" 2>&1
convert "$out/qesem.png" -background white -alpha remove -alpha off -trim +repage -bordercolor white -border 40 -resize 620x620 \
  -gravity center -extent 760x660 "$out/p1.png"
view "$out/p2.png" 0 0 "$out/qesem_curves.obj"
view "$out/p3.png" 0 0 "$out/qesem_levels.ply"
view "$out/p4.png" 220 2 "$out/qesem_relief.ply"
label "$out/p1.png" "1. drawing"; label "$out/p2.png" "2. Line Drawing to Curves"
label "$out/p3.png" "3. levels (height colours)"; label "$out/p4.png" "4. relief"
convert "$out/p1.png" "$out/p2.png" "$out/p3.png" "$out/p4.png" +append -resize 1600x "$img/drawing_pipeline.png"

# 2. The real drawings at the defaults (the small cuneiform tablet: line scale 1 px, step width 2 px, its best):
# drawing | relief coloured by height | the relief shaded, turned.
rows=()
for d in lithic_replica_1.png:0:4 lithic_qesem_cave.png:0:4 cuneiform_P102630_obverse.png:1:2 pottery_bowl_half_section.jpg:0:4; do
  IFS=: read -r file sigma margin <<<"$d"
  name="${file%.*}"
  cp "$shared/$file" "$out/$file"
  script "$out/$file" 0 "$sigma" "$margin" >"$out/$name.mlx"
  "$server" -s "$out/$name.mlx" -o "$out/${name}_relief.ply" -l 0 -m vq >"$out/$name.log" 2>&1
  convert "$out/$file" -background white -alpha remove -alpha off -trim +repage -bordercolor white -border 20 -resize 600x600 \
    -gravity center -extent 760x660 "$out/${name}_d.png"
  colorize "$out/$name.log" >"$out/${name}_colorize.mlx"
  "$server" -i "$out/${name}_relief.ply" -s "$out/${name}_colorize.mlx" -o "$out/${name}_levels.ply" -m vc vq >/dev/null 2>&1
  view "$out/${name}_r.png" 220 1 "$out/${name}_levels.ply"
  view "$out/${name}_s.png" 220 1 "$out/${name}_relief.ply"
  convert "$out/${name}_d.png" "$out/${name}_r.png" "$out/${name}_s.png" +append "$out/${name}_row.png"
  rows+=("$out/${name}_row.png")
done
convert "${rows[@]}" -append -resize 1500x "$img/drawing_real.png"

# 2b. The plate of 28 stone tools (../shared/data/drawings; its crop in tests/data when the shared
# folder is absent): the drawing | the relief at the defaults, shaded, from above | with its shading
# engraved 0.2 step deep (Shading engraved), turned.
plate="$here/../shared/data/drawings/lithic_plate_morar_quartz.jpg"
[ -f "$plate" ] || plate="$shared/lithic_plate_morar_quartz_crop.jpg"
cp "$plate" "$out/plate.jpg"
script "$out/plate.jpg" 0 0 4 >"$out/plate.mlx"
sed -e 's#name="shading_depth" value="0"#name="shading_depth" value="0.2"#' "$out/plate.mlx" >"$out/plate_engraved.mlx"
"$server" -s "$out/plate.mlx" -o "$out/plate_relief.ply" -l 0 -m vq >"$out/plate.log" 2>&1
"$server" -s "$out/plate_engraved.mlx" -o "$out/plate_engraved.ply" -l 0 -m vq >"$out/plate_engraved.log" 2>&1
convert "$out/plate.jpg" -resize 740x640 -gravity center -background white -extent 760x660 "$out/pl1.png"
view "$out/pl2.png" 160 1 "$out/plate_relief.ply"
view "$out/pl3.png" 160 2 "$out/plate_engraved.ply"
label "$out/pl1.png" "plate of stone tools"; label "$out/pl2.png" "relief (defaults), turned"
label "$out/pl3.png" "shading engraved 0.2 step, turned"
convert "$out/pl1.png" "$out/pl2.png" "$out/pl3.png" +append -resize 1600x "$img/drawing_plate.png"

# 3. Bases: the Qesem drawing rolled round a cylinder; the nested drawing on a dome (current layer).
script "$out/qesem.png" 1 0 4 >"$out/cyl.mlx"
"$server" -s "$out/cyl.mlx" -o "$out/cyl.ply" -l 0 -m vq >"$out/cyl.log" 2>&1
cp "$here/examples/data/nested_drawing.png" "$out/nested.png"
"$here/build/tests/rk_make_mesh" dome 800 600 2 "$out/dome.ply"
script "$out/nested.png" 2 0 4 >"$out/dome.mlx"
"$server" -i "$out/dome.ply" -s "$out/dome.mlx" -o "$out/dome_relief.ply" -l 1 -m vq >"$out/dome.log" 2>&1
view "$out/b1.png" 0 2 "$out/cyl.ply"
view "$out/b2.png" 200 0 "$out/dome_relief.ply"
label "$out/b1.png" "Cylinder"; label "$out/b2.png" "Current layer (a dome)"
convert "$out/b1.png" "$out/b2.png" +append -resize 1200x "$img/drawing_bases.png"

# 4. The interpretation file edited: the inner disc sunk (examples/data/nested_drawing.sunk.json).
script "$out/nested.png" 0 0 4 >"$out/auto.mlx"
script "$out/nested.png" 0 0 4 "$here/examples/data/nested_drawing.sunk.json" >"$out/sunk.mlx"
"$server" -s "$out/auto.mlx" -o "$out/auto.ply" -l 0 -m vq >"$out/auto.log" 2>&1
"$server" -s "$out/sunk.mlx" -o "$out/sunk.ply" -l 0 -m vq >"$out/sunk.log" 2>&1
view "$out/s1.png" 200 2 "$out/auto.ply"
view "$out/s2.png" 200 2 "$out/sunk.ply"
label "$out/s1.png" "automatic"; label "$out/s2.png" "curve 4: direction right-lower"
convert "$out/s1.png" "$out/s2.png" +append -resize 1200x "$img/drawing_sunk.png"

# 5. The GUI: Filters search > Relief from Line Drawing, the file chosen with "..." (MeshLab
# 2020.09 reads a file parameter only from its file dialog), Apply, the dialog closed, the view turned.
cat >"$out/gui.txt" <<EOF
click 1258 46
sleep 1
type Relief from Line
sleep 2
click 860 99
sleep 3
click 585 385
sleep 3
type $out/qesem.png
key Return
sleep 2
shot $out/gui_dialog.png
click 479 897
sleep 20
click 164 897
sleep 2
click 231 10
sleep 1
click 290 113
sleep 2
drag 430 560 430 410
sleep 4
shot $out/gui_applied.png
EOF
"$here/scripts/gui-shots.sh" "$out/gui.txt" -- >/dev/null
convert "$out/gui_dialog.png" -crop 645x900+0+0 +repage "$img/gui_drawing_relief_dialog.png"
convert "$out/gui_applied.png" -resize 75% "$img/gui_drawing_relief_applied.png"
echo "pictures written to $img"
