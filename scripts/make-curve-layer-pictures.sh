#!/usr/bin/env bash
# Before and after pictures of every curve filter at its defaults on every shared scan
# (docs/curve-layers.md): the plates bench/curve_layers.py --plates exported (one view, automatic
# view, multi-directional light) for two builds, side by side, one sheet per filter in docs/img/.
# Usage: scripts/make-curve-layer-pictures.sh BEFORE_WORK AFTER_WORK [BEFORE_LABEL AFTER_LABEL]
# Also the shared flake's lithic plate by this build (docs/img/curve_layers_lithic_flake.png).
#   BEFORE_WORK, AFTER_WORK: the --work folders of two runs of bench/curve_layers.py --plates
#   (the first with RELIEFKIT_BUILD_DIR set to the earlier build).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
before="$1"; after="$2"; before_label="${3:-before}"; after_label="${4:-after}"
sheets="$(mktemp -d)"; trap 'rm -rf "$sheets"' EXIT
for filter_dir in "$after"/out/*/; do
  filter="$(basename "$filter_dir")"
  tiles=()
  for plate in "$filter_dir"*/plate.svg; do
    scan="$(basename "$(dirname "$plate")")"
    case "$scan" in *_decimated) continue ;; esac
    old="$before/out/$filter/$scan/plate.svg"
    [ -f "$old" ] || continue
    for side in before after; do
      svg="$old"; [ "$side" = after ] && svg="$plate"
      rsvg-convert -w 420 -b white -o "$sheets/$scan-$side.png" "$svg"
      # The plate's scale bar is below the drawing: cropped away, the drawing kept.
      convert "$sheets/$scan-$side.png" -gravity south -chop 0x70 -trim +repage -resize 400x400 \
        -gravity center -background white -extent 420x420 "$sheets/$scan-$side.png"
      tiles+=("$sheets/$scan-$side.png")
    done
  done
  [ ${#tiles[@]} -gt 0 ] || continue
  name="$(echo "$filter" | tr 'A-Z' 'a-z' | tr -c 'a-z0-9\n' '_')"
  montage "${tiles[@]}" -tile 4x -geometry +6+6 -background white "$sheets/$name.png"
  convert "$sheets/$name.png" -gravity north -background white -splice 0x40 -font DejaVu-Sans -pointsize 22 \
    -annotate +0+8 "${filter//_/ } at its defaults: $before_label | $after_label (pairs, left to right)" \
    -colors 64 "$here/docs/img/curve_layers_$name.png"
  echo "docs/img/curve_layers_$name.png"
done
# The shared flake's lithic plate at the example's settings (examples/lithic_plate.mlx: Ridges and
# Valleys at its defaults, the Lithic layout), by this build.
flake="$here/../shared/data/meshes/lithic_flake_PGCS_Vau2.ply"
if [ -f "$flake" ]; then
  sed -e 's|value="" name="file"|value="{output}/plate.svg" name="file"|; s|value="true" name="pdf"|value="false" name="pdf"|' \
    "$here/examples/lithic_plate.mlx" > "$sheets/lithic.mlx"
  "${RELIEFKIT_BUILD_DIR:-$here/build}/prefix/bin/reliefkit-batch" --script "$sheets/lithic.mlx" --save none "$flake" \
    "$sheets/lithic" > "$sheets/lithic.log" 2>&1
  rsvg-convert -w 1100 -b white -o "$here/docs/img/curve_layers_lithic_flake.png" "$sheets/lithic/lithic_flake_PGCS_Vau2/plate.svg"
  echo "docs/img/curve_layers_lithic_flake.png"
fi
# The flake's ridges (red) and valleys (blue) of AFTER_WORK in the real MeshLab GUI: as it opens
# (the ventral face) and turned to the dorsal scars (docs/img/curve_layers_gui_flake.png).
layers="$after/out/Ridges_and_Valleys/lithic_flake_PGCS_Vau2"
if [ -f "$flake" ] && [ -d "$layers" ]; then
  printf 'sleep 3\nshot %s/open.png\nclick 231 10\nsleep 1\nclick 290 113\nsleep 1\ndrag 230 430 660 430\nsleep 4\nshot %s/turned.png\n' \
    "$sheets" "$sheets" > "$sheets/gui.txt"
  "$here/scripts/gui-shots.sh" "$sheets/gui.txt" -- "$flake" "$layers"/*-ridges.obj "$layers"/*-valleys.obj >/dev/null
  convert "$sheets/turned.png" -crop 860x700+0+70 +repage -resize x630 "$sheets/turned.png"
  convert "$sheets/open.png" -resize 900x "$sheets/turned.png" +append -colors 128 "$here/docs/img/curve_layers_gui_flake.png"
  echo "docs/img/curve_layers_gui_flake.png"
fi
