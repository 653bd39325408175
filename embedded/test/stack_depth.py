#!/usr/bin/env python3
"""Worst-case stack depth of a firmware from GCC's -fcallgraph-info=su files (docs/embedded.md).

Usage: stack_depth.py BUILD_DIR [ROOT_FUNCTION]   (ROOT_FUNCTION defaults to main)

Reads every *.ci file under BUILD_DIR (one per object, written next to it by GCC), takes each
function's static frame and the direct calls, and prints the deepest call chain from the root by
the sum of frames. Reported separately, not in the sum: calls to functions without frame data
(newlib's libm and libgcc helpers), indirect calls (function pointers) and recursion, which make
the figure a lower bound of the true worst case for those paths.
"""
import glob
import os
import re
import sys

NODE = re.compile(r'node:\s*\{\s*title:\s*"([^"]+)"\s*label:\s*"([^"]*)"')
EDGE = re.compile(r'edge:\s*\{\s*sourcename:\s*"([^"]+)"\s*targetname:\s*"([^"]+)"')
FRAME = re.compile(r"(\d+) bytes \((static|dynamic[^)]*)\)")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = sys.argv[2] if len(sys.argv) > 2 else "main"
    frames, kinds, edges = {}, {}, {}
    files = glob.glob(os.path.join(sys.argv[1], "**", "*.ci"), recursive=True)
    if not files:
        sys.exit(f"no *.ci files under {sys.argv[1]} (build with -fcallgraph-info=su)")
    for ci in files:
        text = open(ci, errors="replace").read()
        for m in NODE.finditer(text):
            f = FRAME.search(m.group(2))
            if f:
                frames[m.group(1)] = max(frames.get(m.group(1), 0), int(f.group(1)))
                kinds[m.group(1)] = f.group(2)
        for m in EDGE.finditer(text):
            edges.setdefault(m.group(1), set()).add(m.group(2))
    memo, active, recursion, unknown, indirect = {}, set(), set(), set(), set()

    def depth(f):
        if f in memo:
            return memo[f]
        if f in active:
            recursion.add(f)
            return 0, []
        active.add(f)
        best = (0, [])
        for g in sorted(edges.get(f, ())):
            if g == "__indirect_call":
                indirect.add(f)
                continue
            if g not in frames and g not in edges:
                unknown.add(g)
                continue
            d = depth(g)
            if d[0] > best[0]:
                best = d
        active.discard(f)
        memo[f] = (frames.get(f, 0) + best[0], [f] + best[1])
        return memo[f]

    roots = [t for t in set(frames) | set(edges) if t == root or t.endswith(":" + root)]
    if not roots:
        sys.exit(f"function {root} not found")
    for r in roots:
        total, chain = depth(r)
        print(f"deepest chain from {r}: {total} bytes")
        for f in chain:
            print(f"  {frames.get(f, 0):6d}  {f.rsplit(':', 1)[-1]}")
    dynamic = sorted(f for f, k in kinds.items() if k != "static")
    print("frames not static:", ", ".join(dynamic) if dynamic else "none")
    print("recursion:", ", ".join(sorted(recursion)) if recursion else "none")
    print("functions making indirect calls (not followed):",
          ", ".join(sorted(f.rsplit(':', 1)[-1] for f in indirect)) or "none")
    print("callees without frame data (not counted):", ", ".join(sorted(unknown)) or "none")


if __name__ == "__main__":
    main()
