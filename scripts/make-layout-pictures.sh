#!/usr/bin/env bash
# Re-makes the layout pictures of docs/illustration.md (issue 44): the shared scans of
# ../shared/data/meshes (the OBJ ones converted to PLY) through reliefkit-batch — Demarcating
# Curves, then Export Illustration Plate at its defaults (the default view), with the tablet,
# lithic and figurine layouts, and with the four headless shadings (raking, multi-directional,
# openness, radiance scaling; the raking one with a light stack of 8) — rendered with rsvg-convert.
# Output: docs/img/plate_default_views.png, plate_layout_figurine.png, plate_layout_tablet.png,
# plate_layout_lithic.png, plate_shadings_coin.png, plate_shadings_gargoyle.png (working files
# in build/layout-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/layout-pictures"; rm -rf "$out"; mkdir -p "$out/scans"
for f in "$here"/../shared/data/meshes/*; do
  name="$(basename "$f")"
  case "$name" in
    *.obj) "$here/build/tests/rk_make_mesh" convert "$f" "$out/scans/${name%.obj}.ply" ;;
    *.ply) ln -s "$f" "$out/scans/$name" ;;
  esac
done
script() {  # $1: layout (0 one view, 1 tablet, 2 lithic, 4 figurine), $2: shading (0 automatic; 4-7 the core's), $3: light stack
  cat <<EOS
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Demarcating Curves"/>
 <filter name="Export Illustration Plate"><Param type="RichBool" name="pdf" value="false"/><Param type="RichInt" name="dpi" value="150"/><Param type="RichEnum" name="layout" value="$1" enum_cardinality="5"/><Param type="RichEnum" name="shading" value="$2" enum_cardinality="8"/><Param type="RichInt" name="light_stack" value="$3"/></filter>
</FilterScript>
EOS
}
run() {  # $1: the output's name, then script's arguments
  local name="$1"; shift
  script "$@" >"$out/$name.mlx"
  "$here/build/prefix/bin/reliefkit-batch" -j 2 -s "$out/$name.mlx" "$out/scans" "$out/out$name" 2>&1 |
    grep -E "Plate (view|layout)|Illustration plate:|Light stack" | sed 's/^.*Export Illustration Plate: //' | cut -c1-200
}
for layout in 0 1 2 4; do run "$layout" "$layout" 0 0; done
run s4 0 4 8
for shading in 5 6 7; do run "s$shading" 0 "$shading" 0; done
svg() { ls "$out/out$1/$2"/*.svg; }
png() { rsvg-convert -h "$3" -b white "$(svg "$1" "$2")" -o "$4"; }
for s in cycladic_figurine_torso fertility gargoyle oxhide_ingot penny_gigamacro stanford-bunny; do png 0 "$s" 420 "$out/default_$s.png"; done
convert "$out"/default_*.png +append -resize 1600x "$here/docs/img/plate_default_views.png"
png 4 cycladic_figurine_torso 700 "$here/docs/img/plate_layout_figurine.png"
png 1 oxhide_ingot 800 "$here/docs/img/plate_layout_tablet.png"
png 2 cycladic_figurine_torso 600 "$here/docs/img/plate_layout_lithic.png"
for scan in penny_gigamacro gargoyle; do
  for shading in 4 5 6 7; do png "s$shading" "$scan" 400 "$out/shading_${scan}_$shading.png"; done
  convert "$out"/shading_"${scan}"_{4,5,6,7}.png +append -resize 1600x "$out/shadings_$scan.png"
done
cp "$out/shadings_penny_gigamacro.png" "$here/docs/img/plate_shadings_coin.png"
cp "$out/shadings_gargoyle.png" "$here/docs/img/plate_shadings_gargoyle.png"
echo "pictures written to $here/docs/img: plate_default_views.png, plate_layout_figurine.png, plate_layout_tablet.png, plate_layout_lithic.png, plate_shadings_coin.png, plate_shadings_gargoyle.png"
