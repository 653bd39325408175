#!/usr/bin/env bash
# The embedded demo (docs/embedded.md): cross-build libtdo and the demo firmware for a Cortex-M7,
# check that the images use no heap, exceptions or RTTI, run them under QEMU (mps2-an500) and
# compare their output with the host twins, digit for digit.
#
#   bash scripts/embedded.sh                       # build, symbols, run Map1, sizes (build-arm/, build/)
#   bash scripts/embedded.sh build [DIR]           # configure + build the firmware (default build-arm)
#   bash scripts/embedded.sh symbols ELF...        # the heap/exception/RTTI symbol check
#   bash scripts/embedded.sh symbols-selftest ELF  # ELF must FAIL the check, naming symbols + objects
#   bash scripts/embedded.sh run FW.elf HOST_EXE   # QEMU run, diff against the host twin
#   bash scripts/embedded.sh sizes [DIR]           # flash / RAM / arena / stack figures
#   bash scripts/embedded.sh libm [DIR] [HOST_DIR]  # newlib's libm rounding against the host's
#
# Environment: JOBS (parallel build jobs), QEMU_TIMEOUT (seconds, default 120).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TOOLCHAIN="$ROOT/cmake/toolchains/arm-none-eabi-cortex-m7.cmake"
CONFIGS=(map1 map4 map5)

log() { printf '[embedded] %s\n' "$*"; }
die() {
  printf '[embedded] error: %s\n' "$*" >&2
  exit 1
}
need() {
  command -v "$1" >/dev/null 2>&1 ||
    die "$1 not found; install it with: bash scripts/setup.sh (Debian package ${2:-$1})"
}

cmd_build() {
  local dir="${1:-$ROOT/build-arm}"
  need arm-none-eabi-gcc gcc-arm-none-eabi
  local configure=(cmake -S "$ROOT" -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$TOOLCHAIN"
    -DCMAKE_BUILD_TYPE=Release -DTDO_WERROR=ON
    -DTDO_BUILD_TESTS=OFF -DTDO_BUILD_TOOLS=OFF -DTDO_BUILD_APPS=OFF -DTDO_BUILD_EMBEDDED=ON)
  if [[ ! -f "$dir/CMakeCache.txt" ]] && command -v ninja >/dev/null 2>&1; then
    configure+=(-G Ninja)
  fi
  log "${configure[*]}"
  "${configure[@]}"
  log "cmake --build $dir --parallel ${JOBS:-$(nproc)}"
  cmake --build "$dir" --parallel "${JOBS:-$(nproc)}"
}

# Symbols no firmware may contain: the heap (newlib's reentrant variants and sbrk included),
# C++ operator new/delete (mangled _Znw*, _Zna*, _Zdl*, _Zda*), the C++ ABI runtime (__cxa_*:
# exceptions, guards, pure virtuals), unwinding and personality routines, and RTTI objects
# (typeinfo _ZTI*, typeinfo names _ZTS*).
FORBIDDEN='^(malloc|free|calloc|realloc|reallocf|memalign|aligned_alloc|posix_memalign|valloc|pvalloc|_malloc_r|_free_r|_calloc_r|_realloc_r|_memalign_r|_sbrk|sbrk|_sbrk_r|_Znw.*|_Zna.*|_Zdl.*|_Zda.*|__cxa_.*|__gxx_personality.*|_Unwind_.*|__aeabi_unwind_cpp_pr.*|_ZTI.*|_ZTS.*)$'

# Print who references `sym`, from the linker map's cross-reference table (-Wl,--cref): the first
# file listed defines the symbol, the following ones reference it. A long symbol name stands alone
# on its line and its files follow on indented lines.
who_pulled() {
  local map="$1" sym="$2"
  awk -v sym="$sym" '
    /^Cross Reference Table/ { in_table = 1; next }
    !in_table { next }
    /^[^ \t]/ { cur = $1; files = 0; if (NF < 2) next; file = $2 }
    /^[ \t]/ { file = $1 }
    cur == sym && file != "" {
      print (files == 0 ? "    defined in " : "    referenced by ") file
      ++files
    }
    { file = "" }
  ' "$map"
}

