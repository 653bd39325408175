#!/usr/bin/env bash
# Regenerate docs/results.md and docs/images/results/*.png: the paper's comparison (issue 6).
#
#   bash scripts/results.sh [extra tdo-bench options]
#
# Builds tdo-bench and tdo-tune, runs the full bench (Map1-Map6, 5 random maps, the 300 published
# forest_gen pairs; Tables 6/7, 8, 3) and the NLopt tuning, draws the trajectories and assembles
# docs/results.md. Takes tens of minutes on 2 cores; not part of CTest (see the bench.tables and
# tune.smoke tests for the small versions). Raw outputs go to $RESULTS_OUT (default
# build/results). Environment: BUILD_DIR (default build).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
OUT="${RESULTS_OUT:-$BUILD_DIR/results}"
cd "$ROOT"

if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
  bash scripts/build.sh
fi
cmake --build "$BUILD_DIR" --target tdo-bench tdo-tune

rm -rf "$OUT"
mkdir -p "$OUT"
"$BUILD_DIR/tools/tdo-bench/tdo-bench" --out "$OUT/bench" "$@"
"$BUILD_DIR/tools/tdo-tune/tdo-tune" --out "$OUT/tune"

python=/usr/bin/python3
[[ -x "$python" ]] || python=python3
rm -rf docs/images/results
mkdir -p docs/images/results
paths=("$OUT"/bench/paths/map*.json)
[[ -f "$OUT/bench/paths/random_0.json" ]] && paths+=("$OUT/bench/paths/random_0.json")
[[ -f "$OUT/bench/paths/forest0_q0.json" ]] && paths+=("$OUT/bench/paths/forest0_q0.json")
"$python" tools/plot/bench_plot.py "${paths[@]}" --out-dir docs/images/results --dpi 70

"$python" tools/tdo-bench/results_md.py "$OUT/bench" "$OUT/tune" images/results \
  "bash scripts/results.sh${*:+ $*}" >docs/results.md
echo "[results] wrote docs/results.md (raw data in $OUT)"
