#!/usr/bin/env bash
# Builds ReliefKit against MeshLab 2022.02 (the FilterPlugin API: common/meshlab2022) inside the
# Debian 13 root of scripts/meshlab2022-root.sh, where MeshLab 2022.02 is installed. The source
# tree is seen in the root at /src/reliefkit-<hash> (a bind mount for the build's time); the build goes
# to build-2022/ with its private prefix build-2022/prefix (MeshLab 2022.02's binary and plugins,
# ours added), so nothing is written into the root's MeshLab. Needs root (chroot, mount).
#   scripts/build-2022.sh [cmake --build arguments]
#   CCACHE_DISABLE=1 scripts/build-2022.sh      (a cold build's time: the compiler cache not used)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="$(bash "$here/scripts/meshlab2022-root.sh")"
source "$here/scripts/chroot-mounts.sh"
with_root_mounts "$root" "$here"
chroot "$root" env HOME=/root CCACHE_DIR=/root/.cache/ccache ${CCACHE_DISABLE:+CCACHE_DISABLE=$CCACHE_DISABLE} bash -c "
  set -e
  cd $tree_in_root
  cmake -S . -B build-2022 -G Ninja -DCMAKE_BUILD_TYPE=Release -DRELIEFKIT_MESHLAB_API=2022 \
    -DMESHLAB_SOURCE_DIR=/opt/meshlab-src -DRELIEFKIT_BENCHMARKS=OFF -DRELIEFKIT_TESTS=OFF > /dev/null
  cmake --build build-2022 -j\$(nproc) $*"
