#!/usr/bin/env bash
# Re-makes the pictures of the base section of docs/drawing_recon.md in the real MeshLab GUI under
# a virtual display: drawing -> retrieved model -> deformed base -> relief on the base (the example
# script examples/base_and_relief.mlx), the cylinder deformed to a goblet, and the filter's dialog
# and result in the GUI. Output: docs/img/base_*.png, docs/img/gui_base_*.png (working files in
# build/base-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/base-pictures"; rm -rf "$out"; mkdir -p "$out"
img="$here/docs/img"
server="$here/scripts/meshlabserver"

source "$here/scripts/picture-helpers.sh"  # view(), label()
colorize() {  # colorize(max height) > mlx
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="Colorize by vertex Quality">\n'
  printf '  <Param type="RichFloat" name="minVal" value="0"/>\n  <Param type="RichFloat" name="maxVal" value="%s"/>\n' "$1"
  printf '  <Param type="RichDynamicFloat" name="perc" value="0" min="0" max="100"/>\n'
  printf '  <Param type="RichBool" name="zeroSym" value="false"/>\n </filter>\n</FilterScript>\n'
}

# 1. The example: drawing -> retrieved -> base -> relief.
cp "$here/examples/data/lamp_figure.png" "$here/examples/data/nested_drawing.png" "$out/"
sed -e "s#value=\"examples/data/#value=\"$out/#" "$here/examples/base_and_relief.mlx" >"$out/example.mlx"
"$server" -s "$out/example.mlx" -o "$out/retrieved.ply" -l 0 -o "$out/base.ply" -l 1 -o "$out/relief.ply" -l 2 -m vq \
  >"$out/example.log" 2>&1
step=$(grep -o 'step [0-9.e+-]* mesh units' "$out/example.log" | head -1 | cut -d' ' -f2)
colorize "$(python3 -c "print(3 * $step)")" >"$out/colorize.mlx"
"$server" -i "$out/relief.ply" -s "$out/colorize.mlx" -o "$out/relief_c.ply" -m vc vq >/dev/null 2>&1
convert "$out/lamp_figure.png" -trim +repage -bordercolor white -border 30 -resize 600x620 -gravity center -extent 760x660 "$out/p1.png"
view "$out/p2.png" -150 0 "$out/retrieved.ply"
view "$out/p3.png" -150 0 "$out/base.ply"
view "$out/p4.png" -150 0 "$out/relief_c.ply"
label "$out/p1.png" "1. drawing (front, top)"; label "$out/p2.png" "2. retrieved: lamp_31"
label "$out/p3.png" "3. deformed base"; label "$out/p4.png" "4. relief on the base"
convert "$out/p1.png" "$out/p2.png" "$out/p3.png" "$out/p4.png" +append -resize 1600x "$img/base_pipeline.png"

# 2. Thesis fig. 7.10 (a): a cylinder made a goblet.
"$here/build/tests/rk_make_mesh" goblet-figure "$out/goblet.png"
sed -e "s#value=\"examples/data/lamp_figure.png\"#value=\"$out/goblet.png\"#" -e 's#name="views" value="front; top"#name="views" value="front"#' \
    -e 's#name="model" value=""#name="model" value="cylinder_05"#' "$here/examples/base_and_relief.mlx" |
  python3 -c "import sys; s=sys.stdin.read(); i=s.index(' <!-- MeshLab'); print(s[:i] + '</FilterScript>')" >"$out/goblet.mlx"
"$server" -s "$out/goblet.mlx" -o "$out/cyl.ply" -l 0 -o "$out/goblet.ply" -l 1 >"$out/goblet.log" 2>&1
convert "$out/goblet.png" -trim +repage -bordercolor white -border 30 -resize 600x620 -gravity center -extent 760x660 "$out/g1.png"
sed -e 's#name="round" value="false"#name="round" value="true"#' "$out/goblet.mlx" >"$out/goblet_round.mlx"
"$server" -s "$out/goblet_round.mlx" -o "$out/goblet_round.ply" -l 1 >"$out/goblet_round.log" 2>&1
view "$out/g2.png" 0 0 "$out/cyl.ply"
view "$out/g3.png" 0 0 "$out/goblet.ply"
view "$out/g4.png" -120 0 "$out/goblet.ply"
view "$out/g5.png" -120 0 "$out/goblet_round.ply"
label "$out/g1.png" "drawing (front view)"; label "$out/g2.png" "cylinder_05, placed"; label "$out/g3.png" "deformed (depth kept)"
label "$out/g4.png" "the same from above"; label "$out/g5.png" "taken as round, from above"
convert "$out/g1.png" "$out/g2.png" "$out/g3.png" "$out/g4.png" "$out/g5.png" +append -resize 1600x "$img/base_goblet.png"

# 3. The GUI: Filters search > Base from Drawing Silhouette, the drawing chosen with "...", views
# typed, Apply, the dialog closed, the view turned.
cat >"$out/gui.txt" <<EOF
click 1258 46
sleep 1
type Base from Drawing
sleep 2
click 860 99
sleep 3
click 592 425
sleep 3
type $out/lamp_figure.png
key Return
sleep 2
click 430 456
key ctrl+a
type front; top
sleep 1
shot $out/gui_dialog.png
click 485 822
sleep 15
click 166 822
sleep 2
click 231 10
sleep 1
click 290 113
sleep 2
drag 430 560 430 710
sleep 4
shot $out/gui_applied.png
EOF
"$here/scripts/gui-shots.sh" "$out/gui.txt" -- >/dev/null
convert "$out/gui_dialog.png" -crop 652x845+0+0 +repage "$img/gui_base_dialog.png"
convert "$out/gui_applied.png" -resize 75% "$img/gui_base_applied.png"
echo "pictures written to $img"
