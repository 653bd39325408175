#!/usr/bin/env python3
"""Draw a map and a tdo-plan result as a PNG: a top view (x-y) and a 3D view.

usage:
  python3 tools/plot/tdo_plot.py --map maps/map5.tdomap [--plan plan.json] -o out.png

--map   .tdomap (boxes, start/goal, movers), MovingAI .3dmap, OctoMap .bt/.ot (occupied voxels;
        read here in pure Python, no OctoMap bindings needed)
--plan  the JSON object of `tdo-plan --json` (docs/design.md s.10): grid_path, waypoints,
        trajectory.samples [[t, x,y,z, vx,vy,vz, ax,ay,az], ...], metrics, planner, status;
        every key is optional.

Draws the grid path (thin grey), the corrected waypoints (markers), the smoothed trajectory
(coloured by speed), start and goal; obstacles shaded by height. Needs only python3 and matplotlib
(Debian: python3-matplotlib); renders with the Agg backend. Exit status 0 written, 2 bad input.
"""
import argparse
import json
import math
import os
import struct
import sys

PROG = "tdo_plot"


def die(msg):
    sys.stderr.write(f"{PROG}: error: {msg}\n")
    sys.exit(2)


try:
    import matplotlib
except ImportError:
    # A Python without matplotlib (say, a pyenv shim first on PATH): retry with Debian's python3.
    _alt = "/usr/bin/python3"
    if (os.path.exists(_alt) and not os.environ.get("TDO_PLOT_REEXEC")
            and os.path.realpath(sys.executable) != os.path.realpath(_alt)):
        os.environ["TDO_PLOT_REEXEC"] = "1"
        os.execv(_alt, [_alt] + sys.argv)
    die("matplotlib is not installed (Debian: apt-get install python3-matplotlib)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import cm, colors  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Circle, Patch, Rectangle  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402


class BadInput(Exception):
    pass


# ------------------------------------------------------------------------------------ maps

class Map:
    def __init__(self, path):
        self.path = path
        self.kind = ""
        self.bounds = None  # ((xmin, ymin, zmin), (xmax, ymax, zmax))
        self.res = None
        self.boxes = []  # [(x0, y0, z0, x1, y1, z1)]
        self.cubes = []  # [(cx, cy, cz, size)] occupied voxels / leaves
        self.start = None
        self.goal = None
        self.movers = []  # [(id, (x, y, z), (vx, vy, vz), r)]


def _floats(tokens, n, where):
    if len(tokens) != n:
        raise BadInput(f"{where}: expected {n} numbers, got {len(tokens)}")
    try:
        vals = [float(t) for t in tokens]
    except ValueError:
        raise BadInput(f"{where}: expected numbers, got {' '.join(tokens)!r}")
    if not all(math.isfinite(v) for v in vals):
        raise BadInput(f"{where}: non-finite number")
    return vals


def read_tdomap(path, text):
    m = Map(path)
    m.kind = "tdomap"
    header = False
    for no, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].split()
        if not line:
            continue
        where = f"{path}:{no}"
        kw, args = line[0], line[1:]
        if not header:
            if kw != "tdomap" or args != ["1"]:
                raise BadInput(f"{where}: missing header 'tdomap 1'")
            header = True
        elif kw == "bounds":
            v = _floats(args, 6, where)
            m.bounds = (tuple(v[:3]), tuple(v[3:]))
        elif kw == "resolution":
            m.res = _floats(args, 1, where)[0]
        elif kw == "box":
            v = _floats(args, 6, where)
            m.boxes.append(tuple(v))
        elif kw == "start":
            m.start = tuple(_floats(args, 3, where))
        elif kw == "goal":
            m.goal = tuple(_floats(args, 3, where))
        elif kw == "mover":
            v = _floats(args, 8, where)
            m.movers.append((int(v[0]), tuple(v[1:4]), tuple(v[4:7]), v[7]))
        else:
            raise BadInput(f"{where}: unknown keyword '{kw}'")
    if not header:
        raise BadInput(f"{path}: missing header 'tdomap 1' (empty file)")
    if m.bounds is None:
        raise BadInput(f"{path}: missing 'bounds'")
    return m


