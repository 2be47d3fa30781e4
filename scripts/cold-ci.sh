#!/usr/bin/env bash
# CI as a new machine runs it: a bare Debian 12 root (debootstrap --variant=minbase: no compiler,
# no MeshLab, no compiler cache, no MeshLab 2022.02/2025.07 roots), a fresh clone of COMMIT in it
# with a read-only copy of shared/ beside it, then `CI=true bash .ci/run` there. Prints CI's own
# stage table and the wall time. Needs root (debootstrap, chroot, mount); the root is made anew.
# With --warm, the root of an earlier run is kept (its packages, compiler cache and MeshLab roots:
# a developer's machine, CI's next run) and only the clone is new.
#   scripts/cold-ci.sh [--warm] [COMMIT] [ROOT]      (default: HEAD, /var/tmp/reliefkit-cold-ci)
#   RELIEFKIT_SHARED=DIR                    (default: ../shared beside this clone)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
warm=false; [ "${1:-}" = --warm ] && { warm=true; shift; }
commit="$(git -C "$here" rev-parse "${1:-HEAD}")"
root="${2:-/var/tmp/reliefkit-cold-ci}"
shared="${RELIEFKIT_SHARED:-$here/../shared}"
[ "$(id -u)" -eq 0 ] || { echo "cold-ci.sh: needs root (debootstrap, chroot, mount)" >&2; exit 1; }
[ -d "$shared" ] || { echo "cold-ci.sh: no shared/ at $shared (set RELIEFKIT_SHARED)" >&2; exit 1; }
source "$here/scripts/debian-mirror.sh"

mounts=()
unmount_all() {
  for ((k = ${#mounts[@]} - 1; k >= 0; k--)); do umount -R -l "${mounts[k]}" 2>/dev/null || true; done
}
trap unmount_all EXIT
bind() {  # SOURCE TARGET [ro]
  mkdir -p "$2"
  mount --rbind "$1" "$2"
  mounts+=("$2")
  [ "${3:-}" != ro ] || mount -o remount,bind,ro "$2"
}

command -v debootstrap >/dev/null || apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
umount -R -l "$root"/{proc,sys,dev,ci/shared} 2>/dev/null || true
# Nothing of the host may still be mounted inside the old root when it is removed.
! awk '{print $2}' /proc/mounts | grep -q "^$root/" ||
  { echo "cold-ci.sh: mounts left under $root (see /proc/mounts): unmount them first" >&2; exit 1; }
if $warm && [ -x "$root/usr/bin/apt-get" ]; then
  echo "cold-ci.sh: the root of the last run in $root, kept (--warm); a fresh clone"
  rm -rf "$root/ci/main"
else
  rm -rf "$root"
  echo "cold-ci.sh: a bare Debian 12 root in $root"
  debootstrap --variant=minbase bookworm "$root" "$(host_mirror)" >"$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log" >&2; exit 1; }
  cp /etc/apt/apt.conf.d/* "$root/etc/apt/apt.conf.d/" 2>/dev/null || true
  cp -L /etc/resolv.conf "$root/etc/resolv.conf"
fi
git clone -q "$here" "$root/ci/main"
git -C "$root/ci/main" checkout -q "$commit"
mkdir -p "$root/proc" "$root/sys"
mount -t proc proc "$root/proc"; mounts+=("$root/proc")
mount -t sysfs sys "$root/sys"; mounts+=("$root/sys")
bind /dev "$root/dev"
bind "$(cd "$shared" && pwd)" "$root/ci/shared" ro

echo "cold-ci.sh: CI=true bash .ci/run on $commit (a fresh clone in the bare root)"
t0=$SECONDS
status=0
chroot "$root" env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root CI=true \
  LANG=C.UTF-8 bash -c 'cd /ci/main && bash .ci/run' >"$root.ci.log" 2>&1 || status=$?
sed -n '/== time per stage ==/,$p' "$root.ci.log"
echo "cold-ci.sh: .ci/run exited $status after $((SECONDS - t0)) s (log: $root.ci.log)"
exit "$status"
