#!/usr/bin/env bash
# Screenshot of the real MeshLab GUI (with ReliefKit's plugins) under a virtual display.
#   scripts/screenshot.sh OUT.png [--wait S] [--keys "xdotool key sequence"] -- [meshlab arguments: files...]
# Opens MeshLab maximised on a 1280x900 virtual screen, waits until it has drawn, optionally
# sends keys (xdotool), and saves the whole screen to OUT.png. Used for the pictures in docs/.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "$1")"; shift
wait=8; keys=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --wait) wait="$2"; shift 2 ;;
    --keys) keys="$2"; shift 2 ;;
    *) echo "screenshot.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
[ "${1:-}" = "--" ] && shift
args=("$@")
export RK_SHOT_OUT="$out" RK_SHOT_WAIT="$wait" RK_SHOT_KEYS="$keys" RK_HERE="$here"
xvfb-run -a -s "-screen 0 1280x900x24 -noreset" bash -c '
  "$RK_HERE/scripts/meshlab" "$@" >/tmp/rk_meshlab_gui.log 2>&1 &
  pid=$!
  sleep "$RK_SHOT_WAIT"
  if command -v xdotool >/dev/null; then
    win=$(xdotool search --onlyvisible --name "MeshLab" | head -1 || true)
    if [ -n "$win" ]; then
      xdotool windowsize "$win" 1280 900 windowmove "$win" 0 0 || true
      sleep 1
      if [ -n "$RK_SHOT_KEYS" ]; then xdotool windowactivate --sync "$win" key --delay 300 $RK_SHOT_KEYS || true; sleep 3; fi
    fi
  fi
  import -window root "$RK_SHOT_OUT"
  kill $pid 2>/dev/null || true
' _ "${args[@]}"
echo "screenshot: $out"
