#!/usr/bin/env bash
# LCM load benchmark (docs/lcm.md): tdo-planner and tdo-bench-lcm as two processes talking real UDP
# multicast inside a private network namespace (nothing leaves it), on Map5: closed loop (as fast
# as the planner answers) and open loop at 20 requests/s (compact answers, then with samples),
# DURATION seconds each (default 20; 50 s at 20 req/s = 1,000 requests).
#
#   bash scripts/bench_lcm.sh [DURATION]        (after scripts/build.sh; needs unshare -n as root)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
duration="${1:-20}"
if [[ "${2:-}" != "--inside" ]]; then
  cmake --build "$BUILD_DIR" --target tdo-planner tdo-bench-lcm >/dev/null
  exec unshare -n bash "$0" "$duration" --inside
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
# The apps' default URL (udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304, docs/lcm.md).
"$BUILD_DIR/apps/tdo-planner/tdo-planner" --max-size 64 64 32 --heartbeat 0 &
planner=$!
trap 'kill -TERM $planner 2>/dev/null || true' EXIT
rc=0
bench=("$BUILD_DIR/apps/tdo-bench-lcm/tdo-bench-lcm" "$ROOT/maps/map5.tdomap")
"${bench[@]}" --rate 0 --duration "$duration" || rc=1
"${bench[@]}" --rate 20 --duration "$duration" || rc=1
# The same with the sampled form in every answer (~280 kB instead of ~6 kB): transport's share.
"${bench[@]}" --rate 20 --duration "$duration" --samples || rc=1
kill -TERM $planner
wait $planner || true
exit $rc
