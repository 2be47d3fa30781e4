#!/usr/bin/env bash
# Filters sharing the machine. One filter on one scan, timed
#   alone        one job, every core;
#   two jobs     two copies at once through reliefkit-batch --jobs 2 (each job its share of threads);
#   compiler     one job beside a compiler (g++ -O2 in a loop, one process per core);
#   two servers  two meshlabservers at once, each with MeshLab's own OpenMP settings (no variable
#                set: how a user's MeshLab runs the plugins), and one beside a compiler, also with
#                libgomp's default spinning (nothing parked: RELIEFKIT_OPENMP_WAITING=1 set before
#                MeshLab starts, reliefkit/base/openmp_waiting.h);
# each beside "alone" as a ratio, and the bound: 1.5 x what its share of the cores allows (half
# the cores in every case here, so at most 2 x alone for a filter that uses every core fully).
# Every case runs the filter in a process of its own, as a user's MeshLab or reliefkit-batch does;
# reliefkit-batch's cases time the file's job (reading the scan and the filter), meshlabserver's the
# whole run (MeshLab's start, its plugins, the scan and the filter), each against its own "alone".
#   bench/sharing.sh [MESH]    (default: the shared flake, else the bundled coin)
#   FILTERS="Multi-scale Relief Edges|Ridges and Valleys"  (the filters, | between them)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mesh="${1:-$here/../shared/data/meshes/lithic_flake_PGCS_Vau2.ply}"
[ -f "$mesh" ] || mesh="$here/examples/data/penny.ply"
batch="$here/build/prefix/bin/reliefkit-batch"
server="$here/build/prefix/bin/meshlabserver"
[ -x "$batch" ] || { echo "sharing.sh: build first (scripts/build.sh)" >&2; exit 1; }
IFS='|' read -r -a filters <<<"${FILTERS:-Multi-scale Relief Edges|Ridges and Valleys}"
cores="$(nproc)"
work="$(mktemp -d)"
load_pids=()
cleanup() { for p in "${load_pids[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$work"; }
trap cleanup EXIT
source "$here/scripts/virtual-display.sh"
start_virtual_display
trap 'cleanup; stop_virtual_display' EXIT
mkdir -p "$work/one" "$work/two"
ext="${mesh##*.}"
cp "$mesh" "$work/one/a.$ext"; cp "$mesh" "$work/two/a.$ext"; cp "$mesh" "$work/two/b.$ext"
printf '#include <regex>\n#include <map>\n#include <string>\nint main() { std::map<std::string, std::regex> m; m["a"] = std::regex("a+b*"); return int(m.size()); }\n' >"$work/load.cpp"

start_compiler() {  # one g++ -O2 loop per core, in the background
  for _ in $(seq "$cores"); do
    ( while :; do g++ -O2 -c "$work/load.cpp" -o /dev/null; done ) &
    load_pids+=($!)
  done
  sleep 2
}
stop_compiler() {
  for p in "${load_pids[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  load_pids=()
}

seconds_of_batch() {  # OUT: the filter's seconds of each file, from reliefkit-batch's summary
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "seconds") c = i; next } { print $c }' "$1/summary.csv"
}
run_batch() {  # FILTER DIR JOBS OUT
  rm -rf "$4"
  env -u OMP_NUM_THREADS -u OMP_WAIT_POLICY "$batch" --filter "$1" --save none --jobs "$3" "$2" "$4" >/dev/null
  seconds_of_batch "$4"
}
mlx_of() {  # FILTER: a one-filter script, the filter's block from the example scripts (every parameter listed)
  echo '<!DOCTYPE FilterScript>'; echo '<FilterScript>'
  awk -v name="$1" 'index($0, "<filter name=\"" name "\"") { on = 1 } on { print } on && /<\/filter>/ { exit }' \
    $(grep -l "filter name=\"$1\"" "$here"/examples/*.mlx | head -1)
  echo '</FilterScript>'
}
run_server() {  # MLX OUT [VAR=VALUE]: seconds of one meshlabserver run, with no OpenMP variable set but VAR
  local t0 t1
  t0="$(date +%s.%N)"
  env -u OMP_NUM_THREADS -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u RELIEFKIT_OPENMP_WAITING ${3:+"$3"} "$server" -i "$work/one/a.$ext" -s "$1" >"$2" 2>&1
  t1="$(date +%s.%N)"
  echo "$t1 - $t0" | bc -l
}
ratio() { echo "scale=2; $1 / $2" | bc -l; }

printf '%s, %s faces; %s cores; bound: 1.5 x (cores / share) = 3.0 x alone\n' "$(basename "$mesh")" \
  "$(awk '/^element face/ {print $3; exit}' "$mesh" 2>/dev/null || echo '?')" "$cores"
printf '%-28s %-34s %9s %7s\n' filter case seconds ratio
for f in "${filters[@]}"; do
  alone="$(run_batch "$f" "$work/one" 1 "$work/o1")"
  printf '%-28s %-34s %9.2f %7s\n' "$f" "alone (reliefkit-batch)" "$alone" 1.00
  for s in $(run_batch "$f" "$work/two" 2 "$work/o2"); do printf '%-28s %-34s %9.2f %7s\n' "$f" "two jobs (--jobs 2)" "$s" "$(ratio "$s" "$alone")"; done
  start_compiler
  beside="$(run_batch "$f" "$work/one" 1 "$work/o3")"
  stop_compiler
  printf '%-28s %-34s %9.2f %7s\n' "$f" "beside a compiler ($cores x g++)" "$beside" "$(ratio "$beside" "$alone")"
  if [ -x "$server" ]; then
    mlx_of "$f" >"$work/f.mlx"
    solo="$(run_server "$work/f.mlx" "$work/s0.log")"
    printf '%-28s %-34s %9.2f %7s\n' "$f" "meshlabserver alone" "$solo" 1.00
    run_server "$work/f.mlx" "$work/s1.log" >"$work/t1" & p1=$!
    run_server "$work/f.mlx" "$work/s2.log" >"$work/t2" & p2=$!
    wait $p1 $p2
    for t in "$work/t1" "$work/t2"; do
      printf '%-28s %-34s %9.2f %7s\n' "$f" "two meshlabservers side by side" "$(cat "$t")" "$(ratio "$(cat "$t")" "$solo")"
    done
    start_compiler
    beside="$(run_server "$work/f.mlx" "$work/s3.log")"
    spinning="$(run_server "$work/f.mlx" "$work/s4.log" RELIEFKIT_OPENMP_WAITING=1)"
    stop_compiler
    printf '%-28s %-34s %9.2f %7s\n' "$f" "meshlabserver beside a compiler" "$beside" "$(ratio "$beside" "$solo")"
    printf '%-28s %-34s %9.2f %7s\n' "$f" "  the same, nothing parked" "$spinning" "$(ratio "$spinning" "$solo")"
  fi
done
