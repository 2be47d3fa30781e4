#!/usr/bin/env bash
# Builds a private MeshLab prefix that loads ReliefKit's freshly built plugins without
# installing anything: <prefix>/bin/{meshlab,meshlabserver} are copies of the system binaries
# (MeshLab looks for plugins in <binary dir>/../lib/x86_64-linux-gnu/meshlab/plugins), and the
# plugin folder links the system plugins plus ours.
# Usage: make-prefix.sh PREFIX PLUGIN_BUILD_DIR [SYSTEM_MESHLAB_DIR]
set -euo pipefail
prefix="$1"; ours="$2"; sys="${3:-/usr/lib/x86_64-linux-gnu/meshlab}"
libdir="$prefix/lib/x86_64-linux-gnu/meshlab"
mkdir -p "$prefix/bin" "$libdir/plugins"
[ -x /usr/bin/meshlab ] || { echo "make-prefix: /usr/bin/meshlab missing (install the meshlab package: scripts/setup.sh)" >&2; exit 1; }
for b in meshlab meshlabserver; do  # MeshLab 2022.02 has no meshlabserver
  [ -x "/usr/bin/$b" ] || continue
  cmp -s "/usr/bin/$b" "$prefix/bin/$b" || cp -f "/usr/bin/$b" "$prefix/bin/$b"
done
ln -sfn "$sys/libmeshlab-common.so" "$libdir/libmeshlab-common.so"
find "$libdir/plugins" -maxdepth 1 -type l -delete
for p in "$sys"/plugins/*.so; do ln -sfn "$p" "$libdir/plugins/$(basename "$p")"; done
for p in "$ours"/*.so; do [ -e "$p" ] && ln -sfn "$(readlink -f "$p")" "$libdir/plugins/$(basename "$p")"; done
# The base-model library the build made (build/bases), where the plugin looks for it: <bin>/../share.
if [ -d "$ours/../bases" ]; then
  mkdir -p "$prefix/share/reliefkit"
  ln -sfn "$(readlink -f "$ours/../bases")" "$prefix/share/reliefkit/bases"
fi
exit 0
