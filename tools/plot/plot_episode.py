#!/usr/bin/env python3
"""Draw a tdo-sim-run episode as a PNG, like the paper's Figure 10: the planned trajectory versus
the executed path, the movers' tracks, the distances over time, and every contact marked.

usage:
  python3 tools/plot/plot_episode.py episode.json -o episode.png [--title TEXT]

episode.json is written by `tdo-sim-run --map FILE -o episode.json` (keys: plan, steps, movers,
boxes, bounds, start, goal, metrics, follower, params). Three panels:
  top view (x-y): the static boxes shaded by height, the plan (blue, dashed), the executed path
    (red), each mover's track (grey; its position at the vehicle's closest approach drawn as a
    circle of its radius), start and goal;
  side view (x-z): the same, heights visible;
  over time: deviation from the plan, the surface gap to the nearest mover and the distance to the
    static geometry.
A contact is a step whose mover gap is below 0 or whose static distance is below the episode's
static_clearance (as tdo-sim-run counts collisions); each is marked with a black cross in both
views and a vertical line over time. Prints "plot_episode: wrote FILE (N contact steps)".
Needs python3 and matplotlib (Agg backend). Exit status 0 written, 2 bad input.
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
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("episode", help="episode JSON written by tdo-sim-run -o")
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    ap.add_argument("--title", default=None, help="title of the top view (default: map and follower)")
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
    # tdo_plot sets the Agg backend and re-executes with Debian's python3 when matplotlib is missing.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from tdo_plot import plt
    from matplotlib.patches import Circle, Rectangle

    steps = ep["steps"]
    plan = ep["plan"]
    m = ep["metrics"]
    limit = ep.get("params", {}).get("static_clearance", 0.0)
    contacts = [s for s in steps
                if (s.get("mover_gap") is not None and s["mover_gap"] < 0.0)
                or (s.get("static_dist") is not None and s["static_dist"] < limit)]
    fig, (ax, axz, ax2) = plt.subplots(1, 3, figsize=(21, 7), gridspec_kw={"width_ratios": [1.2, 1.2, 1]})
    for view, (i, j) in ((ax, (0, 1)), (axz, (0, 2))):
        for b in ep.get("boxes", []):
            lo, hi = b
            shade = 0.25 + 0.5 * min(1.0, hi[2] / 20.0) if j == 1 else 0.35
            view.add_patch(Rectangle((lo[i], lo[j]), hi[i] - lo[i], hi[j] - lo[j], color="0.55", alpha=shade, lw=0))
        if plan:
            view.plot([p[i] for p in plan], [p[j] for p in plan], "b--", lw=1.5, label="planned trajectory")
        if steps:
            view.plot([s["p"][i] for s in steps], [s["p"][j] for s in steps], "r-", lw=1.5,
                      label="executed (" + ep.get("follower", "?") + ")")
        # Movers: tracks, and where each was at the moment the vehicle came closest to it.
        for k_mv, mv in enumerate(ep["movers"]):
            tr = mv["track"]
            if not tr:
                continue
            view.plot([p[i] for p in tr], [p[j] for p in tr], "-", color="0.3", lw=0.8, alpha=0.7,
                      label="mover tracks" if k_mv == 0 else None)
            best, bk = math.inf, 0
            for k, s in enumerate(steps[: len(tr)]):
                d = math.dist(s["p"], tr[k])
                if d < best:
                    best, bk = d, k
            view.add_patch(Circle((tr[bk][i], tr[bk][j]), mv["radius"], fill=False, color="k", lw=1.0))
            view.plot([steps[bk]["p"][i]], [steps[bk]["p"][j]], "k.", ms=4)
        if contacts:
            view.plot([s["p"][i] for s in contacts], [s["p"][j] for s in contacts], "kx", ms=9, mew=2,
                      label="contact (%d steps)" % len(contacts))
        if "start" in ep:
            view.plot(ep["start"][i], ep["start"][j], "go", ms=8, label="start")
        if "goal" in ep:
            view.plot(ep["goal"][i], ep["goal"][j], "m*", ms=12, label="goal")
        if "bounds" in ep:
            lo, hi = ep["bounds"]
            view.set_xlim(lo[i], hi[i])
            view.set_ylim(lo[j], hi[j])
        view.set_aspect("equal")
        view.set_xlabel("x (m)")
        view.set_ylabel("y (m)" if j == 1 else "z (m)")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(a.title or f"{ep.get('map', '')}: {ep.get('follower', '')}, top view")
    axz.set_title("side view")
    t = [s["t"] for s in steps]
    ax2.plot(t, [s["deviation"] for s in steps], "r-", label="deviation from plan (m)")
    gaps = [s["mover_gap"] if s["mover_gap"] is not None else float("nan") for s in steps]
    ax2.plot(t, gaps, "k-", lw=0.8, label="gap to nearest mover (m)")
    if steps and "static_dist" in steps[0]:
        ax2.plot(t, [s["static_dist"] for s in steps], "g-", lw=0.8, label="distance to static geometry (m)")
    for s in contacts:
        ax2.axvline(s["t"], color="k", lw=0.6, alpha=0.6)
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
    print(f"{PROG}: wrote {a.output} ({len(contacts)} contact steps)")


if __name__ == "__main__":
    main()
