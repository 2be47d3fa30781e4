#!/usr/bin/env bash
# MeshLab 2025.07 of the Debian testing root (its own /usr/bin/meshlab, nothing of ours in its
# installation) loads ReliefKit from the user's MeshLabExtraPlugins/2025.07 folder, put there by
# the build's install-user-plugins target, and runs a filter from its menus. On a virtual display,
# a fresh home: the target, then MeshLab on the coin. Checks that
#   - the target put the seven plugins and the base-model library where MeshLab looks;
#   - MeshLab mapped the six from that folder and raised no "Error while loading plugins." window
#     (its version and precision check throws for a plugin built for another MeshLab);
#   - its filter search finds "Demarcating Curves", the dialog opens and Apply draws the curves
#     (the screen changes inside the view where the curves are);
#   - then every ReliefKit filter, found by its exact name in MeshLab's filter search, opens its
#     dialog and applies at its defaults (on the coin; the drawing filters on the sample drawings,
#     their file typed into the dialog): MeshLab's own log says "Applied filter: <name>" for each.
# With --pictures DIR it also leaves the screenshots (menu, search, dialog, result) in DIR.
#   tests/releases/user-plugins-gui.sh [--pictures docs/img]     (after scripts/build-release.sh 2025)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
pictures=""; [ "${1:-}" = --pictures ] && pictures="$(realpath "$2")"
root="$(bash "$here/scripts/meshlab-root.sh" 2025)"
source "$here/scripts/chroot-mounts.sh"
with_root_mounts "$root" "$here"
home=/tmp/reliefkit-user-$$   # in the root
shots="$(mktemp -d)"
rm -rf "$root$home"; mkdir -p "$root$home"
chroot "$root" env HOME="$home" bash -c "cd $tree_in_root && cmake --build build-2025 --target install-user-plugins" | tail -1
folder="$home/.local/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07"
n="$(ls "$root$folder"/libfilter_reliefkit_*.so | wc -l)"
[ "$n" -eq 8 ] && [ -d "$root$folder/reliefkit-bases" ] ||
  { echo "FAIL: $n plugins in $folder (8 expected) or no reliefkit-bases beside them"; exit 1; }

display=":$((80 + RANDOM % 100))"
Xvfb "$display" -screen 0 1280x900x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
mkdir -p "$root/tmp/.X11-unix"
mount --bind /tmp/.X11-unix "$root/tmp/.X11-unix" && _rk_mounts+=("$root/tmp/.X11-unix")
finish() { pkill -f "^/usr/bin/meshlab $home" || true; kill "$xvfb" 2>/dev/null || true; rm -rf "$root$home" "$shots"; _rk_unmount; }
trap finish EXIT
sleep 1
cp "$here/examples/data/penny.ply" "$root$home/penny.ply"
cp "$here/examples/data/nested_drawing.png" "$root$home/nested.png"
cp "$here/examples/data/lamp_figure.png" "$root$home/lamp.png"
cp "$here/examples/data/jar_half_section.png" "$root$home/jar.png"
chroot "$root" env DISPLAY="$display" HOME="$home" /usr/bin/meshlab "$home/penny.ply" >"$shots/meshlab.log" 2>&1 &
export DISPLAY="$display"
for _ in $(seq 120); do  # until MeshLab has opened the coin (its log), at most a minute
  grep -q "All files opened" "$shots/meshlab.log" 2>/dev/null && break
  sleep 0.5
done
sleep 2
pid="$(pgrep -f "^/usr/bin/meshlab $home" | head -1)"
[ -n "$pid" ] || { echo "FAIL: MeshLab 2025.07 did not start"; exit 1; }
mapped="$(grep -c "MeshLabExtraPlugins/2025.07/libfilter_reliefkit_" <(sort -u -k6 "/proc/$pid/maps" | awk '{print $6}' | sort -u) || true)"
echo "MeshLab 2025.07 (pid $pid) mapped $mapped ReliefKit plugins from $folder"
[ "$mapped" -eq 8 ] || { echo "FAIL: 8 expected"; exit 1; }
if xdotool search --name "Error while loading plugins" >/dev/null 2>&1; then
  import -window root "$shots/error.png"; [ -z "$pictures" ] || cp "$shots/error.png" "$pictures/meshlab2025_error.png"
  echo "FAIL: MeshLab 2025.07 refused plugins (its \"Error while loading plugins.\" window is open)"; exit 1
fi

import -window root -crop 400x540+0+70 "$shots/view-before.png"   # the coin alone, before the filter
shot() { import -window root "$shots/$1.png"; convert "$shots/$1.png" -crop "$2" +repage "$shots/$1.png"; }
xdotool mousemove 116 9 click 1; sleep 1.5                      # Filters
xdotool mousemove 240 263 click 1; sleep 1.5                    # > Normals, Curvatures and Orientation
shot menu 853x900+0+0
xdotool key Escape; sleep 0.3; xdotool key Escape; sleep 0.5
xdotool mousemove 831 43 click 1; sleep 1                       # MeshLab's filter search
xdotool type --delay 60 "Demarcating Curves"; sleep 1.5
shot search 853x300+0+0
xdotool key Down Return; sleep 2
dialog="$(xdotool search --onlyvisible --name "^Demarcating Curves$" | head -1 || true)"
[ -n "$dialog" ] || { echo "FAIL: the filter search did not open the Demarcating Curves dialog"; exit 1; }
shot dialog 853x700+0+0
eval "$(xdotool getwindowgeometry --shell "$dialog")"           # X Y WIDTH HEIGHT of the dialog
xdotool mousemove $((X + WIDTH * 3 / 4)) $((Y + HEIGHT - 20)) click 1; sleep 6   # Apply (bottom right)
xdotool mousemove $((X + WIDTH / 4)) $((Y + HEIGHT - 20)) click 1; sleep 2       # Close (bottom left)
shot result 853x700+0+0
# The curves: the coin's view changed after Apply (both pictures without menu or dialog).
import -window root -crop 400x540+0+70 "$shots/view-after.png"
changed="$(compare -metric AE -fuzz 10% "$shots/view-before.png" "$shots/view-after.png" null: 2>&1 || true)"
echo "Demarcating Curves applied from MeshLab 2025.07's dialog: $changed pixels of the view changed"
[ "${changed%%.*}" -gt 2000 ] 2>/dev/null || { echo "FAIL: the view did not change (no curves drawn?)"; exit 1; }
[ -z "$pictures" ] || for s in menu search dialog result; do cp "$shots/$s.png" "$pictures/meshlab2025_$s.png"; done