def read_3dmap(path, text):
    m = Map(path)
    m.kind = "3dmap"
    lines = text.splitlines()
    if not lines or not lines[0].startswith("voxel"):
        raise BadInput(f"{path}:1: missing header 'voxel X Y Z'")
    size = _floats(lines[0].split()[1:], 3, f"{path}:1")
    for no, raw in enumerate(lines[1:], 2):
        t = raw.split()
        if t:
            x, y, z = _floats(t, 3, f"{path}:{no}")
            m.cubes.append((x, y, z, 1.0))
    m.bounds = ((-0.5, -0.5, -0.5), tuple(s - 0.5 for s in size))
    m.res = 1.0
    return m


BT_HEADER = b"# Octomap OcTree binary file"
OT_HEADER = b"# Octomap OcTree file"


def _octree_header(path, data):
    """Parse the text header of .bt/.ot files; returns (res, offset of the data)."""
    pos = 0
    res = None
    tree_id = None
    while True:
        end = data.find(b"\n", pos)
        if end < 0:
            raise BadInput(f"{path}: truncated OcTree header")
        line = data[pos:end].strip()
        pos = end + 1
        if line.startswith(b"#") or not line:
            continue
        parts = line.split()
        if parts[0] == b"id" and len(parts) > 1:
            tree_id = parts[1].decode("ascii", "replace")
        elif parts[0] == b"res" and len(parts) > 1:
            res = float(parts[1])
        elif parts[0] == b"data":
            break
    if tree_id != "OcTree":
        raise BadInput(f"{path}: tree type {tree_id!r} is not supported (only OcTree)")
    if res is None or not res > 0:
        raise BadInput(f"{path}: OcTree header without a valid 'res'")
    return res, pos


def _child_centre(c, half, i):
    q = half / 2.0
    return (c[0] + (q if i & 1 else -q), c[1] + (q if i & 2 else -q), c[2] + (q if i & 4 else -q))


def read_octree(path, data):
    """OcTree in pure Python: .bt (2 bits per child) or .ot (log-odds float + child bitset)."""
    m = Map(path)
    m.kind = "octree"
    binary = data.startswith(BT_HEADER)
    if not binary and not data.startswith(OT_HEADER):
        raise BadInput(f"{path}: not an OctoMap file (first line should start with "
                       f"'{BT_HEADER.decode()}' or '{OT_HEADER.decode()}')")
    res, pos = _octree_header(path, data)
    root_half = res * 32768.0  # 16 levels, root centred at the origin
    leaves = []
    try:
        if binary:
            # Depth-first in file order: each inner node stores two bytes (4 children x 2 bits).
            # 'half' is the node's half edge, which is the edge of its children.
            def node(c, half):
                nonlocal pos
                b = data[pos] | (data[pos + 1] << 8)
                pos += 2
                inner = []
                for i in range(8):
                    bits = (b >> (2 * i)) & 3
                    if bits == 2:  # occupied leaf
                        leaves.append((_child_centre(c, half, i), half))
                    elif bits == 3:
                        inner.append(i)
                for i in inner:
                    node(_child_centre(c, half, i), half / 2.0)
            node((0.0, 0.0, 0.0), root_half)
        else:
            def node_ot(c, half):
                nonlocal pos
                (logodds,) = struct.unpack_from("<f", data, pos)
                children = data[pos + 4]
                pos += 5
                if children == 0:
                    if logodds >= 0.0:  # OcTree's default threshold, probability 0.5
                        leaves.append((c, 2.0 * half))
                    return
                for i in range(8):
                    if children & (1 << i):
                        node_ot(_child_centre(c, half, i), half / 2.0)
            node_ot((0.0, 0.0, 0.0), root_half)
    except (IndexError, struct.error):
        raise BadInput(f"{path}: truncated OcTree data")
    if not leaves:
        raise BadInput(f"{path}: no occupied voxels in the tree")
    # Occupied leaves as cubes; bounds = their bounding box.
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for c, size in leaves:
        for a in range(3):
            lo[a] = min(lo[a], c[a] - size / 2)
            hi[a] = max(hi[a], c[a] + size / 2)
        m.cubes.append((c[0], c[1], c[2], size))
    m.bounds = (tuple(lo), tuple(hi))
    m.res = res
    return m


