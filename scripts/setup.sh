#!/usr/bin/env bash
# ReliefKit set-up: installs every build/test dependency from Debian's packages and brings
# MeshLab 2020.09's sources (the headers and vcglib our plugins compile against) into
# third_party/meshlab-src (git-ignored). Idempotent: a second run does nothing it need not.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
src_root="$here/third_party"
stamp="$src_root/.setup-done"

# Root runs apt-get directly; another user goes through sudo.
SUDO=""
need_root() {
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup.sh: installing packages needs root; run as root or install sudo" >&2; exit 1; }
    SUDO="sudo"
  fi
}

PKGS=(meshlab build-essential cmake ninja-build ccache pkg-config dpkg-dev
      qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev qtdeclarative5-dev libqt5svg5-dev
      libglew-dev libglu1-mesa-dev libeigen3-dev libsuitesparse-dev libopenblas0-pthread libopencv-dev nlohmann-json3-dev libcgal-dev libgmp-dev libmpfr-dev
      libgtest-dev libgmock-dev xvfb xauth x11-utils xdotool imagemagick time
      clang libclang-rt-14-dev libomp-14-dev
      slurm-wlm munge parallel debootstrap librsvg2-bin poppler-utils
      git python3 procps)  # the tests' source-tree check, the function-length check, pgrep/pkill

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ] || [ ! -f "$stamp" ]; then
  need_root
  # deb-src entries, so that `apt-get source meshlab` finds the source package.
  if [ -f /etc/apt/sources.list.d/debian.sources ] && ! grep -q 'deb-src' /etc/apt/sources.list.d/debian.sources; then
    $SUDO sed -i 's/^Types: deb$/Types: deb deb-src/' /etc/apt/sources.list.d/debian.sources
  fi
  if [ -f /etc/apt/sources.list ] && grep -q '^deb ' /etc/apt/sources.list && ! grep -q '^deb-src ' /etc/apt/sources.list; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list | $SUDO tee -a /etc/apt/sources.list >/dev/null
  fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup.sh: installing ${missing[*]}"
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi

installed="$(dpkg-query -W -f='${Version}' meshlab)"
upstream="${installed%%-*}"; upstream="${upstream#*:}"
srcdir="$src_root/meshlab-src"
if [ -f "$srcdir/.debian-version" ] && [ "$(cat "$srcdir/.debian-version")" = "$installed" ]; then
  :
else
  rm -rf "$src_root/apt-source" "$srcdir"; mkdir -p "$src_root/apt-source"
  ( cd "$src_root/apt-source" && apt-get source -qq "meshlab=$installed" >/dev/null 2>&1 ) || {
    echo "setup.sh: ERROR: 'apt-get source meshlab=$installed' failed." >&2
    echo "  The installed meshlab is $installed; its source package must be the same version." >&2
    echo "  Check that a deb-src entry for the same suite exists and run 'apt-get update'." >&2
    exit 1; }
  d="$(find "$src_root/apt-source" -maxdepth 1 -mindepth 1 -type d -name 'meshlab-*' | head -1)"
  srcver="$(cd "$d" && dpkg-parsechangelog -S Version)"
  if [ "$srcver" != "$installed" ]; then
    echo "setup.sh: ERROR: MeshLab source version $srcver differs from installed meshlab $installed." >&2
    echo "  Plugins must be compiled against the exact headers of the MeshLab that loads them." >&2
    exit 1
  fi
  mv "$d" "$srcdir"; rm -rf "$src_root/apt-source"
  echo "$installed" > "$srcdir/.debian-version"
fi
for f in "$srcdir/src/common/interfaces.h" "$srcdir/vcglib/vcg/complex/complex.h"; do
  [ -f "$f" ] || { echo "setup.sh: ERROR: $f missing in MeshLab sources ($srcdir)" >&2; exit 1; }
done
touch "$stamp"
echo "setup.sh: ready (meshlab $installed, sources in ${srcdir#$here/})"
