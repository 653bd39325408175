#!/usr/bin/env bash
# Flight time against the v/a time optimum along each plan's own path, on Map1-Map5 and 30
# forest_gen pairs (the first 10 queries of forests 0-2): tools/tdo-plan/time_ratio.py.
#
#   bash scripts/time_ratio.sh [--forest N] [extra tdo-plan options]
#
# Environment: BUILD_DIR (default build). Takes about a minute.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
cd "$ROOT"
cmake --build "$BUILD_DIR" --target tdo-plan >/dev/null
python=/usr/bin/python3
[[ -x "$python" ]] || python=python3
"$python" tools/tdo-plan/time_ratio.py "$BUILD_DIR/tools/tdo-plan/tdo-plan" "$@"
