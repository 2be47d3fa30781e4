#!/usr/bin/env bash
# The plates of docs/illustration.md: the coin (examples/illustration_plate.mlx, its unit 0.0099 mm
# and 3:1, with its vertical section) and a shared drawing's relief (Relief from Line Drawing, then
# the plate of its relief and curves), each as SVG and PDF in docs/plates/ with PNG renders by
# rsvg-convert and pdftoppm; the example at its defaults on every scan and drawing of ../shared/data
# (docs/img/plate_shared_defaults.png, the log lines in build/plates/defaults.txt).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$here/build/plates"; out="$here/docs/plates"
rm -rf "$work"; mkdir -p "$work" "$out"
# The coin: a US cent is 19.05 mm across, its scan 1,924 units: 0.0099 mm a unit; drawn 3:1 on A4.
cp "$here/examples/data/penny.ply" "$work/coin.ply"
sed -e 's|name="unit_mm" value="1"|name="unit_mm" value="0.0099"|; s|value="1" name="unit_mm"|value="0.0099" name="unit_mm"|' \
    -e 's|value="0" name="ratio"|value="3" name="ratio"|' \
    -e 's|<Param type="RichEnum" value="0" enum_cardinality="3" name="page"/>|<Param type="RichEnum" value="1" enum_cardinality="3" name="page"/>|' \
    "$here/examples/illustration_plate.mlx" > "$work/coin.mlx"
"$here/scripts/meshlabserver" -i "$work/coin.ply" -s "$work/coin.mlx" > "$work/coin.log" 2>&1
grep "Illustration plate" "$work/coin.log" | tail -1
cp "$work/coin-plate.svg" "$out/coin-plate.svg"; cp "$work/coin-plate.pdf" "$out/coin-plate.pdf"
rsvg-convert --dpi-x 100 --dpi-y 100 -o "$here/docs/img/plate_coin_svg.png" "$out/coin-plate.svg"
pdftoppm -r 100 -png -singlefile "$out/coin-plate.pdf" "$here/docs/img/plate_coin_pdf"
# A shared drawing's relief: Relief from Line Drawing on a lithic drawing of ../shared/data (its
# relief in mm from the drawing's DPI), then the plate of the relief with the drawing's curves,
# from above, 1:1, lit from the top left.
drawing="$here/../shared/data/drawings/lithic_replica_1.png"
if [ -f "$drawing" ]; then
  cp "$drawing" "$work/"; drawing="$work/lithic_replica_1.png"  # its interpretation file is written beside it
  sed -e "s|value=\"examples/data/nested_drawing.png\"|value=\"$drawing\"|" "$here/examples/drawing_relief.mlx" |
    sed -e 's|</FilterScript>||' > "$work/lithic.mlx"
  cat >> "$work/lithic.mlx" <<EOT
 <filter name="Export Illustration Plate">
  <Param type="RichSaveFile" value="$work/lithic-plate.svg" name="file" ext="*.svg"/>
  <Param type="RichBool" value="true" name="pdf"/>
  <Param type="RichString" value="all" name="layers"/>
  <Param type="RichEnum" value="1" enum_cardinality="3" name="view"/>
  <Param type="RichPoint3f" x="0" y="0" z="-1" name="direction"/>
  <Param type="RichEnum" value="0" enum_cardinality="5" name="layout"/>
  <Param type="RichBool" value="false" name="turn_over"/>
  <Param type="RichBool" value="false" name="upside_down"/>
  <Param type="RichString" value="" name="reverse_layer"/>
  <Param type="RichFloat" value="1" name="unit_mm"/>
  <Param type="RichFloat" value="0" name="ratio"/>
  <Param type="RichEnum" value="2" enum_cardinality="8" name="shading"/>
  <Param type="RichFloat" value="315" name="light_azimuth"/>
  <Param type="RichFloat" value="20" name="light_elevation"/>
  <Param type="RichFloat" value="10" name="openness_radius"/>
  <Param type="RichInt" value="0" name="light_stack"/>
  <Param type="RichInt" value="300" name="dpi"/>
  <Param type="RichFloat" value="0.35" name="width"/>
  <Param type="RichEnum" value="1" enum_cardinality="3" name="weights"/>
  <Param type="RichEnum" value="0" enum_cardinality="3" name="section"/>
  <Param type="RichBool" value="true" name="section_fill"/>
  <Param type="RichFloat" value="0.5" name="section_at"/>
  <Param type="RichEnum" value="0" enum_cardinality="3" name="page"/>
 </filter>
