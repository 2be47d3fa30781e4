#!/usr/bin/env bash
# Drives the real MeshLab GUI (with ReliefKit's plugins) under a virtual display and takes
# screenshots along the way: menus, filter dialogs, what the view shows after Apply, the log.
#   scripts/gui-shots.sh ACTIONS_FILE -- [meshlab arguments: files...]
# ACTIONS_FILE holds one action per line (blank lines and # comments ignored):
#   click X Y        left click at screen position X Y (the screen is 1280x900, MeshLab maximised)
#   dclick X Y       double click
#   wheel X Y N      N steps of the mouse wheel at X Y (N > 0 zooms in, N < 0 out)
#   drag X1 Y1 X2 Y2 left-button drag (in the view: turns the trackball)
#   key KEYS         xdotool key names, e.g. "Return" or "ctrl+a"
#   type TEXT        types TEXT into the focused widget
#   sleep S          waits S seconds
#   shot FILE.png    saves the whole screen (relative paths: to the current directory)
#   apply NAME       clicks Apply in the open dialog of the filter NAME, moving the dialog up first
#                    when its bottom is off the screen (a filter with many parameters)
# The view and dialogs take a moment to draw: put a sleep before each shot.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
actions="$(realpath "$1")"; shift
[ "${1:-}" = "--" ] && shift
command -v xdotool >/dev/null || { echo "gui-shots.sh: xdotool missing (scripts/setup.sh installs it)" >&2; exit 1; }
export RK_ACTIONS="$actions" RK_HERE="$here" RK_CWD="$PWD"
xvfb-run -a -s "-screen 0 1280x900x24 -noreset" bash -c '
  set -u
  "$RK_HERE/scripts/meshlab" "$@" >/tmp/rk_meshlab_gui.log 2>&1 &
  pid=$!
  sleep 8
  win=$(xdotool search --onlyvisible --name "MeshLab" | head -1 || true)
  [ -n "$win" ] && { xdotool windowsize "$win" 1280 900 windowmove "$win" 0 0 || true; sleep 1; }
  while read -r verb a b; do
    case "$verb" in
      ""|"#"*) continue ;;
      click) xdotool mousemove "$a" "$b" click 1 ;;
      dclick) xdotool mousemove "$a" "$b" click --repeat 2 1 ;;
      wheel) read -r x y n <<<"$a $b"; btn=5; [ "${n:-1}" -lt 0 ] && btn=4 && n=$((-n))
             xdotool mousemove "$x" "$y" click --repeat "${n:-1}" --delay 300 $btn ;;
      drag) read -r x1 y1 x2 y2 <<<"$a $b"
            xdotool mousemove "$x1" "$y1" mousedown 1 sleep 0.3 mousemove "$(( (x1 + x2) / 2 ))" "$(( (y1 + y2) / 2 ))" \
              sleep 0.3 mousemove "$x2" "$y2" sleep 0.3 mouseup 1 ;;
      key) xdotool key --delay 200 $a $b ;;
      type) xdotool type --delay 50 "$a${b:+ $b}" ;;
      sleep) sleep "$a" ;;
      shot) (cd "$RK_CWD" && import -window root "$a") && echo "screenshot: $a" ;;
      apply) w=$(xdotool search --onlyvisible --name "^$a${b:+ $b}\$" | head -1)
             eval "$(xdotool getwindowgeometry --shell "$w")"
             if [ $((Y + HEIGHT)) -gt 895 ]; then
               xdotool windowmove "$w" "$X" $((895 - HEIGHT)); sleep 1; eval "$(xdotool getwindowgeometry --shell "$w")"
             fi
             xdotool mousemove $((X + WIDTH * 3 / 4)) $((Y + HEIGHT - 20)) click 1 ;;
      *) echo "gui-shots.sh: unknown action $verb" >&2 ;;
    esac
  done <"$RK_ACTIONS"
  kill $pid 2>/dev/null || true
' _ "$@"