# Every filter from the menus. The coin (layer 0) is made current first: a filter that added a
# layer made that one current.
open_filter() {  # NAME: MeshLab's filter search, the entry that opens the dialog titled NAME
  local name="$1" k
  for k in 1 2 3 4; do
    xdotool mousemove 489 111 click 1; sleep 0.5                 # layer 0 (the coin)
    xdotool mousemove 831 43 click 1; sleep 0.8
    xdotool type --delay 30 "$name"; sleep 1.2
    xdotool key --delay 150 $(printf 'Down %.0s' $(seq "$k")) Return; sleep 1.5
    dialog="$(xdotool search --onlyvisible --name "^$name\$" | head -1 || true)"
    [ -n "$dialog" ] && return 0
    xdotool key Escape; sleep 0.5
    for w in $(xdotool search --onlyvisible --name "." 2>/dev/null); do  # another filter's dialog
      [ "$(xdotool getwindowname "$w")" = "MeshLab 2025.07 - [Project_1]" ] || xdotool windowclose "$w" 2>/dev/null || true
    done
  done
  return 1
}
first_field() {  # the first parameter's text field of the open dialog: clicked (the drawing's file)
  eval "$(xdotool getwindowgeometry --shell "$dialog")"
  local top=$((Y + 60)) row                                      # below the title (a tall dialog's top is off screen)
  [ "$top" -ge 0 ] || top=0
  import -window root -crop "1x$((Y + HEIGHT - 200 - top))+$((X + 300))+$top" "$shots/column.png"
  row="$(convert "$shots/column.png" -depth 8 txt:- | awk -F'[,:]' '/#FFFFFF/ {print $2; exit}')"
  [ -n "$row" ] || return 1
  xdotool mousemove $((X + 300)) $((top + row + 8)) click 1; sleep 0.3
}
apply_and_wait() {  # NAME: Apply, then MeshLab's log until the filter ends (applied or failed)
  local name="$1" t
  eval "$(xdotool getwindowgeometry --shell "$dialog")"
  xdotool mousemove $((X + WIDTH * 3 / 4)) $((Y + HEIGHT - 20)) click 1
  for t in $(seq 240); do
    grep -qE "LOG: [0-9]+ (Applied filter: $name in|$name failed)" "$shots/meshlab.log" && break
    sleep 0.5
  done
  eval "$(xdotool getwindowgeometry --shell "$dialog")"
  xdotool mousemove $((X + WIDTH / 4)) $((Y + HEIGHT - 20)) click 1; sleep 1   # Close
  grep -q "LOG: [0-9]* Applied filter: $name in" "$shots/meshlab.log"
}
declare -A drawing_of=(["Line Drawing to Curves"]=nested.png ["Relief from Line Drawing"]=nested.png
                       ["Base from Drawing Silhouette"]=lamp.png ["Vessel from Profile Drawing"]=jar.png)
failed=0; applied=0
for name in "Compute Curvature Tensor and Derivatives" "Demarcating Curves" "Curvature Shading" "Relief Edges" \
            "Estimate Base Normals" "Ridges and Valleys" "Compute Optimal Scale" "Optimally Smoothed Surface" \
            "Multi-scale Ridges and Valleys" "Multi-scale Relief Edges" "Prominent Field" "Prominent Enhancement" \
            "Prominent Coloring" "Export Illustration Plate" "Line Drawing to Curves" "Relief from Line Drawing" \
            "Base from Drawing Silhouette" "Vessel from Profile Drawing"; do
  if ! open_filter "$name"; then echo "FAIL: the filter search did not open \"$name\""; failed=$((failed + 1)); continue; fi
  if [ -n "${drawing_of[$name]:-}" ]; then
    first_field || { echo "FAIL: no file field in \"$name\""; failed=$((failed + 1)); continue; }
    xdotool type --delay 20 "$home/${drawing_of[$name]}"
  fi
  if apply_and_wait "$name"; then
    applied=$((applied + 1)); grep "LOG: [0-9]* Applied filter: $name in" "$shots/meshlab.log" | tail -1 | sed 's/^LOG: [0-9]* /  /'
  else
    echo "FAIL: \"$name\" did not apply from its dialog:"; grep "$name" "$shots/meshlab.log" | grep LOG | tail -2
    failed=$((failed + 1))
  fi
done
echo "$applied of 18 ReliefKit filters applied from MeshLab 2025.07's dialogs"
[ "$failed" -eq 0 ] && [ "$applied" -eq 18 ] || exit 1
[ -z "$pictures" ] || echo "screenshots: $pictures/meshlab2025_{menu,search,dialog,result}.png"
echo "PASS: MeshLab 2025.07 loads ReliefKit from the user's plugin folder and runs its filters from the menus"