</FilterScript>
EOT
  (cd "$here" && scripts/meshlabserver -s "$work/lithic.mlx" > "$work/lithic.log" 2>&1)
  grep "Illustration plate" "$work/lithic.log" | tail -1
  cp "$work/lithic-plate.svg" "$work/lithic-plate.pdf" "$out/"
  rsvg-convert --dpi-x 60 --dpi-y 60 -o "$here/docs/img/plate_lithic_svg.png" "$out/lithic-plate.svg"
fi
# The filter's dialog in MeshLab's GUI, found by MeshLab's filter search.
# open_filter NAME: the gui-shots.sh actions that open a filter's dialog by MeshLab's filter search
# (MeshLab 2020.09 at 1280 x 900).
open_filter() { printf 'click 1258 46\nsleep 1\ntype %s\nsleep 1.5\nkey Down\nkey Return\nsleep 2.5\n' "$1"; }
{ echo "sleep 6"; open_filter "Export Illustration Plate"; echo "shot dialog.png"; } > "$work/dialog.txt"
(cd "$work" && "$here/scripts/gui-shots.sh" "$work/dialog.txt" -- "$work/coin.ply" > /dev/null)
convert "$work/dialog.png" -crop 556x752+0+0 +repage "$here/docs/img/plate_dialog.png"
# The same from the menus: Demarcating Curves applied (its Apply, then Close), then the plate at
# its defaults (Apply); MeshLab's layers and log after it (the plate beside coin.ply).
{ echo "sleep 6"; open_filter "Demarcating Curves"; printf 'click 414 577\nsleep 10\nclick 142 577\nsleep 1\n'
  open_filter "Export Illustration Plate"; printf 'apply Export Illustration Plate\nsleep 6\nshot applied.png\n'; } > "$work/apply.txt"
(cd "$work" && "$here/scripts/gui-shots.sh" "$work/apply.txt" -- "$work/coin.ply" > /dev/null)
convert "$work/applied.png" -resize 75% "$here/docs/img/plate_gui_applied.png"

# The example at its defaults (the mesh unit 1 mm, the scale automatic) on every scan of
# ../shared/data (the OBJs converted to PLY: MeshLab 2020.09's OBJ importer aborts on them) and on
# the relief of every drawing (Relief from Line Drawing at its defaults, then the plate).
shared="$here/../shared/data"
if [ -d "$shared/meshes" ]; then
  : > "$work/defaults.txt"; tiles=()
  for m in "$shared"/meshes/*; do
    n=$(basename "${m%.*}")
    case "$m" in *.obj) "$here/build/tests/rk_make_mesh" convert "$m" "$work/$n.ply" > /dev/null ;; *) cp "$m" "$work/$n.ply" ;; esac
    "$here/scripts/meshlabserver" -i "$work/$n.ply" -s "$here/examples/illustration_plate.mlx" > "$work/$n.log" 2>&1
    echo "$n: $(grep -o 'Illustration plate: .*' "$work/$n.log" | tail -1)" >> "$work/defaults.txt"
    rsvg-convert --dpi-x 40 --dpi-y 40 -o "$work/$n-tile.png" "$work/$n-plate.svg"; tiles+=("$work/$n-tile.png")
  done
  plate_filter=$(sed -n '/<filter name="Export Illustration Plate">/,/<\/filter>/p' "$here/examples/illustration_plate.mlx")
  for d in "$shared"/drawings/*; do
    case "$d" in *.png|*.jpg|*.jpeg|*.tif|*.tiff) ;; *) continue ;; esac
    n=$(basename "${d%.*}")
    cp "$d" "$work/"  # the relief's interpretation file goes beside the drawing: not into the shared data
    d="$work/$(basename "$d")"
    { sed -e "s|value=\"examples/data/nested_drawing.png\"|value=\"$d\"|" -e 's|</FilterScript>||' "$here/examples/drawing_relief.mlx"
      echo "$plate_filter" | sed -e "s|value=\"\" name=\"file\"|value=\"$work/$n-plate.svg\" name=\"file\"|"
      echo "</FilterScript>"; } > "$work/$n.mlx"
    (cd "$here" && scripts/meshlabserver -s "$work/$n.mlx" > "$work/$n.log" 2>&1)
    echo "$n: $(grep -o 'Illustration plate: .*' "$work/$n.log" | tail -1)" >> "$work/defaults.txt"
    rsvg-convert --dpi-x 40 --dpi-y 40 -o "$work/$n-tile.png" "$work/$n-plate.svg"; tiles+=("$work/$n-tile.png")
  done
  montage "${tiles[@]}" -tile 4x -geometry 300x300+6+6 -background white "$here/docs/img/plate_shared_defaults.png"
  cat "$work/defaults.txt"
fi
