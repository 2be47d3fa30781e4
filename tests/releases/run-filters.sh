#!/usr/bin/env bash
# Every ReliefKit filter at its defaults through one reliefkit-batch, each over the inputs it takes
# (tests/releases/compare-releases.sh runs this once per MeshLab release, on the same inputs).
#   run-filters.sh BATCH INPUTS OUTPUT
set -uo pipefail
batch="$1"; inputs="$2"; out="$3"
rm -rf "$out"; mkdir -p "$out"
export OMP_WAIT_POLICY=PASSIVE
status=0
run() {  # slug, input folder, extensions, filter (or --script FILE.mlx), extra arguments
  local slug="$1" folder="$2" ext="$3" filter="$4"; shift 4
  local recipe=(--filter "$filter")
  [ "$filter" = --script ] && { recipe=(--script "$1"); shift; }
  "$batch" "${recipe[@]}" --extensions "$ext" "$@" "$inputs/$folder" "$out/$slug" > "$out/$slug.log" 2>&1
  local rc=$?
  [ $rc -le 1 ] || { echo "reliefkit-batch failed ($rc) for $filter:"; tail -5 "$out/$slug.log"; status=1; }
}
for f in "Compute Curvature Tensor and Derivatives" "Demarcating Curves" "Curvature Shading" "Relief Edges" \
         "Estimate Base Normals" "Ridges and Valleys" "Compute Optimal Scale" "Optimally Smoothed Surface" \
         "Multi-scale Ridges and Valleys" "Multi-scale Relief Edges" "Prominent Field" "Prominent Enhancement" \
         "Prominent Coloring"; do
  run "$(echo "$f" | tr ' A-Z' '_a-z')" mesh ply "$f"
done
run line_drawing_to_curves drawing png "Line Drawing to Curves" --param "drawing={input}"
run relief_from_line_drawing drawing png "Relief from Line Drawing" --param "drawing={input}"
run base_from_drawing_silhouette figure png "Base from Drawing Silhouette" --param "drawing={input}"
run vessel_from_profile_drawing profile png "Vessel from Profile Drawing" --param "drawing={input}"
# The illustration plate (files, not layers): the example script — Demarcating Curves, Prominent
# Coloring, Export Illustration Plate (its SVG in each file's outputs folder).
run illustration_plate mesh ply --script "$(dirname "${BASH_SOURCE[0]}")/../../examples/illustration_plate.mlx"
# Pottery: a synthetic rim sherd turned onto its axis; the example script adds its pottery plate.
run vessel_axis_and_profile sherd ply "Vessel Axis and Profile"
run pottery_plate sherd ply --script "$(dirname "${BASH_SOURCE[0]}")/../../examples/pottery.mlx"
# Rollout: a synthetic cylinder seal unrolled (its rollout layer).
run unroll_around_axis seal ply "Unroll Around Axis"
exit $status
