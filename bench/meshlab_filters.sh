#!/usr/bin/env bash
# Every ReliefKit filter at its defaults inside the real meshlabserver, one process per filter, on
# relief tori of about 1 M and 10 M faces (build/tests/rk_make_mesh relief-torus): wall time and
# peak memory of the whole process (load + filter, no save), next to a baseline process that only
# loads the mesh and runs MeshLab's "Select None". Figures for docs/reliability.md.
#   bench/meshlab_filters.sh [faces ...]      (default: 1000000 10000000)
#   RELIEFKIT_BENCH_FILTERS="baseline relief_edges" bench/meshlab_filters.sh ...   (a subset)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="${RELIEFKIT_BENCH_DIR:-$here/build/bench-meshlab}"; mkdir -p "$work"
sizes=("$@"); [ ${#sizes[@]} -gt 0 ] || sizes=(1000000 10000000)
p_float() { echo "<Param type=\"RichFloat\" name=\"$1\" value=\"$2\"/>"; }
p_bool() { echo "<Param type=\"RichBool\" name=\"$1\" value=\"$2\"/>"; }
p_str() { echo "<Param type=\"RichString\" name=\"$1\" value=\"$2\"/>"; }
p_enum() { echo "<Param type=\"RichEnum\" name=\"$1\" value=\"$2\" enum_cardinality=\"$3\"/>"; }
script() {  # name, params...
  local name="$1"; shift
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="%s">\n' "$name"
  for p in "$@"; do printf '  %s\n' "$p"; done
  printf ' </filter>\n</FilterScript>\n'
}
declare -A S
S[baseline]="$(script "Select None" "$(p_bool allFaces true)" "$(p_bool allVerts true)")"
S[curvature]="$(script "Compute Curvature Tensor and Derivatives" "$(p_enum estimator 0 2)" "$(p_str presmoothing auto)" "$(p_enum quality 0 6)")"
S[demarcating]="$(script "Demarcating Curves" "$(p_float threshold 1)" "$(p_str presmoothing auto)" "$(p_float min_length 4)" "$(p_bool per_vertex true)" "$(p_bool quality false)" "$(p_float lift 0.2)")"
S[shading]="$(script "Curvature Shading" "$(p_float contrast 1)" "$(p_bool darken false)" "$(p_float darkness 0.6)" "$(p_float threshold 1)" "$(p_str presmoothing auto)")"
S[relief_edges]="$(script "Relief Edges" "$(p_str presmoothing auto)" "$(p_str base_scale auto)" "$(p_str edge_smoothing auto)" "$(p_bool restrict true)" "$(p_float strong_error 0.5)" "$(p_float weak_error 0.8)" "$(p_float strong_angle 0)" "$(p_float weak_angle 0)" "$(p_float min_length 2)" "$(p_float gap 3)" "$(p_bool per_vertex true)" "$(p_bool quality false)" "$(p_float lift 0.2)")"
S[base_normals]="$(script "Estimate Base Normals" "$(p_str base_scale auto)" "$(p_bool quality true)")"
S[ridges]="$(script "Ridges and Valleys" "$(p_float threshold 1)" "$(p_str presmoothing auto)" "$(p_float min_length 4)" "$(p_float lift 0.2)")"
printf "%-10s %-14s %10s %10s\n" faces filter "wall s" "peak MiB"
for n in "${sizes[@]}"; do
  mesh="$work/relief$n.ply"
  [ -f "$mesh" ] || "$here/build/tests/rk_make_mesh" relief-torus "$n" "$mesh" >/dev/null
  for f in ${RELIEFKIT_BENCH_FILTERS:-baseline curvature demarcating shading relief_edges base_normals ridges}; do
    echo "${S[$f]}" > "$work/$f.mlx"
    /usr/bin/time -f "%e %M" -o "$work/time.txt" "$here/scripts/meshlabserver" -i "$mesh" -s "$work/$f.mlx" \
      >"$work/$f-$n.log" 2>&1 || echo "($f failed: see $work/$f-$n.log)"
    read -r secs kib < <(tail -1 "$work/time.txt")
    printf "%-10s %-14s %10.2f %10.0f\n" "$n" "$f" "$secs" "$((kib / 1024))"
  done
done
