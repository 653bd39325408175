#!/usr/bin/env bash
# Run a command inside a private network namespace made here (loopback up, a multicast route on
# it; no packet can leave), with TDO_TEST_UDPM_URL set to a udpm:// URL for it. Exit 77 (CTest
# SKIP_RETURN_CODE) when namespaces are not available.
#
#   netns_run.sh COMMAND [ARGS...]
set -euo pipefail
if [[ "${1:-}" != "--inside" ]]; then
  for way in "unshare -n" "unshare -rn"; do
    if $way true 2>/dev/null && $way bash -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo' 2>/dev/null; then
      exec $way bash "$0" --inside "$@"
    fi
  done
  echo "SKIPPED: cannot create a private network namespace (unshare -n / -rn not permitted here)"
  exit 77
fi
shift
ip link set lo up
ip route add 224.0.0.0/4 dev lo
# A 4 MB receive buffer: a burst of requests must not be dropped by the kernel before LCM sees it.
export TDO_TEST_UDPM_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
exec "$@"
