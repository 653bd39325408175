#!/usr/bin/env bash
# Clean shutdown of an LCM program: start it on memq:// (no network), wait for its start line,
# send SIGNAL, expect exit status 0 and its "stopped" line within a few seconds.
#   signal_stop_app.sh NAME EXE SIGNAL [ARGS...]     e.g. NAME = tdo-avoid
set -euo pipefail
name="$1"
exe="$2"
sig="$3"
shift 3
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$exe" "$@" 2>"$log" &
pid=$!
# Wait until it is serving (its start line "NAME: vehicle ..."), at most 10 s.
for _ in $(seq 100); do
  grep -q "$name: vehicle" "$log" && break
  sleep 0.1
done
grep -q "$name: vehicle" "$log" || { cat "$log"; kill -KILL "$pid"; echo "never started"; exit 1; }
kill "-$sig" "$pid"
rc=0
# A program that ignores the signal is killed rather than waited for forever.
timeout 10 tail --pid="$pid" -f /dev/null || { kill -KILL "$pid"; echo "did not stop on $sig"; exit 1; }
wait "$pid" || rc=$?
cat "$log"
if [[ $rc -ne 0 ]]; then
  echo "exit status $rc after SIG$sig, expected 0"
  exit 1
fi
grep -q "$name: stopped:" "$log" || { echo "no 'stopped' line"; exit 1; }
echo "stopped cleanly on SIG$sig"
