#!/usr/bin/env bash
# The same filters, inputs and parameters through MeshLab 2020.09 (build/, this machine) and each
# newer release given — 2022.02 (build-2022/, Debian 13 root) and 2025.07 (build-2025/, Debian
# testing root; scripts/meshlab-root.sh, scripts/build-release.sh): every ReliefKit filter at its
# defaults (tests/releases/run-filters.sh), then rk_compare_outputs on each filter's records and
# layers against 2020.09's. Fails on any difference of name, parameters or results.
#   tests/releases/compare-releases.sh [2022] [2025]    (default: both; after their builds)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
releases=("$@"); [ ${#releases[@]} -gt 0 ] || releases=(2022 2025)
work="$here/build/releases"   # inside the tree: the roots see it at $tree_in_root/build/releases
rm -rf "$work"; mkdir -p "$work/inputs/mesh" "$work/inputs/drawing" "$work/inputs/figure" "$work/inputs/profile" "$work/inputs/sherd" "$work/inputs/seal"
cp "$here/examples/data/penny.ply" "$work/inputs/mesh/penny.ply"  # a real scan: every filter draws curves on it
cp "$here/examples/data/nested_drawing.png" "$work/inputs/drawing/nested.png"
cp "$here/examples/data/lamp_figure.png" "$work/inputs/figure/lamp.png"
cp "$here/examples/data/jar_half_section.png" "$work/inputs/profile/jar.png"
"$here/build/tests/rk_make_mesh" sherd jar 108 0.7 1 0.1 1 "$work/inputs/sherd/rim_sherd.ply" >/dev/null  # a third of a jar's rim
"$here/build/tests/rk_make_mesh" turned cylinder 1.0 0 1 "$work/inputs/seal/seal.ply" >/dev/null  # a cylinder seal with five figures
source "$here/scripts/chroot-mounts.sh"

# The three releases run their filters side by side (each a small input at a time: one release alone
# leaves a core idle), each into its own log, printed in order once all are done.
run_release() {  # RELEASE: its filters over the inputs, into out-RELEASE
  local t0=$SECONDS
  if [ "$1" = 2020 ]; then
    bash "$here/tests/releases/run-filters.sh" "$here/build/prefix/bin/reliefkit-batch" "$work/inputs" "$work/out-2020"
  else
    chroot "${root_of[$1]}" env HOME=/root bash "$tree_in_root/tests/releases/run-filters.sh" \
      "$tree_in_root/build-$1/prefix/bin/reliefkit-batch" "$tree_in_root/build/releases/inputs" \
      "$tree_in_root/build/releases/out-$1"
  fi
  echo "MeshLab $1: $((SECONDS - t0)) s"
}
declare -A root_of pid_of
for release in "${releases[@]}"; do
  root_of[$release]="$(bash "$here/scripts/meshlab-root.sh" "$release")"
  with_root_mounts "${root_of[$release]}" "$here"
done
for release in 2020 "${releases[@]}"; do
  run_release "$release" >"$work/run-$release.log" 2>&1 &
  pid_of[$release]=$!
done
status=0
for release in 2020 "${releases[@]}"; do
  wait "${pid_of[$release]}" || { echo "FAIL: MeshLab $release's filter runs failed"; status=1; }
  cat "$work/run-$release.log"
done
for release in "${releases[@]}"; do
  batch="$tree_in_root/build-$release/prefix/bin/reliefkit-batch"
  again="$(chroot "${root_of[$release]}" env HOME=/root "$batch" --filter "Demarcating Curves" --extensions ply \
    "$tree_in_root/build/releases/inputs/mesh" "$tree_in_root/build/releases/out-$release/demarcating_curves" 2>&1)"
  echo "$again" | grep -q "1, 1 done before, 0 to do" ||
    { echo "FAIL: MeshLab $release's reliefkit-batch did not resume:"; echo "$again"; status=1; }
  for d in "$work/out-2020"/*/; do
    slug="$(basename "$d")"
    printf '%-6s %-36s ' "$release" "$slug"
    "$here/build/tests/rk_compare_outputs" "$d" "$work/out-$release/$slug" || status=1
  done
done
[ $status -eq 0 ] && echo "PASS: every filter the same on MeshLab 2020.09 and ${releases[*]}" ||
  echo "FAIL: the releases differ"
exit $status
