#!/usr/bin/env python3
"""Draw a tdo-sim-run episode as a PNG, like the paper's Figure 10: the planned trajectory versus
the executed path, the movers' tracks, and the distances over time.

usage:
  python3 tools/plot/plot_episode.py episode.json -o episode.png [--title TEXT]

episode.json is written by `tdo-sim-run --map FILE -o episode.json` (keys: plan, steps, movers,
boxes, bounds, start, goal, metrics, follower). Left: top view (x-y) with the static boxes shaded,
the plan (blue, dashed), the executed path (red), each mover's track (grey, its position at the
moment of closest approach drawn as a circle of its radius). Right: deviation from the plan and
the surface gap to the nearest mover over time. Needs python3 and matplotlib (Agg backend).
Exit status 0 written, 2 bad input.
"""
import argparse
import json
import math
import os
import sys

PROG = "plot_episode"


def die(msg):
    sys.stderr.write(f"{PROG}: error: {msg}\n")
    sys.exit(2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("episode")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--title", default=None)
    a = ap.parse_args()
    try:
        with open(a.episode) as f:
            ep = json.load(f)
    except OSError as e:
        die(f"{a.episode}: cannot open: {e.strerror}")
    except json.JSONDecodeError as e:
        die(f"{a.episode}: not JSON: {e}")
    for k in ("plan", "steps", "movers", "metrics"):
        if k not in ep:
            die(f"{a.episode}: missing key '{k}' (not a tdo-sim-run episode)")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Circle, Rectangle
    except ImportError:
        # A Python without matplotlib (a venv first on PATH): retry once with Debian's python3.
        alt = "/usr/bin/python3"
        if (os.path.exists(alt) and not os.environ.get("TDO_PLOT_REEXEC")
                and os.path.realpath(sys.executable) != os.path.realpath(alt)):
            os.environ["TDO_PLOT_REEXEC"] = "1"
            os.execv(alt, [alt] + sys.argv)
        die("matplotlib is not installed (Debian: python3-matplotlib)")

    steps = ep["steps"]
    plan = ep["plan"]
    m = ep["metrics"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(15, 7), gridspec_kw={"width_ratios": [1.2, 1]})
    for b in ep.get("boxes", []):
        (x0, y0, _), (x1, y1, z1) = b
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, color="0.55", alpha=0.25 + 0.5 * min(1.0, z1 / 20.0), lw=0))
    if plan:
        ax.plot([p[0] for p in plan], [p[1] for p in plan], "b--", lw=1.5, label="planned trajectory")
    if steps:
        ax.plot([s["p"][0] for s in steps], [s["p"][1] for s in steps], "r-", lw=1.5, label="executed (" + ep.get("follower", "?") + ")")
    # Movers: tracks, and where each was at the moment the vehicle came closest to it.
    for i, mv in enumerate(ep["movers"]):
        tr = mv["track"]
        if not tr:
            continue
        ax.plot([p[0] for p in tr], [p[1] for p in tr], "-", color="0.3", lw=0.8, alpha=0.7, label="mover tracks" if i == 0 else None)
        best, bk = math.inf, 0
        for k, s in enumerate(steps[: len(tr)]):
            d = math.dist(s["p"], tr[k])
            if d < best:
                best, bk = d, k
        ax.add_patch(Circle((tr[bk][0], tr[bk][1]), mv["radius"], fill=False, color="k", lw=1.0))
        ax.plot([steps[bk]["p"][0]], [steps[bk]["p"][1]], "k.", ms=4)
    if "start" in ep:
        ax.plot(ep["start"][0], ep["start"][1], "go", ms=8, label="start")
    if "goal" in ep:
        ax.plot(ep["goal"][0], ep["goal"][1], "m*", ms=12, label="goal")
    if "bounds" in ep:
        (x0, y0, _), (x1, y1, _) = ep["bounds"]
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(a.title or f"{ep.get('map', '')}: {ep.get('follower', '')}")
    t = [s["t"] for s in steps]
    ax2.plot(t, [s["deviation"] for s in steps], "r-", label="deviation from plan (m)")
    gaps = [s["mover_gap"] if s["mover_gap"] is not None else float("nan") for s in steps]
    ax2.plot(t, gaps, "k-", lw=0.8, label="gap to nearest mover (m)")
    ax2.axhline(0.0, color="k", lw=0.5)
    ax2.set_ylim(-0.2, max(3.0, 1.1 * max([s["deviation"] for s in steps] or [0.0])))
    ax2.set_xlabel("t (s)")
    ax2.legend(loc="upper right", fontsize=8)
    ax2.set_title(
        "success %s, collision %s, min sep %.2f m, dev max %.2f / mean %.3f m, LM events %d"
        % (m["success"], m["collision"], m["min_mover_separation_m"] or float("nan"), m["max_deviation_m"],
           m["mean_deviation_m"], m["local_minimum_events"]), fontsize=9)
    fig.tight_layout()
    try:
        fig.savefig(a.output, dpi=110)
    except OSError as e:
        die(f"{a.output}: cannot write: {e.strerror}")


if __name__ == "__main__":
    main()
