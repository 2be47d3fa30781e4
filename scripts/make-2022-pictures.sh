#!/usr/bin/env bash
# The pictures of ReliefKit in MeshLab 2022.02's GUI (docs/meshlab-releases.md): MeshLab 2022.02 of the
# Debian 13 root (scripts/meshlab-root.sh 2022, build-2022/ by scripts/build-release.sh 2022) on a virtual
# display of this machine, driven with xdotool: the coin opened, the Filters menu with ours,
# MeshLab's filter search finding them, the Demarcating Curves dialog, and its result. Needs root
# (chroot, mount).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="$(bash "$here/scripts/meshlab-root.sh" 2022)"
img="$here/docs/img"
source "$here/scripts/chroot-mounts.sh"
with_root_mounts "$root" "$here"
display=":$((80 + RANDOM % 100))"
Xvfb "$display" -screen 0 1280x900x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
mkdir -p "$root/tmp/.X11-unix"
mount --bind /tmp/.X11-unix "$root/tmp/.X11-unix" && _rk_mounts+=("$root/tmp/.X11-unix")
finish() { pkill -f build-2022/prefix/bin/meshlab || true; kill "$xvfb" 2>/dev/null || true; _rk_unmount; }
trap finish EXIT
sleep 1
cp "$here/examples/data/penny.ply" "$root/tmp/penny.ply"
chroot "$root" env DISPLAY="$display" HOME=/root $tree_in_root/build-2022/prefix/bin/meshlab /tmp/penny.ply >/dev/null 2>&1 &
export DISPLAY="$display"
sleep 10
shot() { import -window root "$1"; convert "$1" -crop "$2" +repage "$1"; }
xdotool mousemove 116 9 click 1; sleep 1.5                      # Filters
xdotool mousemove 240 263 click 1; sleep 1.5                    # > Normals, Curvatures and Orientation
shot "$img/meshlab2022_menu.png" 853x900+0+0
xdotool key Escape; sleep 0.3; xdotool key Escape; sleep 0.5
xdotool mousemove 831 43 click 1; sleep 1                       # MeshLab's filter search
xdotool type --delay 60 "Demarcating Curves"; sleep 1.5
shot "$img/meshlab2022_search.png" 853x300+0+0
xdotool key Down Return; sleep 2
shot "$img/meshlab2022_dialog.png" 853x700+0+0
xdotool mousemove 555 619 click 1; sleep 6                      # Apply
xdotool mousemove 296 619 click 1; sleep 2                      # Close
shot "$img/meshlab2022_demarcating.png" 853x700+0+0
echo "make-2022-pictures: docs/img/meshlab2022_{menu,search,dialog,demarcating}.png"
