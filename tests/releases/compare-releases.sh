#!/usr/bin/env bash
# The same filters, inputs and parameters through MeshLab 2020.09 (build/, this machine) and
# MeshLab 2022.02 (build-2022/, in the Debian 13 root of scripts/meshlab2022-root.sh): every
# ReliefKit filter at its defaults (tests/releases/run-filters.sh), then rk_compare_outputs on
# each filter's records and layers. Fails on any difference of name, parameters or results.
#   tests/releases/compare-releases.sh          (after scripts/build.sh and scripts/build-2022.sh)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
work="$here/build/releases"   # inside the tree: the root sees it at $tree_in_root/build/releases
rm -rf "$work"; mkdir -p "$work/inputs/mesh" "$work/inputs/drawing" "$work/inputs/figure" "$work/inputs/profile"
cp "$here/examples/data/penny.ply" "$work/inputs/mesh/penny.ply"  # a real scan: every filter draws curves on it
cp "$here/examples/data/nested_drawing.png" "$work/inputs/drawing/nested.png"
cp "$here/examples/data/lamp_figure.png" "$work/inputs/figure/lamp.png"
cp "$here/examples/data/jar_half_section.png" "$work/inputs/profile/jar.png"

t0=$SECONDS
bash "$here/tests/releases/run-filters.sh" "$here/build/prefix/bin/reliefkit-batch" "$work/inputs" "$work/out-2020"
t1=$SECONDS
root="$(bash "$here/scripts/meshlab2022-root.sh")"
source "$here/scripts/chroot-mounts.sh"
with_root_mounts "$root" "$here"
chroot "$root" env HOME=/root bash $tree_in_root/tests/releases/run-filters.sh \
  $tree_in_root/build-2022/prefix/bin/reliefkit-batch $tree_in_root/build/releases/inputs $tree_in_root/build/releases/out-2022
t2=$SECONDS
echo "MeshLab 2020.09: $((t1 - t0)) s, MeshLab 2022.02: $((t2 - t1)) s"
# reliefkit-batch of 2022.02 resumes too: run again over the same output, nothing is left to do.
again="$(chroot "$root" env HOME=/root $tree_in_root/build-2022/prefix/bin/reliefkit-batch --filter "Demarcating Curves" \
  --extensions ply $tree_in_root/build/releases/inputs/mesh $tree_in_root/build/releases/out-2022/demarcating_curves 2>&1)"
echo "$again" | grep -q "1, 1 done before, 0 to do" || { echo "FAIL: MeshLab 2022.02's reliefkit-batch did not resume:"; echo "$again"; exit 1; }
status=0
for d in "$work/out-2020"/*/; do
  slug="$(basename "$d")"
  printf '%-36s ' "$slug"
  "$here/build/tests/rk_compare_outputs" "$d" "$work/out-2022/$slug" || status=1
done
[ $status -eq 0 ] && echo "PASS: every filter the same on MeshLab 2020.09 and 2022.02" || echo "FAIL: the releases differ"
exit $status
