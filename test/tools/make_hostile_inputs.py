#!/usr/bin/env python3
"""Write issue 24's hostile map files into DIR (the tdo_plan.hostile_* tests read them).

    python3 make_hostile_inputs.py DIR MAPS_DIR

MAPS_DIR is the repository's maps/ (forest0.bt is edited into several of them).
"""
import os
import sys


def main() -> int:
    out, maps = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    forest = open(os.path.join(maps, "forest_gen", "forest0.bt"), "rb").read()
    bt = b"# Octomap OcTree binary file\nid OcTree\nsize 1000\nres 0.1\ndata\n"
    files = {
        # OctoMap's reader recursed ~87,000 deep on this and the process died (exit 139).
        "all_inner_300k.bt": bt + b"\xff" * 300000,
        # 100 kB of 0xff: 3.2 M nodes (180 MB) were built before the size check.
        "all_inner_100k.bt": bt + b"\xff" * 100000,
        "res_1e300.bt": forest.replace(b"res 0.1\n", b"res 1e300\n"),
        "res_1e-6.bt": forest.replace(b"res 0.1\n", b"res 1e-6\n"),
        "color.bt": forest.replace(b"id OcTree\n", b"id ColorOcTree\n"),
        "garbage.ot": b"# Octomap OcTree file\nid OcTree\nsize 1000\nres 0.1\ndata\n"
        + bytes(range(256)) * 40,
        "token_10mb.tdomap": b"x" * 10_000_000,
        "control.tdomap": b"tdomap 1\nbo\x1b[31m\x07unds 0 0 0 1 1 1\n",
    }
    for name, data in files.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    os.makedirs(os.path.join(out, "directory.tdomap"), exist_ok=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
