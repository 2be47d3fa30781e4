# Sourced: host_mirror prints the Debian mirror the host's package sources name (the roots of
# scripts/meshlab-root.sh and scripts/cold-ci.sh are fetched from the same one).
host_mirror() {
  local uri=""
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    uri="$(awk '/^URIs:/ {print $2}' /etc/apt/sources.list.d/debian.sources | grep -v -- '-security' | head -1)"
  fi
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    uri="$(awk '$1 == "deb" && $2 !~ /security/ {print $2; exit}' /etc/apt/sources.list)"
  fi
  [ -n "$uri" ] || { echo "no Debian mirror found in the host's apt sources" >&2; return 1; }
  echo "$uri"
}
