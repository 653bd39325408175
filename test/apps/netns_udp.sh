#!/usr/bin/env bash
# Multi-process end to end over real UDP multicast, inside a private network namespace made here
# (no packet can leave it): tdo-planner, tdo-publish-map (Map6), lcm-logger and a Python client
# (the wheel's bindings + the generated types) as separate processes; then tdo-replay checks the
# log lcm-logger recorded. Exit 77 (CTest SKIP_RETURN_CODE) when namespaces are not available.
#
#   netns_udp.sh TDO_PLANNER TDO_PUBLISH_MAP TDO_REPLAY VENV_PYTHON LCM_LOGGER PYDIR MAP SCRATCH
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/netns_enter.sh" "$0" "$@"
shift
planner="$1" publish_map="$2" replay="$3" python="$4" logger="$5" pydir="$6" map="$7" scratch="$8"

# Answers carry thousands of samples (~270 kB): a receive buffer of 4 MB (the kernel's rmem_max
# here) or UDP drops fragments under load (docs/design.md s.11).
url="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
mkdir -p "$scratch"
log="$scratch/udp_run.lcmlog"
rm -f "$log"
pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

"$logger" --lcm-url="$url" --quiet --force "$log" &
pids+=($!)
"$planner" --lcm-url "$url" --heartbeat 0.2 --max-size 64 64 32 --duration 120 \
  2>"$scratch/planner.err" &
planner_pid=$!
pids+=($planner_pid)

rc=0
"$python" "$(dirname "$0")/udp_client.py" "$url" "$pydir" "$publish_map" "$map" || rc=$?

kill -TERM "$planner_pid"
wait "$planner_pid" || { echo "tdo-planner exit status $?"; rc=1; }
sleep 0.3  # lcm-logger receives the last heartbeat
kill -INT "${pids[0]}"
wait "${pids[0]}" || true
cat "$scratch/planner.err"
grep -q "tdo-planner: stopped:" "$scratch/planner.err" || { echo "FAILED: no clean stop"; rc=1; }
[[ $rc -eq 0 ]] || exit "$rc"

# The log lcm-logger recorded from the live run replays in-process with identical answers.
"$replay" "$log" --max-size 64 64 32 || { echo "FAILED: tdo-replay on the UDP log"; exit 1; }
echo "udp multicast end to end ok (namespace $(readlink /proc/self/ns/net))"
