#!/usr/bin/env bash
# Set up, build, and run the main job: plan the paper's Map5 (50 x 50 x 20 m, 500 columns) with the
# full TDO-MSF pipeline, print the metrics table, and draw the map with the grid path, the corrected
# waypoints and the smoothed trajectory into build/demo/map5.png.
# Extra arguments are passed to tdo-plan (for example --map maps/map4.tdomap or --planner msf-mtpo).
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

map="$ROOT/maps/map5.tdomap"
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do
  [[ "${args[$i]}" == "--map" && $((i + 1)) -lt ${#args[@]} ]] && map="${args[$((i + 1))]}"
done
out="$BUILD_DIR/demo"
mkdir -p "$out"
name="$(basename "${map%.*}")"

cmd=("$plan" --map "$map" "$@")
printf '[demo] %s\n' "${cmd[*]}"
"${cmd[@]}"
"${cmd[@]}" --json > "$out/$name.json"
python3 "$ROOT/tools/plot/tdo_plot.py" --map "$map" --plan "$out/$name.json" -o "$out/$name.png"
printf '[demo] plan: %s\n[demo] picture: %s\n' "$out/$name.json" "$out/$name.png"
