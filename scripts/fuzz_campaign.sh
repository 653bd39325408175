#!/usr/bin/env bash
# A long libFuzzer campaign of the five fuzz targets (test/fuzz/, docs/fuzzing.md), all at the same
# time, each at nice 19 from a fresh copy of its seed corpus, and a table of the results.
#
#   bash scripts/fuzz_campaign.sh [seconds]        # default 1800 (30 minutes per target)
#
# Environment: BUILD_DIR (the TDO_FUZZ=ON clang build, default <repo>/build-clang), OUT (corpora,
# logs and crash artifacts, default /tmp/tdo-fuzz; emptied first), TARGETS (default all five),
# RSS_MB (libFuzzer's -rss_limit_mb per process, default 2048), TIMEOUT (seconds one input may
# run, default 20). Each target fuzzes $OUT/corpus/<target> (a copy of test/fuzz/corpus/<target>)
# plus the regression inputs, writes its log to $OUT/<target>.log and any crash, leak, timeout or
# out-of-memory input to $OUT/artifacts/<target>/. Exit status 0 when every target ran its full
# time with no such finding, 1 otherwise, 2 on a usage error.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-clang}"
OUT="${OUT:-/tmp/tdo-fuzz}"
TARGETS="${TARGETS:-fuzz_tdomap fuzz_3dmap fuzz_octree fuzz_lcm fuzz_replay}"
RSS_MB="${RSS_MB:-2048}"
TIMEOUT="${TIMEOUT:-20}"
seconds="${1:-1800}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || ((seconds < 1)); then
  printf 'usage: %s [seconds]\n' "$0" >&2
  exit 2
fi
for t in $TARGETS; do
  if [[ ! -x "$BUILD_DIR/test/fuzz/$t" ]]; then
    printf '%s: %s not built (configure with -DTDO_FUZZ=ON and clang, docs/fuzzing.md)\n' "$0" \
      "$BUILD_DIR/test/fuzz/$t" >&2
    exit 2
  fi
done

rm -rf "$OUT"
mkdir -p "$OUT"
printf '[fuzz] %s s per target, build %s (commit %s), output %s\n' "$seconds" "$BUILD_DIR" \
  "$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)" "$OUT"
declare -A pids
for t in $TARGETS; do
  mkdir -p "$OUT/corpus/$t" "$OUT/artifacts/$t"
  cp "$ROOT/test/fuzz/corpus/$t/"* "$OUT/corpus/$t/"
  nice -n 19 "$BUILD_DIR/test/fuzz/$t" -max_total_time="$seconds" -max_len=1048576 \
    -timeout="$TIMEOUT" -rss_limit_mb="$RSS_MB" -malloc_limit_mb="$RSS_MB" -print_final_stats=1 \
    -artifact_prefix="$OUT/artifacts/$t/" "$OUT/corpus/$t" "$ROOT/test/fuzz/regressions/$t" \
    >"$OUT/$t.log" 2>&1 &
  pids[$t]=$!
done

# stat::<name> from a log's final statistics (empty when the run ended before printing them).
final_stat() { sed -n "s/^stat::$2: *//p" "$1" | tail -n 1; }

failed=0
printf '| target | seconds | executions | execs/s | peak RSS (MB) | new corpus files | result |\n'
printf '|---|---|---|---|---|---|---|\n'
for t in $TARGETS; do
  rc=0
  wait "${pids[$t]}" || rc=$?
  log="$OUT/$t.log"
  secs="$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)"
  findings="$(find "$OUT/artifacts/$t" -type f | wc -l)"
  result="no crash, hang or sanitizer report"
  if ((rc != 0 || findings > 0)) ||
    grep -qE 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$log"; then
    result="FAILED (exit $rc, $findings artifact(s) in $OUT/artifacts/$t, see $log)"
    failed=1
  fi
  seeds="$(find "$ROOT/test/fuzz/corpus/$t" -type f | wc -l)"
  corpus_files="$(($(find "$OUT/corpus/$t" -type f | wc -l) - seeds))"
  printf '| `%s` | %s | %s | %s | %s | %s | %s |\n' "$t" "${secs:-?}" \
    "$(final_stat "$log" number_of_executed_units)" "$(final_stat "$log" average_exec_per_sec)" \
    "$(final_stat "$log" peak_rss_mb)" "$corpus_files" "$result"
done
printf '[fuzz] load average at the end: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
exit "$failed"
