#!/usr/bin/env bash
# Re-makes the pictures of docs/filters-by-object.md: every curve filter at its defaults (the
# example scripts) on the bundled coin and the scans of ../shared/data, shown in the real MeshLab
# GUI under a virtual display (scripts/screenshot.sh). Output: docs/img/scan_<scan>_<what>.png.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/build/doc-pictures"; mkdir -p "$out"
shared="$here/../shared/data/meshes"
scans=("$here/examples/data/penny.ply" "$shared/fertility.obj" "$shared/stanford-bunny.obj"
       "$shared/cycladic_figurine_torso.ply" "$shared/oxhide_ingot.ply" "$shared/gargoyle.ply")
for scan in "${scans[@]}"; do
  [ -f "$scan" ] || { echo "skipping $scan (missing)"; continue; }
  if [ "${scan##*.}" = "obj" ]; then
    # MeshLab 2020.09's OBJ importer aborts on some files (fertility.obj: an assertion on the
    # face count): hand it a PLY copy.
    "$here/build/tests/rk_make_mesh" convert "$scan" "$out/$(basename "${scan%.*}").ply"
    scan="$out/$(basename "${scan%.*}").ply"
  fi
  name="$(basename "${scan%.*}")"; name="${name%%_*}"; name="${name%%-*}"
  [ "$name" = "stanford" ] && name="bunny"
  "$here/scripts/meshlabserver" -i "$scan" -o "$out/${name}_shaded.ply" -l 0 -m vc -o "$out/${name}_demarcating.obj" -l 1 \
    -s "$here/examples/demarcating_shading.mlx" >"$out/${name}_demarcating.log" 2>&1
  "$here/scripts/meshlabserver" -i "$scan" -o "$out/${name}_relief.obj" -l 1 -o "$out/${name}_ridges.obj" -l 2 \
    -o "$out/${name}_valleys.obj" -l 3 -s "$here/examples/relief_edges.mlx" >"$out/${name}_relief.log" 2>&1
  "$here/scripts/screenshot.sh" "$out/${name}_demarcating_full.png" -- "$out/${name}_shaded.ply" "$out/${name}_demarcating.obj"
  "$here/scripts/screenshot.sh" "$out/${name}_relief_full.png" -- "$out/${name}_shaded.ply" "$out/${name}_relief.obj"
  "$here/scripts/screenshot.sh" "$out/${name}_ridges_full.png" -- "$out/${name}_shaded.ply" "$out/${name}_ridges.obj" "$out/${name}_valleys.obj"
  for what in demarcating relief ridges; do
    convert "$out/${name}_${what}_full.png" -crop 700x640+75+140 +repage "$here/docs/img/scan_${name}_${what}.png"
  done
done
echo "pictures in docs/img/scan_*.png"
