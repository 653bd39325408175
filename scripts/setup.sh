#!/usr/bin/env bash
# Set up a Debian bookworm machine for libtdo: the system packages the build, the tools and the
# tests need (and, in later issues, a project-local Python virtual environment).
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

# ---- Python virtual environment (.venv) --------------------------------------------------------
# Reserved for later issues: create "$ROOT/.venv" (python3 -m venv) and `pip install lcm` into it,
# skipping pip when the venv already has it, so the LCM programs and tests find it. Nothing yet.

log "done"
