#!/usr/bin/env bash
# Cortex-M7 code size of the vec3-eigen kernels (vec3_eigen.cpp), each written once and built with
# libtdo's vec3.h and with Eigen::Vector3d: the firmware's compiler and flags (-O3, hard-float
# FPv5-D16, -ffp-contract=off, no exceptions/RTTI). Prints the bytes of each kernel.
#
#   bash tools/vec3-eigen/sizes.sh
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
arm-none-eabi-g++ -std=c++17 -O3 -DNDEBUG -DVEC3_EIGEN_KERNELS_ONLY \
  -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard -mthumb -ffp-contract=off \
  -ffunction-sections -fdata-sections -fno-exceptions -fno-rtti -fno-unwind-tables \
  -fno-asynchronous-unwind-tables -I/usr/include/eigen3 -I"$ROOT/libtdo/include" \
  -I"$ROOT/libtdo/src" -c "$ROOT/tools/vec3-eigen/vec3_eigen.cpp" -o "$out/k.o"
arm-none-eabi-size -A "$out/k.o" | awk '/^\.text\.kernel_ops_/ {
  sub(/^\.text\.kernel_ops_/, "", $1); printf "vec3-eigen cortex-m7: %-6s %5d bytes\n", $1, $2 }'