def read_map(path):
    ext = os.path.splitext(path)[1].lower()
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise BadInput(f"{path}: cannot open ({e.strerror})")
    if ext in (".bt", ".ot"):
        return read_octree(path, data)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise BadInput(f"{path}: not a text map file")
    if ext == ".tdomap":
        return read_tdomap(path, text)
    if ext == ".3dmap":
        return read_3dmap(path, text)
    raise BadInput(f"{path}: unknown map format '{ext}' (expected .tdomap, .3dmap, .bt or .ot)")


# ------------------------------------------------------------------------------------ plan

def _points(value, width, name, path):
    if value is None:
        return []
    if not isinstance(value, list):
        raise BadInput(f"{path}: '{name}' must be a list")
    out = []
    for p in value:
        if not isinstance(p, list) or len(p) < width or not all(
                isinstance(v, (int, float)) for v in p[:width]):
            raise BadInput(f"{path}: '{name}' entries must be lists of {width} numbers")
        out.append([float(v) for v in p[:width]])
    return out


def read_plan(path):
    try:
        with open(path, "r", encoding="utf-8") as f:
            doc = json.load(f)
    except OSError as e:
        raise BadInput(f"{path}: cannot open ({e.strerror})")
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise BadInput(f"{path}: not valid JSON ({e})")
    if not isinstance(doc, dict):
        raise BadInput(f"{path}: expected one JSON object (tdo-plan --json)")
    traj = doc.get("trajectory")
    samples = []
    if traj is not None:
        if not isinstance(traj, dict):
            raise BadInput(f"{path}: 'trajectory' must be an object")
        samples = _points(traj.get("samples"), 4, "trajectory.samples", path)
        # keep the velocity columns when present
        raw = traj.get("samples") or []
        for s, r in zip(samples, raw):
            s.extend(float(v) for v in r[4:7] if isinstance(v, (int, float)))
    metrics = doc.get("metrics") if isinstance(doc.get("metrics"), dict) else {}
    return {
        "planner": doc.get("planner"),
        "status": doc.get("status"),
        "grid_path": _points(doc.get("grid_path"), 3, "grid_path", path),
        "waypoints": _points(doc.get("waypoints"), 3, "waypoints", path),
        "samples": samples,
        "metrics": metrics,
    }


# ------------------------------------------------------------------------------------ drawing

HEIGHT_CMAP = "Greys"
# plasma without its palest yellow, which vanishes on a white background
SPEED_CMAP = colors.LinearSegmentedColormap.from_list(
    "tdo_speed", [plt.get_cmap("plasma")(x / 20.0 * 0.85) for x in range(21)])


def _height_norm(m):
    (x0, y0, z0), (x1, y1, z1) = m.bounds
    return colors.Normalize(vmin=z0, vmax=z1)


def _box_faces(b):
    x0, y0, z0, x1, y1, z1 = b
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    idx = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 3, 7, 4)]
    return [[v[i] for i in f] for f in idx]


