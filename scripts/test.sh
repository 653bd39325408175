#!/usr/bin/env bash
# Set up, build, and run the whole test suite with CTest.
# Extra arguments are passed to ctest (for example -R grid).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"

bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"

printf '[test] ctest --test-dir %s --output-on-failure -j2\n' "$BUILD_DIR"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 "$@"
