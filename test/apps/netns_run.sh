#!/usr/bin/env bash
# Run a command inside a private network namespace made here (loopback up, a multicast route on
# it; no packet can leave), with TDO_TEST_UDPM_URL set to a udpm:// URL for it. Exit 77 (CTest
# SKIP_RETURN_CODE) when namespaces are not available.
#
#   netns_run.sh COMMAND [ARGS...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/netns_enter.sh" "$0" "$@"
shift
# A 4 MB receive buffer: a burst of requests must not be dropped by the kernel before LCM sees it.
export TDO_TEST_UDPM_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
exec "$@"