def draw_top(ax, m, plan, norm, speed_norm):
    (x0, y0, _), (x1, y1, _) = m.bounds
    cmap = matplotlib.colormaps[HEIGHT_CMAP] if hasattr(matplotlib, "colormaps") else cm.get_cmap(
        HEIGHT_CMAP)
    mappable = cm.ScalarMappable(norm=norm, cmap=cmap)
    extra_handles = []
    if m.boxes:
        # Lower boxes first so taller ones stay visible on top. Boxes that do not stand on the
        # ground (beams, lintels, slabs) are hatched: one can fly under them.
        ground_z = m.bounds[0][2]
        rects, shades, hanging = [], [], []
        for b in sorted(m.boxes, key=lambda b: (b[5], b[2])):
            r = Rectangle((b[0], b[1]), b[3] - b[0], b[4] - b[1])
            if b[2] > ground_z + 1e-9:
                hanging.append((r, cmap(0.25 + 0.75 * norm(b[5]))))
            else:
                rects.append(r)
                shades.append(0.25 + 0.75 * norm(b[5]))
        pc = PatchCollection(rects, facecolor=cmap(shades), edgecolor="black", linewidth=0.3,
                             zorder=1)
        ax.add_collection(pc)
        for r, col in hanging:
            r.set_facecolor((*col[:3], 0.35))
            r.set_edgecolor("tab:blue")
            r.set_hatch("////")
            r.set_linewidth(0.4)
            r.set_zorder(2)
            ax.add_patch(r)
        if hanging:
            extra_handles.append(Patch(facecolor="white", edgecolor="tab:blue", hatch="////",
                                       label="overhead (z min > 0)"))
    if m.cubes:
        # Height map: the top of the highest occupied voxel per x-y cell.
        res = min(c[3] for c in m.cubes)
        nx = max(1, int(math.ceil((x1 - x0) / res)))
        ny = max(1, int(math.ceil((y1 - y0) / res)))
        scale = max(1.0, math.sqrt(nx * ny / 1.5e6))  # cap the image size
        cell = res * scale
        nx = max(1, int(math.ceil((x1 - x0) / cell)))
        ny = max(1, int(math.ceil((y1 - y0) / cell)))
        top = [[math.nan] * nx for _ in range(ny)]
        for cx, cy, cz, s in m.cubes:
            zt = cz + s / 2
            i0 = int((cx - s / 2 - x0) / cell + 1e-9)
            i1 = int(math.ceil((cx + s / 2 - x0) / cell - 1e-9))
            j0 = int((cy - s / 2 - y0) / cell + 1e-9)
            j1 = int(math.ceil((cy + s / 2 - y0) / cell - 1e-9))
            for j in range(max(j0, 0), min(j1, ny)):
                row = top[j]
                for i in range(max(i0, 0), min(i1, nx)):
                    if not zt <= row[i]:
                        row[i] = zt
        masked = [[(0.25 + 0.75 * norm(v)) if v == v else math.nan for v in row] for row in top]
        ax.imshow(masked, origin="lower", extent=(x0, x0 + nx * cell, y0, y0 + ny * cell),
                  cmap=cmap, vmin=0.0, vmax=1.0, interpolation="nearest", zorder=1)
    for mid, p, v, r in m.movers:
        ax.add_patch(Circle((p[0], p[1]), r, facecolor="tab:cyan", edgecolor="tab:blue",
                            alpha=0.6, zorder=3))
        ax.annotate("", xy=(p[0] + 3 * v[0], p[1] + 3 * v[1]), xytext=(p[0], p[1]),
                    arrowprops=dict(arrowstyle="->", color="tab:blue", lw=1.0), zorder=3)
    if plan:
        gp = plan["grid_path"]
        if gp:
            ax.plot([p[0] for p in gp], [p[1] for p in gp], color="0.45", lw=0.9, zorder=4,
                    label="grid path")
        wp = plan["waypoints"]
        if wp:
            ax.plot([p[0] for p in wp], [p[1] for p in wp], ls="none", marker="s", ms=5,
                    mfc="white", mec="tab:orange", mew=1.5, zorder=6, label="waypoints")
        ss = plan["samples"]
        if len(ss) >= 2:
            segs = [[(a[1], a[2]), (b[1], b[2])] for a, b in zip(ss[:-1], ss[1:])]
            lc = LineCollection(segs, cmap=SPEED_CMAP, norm=speed_norm, lw=2.2, zorder=5)
            lc.set_array(_speeds(ss)[:-1])
            ax.add_collection(lc)
            ax.plot([], [], color=SPEED_CMAP(0.6), lw=2.2, label="trajectory")
    _start_goal(ax, m, plan, three_d=False)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("top view (obstacles shaded by height)", fontsize=10)
    ax.grid(True, lw=0.3, alpha=0.5)
    handles, _ = ax.get_legend_handles_labels()
    if handles or extra_handles:
        ax.legend(handles=handles + extra_handles, loc="upper left", fontsize=8, framealpha=0.85)
    return mappable


def _speeds(ss):
    out = []
    for s in ss:
        if len(s) >= 7:
            out.append(math.sqrt(s[4] ** 2 + s[5] ** 2 + s[6] ** 2))
        else:
            out.append(0.0)
    if all(v == 0.0 for v in out) and len(ss) >= 2:  # no velocities: finite differences
        out = []
        for a, b in zip(ss[:-1], ss[1:]):
            dt = b[0] - a[0]
            d = math.dist(a[1:4], b[1:4])
            out.append(d / dt if dt > 0 else 0.0)
        out.append(out[-1])
    return out


