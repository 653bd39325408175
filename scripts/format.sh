#!/usr/bin/env bash
# Format the C and C++ sources with clang-format and the repository's .clang-format.
#
#   bash scripts/format.sh           rewrite files in place
#   bash scripts/format.sh --check   change nothing; list unformatted files and fail if any
#
# Files: every tracked or new (not ignored) *.c *.cpp *.h *.hpp under libtdo/ tools/ test/ apps/ embedded/.
# CLANG_FORMAT overrides the binary (default: clang-format, Debian's package).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

check=0
case "${1:-}" in
  "") ;;
  --check) check=1 ;;
  *)
    printf 'usage: %s [--check]\n' "$0" >&2
    exit 2
    ;;
esac

CLANG_FORMAT="${CLANG_FORMAT:-clang-format}"
if ! command -v "$CLANG_FORMAT" >/dev/null 2>&1; then
  printf '[format] error: %s not found (run scripts/setup.sh)\n' "$CLANG_FORMAT" >&2
  exit 1
fi

listed=()
mapfile -d '' -t listed < <(git ls-files -z -co --exclude-standard -- libtdo tools test apps embedded)
wait "$!" || {
  printf '[format] error: git ls-files failed (run inside the git work tree)\n' >&2
  exit 1
}
files=()
for f in "${listed[@]}"; do
  case "$f" in
    *.c | *.cpp | *.h | *.hpp) [[ -f "$f" ]] && files+=("$f") ;;
    *) ;;
  esac
done

printf '[format] %s, %d files\n' "$("$CLANG_FORMAT" --version)" "${#files[@]}"

if ((check == 0)); then
  if ((${#files[@]} > 0)); then
    "$CLANG_FORMAT" -i --style=file "${files[@]}"
  fi
  exit 0
fi

bad=()
for f in "${files[@]}"; do
  if ! "$CLANG_FORMAT" --style=file "$f" | cmp -s - "$f"; then
    bad+=("$f")
  fi
done

if ((${#bad[@]} > 0)); then
  printf '[format] %d file(s) not formatted (fix with: bash scripts/format.sh):\n' "${#bad[@]}" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
printf '[format] all files formatted\n'
