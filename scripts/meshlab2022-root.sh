#!/usr/bin/env bash
# A Debian 13 (trixie) root with MeshLab 2022.02, for building and testing ReliefKit against the
# 2022.02 plugin API (issue 24). Debian 12 does not have MeshLab 2022.02; Debian 13 does, so the
# root is made with `debootstrap --variant=minbase trixie` and MeshLab, Xvfb and the build
# dependencies are installed into it from Debian 13's packages. The trixie entry lives only inside
# the root: the host's package sources are not touched.
#
#   scripts/meshlab2022-root.sh            # make (or check) the root; prints its path
#   RELIEFKIT_TRIXIE_ROOT=DIR ...          # where (default /var/cache/reliefkit/trixie-root)
#
# The root is kept between runs (CI finds it on the next run of the same machine) and made again
# only when its recipe (the package list below) changes. Needs root (debootstrap, chroot).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="${RELIEFKIT_TRIXIE_ROOT:-/var/cache/reliefkit/trixie-root}"

# meshlab with the libraries it recommends (some of its own plugins need them), then the build's.
PKGS=(meshlab lib3ds-1-3 libmuparser2v5 libopenctm1 libqhull-r8.0 libxerces-c3.2t64
      xvfb xauth build-essential cmake ninja-build pkg-config dpkg-dev ccache
      qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev libqt5svg5-dev
      libglew-dev libglu1-mesa-dev libeigen3-dev libsuitesparse-dev libopenblas0-pthread libopencv-dev
      nlohmann-json3-dev libgtest-dev libgmock-dev)
recipe="$(printf '%s\n' "trixie minbase" "${PKGS[@]}" | sha256sum | cut -c1-16)"

if [ -f "$root/.reliefkit-recipe" ] && [ "$(cat "$root/.reliefkit-recipe")" = "$recipe" ]; then
  echo "$root"
  exit 0
fi
[ "$(id -u)" -eq 0 ] || { echo "meshlab2022-root.sh: making the Debian 13 root needs root (debootstrap, chroot)" >&2; exit 1; }

# The host's Debian mirror (its package sources name it): the root is fetched from the same one.
host_mirror() {
  local uri=""
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    uri="$(awk '/^URIs:/ {print $2}' /etc/apt/sources.list.d/debian.sources | grep -v -- '-security' | head -1)"
  fi
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    uri="$(awk '$1 == "deb" && $2 !~ /security/ {print $2; exit}' /etc/apt/sources.list)"
  fi
  [ -n "$uri" ] || { echo "meshlab2022-root.sh: no Debian mirror found in the host's apt sources" >&2; exit 1; }
  echo "$uri"
}

mounted=()
unmount_all() {
  for ((k = ${#mounted[@]} - 1; k >= 0; k--)); do umount -l "${mounted[k]}" 2>/dev/null || true; done
}
trap unmount_all EXIT
mount_system() {  # /proc, /sys and /dev of the host inside the root, for the packages' scripts
  for d in proc sys dev dev/pts; do
    mountpoint -q "$root/$d" && continue
    mkdir -p "$root/$d"
    case "$d" in
      proc) mount -t proc proc "$root/proc" ;;
      sys) mount -t sysfs sys "$root/sys" ;;
      *) mount --bind "/$d" "$root/$d" ;;
    esac
    mounted+=("$root/$d")
  done
}

if ! command -v debootstrap >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap >/dev/null ||
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap >/dev/null; }
fi
mirror="$(host_mirror)"
t0=$SECONDS
if [ ! -x "$root/usr/bin/apt-get" ]; then
  rm -rf "$root"; mkdir -p "$(dirname "$root")"
  echo "meshlab2022-root.sh: debootstrap --variant=minbase trixie $root"
  debootstrap --variant=minbase trixie "$root" "$mirror" > "$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log" >&2; echo "meshlab2022-root.sh: debootstrap failed (log: $root.debootstrap.log)" >&2; exit 1; }
fi
# The root's own package sources (with deb-src, for `apt-get source meshlab`), the host's apt
# settings and name resolution.
cat > "$root/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb deb-src
URIs: $mirror
Suites: trixie
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
rm -f "$root/etc/apt/sources.list"
cp /etc/apt/apt.conf.d/* "$root/etc/apt/apt.conf.d/" 2>/dev/null || true
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
mount_system
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${PKGS[@]}" > "$root.install.log" 2>&1 ||
  { tail -20 "$root.install.log" >&2; echo "meshlab2022-root.sh: installing into the root failed (log: $root.install.log)" >&2; exit 1; }
# MeshLab 2022.02's sources (its plugin API headers and vcglib): the upstream tarball of Debian
# 13's source package (apt checks it against the signed index; only the tarball is fetched).
version="$(chroot "$root" dpkg-query -W -f='${Version}' meshlab)"
rm -rf "$root/opt/meshlab-src" "$root/opt/apt-source"; mkdir -p "$root/opt/apt-source" "$root/opt/meshlab-src"
chroot "$root" sh -c "cd /opt/apt-source && apt-get source -qq --tar-only 'meshlab=$version' > /dev/null 2>&1" ||
  { echo "meshlab2022-root.sh: 'apt-get source --tar-only meshlab=$version' failed inside the root" >&2; exit 1; }
tar -xf "$root"/opt/apt-source/meshlab_*.orig.tar.* -C "$root/opt/meshlab-src" --strip-components=1
rm -rf "$root/opt/apt-source"
echo "$version" > "$root/opt/meshlab-src/.debian-version"
[ -f "$root/opt/meshlab-src/src/common/plugins/interfaces/filter_plugin.h" ] ||
  { echo "meshlab2022-root.sh: the MeshLab sources in the root have no filter_plugin.h (not the 2022.02 API?)" >&2; exit 1; }
chroot "$root" apt-get clean
echo "$recipe" > "$root/.reliefkit-recipe"
echo "meshlab2022-root.sh: Debian 13 root ready in $((SECONDS - t0)) s (meshlab $version)" >&2
echo "$root"
