#!/usr/bin/env python3
"""Structure goals of the code base, checked by command (docs/design.md s.12, issue 21).

  python3 scripts/check_structure.py [--root DIR] [--max-lines 150]

Checks, and prints one line per finding:
  - no function in libtdo/, tools/, apps/ or embedded/ is longer than --max-lines lines
    (function extents from universal-ctags, `--fields=+ne`);
  - no tracked file cites a design document outside the repository;
  - at most 2 files in tools/ and apps/ name `theta_max` (the parameter table serves the rest);
  - docs/performance.md has at most 250 lines.
Exit status: 0 when every check holds, 1 when one fails, 2 for bad usage (ctags missing).
"""
import argparse
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

CODE_DIRS = ("libtdo", "tools", "apps", "embedded")
CODE_SUFFIXES = {".c", ".cc", ".cpp", ".h", ".hpp"}
OUTSIDE = re.compile(r"pipeline\.md|\.\./shared|shared/design")
THIS = "scripts/check_structure.py"


def tracked(root):
    out = subprocess.run(["git", "-C", str(root), "ls-files"], check=True, capture_output=True,
                         text=True).stdout
    return [p for p in out.splitlines() if (root / p).is_file()]


def long_functions(root, files, max_lines):
    code = [f for f in files if f.split("/")[0] in CODE_DIRS and Path(f).suffix in CODE_SUFFIXES]
    cmd = ["ctags", "--output-format=json", "--fields=+ne", "--kinds-C++=f", "--kinds-C=f",
           "--language-force=C++", "-f", "-"] + code
    out = subprocess.run(cmd, cwd=root, check=True, capture_output=True, text=True).stdout
    found = []
    for line in out.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag:
            continue
        n = int(tag["end"]) - int(tag["line"]) + 1
        if n > max_lines:
            found.append(f"{tag['path']}:{tag['line']}: {tag['name']} is {n} lines "
                         f"(at most {max_lines})")
    return found, len(code)


def outside_citations(root, files):
    found = []
    for f in files:
        if f == THIS:
            continue
        try:
            text = (root / f).read_text(encoding="utf-8")
        except (UnicodeDecodeError, OSError):
            continue
        for i, line in enumerate(text.splitlines(), 1):
            if OUTSIDE.search(line):
                found.append(f"{f}:{i}: cites a design document outside the repository")
    return found


def theta_max_files(root, files):
    named = []
    for f in files:
        if f.split("/")[0] not in ("tools", "apps"):
            continue
        try:
            if "theta_max" in (root / f).read_text(encoding="utf-8"):
                named.append(f)
        except (UnicodeDecodeError, OSError):
            continue
    return ([f"theta_max is named in {len(named)} files of tools/ and apps/ (at most 2): "
             + ", ".join(named)] if len(named) > 2 else []), named


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=str(Path(__file__).resolve().parent.parent))
    ap.add_argument("--max-lines", type=int, default=150)
    a = ap.parse_args()
    if shutil.which("ctags") is None:
        print("check_structure: ctags not found (Debian package universal-ctags)", file=sys.stderr)
        return 2
    root = Path(a.root)
    files = tracked(root)
    longs, n_code = long_functions(root, files, a.max_lines)
    cites = outside_citations(root, files)
    theta, named = theta_max_files(root, files)
    perf = (root / "docs/performance.md").read_text(encoding="utf-8").count("\n")
    perf_bad = [f"docs/performance.md has {perf} lines (at most 250)"] if perf > 250 else []
    problems = longs + cites + theta + perf_bad
    for p in problems:
        print(p)
    print(f"check_structure: {n_code} code files, functions over {a.max_lines} lines: {len(longs)}; "
          f"outside citations: {len(cites)}; files naming theta_max: {len(named)}; "
          f"docs/performance.md: {perf} lines")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
