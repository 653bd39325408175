#!/usr/bin/env bash
# Clean shutdown: start tdo-planner on memq:// (no network), send SIGNAL, expect exit status 0 and
# its "stopped" line, within a few seconds.   signal_stop.sh TDO_PLANNER SIGNAL
set -euo pipefail
exe="$1"
sig="$2"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$exe" --lcm-url memq:// --max-size 16 16 8 --max-nodes 10000 2>"$log" &
pid=$!
# Wait until it is serving (its start line), at most 10 s.
for _ in $(seq 100); do
  grep -q "tdo-planner: vehicle" "$log" && break
  sleep 0.1
done
kill "-$sig" "$pid"
rc=0
# A planner that ignores the signal is killed by the test's timeout rather than waited for forever.
timeout 10 tail --pid="$pid" -f /dev/null || { kill -KILL "$pid"; echo "did not stop on $sig"; exit 1; }
wait "$pid" || rc=$?
cat "$log"
if [[ $rc -ne 0 ]]; then
  echo "exit status $rc after SIG$sig, expected 0"
  exit 1
fi
grep -q "tdo-planner: stopped:" "$log" || { echo "no 'stopped' line"; exit 1; }
echo "stopped cleanly on SIG$sig"