def _endpoints(m, plan):
    start, goal = m.start, m.goal
    if plan:
        for key in ("samples", "waypoints", "grid_path"):
            pts = plan[key]
            if pts:
                p0 = pts[0][1:4] if key == "samples" else pts[0]
                p1 = pts[-1][1:4] if key == "samples" else pts[-1]
                start, goal = tuple(p0), tuple(p1)
                break
    return start, goal


def _start_goal(ax, m, plan, three_d):
    start, goal = _endpoints(m, plan)
    for p, mk, col, name in ((start, "^", "tab:green", "start"), (goal, "*", "tab:red", "goal")):
        if p is None:
            continue
        if three_d:
            ax.scatter([p[0]], [p[1]], [p[2]], marker=mk, s=140, c=col, edgecolors="black",
                       depthshade=False, zorder=10)
        else:
            ax.plot([p[0]], [p[1]], marker=mk, ms=13, color=col, mec="black", ls="none",
                    zorder=10, label=name)


def draw_3d(ax, m, plan, norm, speed_norm, max_points, zoom=1.0):
    (x0, y0, z0), (x1, y1, z1) = m.bounds
    cmap = plt.get_cmap(HEIGHT_CMAP)
    if m.boxes:
        # Sides fade with the number of boxes so dense maps stay readable; tops stay visible.
        side_alpha = min(0.3, max(0.03, 0.9 / math.sqrt(len(m.boxes))))
        faces, fcs = [], []
        for b in m.boxes:
            shade = cmap(0.25 + 0.75 * norm(b[5]))
            for n, f in enumerate(_box_faces(b)):
                faces.append(f)
                fcs.append((*shade[:3], 0.55 if n == 1 else side_alpha))
        pc = Poly3DCollection(faces, facecolors=fcs, edgecolors=(0, 0, 0, 0.12), linewidths=0.2)
        ax.add_collection3d(pc)
    if m.cubes:
        cubes = m.cubes
        step = max(1, len(cubes) // max_points)
        pts = cubes[::step]
        ax.scatter([c[0] for c in pts], [c[1] for c in pts], [c[2] for c in pts], s=1.0,
                   c=[c[2] for c in pts], cmap="Greys", norm=colors.Normalize(z0 - (z1 - z0), z1),
                   alpha=0.25, depthshade=False, linewidths=0)
    for mid, p, v, r in m.movers:
        ax.scatter([p[0]], [p[1]], [p[2]], s=40 * r, c="tab:cyan", edgecolors="tab:blue",
                   depthshade=False)
    if plan:
        gp = plan["grid_path"]
        if gp:
            ax.plot([p[0] for p in gp], [p[1] for p in gp], [p[2] for p in gp], color="0.3",
                    lw=1.0)
        wp = plan["waypoints"]
        if wp:
            ax.plot([p[0] for p in wp], [p[1] for p in wp], [p[2] for p in wp], ls="none",
                    marker="s", ms=4, mfc="white", mec="tab:orange", mew=1.3)
        ss = plan["samples"]
        if len(ss) >= 2:
            segs = [[tuple(a[1:4]), tuple(b[1:4])] for a, b in zip(ss[:-1], ss[1:])]
            lc = Line3DCollection(segs, cmap=SPEED_CMAP, norm=speed_norm, lw=2.2)
            lc.set_array(_speeds(ss)[:-1])
            ax.add_collection3d(lc)
    _start_goal(ax, m, plan, three_d=True)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_zlim(z0, z1)
    aspect = (x1 - x0, y1 - y0, max(z1 - z0, 0.25 * max(x1 - x0, y1 - y0)))
    try:
        ax.set_box_aspect(aspect, zoom=zoom)
    except TypeError:  # matplotlib < 3.3: no zoom
        ax.set_box_aspect(aspect)
    except AttributeError:
        pass
    ax.view_init(elev=28, azim=-125)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title("3D view", fontsize=10)


def _title(m, plan):
    name = os.path.basename(m.path)
    if not plan:
        return name
    head = f"{name}: {plan.get('planner') or 'plan'}"
    if plan.get("status") and plan["status"] != "ok":
        head += f" ({plan['status']})"
    mt = plan["metrics"]
    parts = []
    fmt = [("length_m", "length {:.2f} m"), ("turns", "turns {:g}"),
           ("total_turn_deg", "total turn {:.0f} deg"), ("min_clearance_m", "min clearance {:.2f} m"),
           ("avg_curvature", "avg curvature {:.3f} 1/m"), ("flight_time_s", "flight {:.1f} s"),
           ("plan_time_ms", "planned in {:.2f} ms")]
    for key, f in fmt:
        if key == "flight_time_s" and not plan["samples"]:
            continue  # no trajectory: nothing was flown
        v = mt.get(key)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
            parts.append(f.format(v))
    return head + ("\n" + ", ".join(parts) if parts else "")


def render(m, plan, out, max_points, dpi):
    norm = _height_norm(m)
    speeds = _speeds(plan["samples"]) if plan and len(plan["samples"]) >= 2 else []
    speed_norm = colors.Normalize(vmin=0.0, vmax=max(max(speeds), 1e-9)) if speeds else None
    (x0, y0, _), (x1, y1, _) = m.bounds
    stacked = (x1 - x0) > 1.8 * (y1 - y0)
    if stacked:  # long and narrow (a building floor): views stacked
        fig = plt.figure(figsize=(13, 12))
        grid = fig.add_gridspec(2, 1, height_ratios=(1.0, 1.25))
        ax1 = fig.add_subplot(grid[0])
        ax2 = fig.add_subplot(grid[1], projection="3d")
    else:
        fig = plt.figure(figsize=(15, 7))
        ax1 = fig.add_subplot(1, 2, 1)
        ax2 = fig.add_subplot(1, 2, 2, projection="3d")
    mappable = draw_top(ax1, m, plan, norm, speed_norm)
    draw_3d(ax2, m, plan, norm, speed_norm, max_points, zoom=1.45 if stacked else 1.0)
    cb = fig.colorbar(mappable, ax=ax1, fraction=0.04, pad=0.02)
    cb.set_label("obstacle height (m)")
    if speed_norm is not None:
        sm = cm.ScalarMappable(norm=speed_norm, cmap=SPEED_CMAP)
        cb2 = fig.colorbar(sm, ax=ax2, fraction=0.03, pad=0.08, shrink=0.7)
        cb2.set_label("trajectory speed (m/s)")
    fig.suptitle(_title(m, plan), fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    try:
        fig.savefig(out, dpi=dpi, bbox_inches="tight", pad_inches=0.15)
    except OSError as e:
        raise BadInput(f"{out}: cannot write ({e.strerror})")
    plt.close(fig)


def crop_z(m, zmin, zmax):
    """Keep only obstacle geometry with zmin <= z <= zmax (e.g. below a building's ceiling)."""
    if zmin is None and zmax is None:
        return
    lo = -math.inf if zmin is None else zmin
    hi = math.inf if zmax is None else zmax
    if not lo < hi:
        raise BadInput("--zmin must be below --zmax")
    m.cubes = [c for c in m.cubes if lo <= c[2] <= hi]
    boxes = []
    for b in m.boxes:
        z0, z1 = max(b[2], lo), min(b[5], hi)
        if z0 < z1:
            boxes.append((b[0], b[1], z0, b[3], b[4], z1))
    m.boxes = boxes


def main(argv):
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--map", required=True, help=".tdomap, .3dmap, .bt or .ot map file")
    ap.add_argument("--plan", help="JSON of tdo-plan --json (optional)")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--max-points", type=int, default=40000,
                    help="voxels drawn in the 3D view of voxel maps (subsampled beyond)")
    ap.add_argument("--dpi", type=int, default=110)
    ap.add_argument("--zmin", type=float, help="draw only obstacles above this height (m)")
    ap.add_argument("--zmax", type=float,
                    help="draw only obstacles below this height (m), e.g. under a ceiling")
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:
        sys.exit(0 if e.code == 0 else 2)
    if args.max_points < 1 or not 20 <= args.dpi <= 600:
        die("--max-points must be >= 1 and --dpi in [20, 600]")
    try:
        m = read_map(args.map)
        crop_z(m, args.zmin, args.zmax)
        plan = read_plan(args.plan) if args.plan else None
        render(m, plan, args.output, args.max_points, args.dpi)
    except BadInput as e:
        die(str(e))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
