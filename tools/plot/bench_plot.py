#!/usr/bin/env python3
"""Draw the trajectories of all planners of one tdo-bench map over its obstacles (like the paper's
Figures 8 and 9): a top view and a 3D view, one colour per planner.

usage:
  python3 tools/plot/bench_plot.py BENCH_OUT/paths/map4.json -o map4.png [--dpi 80]
  python3 tools/plot/bench_plot.py BENCH_OUT/paths/*.json --out-dir DIR

Input: the paths/<map>.json files tdo-bench writes (map file, start, goal, and per planner the
final path sampled: `curve`). Maps are read with tools/plot/tdo_plot.py (.tdomap, .3dmap, OcTrees).
Exit status 0 written, 2 bad input.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tdo_plot  # noqa: E402  (sets the Agg backend, re-executes with Debian's python if needed)
from tdo_plot import BadInput, plt  # noqa: E402
from matplotlib import colors  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

STYLE = {
    "tdo": ("#d62728", 2.6),
    "msf-mtpo": ("#1f77b4", 1.8),
    "astar": ("#7f7f7f", 1.2),
    "rrtconnect": ("#bcbd22", 0.9),
    "rrtconnect-simplify": ("#2ca02c", 1.5),
    "rrtstar": ("#17becf", 0.9),
    "rrtstar-simplify": ("#9467bd", 1.5),
    "pso": ("#ff7f0e", 1.5),
    "gwo": ("#8c564b", 1.5),
}


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise BadInput(f"{path}: cannot read ({e})")
    for k in ("map", "planners", "start", "goal"):
        if k not in doc:
            raise BadInput(f"{path}: missing '{k}' (not a tdo-bench paths file)")
    return doc


def draw(doc, out, dpi):
    m = tdo_plot.read_map(doc["map"])
    slice_note = "obstacles shaded by height"
    if m.cubes:
        # voxel maps (forests): show the voxels in the slice the paths fly through, else the
        # canopy hides everything in the top view
        zs = [q[2] for p in doc["planners"] for q in p.get("curve", [])]
        zs += [doc["start"][2], doc["goal"][2]]
        c = float(doc.get("clearance", 0.0))
        zlo, zhi = min(zs) - c, max(zs) + c
        m.cubes = [q for q in m.cubes if q[2] + q[3] / 2 >= zlo and q[2] - q[3] / 2 <= zhi]
        slice_note = f"occupied voxels with z in [{zlo:.1f}, {zhi:.1f}] m"
    (x0, y0, z0), (x1, y1, z1) = m.bounds
    fig = plt.figure(figsize=(12, 6.4))
    ax = fig.add_subplot(1, 2, 1)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    norm = colors.Normalize(vmin=z0, vmax=z1)
    cmap = plt.get_cmap("Greys")
    rects, shades = [], []
    for b in sorted(m.boxes, key=lambda b: b[5]):
        rects.append(Rectangle((b[0], b[1]), b[3] - b[0], b[4] - b[1]))
        shades.append(cmap(0.25 + 0.6 * norm(b[5])))
    for c in m.cubes:
        h = c[3] / 2
        rects.append(Rectangle((c[0] - h, c[1] - h), c[3], c[3]))
        shades.append("#aaaaaa")
    if rects:
        ax.add_collection(PatchCollection(rects, facecolor=shades, edgecolor="none", alpha=0.85,
                                          zorder=1))
    faces = []
    for b in m.boxes:
        faces.extend(tdo_plot._box_faces(b))
    if faces:
        ax3.add_collection3d(Poly3DCollection(faces, facecolor="#999999", edgecolor="none",
                                              alpha=0.12))
    if m.cubes:
        step = max(1, len(m.cubes) // 5000)  # a thinned cloud is enough to show the trees
        sub = m.cubes[::step]
        ax3.scatter([c[0] for c in sub], [c[1] for c in sub], [c[2] for c in sub], s=0.5,
                    c="#999999", alpha=0.2)
    for p in doc["planners"]:
        name = p["planner"]
        color, width = STYLE.get(name, ("#000000", 1.0))
        if not p.get("ok") or len(p.get("curve", [])) < 2:
            ax.plot([], [], color=color, lw=width, ls=":", label=f"{name}: failed ({p.get('status')})")
            continue
        xs = [q[0] for q in p["curve"]]
        ys = [q[1] for q in p["curve"]]
        zs = [q[2] for q in p["curve"]]
        label = f"{name}: {p.get('turns')} turns, {p.get('length_m', 0):.1f} m"
        ax.plot(xs, ys, color=color, lw=width, label=label, zorder=3 if name == "tdo" else 2)
        ax3.plot(xs, ys, zs, color=color, lw=width)
    s, g = doc["start"], doc["goal"]
    for a in (ax,):
        a.plot(s[0], s[1], "o", color="#2ca02c", ms=8, mec="k", zorder=4)
        a.plot(g[0], g[1], "*", color="#d62728", ms=13, mec="k", zorder=4)
    ax3.scatter([s[0]], [s[1]], [s[2]], color="#2ca02c", s=40)
    ax3.scatter([g[0]], [g[1]], [g[2]], color="#d62728", marker="*", s=90)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{doc.get('name')}: top view ({slice_note})")
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="lower center", ncol=3,
               framealpha=0.9)
    ax3.set_xlim(x0, x1)
    ax3.set_ylim(y0, y1)
    ax3.set_zlim(z0, z1)
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z")
    ax3.view_init(elev=28, azim=-120)
    ax3.set_title("3D view")
    fig.subplots_adjust(left=0.05, right=0.98, bottom=0.2, top=0.93, wspace=0.15)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="bench_plot", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+", help="tdo-bench paths/<map>.json files")
    ap.add_argument("-o", "--output", help="PNG (one input)")
    ap.add_argument("--out-dir", help="directory for <name>.png (any number of inputs)")
    ap.add_argument("--dpi", type=int, default=80)
    a = ap.parse_args(argv)
    if not a.output and not a.out_dir:
        tdo_plot.die("give -o FILE or --out-dir DIR")
    if a.output and len(a.paths) != 1:
        tdo_plot.die("-o takes one input; use --out-dir for several")
    try:
        for p in a.paths:
            doc = load(p)
            if a.output:
                out = a.output
            else:
                os.makedirs(a.out_dir, exist_ok=True)
                out = os.path.join(a.out_dir, os.path.splitext(os.path.basename(p))[0] + ".png")
            draw(doc, out, a.dpi)
            print(f"wrote {out}")
    except BadInput as e:
        tdo_plot.die(str(e))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
