# Sourced first by the netns_*.sh tests: `source netns_enter.sh "$0" "$@"`, then `shift` (the
# --inside marker). Outside, it runs the calling script again inside a private network namespace
# made here (no packet can leave it), or exits 77 (CTest SKIP_RETURN_CODE) when namespaces are not
# available. Inside, it brings the loopback up with a multicast route on it.
netns_script="$1"
shift
if [[ "${1:-}" != "--inside" ]]; then
  for way in "unshare -n" "unshare -rn"; do
    if $way true 2>/dev/null && $way bash -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo' 2>/dev/null; then
      exec $way bash "$netns_script" --inside "$@"
    fi
  done
  echo "SKIPPED: cannot create a private network namespace (unshare -n / -rn not permitted here)"
  exit 77
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
