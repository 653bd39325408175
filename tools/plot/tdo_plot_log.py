#!/usr/bin/env python3
"""Plot a run from an LCM log (scripts/lcm-logger, tdo-make-replay-log).

Draws, for one answer on TDO_TRAJECTORY (default: the last successful one):
  - top view: the map it was planned on (boxes and run-length voxels, shaded by height), the
    planned trajectory coloured by speed, the grid path and waypoints, start and goal, the other
    plans of the same vehicle in the log (replans, thin grey), the executed path of that vehicle
    (TDO_UAV_STATE, red) and the moving obstacles' tracks (TDO_OBSTACLES, grey dots);
  - side view: height over the horizontal distance flown, planned and executed;
  - speed and height over time, planned and executed (time from the first state).
The planned trajectory comes from the answer's samples when it carries them (SAMPLES_ON), else
from its compact form sampled every --step s (tools/plot/tdo_compact.py).

usage (the project venv's Python, which has the lcm wheel; the generated Python types are built
into build/lcmtypes/python):
  .venv/bin/python tools/plot/tdo_plot_log.py LOG [--request-id N] [--types DIR] -o run.png

Exit status 0 written, 2 bad input (no such log, no answer, no types, cannot write).
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


ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("log", help="LCM log file (lcm-logger format)")
ap.add_argument("--request-id", type=int,
                help="plot the answer to this request (default: the last successful one)")
ap.add_argument("--types", default=os.path.join(ROOT, "build", "lcmtypes", "python"),
                help="directory of the generated Python types (package tdo)")
ap.add_argument("--map-channel", default="TDO_MAP", help="maps (default TDO_MAP)")
ap.add_argument("--trajectory-channel", default="TDO_TRAJECTORY",
                help="answers (default TDO_TRAJECTORY)")
ap.add_argument("--state-channel", default="TDO_UAV_STATE",
                help="vehicle states: the executed path (default TDO_UAV_STATE)")
ap.add_argument("--obstacles-channel", default="TDO_OBSTACLES",
                help="moving obstacles: their tracks (default TDO_OBSTACLES)")
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
states = []      # vehicle_state_t, in log order
tracks = {}      # mover id -> [(x, y, z)]
try:
    for ev in log:
        try:
            if ev.channel == a.state_channel:
                states.append(tdo.vehicle_state_t.decode(ev.data))
            elif ev.channel == a.obstacles_channel:
                o = tdo.obstacles_t.decode(ev.data)
                for i, mid in enumerate(o.id[:o.n]):
                    tracks.setdefault(mid, []).append(tuple(o.position[i]))
            elif ev.channel == a.map_channel:
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

fig = plt.figure(figsize=(15, 7))
grid = fig.add_gridspec(2, 2, width_ratios=[1.2, 1])
ax = fig.add_subplot(grid[:, 0])
ax3 = fig.add_subplot(grid[0, 1])  # side view
ax2 = fig.add_subplot(grid[1, 1])  # over time
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
def rows_of(t):
    return t.samples if t.n_samples > 0 else tdo_compact.samples(t, a.step)


rows = rows_of(traj)
# Replans: the vehicle's other successful plans in the log, thin and grey under this one.
others = [t for t, _ in runs if t is not traj and t.vehicle_id == traj.vehicle_id
          and t.map_id == traj.map_id
          and t.status == "ok" and (t.n_samples > 0 or t.n_pieces > 0)]
for i, t in enumerate(others):
    r = rows_of(t)
    ax.plot([q[1] for q in r], [q[2] for q in r], color="0.55", lw=0.6,
            label="other plans" if i == 0 else None)
# Movers' tracks and the executed path of this vehicle.
for i, tr in enumerate(tracks.values()):
    ax.plot([q[0] for q in tr], [q[1] for q in tr], ".", color="0.35", ms=1,
            label="movers" if i == 0 else None)
flown = [st for st in states if st.vehicle_id == traj.vehicle_id]
if flown:
    ax.plot([st.position[0] for st in flown], [st.position[1] for st in flown], color="tab:red",
            lw=1.2, label="executed")


def along(points):
    """Horizontal distance flown at each point (m)."""
    d, out = 0.0, []
    for i, q in enumerate(points):
        if i:
            d += math.hypot(q[0] - points[i - 1][0], q[1] - points[i - 1][1])
        out.append(d)
    return out


if len(rows) > 1:
    ax3.plot(along([(q[1], q[2]) for q in rows]), [q[3] for q in rows], label="planned")
if flown:
    ax3.plot(along([(st.position[0], st.position[1]) for st in flown]),
             [st.position[2] for st in flown], color="tab:red", label="executed")
ax3.set_xlabel("horizontal distance flown (m)")
ax3.set_ylabel("z (m)")
ax3.set_title("side view", fontsize=9)
ax3.grid(alpha=0.3)
if len(rows) > 1 or flown:
    ax3.legend(fontsize=8)
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
    if flown:
        t0 = flown[0].utime
        ax2.plot([(st.utime - t0) * 1e-6 for st in flown],
                 [math.sqrt(sum(v * v for v in st.velocity)) for st in flown], "--",
                 color="tab:red", label="executed speed (m/s)")
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
      f"{len(rows)} samples{'' if traj.n_samples else ' (compact form)'}, {traj.length_m:.2f} m, "
      f"{len(patches)} obstacles, {len(flown)} states, {len(tracks)} movers, "
      f"{len(others)} other plans -> {a.output}")
