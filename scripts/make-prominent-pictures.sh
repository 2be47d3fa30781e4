#!/usr/bin/env bash
# Re-makes the pictures of docs/prominent.md on the bundled coin, in the real MeshLab GUI under a
# virtual display: the three colourings side by side (thesis fig. 6.16), the enhancement before and
# after, the prominent field drawn by Render > Show Curvature, and the filter dialogs.
# Output: docs/img/prominent_*.png (working files in build/prominent-pictures).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/prominent-pictures"; mkdir -p "$out"
coin="$here/examples/data/penny.ply"
img="$here/docs/img"

# Colourings: the example script's coloring filter with each curvature, alone.
for c in 0 1 2; do
  python3 - "$here/examples/prominent.mlx" "$c" >"$out/coloring$c.mlx" <<'EOF'
import re, sys
s = open(sys.argv[1]).read()
s = re.sub(r' <filter name="Prominent (Field|Enhancement)">.*?</filter>\n', '', s, flags=re.S)
print(s.replace('name="curvature" value="0"', 'name="curvature" value="%s"' % sys.argv[2]))
EOF
  "$here/scripts/meshlabserver" -i "$coin" -o "$out/coin_coloring$c.ply" -m vc -s "$out/coloring$c.mlx" >"$out/coloring$c.log" 2>&1
done
"$here/scripts/meshlabserver" -i "$coin" -o "$out/coin_colored.ply" -l 0 -m vc vq -o "$out/coin_enhanced.ply" -l 1 -m vq \
  -s "$here/examples/prominent.mlx" >"$out/prominent.log" 2>&1

zoom() {  # zoom(steps, file.png, meshlab files...)
  local steps="$1" shot="$2"; shift 2
  printf 'wheel 430 440 %s\nsleep 4\nshot %s\n' "$steps" "$shot" >"$out/zoom.txt"
  "$here/scripts/gui-shots.sh" "$out/zoom.txt" -- "$@" >/dev/null
}
for c in 2 1 0; do zoom 2 "$out/coloring$c.png" "$out/coin_coloring$c.ply"; done
convert \( "$out/coloring2.png" -crop 600x600+130+140 +repage \) \( "$out/coloring1.png" -crop 600x600+130+140 +repage \) \
  \( "$out/coloring0.png" -crop 600x600+130+140 +repage \) +append -resize 66% "$img/prominent_colorings.png"
zoom 5 "$out/scan.png" "$coin"
zoom 5 "$out/enhanced.png" "$out/coin_enhanced.ply"
convert \( "$out/scan.png" -crop 560x500+150+200 +repage \) \( "$out/enhanced.png" -crop 560x500+150+200 +repage \) \
  +append "$img/prominent_enhancement.png"

# Enhancement on the statuette and the bunny (their scans converted to PLY: MeshLab 2020.09's OBJ
# importer aborts on fertility.obj), scan | enhanced, whole objects.
pairs=()
for s in fertility stanford-bunny; do
  src="$here/../shared/data/meshes/$s.obj"
  [ -f "$src" ] || { echo "skipping $s (missing)"; continue; }
  "$here/build/tests/rk_make_mesh" convert "$src" "$out/$s.ply" >/dev/null
  "$here/scripts/meshlabserver" -i "$out/$s.ply" -o "$out/${s}_enhanced.ply" -l 1 -m vq -s "$here/examples/prominent.mlx" \
    >"$out/${s}_prominent.log" 2>&1
  "$here/scripts/screenshot.sh" "$out/${s}_scan.png" -- "$out/$s.ply" >/dev/null
  "$here/scripts/screenshot.sh" "$out/${s}_enh.png" -- "$out/${s}_enhanced.ply" >/dev/null
  convert "$out/${s}_scan.png" "$out/${s}_enh.png" -crop 700x640+75+140 +repage +append -resize 60% "$out/${s}_pair.png"
  pairs+=("$out/${s}_pair.png")
done
[ ${#pairs[@]} -gt 0 ] && convert "${pairs[@]}" -append "$img/prominent_scans_enhanced.png"

# The field in the GUI: Filters search > Prominent Field > Apply, Render > Show Curvature with a
# short vector length, zoomed in on the portrait. Screen positions of MeshLab 2020.09 at 1280x900.
cat >"$out/field.txt" <<EOF
click 1258 46
sleep 1
type Prominent Field
sleep 2
click 860 99
sleep 3
shot $out/field_dialog.png
click 425 577
sleep 8
shot $out/field_applied.png
click 147 577
sleep 2
click 178 10
sleep 1
click 230 286
sleep 3
dclick 920 613
sleep 2
click 1110 632
key ctrl+a
type 0.008
key Return
sleep 3
wheel 430 400 7
sleep 4
shot $out/field_zoom.png
EOF
"$here/scripts/gui-shots.sh" "$out/field.txt" -- "$coin" >/dev/null
convert "$out/field_zoom.png" -crop 860x700+0+70 +repage -resize 80% "$img/prominent_field.png"
convert "$out/field_dialog.png" -crop 575x600+0+0 +repage "$img/gui_prominent_field_dialog.png"
convert "$out/field_applied.png" -resize 60% "$img/gui_prominent_field_applied.png"

# The other two dialogs (the search lists the best match first).
for f in "Prominent Enhancement:enhancement:99" "Prominent Coloring:coloring:99"; do
  IFS=: read -r name key y <<<"$f"
  printf 'click 1258 46\nsleep 1\ntype %s\nsleep 2\nclick 860 %s\nsleep 3\nshot %s\n' "$name" "$y" "$out/${key}_dialog.png" >"$out/d.txt"
  "$here/scripts/gui-shots.sh" "$out/d.txt" -- "$coin" >/dev/null
  convert "$out/${key}_dialog.png" -crop 575x640+0+0 +repage "$img/gui_prominent_${key}_dialog.png"
done
echo "pictures in $img/prominent_*.png and gui_prominent_*.png"
