#!/usr/bin/env bash
# Set up a Debian bookworm machine for libtdo: the system packages the build, the tools and the
# tests need, and a project-local Python virtual environment .venv with LCM.
#
# Idempotent: when every package is already installed, apt is not touched at all, so a second run
# is fast and needs no network. Works as root, or through sudo for another user.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

# Debian bookworm package names.
PACKAGES=(
  build-essential
  cmake
  ninja-build
  git
  libgtest-dev
  libgmock-dev
  libbenchmark-dev
  nlohmann-json3-dev
  libcli11-dev
  libeigen3-dev
  liboctomap-dev
  clang-format
  python3
  python3-venv
  python3-matplotlib
  python3-numpy
  libglib2.0-dev # LCM: the wheel's liblcm links the system GLib (apps, lcm-gen)
  # Embedded demo (scripts/embedded.sh): Cortex-M7 cross toolchain, C/C++ libraries, QEMU
  gcc-arm-none-eabi
  libnewlib-arm-none-eabi
  libstdc++-arm-none-eabi-newlib
  qemu-system-arm
  libompl-dev      # tools/baselines: OMPL RRTConnect / RRT* (tdo-bench)
  libpagmo-dev     # tools/baselines: pagmo2 PSO / grey wolf optimizer (tdo-bench)
  libnlopt-dev     # tools/tdo-tune: NLopt (C library)
  libnlopt-cxx-dev # tools/tdo-tune: nlopt.hpp
  clang-14           # the clang build and the libFuzzer targets (TDO_FUZZ, docs/fuzzing.md)
  libclang-rt-14-dev # clang's libFuzzer, ASan and UBSan runtimes
  universal-ctags    # scripts/check_structure.py (function lengths, CTest repo.structure)
)

log() { printf '[setup] %s\n' "$*"; }

# ---- System packages ---------------------------------------------------------------------------
if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  log "error: dpkg-query/apt-get not found; this script expects Debian bookworm" >&2
  exit 1
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  state="$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)"
  if [[ "$state" != "installed" ]]; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  log "all ${#PACKAGES[@]} system packages present; apt skipped"
else
  log "installing: ${missing[*]}"
  if ((EUID == 0)); then
    as_root=()
  elif command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
  else
    log "error: not root and sudo is not available; install as root: ${missing[*]}" >&2
    exit 1
  fi
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y --no-install-recommends "${missing[@]}"
fi

# ---- Python virtual environment (.venv) with LCM -----------------------------------------------
# LCM 1.5 comes from the official wheel on PyPI (docs/design.md s.11): the C library, its
# headers, lcmConfig.cmake, lcm-gen, lcm-logger/-logplayer/-spy and the Python bindings. It goes into
# a project-local venv; scripts/build.sh hands its lcm/cmake directory to CMake. The venv sees the
# system site packages (Debian's numpy and matplotlib) for the plotting scripts. pip is skipped when
# the venv already imports this exact version. TDO_PYTHON overrides the interpreter.
LCM_VERSION=1.5.3
VENV="$ROOT/.venv"
venv_lcm_version() {
  "$VENV/bin/python" -c 'import importlib.metadata as m, lcm; print(m.version("lcm"))' 2>/dev/null
}
if [[ "$(venv_lcm_version || true)" == "$LCM_VERSION" ]]; then
  log "lcm $LCM_VERSION present in .venv; pip skipped"
else
  python="${TDO_PYTHON:-}"
  if [[ -z "$python" ]]; then
    # Debian's interpreter (python3-venv is in PACKAGES) rather than whatever is first on PATH.
    if [[ -x /usr/bin/python3 ]]; then python=/usr/bin/python3; else python=python3; fi
  fi
  if ! "$VENV/bin/python" -c 'import sys' >/dev/null 2>&1; then
    log "creating .venv with $python"
    "$python" -m venv --clear --system-site-packages "$VENV"
  fi
  log "installing lcm==$LCM_VERSION into .venv"
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-input \
    "lcm==$LCM_VERSION"
  got="$(venv_lcm_version || true)"
  if [[ "$got" != "$LCM_VERSION" ]]; then
    log "error: .venv does not import lcm $LCM_VERSION after pip install (got '${got:-nothing}')" >&2
    exit 1
  fi
fi

log "done"
