# Sourced: with_root_mounts ROOT SOURCE_TREE — /proc, /dev and /dev/pts of the host and the source
# tree mounted in the Debian root (scripts/meshlab-root.sh) until the calling script exits. The tree is seen in the root
# at $tree_in_root, /src/reliefkit-<hash of its path>: two clones (a developer's and CI's) can use
# the root at once.
_rk_mounts=()
_rk_unmount() {
  for ((k = ${#_rk_mounts[@]} - 1; k >= 0; k--)); do umount -l "${_rk_mounts[k]}" 2>/dev/null || true; done
}
with_root_mounts() {
  local root="$1" tree="$2"
  tree_in_root="/src/reliefkit-$(printf '%s' "$(cd "$tree" && pwd)" | md5sum | cut -c1-10)"
  trap _rk_unmount EXIT
  mkdir -p "$root/proc" "$root/dev" "$root$tree_in_root" "$root/tmp"
  mountpoint -q "$root/proc" || { mount -t proc proc "$root/proc" && _rk_mounts+=("$root/proc"); }
  mountpoint -q "$root/dev" || { mount --bind /dev "$root/dev" && _rk_mounts+=("$root/dev"); }
  mountpoint -q "$root/dev/pts" || { mount --bind /dev/pts "$root/dev/pts" && _rk_mounts+=("$root/dev/pts"); }
  mountpoint -q "$root$tree_in_root" || { mount --bind "$tree" "$root$tree_in_root" && _rk_mounts+=("$root$tree_in_root"); }
}
