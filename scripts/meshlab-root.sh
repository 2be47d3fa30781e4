#!/usr/bin/env bash
# A Debian root with a newer MeshLab than Debian 12's, for building and testing ReliefKit against
# that release's plugin API: MeshLab 2022.02 in a Debian 13 (trixie) root (issue 24), MeshLab
# 2025.07 in a Debian testing (forky) root (issue 41). Debian 12 has neither, so the root is made
# with `debootstrap --variant=minbase` (forky through the sid script: Debian 12's debootstrap has
# no forky script) and MeshLab, Xvfb and the build dependencies are installed into it from that
# suite's packages. The suite's entry lives only inside the root: the host's package sources are
# not touched.
#
#   scripts/meshlab-root.sh 2022|2025      # make (or check) the root; prints its path
#   RELIEFKIT_TRIXIE_ROOT=DIR / RELIEFKIT_FORKY_ROOT=DIR   # where (default /var/cache/reliefkit/<suite>-root)
#
# The root is kept between runs (CI finds it on the next run of the same machine) and made again
# only when its recipe (suite and package list below) changes. Needs root (debootstrap, chroot).
set -euo pipefail
release="${1:-}"
# Both suites: meshlab with the libraries it recommends (some of its own plugins need them), Xvfb,
# then the build's dependencies (Qt 5 in both: Debian builds MeshLab 2025.07 with Qt 5.15).
PKGS=(meshlab lib3ds-1-3 libmuparser2v5 libopenctm1 libqhull-r8.0 libxerces-c3.2t64
      xvfb xauth build-essential cmake ninja-build pkg-config dpkg-dev ccache
      qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev libqt5svg5-dev
      libglew-dev libglu1-mesa-dev libeigen3-dev libsuitesparse-dev libopenblas0-pthread libopencv-dev
      nlohmann-json3-dev libgtest-dev libgmock-dev)
case "$release" in
  2022) suite=trixie; script=trixie; name="Debian 13"; root="${RELIEFKIT_TRIXIE_ROOT:-/var/cache/reliefkit/trixie-root}" ;;
  2025) suite=forky; script=/usr/share/debootstrap/scripts/sid; name="Debian testing (forky)"
        root="${RELIEFKIT_FORKY_ROOT:-/var/cache/reliefkit/forky-root}" ;;
  *) echo "usage: scripts/meshlab-root.sh 2022|2025 (MeshLab 2022.02 in Debian 13, 2025.07 in Debian testing)" >&2; exit 2 ;;
esac
me="meshlab-root.sh $release"
recipe="$(printf '%s\n' "$suite minbase" "${PKGS[@]}" | sha256sum | cut -c1-16)"

root_ready() { [ -f "$root/.reliefkit-recipe" ] && [ "$(cat "$root/.reliefkit-recipe")" = "$recipe" ]; }
if root_ready; then
  echo "$root"
  exit 0
fi
[ "$(id -u)" -eq 0 ] || { echo "$me: making the $name root needs root (debootstrap, chroot)" >&2; exit 1; }
# One maker per root: a second run (another CI on the same machine) waits for the first, then finds
# the root ready.
mkdir -p "$(dirname "$root")"
exec 9>"$root.lock"
flock 9
if root_ready; then
  echo "$root"
  exit 0
fi

source "$(dirname "${BASH_SOURCE[0]}")/debian-mirror.sh"

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
make_root() {  # anything a killed run left mounted inside is let go first: /dev is the host's own
  awk -v r="$root/" 'index($2, r) == 1 { print $2 }' /proc/mounts | sort -r | xargs -r -n1 umount -l
  rm -rf --one-file-system "$root"
  echo "$me: debootstrap --variant=minbase $suite $root" >&2
  debootstrap --variant=minbase "$suite" "$root" "$mirror" "$script" > "$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log" >&2; echo "$me: debootstrap failed (log: $root.debootstrap.log)" >&2; exit 1; }
}
# The root's own package sources (with deb-src, for `apt-get source meshlab`), the host's apt
# settings (a frozen mirror's expired Release files accepted as on the host) and name resolution.
write_apt_settings() {
  cat > "$root/etc/apt/sources.list.d/debian.sources" <<SOURCES
Types: deb deb-src
URIs: $mirror
Suites: $suite
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
  rm -f "$root/etc/apt/sources.list"
  cp /etc/apt/apt.conf.d/* "$root/etc/apt/apt.conf.d/" 2>/dev/null || true
  cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
}
[ -x "$root/usr/bin/apt-get" ] && [ -d "$root/etc/apt/sources.list.d" ] || make_root
write_apt_settings
mount_system
# A root whose making was stopped (a killed run) has dpkg's work half done: it is finished first
# (`dpkg --configure -a`, then apt's own repair); a root that still cannot install is made anew once.
install_packages() {
  chroot "$root" env DEBIAN_FRONTEND=noninteractive dpkg --configure -a &&
    chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get update -qq &&
    chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -f --no-install-recommends &&
    chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${PKGS[@]}"
} > "$root.install.log" 2>&1
if ! install_packages; then
  tail -5 "$root.install.log" >&2
  echo "$me: the root could not install its packages; making it anew" >&2
  unmount_all; mounted=()
  make_root
  write_apt_settings
  mount_system
  install_packages ||
    { tail -20 "$root.install.log" >&2; echo "$me: installing into the root failed (log: $root.install.log)" >&2; exit 1; }
fi
# MeshLab's sources (its plugin API headers and vcglib): the upstream tarball of the suite's source
# package (apt checks it against the signed index; only the tarball is fetched).
version="$(chroot "$root" dpkg-query -W -f='${Version}' meshlab)"
case "$version" in "$release".*) ;; *) echo "$me: $suite has meshlab $version, not $release.*" >&2; exit 1 ;; esac
rm -rf "$root/opt/meshlab-src" "$root/opt/apt-source"; mkdir -p "$root/opt/apt-source" "$root/opt/meshlab-src"
chroot "$root" sh -c "cd /opt/apt-source && apt-get source -qq --tar-only 'meshlab=$version' > /dev/null 2>&1" ||
  { echo "$me: 'apt-get source --tar-only meshlab=$version' failed inside the root" >&2; exit 1; }
tar -xf "$root"/opt/apt-source/meshlab_*.orig.tar.* -C "$root/opt/meshlab-src" --strip-components=1
rm -rf "$root/opt/apt-source"
echo "$version" > "$root/opt/meshlab-src/.debian-version"
[ -f "$root/opt/meshlab-src/src/common/plugins/interfaces/filter_plugin.h" ] ||
  { echo "$me: the MeshLab sources in the root have no filter_plugin.h (not the FilterPlugin API?)" >&2; exit 1; }
chroot "$root" apt-get clean
echo "$recipe" > "$root/.reliefkit-recipe"
echo "$me: $name root ready in $((SECONDS - t0)) s (meshlab $version)" >&2
echo "$root"