cmd_symbols() {
  (($# > 0)) || die "symbols: give the ELF files"
  need arm-none-eabi-nm gcc-arm-none-eabi
  local failed=0 elf map bad
  for elf in "$@"; do
    [[ -f "$elf" ]] || die "symbols: $elf does not exist (build it: bash scripts/embedded.sh build)"
    map="${elf%.elf}.map"
    bad="$(arm-none-eabi-nm "$elf" | awk '{print $NF}' | grep -E "$FORBIDDEN" | sort -u || true)"
    if [[ -z "$bad" ]]; then
      log "symbols: $(basename "$elf"): no heap, operator new/delete, __cxa_*, unwind or RTTI symbol"
      continue
    fi
    failed=1
    while read -r sym; do
      printf '[embedded] symbols: %s: forbidden symbol %s\n' "$(basename "$elf")" "$sym" >&2
      if [[ "$sym" == _Z* ]] && command -v arm-none-eabi-c++filt >/dev/null 2>&1; then
        printf '    (%s)\n' "$(arm-none-eabi-c++filt "$sym")" >&2
      fi
      if [[ -f "$map" ]]; then
        who_pulled "$map" "$sym" >&2
      else
        printf '    (no map file %s to say who pulled it in)\n' "$map" >&2
      fi
    done <<<"$bad"
  done
  return "$failed"
}

cmd_symbols_selftest() {
  local elf="${1:?symbols-selftest: give the ELF}" out rc=0
  out="$(cmd_symbols "$elf" 2>&1)" || rc=$?
  printf '%s\n' "$out"
  ((rc != 0)) || die "symbols-selftest: the check accepted $elf, which calls malloc and new"
  local want
  for want in malloc _Znwj _ZdlPv __cxa_throw _ZTISt9bad_alloc; do
    grep -q "forbidden symbol $want\$" <<<"$out" || die "symbols-selftest: $want not named"
  done
  # The objects that pulled them in: malloc from the C file, operator new from the C++ file.
  awk '/forbidden symbol malloc$/ { s = 1; next } /forbidden symbol/ { s = 0 } s' <<<"$out" |
    grep -qE 'referenced by .*symcheck_bad\.c\.o(bj)?$' ||
    die "symbols-selftest: the object that pulled malloc in (symcheck_bad.c) is not named"
  awk '/forbidden symbol _Znwj$/ { s = 1; next } /forbidden symbol/ { s = 0 } s' <<<"$out" |
    grep -qE 'referenced by .*symcheck_bad_cxx\.cpp\.o(bj)?$' ||
    die "symbols-selftest: the object that pulled operator new in (symcheck_bad_cxx.cpp) is not named"
  log "symbols-selftest: the check rejects $(basename "$elf"), names malloc, operator new/delete," \
    "__cxa_throw and typeinfo, and the objects symcheck_bad.c and symcheck_bad_cxx.cpp"
}

cmd_run() {
  local elf="${1:?run: give the firmware ELF}" host="${2:?run: give the host twin}"
  need qemu-system-arm qemu-system-arm
  [[ -f "$elf" ]] || die "run: $elf does not exist"
  [[ -x "$host" ]] || die "run: $host is not an executable"
  local rc=0
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  # -semihosting with the semihosting console sent to a file: the firmware's lines alone, apart from
  # QEMU's own diagnostics (stderr).
  log "run: timeout ${QEMU_TIMEOUT:-120} qemu-system-arm -M mps2-an500 -nographic -semihosting ... -kernel $(basename "$elf")"
  timeout "${QEMU_TIMEOUT:-120}" qemu-system-arm -M mps2-an500 -nographic -monitor none -serial none \
    -chardev file,id=semihost,path="$tmp/fw.txt" \
    -semihosting-config enable=on,target=native,chardev=semihost \
    -kernel "$elf" >"$tmp/fw.err" 2>&1 </dev/null || rc=$?
  touch "$tmp/fw.txt"
  cat "$tmp/fw.txt"
  if ((rc != 0)); then
    cat "$tmp/fw.err" >&2
    if ((rc == 124)); then die "run: the firmware did not finish within ${QEMU_TIMEOUT:-120} s"; fi
    die "run: the firmware exited with status $rc"
  fi
  grep -qx 'end' "$tmp/fw.txt" || die "run: the firmware output has no 'end' line"
  "$host" >"$tmp/host.txt" || die "run: the host twin $host failed (status $?)"
  # '@' lines hold what differs by platform (sizes, stack); everything else must match exactly.
  grep -v '^@' "$tmp/fw.txt" >"$tmp/fw.cmp" || true
  grep -v '^@' "$tmp/host.txt" >"$tmp/host.cmp" || true
  if ! diff -u "$tmp/host.cmp" "$tmp/fw.cmp" >"$tmp/diff.txt"; then
    cat "$tmp/diff.txt" >&2
    die "run: firmware and host outputs differ (diff above: - host, + firmware)"
  fi
  log "run: $(basename "$elf") printed the same $(wc -l <"$tmp/fw.cmp") lines as $(basename "$host")"
}

cmd_sizes() {
  local dir="${1:-$ROOT/build-arm}" elf cfg
  need arm-none-eabi-size gcc-arm-none-eabi
  for cfg in "${CONFIGS[@]}"; do
    elf="$dir/embedded/tdo-fw-$cfg.elf"
    [[ -f "$elf" ]] || die "sizes: $elf does not exist"
    printf '\n%s\n' "== $cfg: arm-none-eabi-size -A $elf"
    arm-none-eabi-size "$elf"
    arm-none-eabi-size -A "$elf" | grep -E '^\.(text|ARM.exidx|data|bss|stack) '
    printf 'arena (tdo_demo_arena): '
    arm-none-eabi-nm -S -t d "$elf" | awk '$4 == "tdo_demo_arena" { printf "%d bytes\n", $2 + 0 }'
  done
}

# Run the libm probe on both platforms and say, per function, whether the result bits agree.
cmd_libm() {
  local dir="${1:-$ROOT/build-arm}" host="${2:-${BUILD_DIR:-$ROOT/build}}"
  need qemu-system-arm qemu-system-arm
  cmake --build "$host" --target tdo-libm-probe >/dev/null
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  timeout "${QEMU_TIMEOUT:-120}" qemu-system-arm -M mps2-an500 -nographic -monitor none -serial none \
    -chardev file,id=semihost,path="$tmp/fw.txt" \
    -semihosting-config enable=on,target=native,chardev=semihost \
    -kernel "$dir/embedded/tdo-fw-libm-probe.elf" >/dev/null 2>&1 </dev/null
  "$host/embedded/tdo-libm-probe" | grep -v -e '^@' -e '^end' >"$tmp/host.txt"
  grep -v -e '^@' -e '^end' "$tmp/fw.txt" >"$tmp/fw.cmp"
  printf '%-18s %-18s %-18s %s\n' function host cortex-m7 bits
  paste -d' ' "$tmp/host.txt" "$tmp/fw.cmp" | awk '{
    n = NF / 2; name = $1; for (i = 2; i < n; ++i) name = name " " $i
    printf "%-18s %-18s %-18s %s\n", name, $n, $NF, ($n == $NF ? "same" : "DIFFERENT") }'
}

cmd_all() {
  local arm="$ROOT/build-arm" host="${BUILD_DIR:-$ROOT/build}"
  cmd_build "$arm"
  cmd_symbols "$arm"/embedded/tdo-fw-{map1,map4,map5}.elf
  cmd_symbols_selftest "$arm/embedded/tdo-fw-symcheck-bad.elf"
  [[ -f "$host/CMakeCache.txt" ]] || die "no host build in $host: run bash scripts/build.sh first"
  cmake --build "$host" --target tdo-demo-map1 tdo-demo-map5
  # Map1 and Map5: Map4's 20 MB arena does not fit the board's 4 MB of data RAM (docs/embedded.md).
  cmd_run "$arm/embedded/tdo-fw-map1.elf" "$host/embedded/tdo-demo-map1"
  cmd_run "$arm/embedded/tdo-fw-map5.elf" "$host/embedded/tdo-demo-map5"
  cmd_sizes "$arm"
}

case "${1:-all}" in
  all) cmd_all ;;
  build) cmd_build "${@:2}" ;;
  symbols) cmd_symbols "${@:2}" ;;
  symbols-selftest) cmd_symbols_selftest "${@:2}" ;;
  run) cmd_run "${@:2}" ;;
  sizes) cmd_sizes "${@:2}" ;;
  libm) cmd_libm "${@:2}" ;;
  *) die "unknown command '$1' (all, build, symbols, symbols-selftest, run, sizes, libm)" ;;
esac
