#!/usr/bin/env bash
# Set up, build, and run the main job: plan one query on the MovingAI "Simple" map.
# Extra arguments are passed to tdo-plan (for example --json).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"

bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"

plan="$BUILD_DIR/tools/tdo-plan/tdo-plan"
if [[ ! -x "$plan" ]]; then
  printf '[demo] error: %s was not built\n' "$plan" >&2
  exit 1
fi

cmd=("$plan" --map "$ROOT/maps/movingai/Simple.3dmap"
  --start 56 76 52 --goal 48 85 45 --planner bidir "$@")
printf '[demo] %s\n' "${cmd[*]}"
"${cmd[@]}"
