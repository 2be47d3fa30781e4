#!/usr/bin/env bash
# Re-makes the layout pictures of docs/illustration.md (issue 44): the shared scans of
# ../shared/data/meshes (the OBJ ones converted to PLY) through reliefkit-batch — Demarcating
# Curves, then Export Illustration Plate at its defaults (the default view) and with the four
# headless shadings (raking, multi-directional, openness, radiance scaling; the raking one with a
# light stack of 8) — rendered with rsvg-convert; then the four plates of the disciplines, each
# beside MeshLab 2020.09's view of the piece (its GUI under a virtual display): a synthetic tablet
# (examples/tablet_plate.mlx), blade (lithic_plate.mlx) and two-faced coin (coin_two_faces.mlx),
# made by rk_make_mesh, and the shared Cycladic torso (figurine_plate.mlx), through meshlabserver.
# Output: docs/img/plate_default_views.png, plate_shadings_coin.png, plate_shadings_gargoyle.png,
# plate_layout_tablet.png, plate_layout_lithic.png, plate_layout_coin.png,
# plate_layout_figurine.png (working files in build/layout-pictures).
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
source "$here/scripts/picture-helpers.sh"  # view(), label()
script() {  # $1: layout (0 one view), $2: shading (0 automatic; 4-7 the core's), $3: light stack
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
run 0 0 0 0
run s4 0 4 8
for shading in 5 6 7; do run "s$shading" 0 "$shading" 0; done
svg() { ls "$out/out$1/$2"/*.svg; }
png() { rsvg-convert -h "$3" -b white "$(svg "$1" "$2")" -o "$4"; }
for s in cycladic_figurine_torso fertility gargoyle oxhide_ingot penny_gigamacro stanford-bunny; do png 0 "$s" 420 "$out/default_$s.png"; done
convert "$out"/default_*.png +append -resize 1600x "$here/docs/img/plate_default_views.png"
for scan in penny_gigamacro gargoyle; do
  for shading in 4 5 6 7; do png "s$shading" "$scan" 400 "$out/shading_${scan}_$shading.png"; done
  convert "$out"/shading_"${scan}"_{4,5,6,7}.png +append -resize 1600x "$out/shadings_$scan.png"
done
cp "$out/shadings_penny_gigamacro.png" "$here/docs/img/plate_shadings_coin.png"
cp "$out/shadings_gargoyle.png" "$here/docs/img/plate_shadings_gargoyle.png"
# The disciplines' plates: each piece through its example script in meshlabserver (the plate beside
# the mesh's file), beside MeshLab's view of it.
for find in tablet blade coin; do "$here/build/tests/rk_make_mesh" "$find" upright "$out/$find.ply" | sed "s/^/$find: /"; done
cp "$out/scans/cycladic_figurine_torso.ply" "$out/torso.ply"
plate_beside_view() {  # $1: mesh, $2: example script, $3: picture, $4: caption of the view, $5: of the plate
  "$here/scripts/meshlabserver" -i "$out/$1.ply" -s "$here/examples/$2.mlx" >"$out/$1.log" 2>&1
  grep -E "^LOG: 2 (Plate layout|Illustration plate)" "$out/$1.log" | sed 's/^LOG: 2 //' | cut -c1-240
  view "$out/$1_view.png" 0 0 "$out/$1.ply"
  label "$out/$1_view.png" "$4"
  rsvg-convert -h 1100 -b white "$out/$1-plate.svg" -o "$out/$1_plate.png"
  convert "$out/$1_plate.png" -resize x660 "$out/$1_plate.png"
  label "$out/$1_plate.png" "$5"
  convert "$out/$1_view.png" "$out/$1_plate.png" -background white -gravity north +append "$here/docs/img/$3"
}
plate_beside_view tablet tablet_plate plate_layout_tablet.png "a tablet in MeshLab" "Tablet layout, raking light"
plate_beside_view blade lithic_plate plate_layout_lithic.png "a blade in MeshLab" "Lithic layout with its section"
plate_beside_view coin coin_two_faces plate_layout_coin.png "a coin in MeshLab" "Two faces, raking light"
plate_beside_view torso figurine_plate plate_layout_figurine.png "the Cycladic torso in MeshLab" "Figurine layout"
# From the menus: the tablet opened in MeshLab's GUI, the filter found by its search, Layout set to
# Tablet and Shading to Raking light in its dialog, Apply; the dialog and MeshLab's log beside the plate.
mkdir -p "$out/gui"; cp "$out/tablet.ply" "$out/gui/"
cat > "$out/gui/actions.txt" <<'EOT'
sleep 6
click 1258 46
sleep 1
type Export Illustration Plate
sleep 1.5
key Down
key Return
sleep 2.5
# Layout: Tablet; Shading: Raking light
click 395 376
sleep 1
click 417 402
sleep 1
click 395 558
sleep 1
click 280 659
sleep 1
apply Export Illustration Plate
sleep 15
shot applied.png
EOT
(cd "$out/gui" && "$here/scripts/gui-shots.sh" "$out/gui/actions.txt" -- "$out/gui/tablet.ply" >/dev/null)
[ -f "$out/gui/tablet-plate.svg" ] || { echo "make-layout-pictures.sh: the plate was not written from MeshLab's dialog" >&2; exit 1; }
convert "$out/gui/applied.png" -resize x660 "$out/gui/applied_small.png"
label "$out/gui/applied_small.png" "MeshLab: Layout Tablet, Shading Raking light, Apply"
rsvg-convert -h 1100 -b white "$out/gui/tablet-plate.svg" | convert - -resize x660 "$out/gui/plate.png"
label "$out/gui/plate.png" "the plate it wrote"
convert "$out/gui/applied_small.png" "$out/gui/plate.png" -background white -gravity north +append "$here/docs/img/plate_gui_tablet.png"
echo "pictures written to $here/docs/img: plate_default_views.png, plate_shadings_coin.png, plate_shadings_gargoyle.png, plate_layout_tablet.png, plate_layout_lithic.png, plate_layout_coin.png, plate_layout_figurine.png, plate_gui_tablet.png"
