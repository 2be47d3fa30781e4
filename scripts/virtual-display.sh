# Sourced by scripts that run meshlabserver many times, possibly at once: one Xvfb for all of them
# (xvfb-run -a per call races for a display number when two calls start together).
_virtual_display_pid=""

start_virtual_display() {
  [ -z "${DISPLAY:-}" ] || return 0
  local numfile
  numfile="$(mktemp)"
  # -displayfd: the server picks a free display and writes its number once it accepts clients.
  # -noreset: by default Xvfb resets when its last client leaves and refuses the clients that
  # connect meanwhile (two xdpyinfo loops: 10 refusals in 4,000 connections; none with -noreset).
  Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$numfile" 2>/dev/null &
  _virtual_display_pid=$!
  for _ in $(seq 100); do [ -s "$numfile" ] && break; sleep 0.1; done
  [ -s "$numfile" ] || { echo "virtual-display: Xvfb did not start" >&2; rm -f "$numfile"; return 1; }
  export DISPLAY=":$(tr -d '[:space:]' <"$numfile")"
  rm -f "$numfile"
}

stop_virtual_display() {
  [ -n "$_virtual_display_pid" ] || return 0
  kill "$_virtual_display_pid" 2>/dev/null || true
  wait "$_virtual_display_pid" 2>/dev/null || true
  _virtual_display_pid=""
  unset DISPLAY
}
