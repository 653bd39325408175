#!/usr/bin/env python3
"""Plot a planner run from an LCM log (lcm-logger, tdo-make-replay-log): the map the plan was made
on (top view: boxes and run-length voxels, shaded by height), the trajectory coloured by speed, the
corrected waypoints, start and goal; and speed and height over time.

usage (the project venv's Python, which has the lcm wheel; the generated Python types are built
into build/lcmtypes/python):
  .venv/bin/python tools/plot/tdo_plot_log.py LOG [--request-id N] [--types DIR] -o run.png

Without --request-id: the last successful trajectory in the log. Exit status 0 written, 2 bad input.
"""
import argparse
import math
import os
import sys

PROG = "tdo_plot_log"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def die(msg):
    sys.stderr.write(f"{PROG}: error: {msg}\n")
    sys.exit(2)


ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("log")
ap.add_argument("--request-id", type=int, help="plot this request's answer")
ap.add_argument("--types", default=os.path.join(ROOT, "build", "lcmtypes", "python"),
                help="directory of the generated Python types (package tdo)")
ap.add_argument("--map-channel", default="TDO_MAP")
ap.add_argument("--trajectory-channel", default="TDO_TRAJECTORY")
ap.add_argument("--step", type=float, default=0.05,
                help="s between the points drawn from a compact-only answer (default 0.05)")
ap.add_argument("-o", "--output", required=True, help="PNG to write")
a = ap.parse_args()

try:
    import lcm
except ImportError:
    die("the lcm Python bindings are missing: run with the project venv (.venv/bin/python)")
sys.path.insert(0, a.types)
try:
    import tdo
except ImportError:
    die(f"no generated types in {a.types} (build the target tdo_lcmtypes_python, or --types)")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tdo_compact  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

if not os.path.isfile(a.log):
    die(f"{a.log}: no such file")
try:
    log = lcm.EventLog(a.log, "r")
except (IOError, OSError, ValueError) as e:
    die(f"{a.log}: cannot open: {e}")

maps = {}        # map_id -> map_t (the latest with that id)
latest_map = None
runs = []        # (trajectory_t, map_t in use when it was answered)
try:
    for ev in log:
        try:
            if ev.channel == a.map_channel:
                m = tdo.map_t.decode(ev.data)
                maps[m.map_id] = m
                latest_map = m
            elif ev.channel == a.trajectory_channel:
                t = tdo.trajectory_t.decode(ev.data)
                runs.append((t, maps.get(t.map_id, latest_map)))
        except ValueError:
            continue  # a malformed message (counted by the planner): nothing to plot
except (IOError, OSError, ValueError) as e:
    die(f"{a.log}: not a readable LCM log: {e}")

if a.request_id is not None:
    pick = [r for r in runs if r[0].request_id == a.request_id]
    if not pick:
        die(f"{a.log}: no answer to request {a.request_id} on {a.trajectory_channel}")
else:
    pick = [r for r in runs if r[0].status == "ok" and (r[0].n_samples > 0 or r[0].n_pieces > 0)]
    if not pick:
        die(f"{a.log}: no successful trajectory on {a.trajectory_channel}")
traj, m = pick[-1]
if m is None:
    die(f"{a.log}: no map before the answer to request {traj.request_id}")

# Occupied columns: max height per (i, j) of run-length voxels; boxes drawn as they are.
nx, ny, nz = m.size
res, (ox, oy, oz) = m.resolution, m.origin
top = {}
if m.encoding == tdo.map_t.ENCODING_RLE and m.n_runs > 0:
    idx = 0
    for r, n in enumerate(m.runs):
        if r % 2 == 1:
            for v in range(idx, idx + n):
                i, j, k = v % nx, (v // nx) % ny, v // (nx * ny)
                top[(i, j)] = max(top.get((i, j), 0.0), oz + (k + 1) * res)
        idx += n
zmax = oz + nz * res

fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 6), gridspec_kw={"width_ratios": [1.2, 1]})
cmap = plt.get_cmap("Greys")
patches, shade = [], []
for (i, j), h in top.items():
    patches.append(Rectangle((ox + i * res, oy + j * res), res, res))
    shade.append(h)
for b in m.boxes:
    patches.append(Rectangle((b[0], b[1]), b[3] - b[0], b[4] - b[1]))
    shade.append(b[5])
if patches:
    pc = PatchCollection(patches, cmap=cmap, alpha=0.7, edgecolor="none")
    pc.set_array([0.25 + 0.75 * min(1.0, (h - oz) / max(zmax - oz, 1e-9)) for h in shade])
    pc.set_clim(0, 1)
    ax.add_collection(pc)
if traj.n_grid_path:
    ax.plot([p[0] for p in traj.grid_path], [p[1] for p in traj.grid_path], color="0.6", lw=0.8,
            label="grid path")
if traj.n_waypoints:
    ax.plot([p[0] for p in traj.waypoints], [p[1] for p in traj.waypoints], "o", ms=3,
            color="tab:orange", label="waypoints")
# The samples when the answer carries them, else the compact form sampled (tdo_compact.py).
rows = traj.samples if traj.n_samples > 0 else tdo_compact.samples(traj, a.step)
speed = [math.sqrt(s[4] ** 2 + s[5] ** 2 + s[6] ** 2) for s in rows]
if len(rows) > 1:
    pts = [(s[1], s[2]) for s in rows]
    lc = LineCollection([[pts[i], pts[i + 1]] for i in range(len(pts) - 1)], cmap="viridis", lw=2)
    lc.set_array(speed[:-1])
    ax.add_collection(lc)
    fig.colorbar(lc, ax=ax, label="speed (m/s)")
    ax.plot(*pts[0], "g^", ms=9, label="start")
    ax.plot(*pts[-1], "r*", ms=12, label="goal")
    t = [s[0] for s in rows]
    ax2.plot(t, speed, label="speed (m/s)")
    ax2.plot(t, [s[3] for s in rows], label="z (m)")
    ax2.set_xlabel("t (s)")
    ax2.legend()
    ax2.grid(alpha=0.3)
ax.set_xlim(ox, ox + nx * res)
ax.set_ylim(oy, oy + ny * res)
ax.set_aspect("equal")
ax.set_xlabel("x (m)")
ax.set_ylabel("y (m)")
ax.legend(loc="upper left", fontsize=8)
title = (f"{os.path.basename(a.log)}: request {traj.request_id} on map {traj.map_id}: "
         f"{traj.status}, {traj.length_m:.1f} m, {traj.flight_time_s:.1f} s")
fig.suptitle(title)
fig.tight_layout()
try:
    fig.savefig(a.output, dpi=90)
except (IOError, OSError, ValueError) as e:
    die(f"{a.output}: cannot write: {e}")
if not os.path.getsize(a.output):
    die(f"{a.output}: empty")
print(f"{PROG}: request {traj.request_id} on map {traj.map_id} ({traj.status}): "
      f"{len(rows)} samples{'' if traj.n_samples else ' (compact form)'}, {traj.length_m:.2f} m, {len(patches)} obstacles -> {a.output}")
