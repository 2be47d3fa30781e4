#!/usr/bin/env bash
# Builds ReliefKit against a newer MeshLab's FilterPlugin API (common/meshlab_filterplugin) inside
# the Debian root of scripts/meshlab-root.sh where that MeshLab is installed: 2022.02 (Debian 13)
# or 2025.07 (Debian testing). The source tree is seen in the root at /src/reliefkit-<hash> (a
# bind mount for the build's time); the build goes to build-<release>/ with its private prefix
# build-<release>/prefix (that MeshLab's binary and plugins, ours added), so nothing is written into
# the root's MeshLab. Needs root (chroot, mount).
#   scripts/build-release.sh 2022|2025 [cmake --build arguments]
#   CCACHE_DISABLE=1 scripts/build-release.sh 2025   (a cold build's time: the compiler cache not used)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
release="${1:-}"
case "$release" in 2022|2025) shift ;; *) echo "usage: scripts/build-release.sh 2022|2025 [cmake --build arguments]" >&2; exit 2 ;; esac
root="$(bash "$here/scripts/meshlab-root.sh" "$release")"
source "$here/scripts/chroot-mounts.sh"
with_root_mounts "$root" "$here"
chroot "$root" env HOME=/root CCACHE_DIR=/root/.cache/ccache ${CCACHE_DISABLE:+CCACHE_DISABLE=$CCACHE_DISABLE} bash -c "
  set -e
  cd $tree_in_root
  cmake -S . -B build-$release -G Ninja -DCMAKE_BUILD_TYPE=Release -DRELIEFKIT_MESHLAB_API=$release \
    -DMESHLAB_SOURCE_DIR=/opt/meshlab-src -DRELIEFKIT_BENCHMARKS=OFF -DRELIEFKIT_TESTS=OFF \
    -DCMAKE_UNITY_BUILD=${RELIEFKIT_UNITY:-OFF} > /dev/null
  cmake --build build-$release -j\$(nproc) $*"
