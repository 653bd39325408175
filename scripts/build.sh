#!/usr/bin/env bash
# Configure (Ninja, Release, warnings as errors) and build libtdo, its tools and tests.
#
#   bash scripts/build.sh [extra cmake -D... arguments]
#
# Environment: BUILD_DIR (default <repo>/build), TDO_CMAKE_ARGS (extra cmake arguments, split on
# spaces), JOBS (parallel build jobs, default: number of cores). Arguments given on the command
# line come last, so they override the defaults (e.g. -DCMAKE_BUILD_TYPE=RelWithDebInfo).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
JOBS="${JOBS:-$(nproc)}"

read -r -a env_args <<<"${TDO_CMAKE_ARGS:-}"

configure=(cmake -S "$ROOT" -B "$BUILD_DIR")
# Choose the generator only on the first configure; an existing build directory keeps its own.
if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
  configure+=(-G Ninja)
fi
configure+=(-DCMAKE_BUILD_TYPE=Release -DTDO_WERROR=ON)
# LCM for the apps: the lcm wheel in the project venv (scripts/setup.sh) ships lcmConfig.cmake in
# <site-packages>/lib/lcm/cmake; ask the venv's Python where its site-packages is.
venv_python="$ROOT/.venv/bin/python"
if [[ -x "$venv_python" ]]; then
  site="$("$venv_python" -c 'import sysconfig; print(sysconfig.get_path("platlib"))' 2>/dev/null ||
    true)"
  if [[ -n "$site" && -f "$site/lib/lcm/cmake/lcmConfig.cmake" ]]; then
    configure+=("-Dlcm_DIR=$site/lib/lcm/cmake")
  fi
fi
configure+=("${env_args[@]}" "$@")

printf '[build] %s\n' "${configure[*]}"
"${configure[@]}"
printf '[build] cmake --build %s --parallel %s\n' "$BUILD_DIR" "$JOBS"
cmake --build "$BUILD_DIR" --parallel "$JOBS"
