#!/usr/bin/env python3
"""tdo-plan --samples: the output does not depend on whether the library stores the samples.

    check_samples_modes.py TDO_PLAN MAP [MAP ...]

For each map: `--json --samples stored` and `--json --samples streamed` must give the same bytes
once the two fields that may differ are removed: plan_time_ms (wall time) and arena_bytes (the
streamed arena holds no samples, so it must be smaller, which also shows the mode took effect).
The stored run must carry a trajectory of samples every dt ending at the flight time, so a
consumer that drops or truncates the streamed samples fails the comparison. The text output (with
the v/a optimum, read from the samples) must match the same way.

`--samples pieces` (tdo_capacity.stream_samples 2, verified per profile piece in closed form):
the same JSON except what that mode measures differently (trajectory.h, tdo_traj_output): the
energy is the integral of |a|^2 rather than the trapezoid over the samples (within 1e-3 relative:
the trapezoid's O(dt^2) error), the report's maxima are upper bounds of the finite differences (at
least the stored run's), its least turn radius is the path's (1 / its curvature bound) and its
clearance, in the report and the metrics, the bound the planner's stages proved (at most the
stored run's). The samples, the path and every other metric must be identical.
"""
import json
import re
import subprocess
import sys

def run(exe, args):
    return subprocess.run([exe] + args, capture_output=True, text=True, timeout=600)


def strip(out, where):
    """The JSON text without arena_bytes and plan_time_ms (each exactly once), and arena_bytes."""
    text, n_arena = re.subn(r'"arena_bytes":([0-9]+),?', "", out)
    text, n_time = re.subn(r'"plan_time_ms":[-+.0-9eE]+,?', "", text)
    if n_arena != 1 or n_time != 1:
        sys.exit(f"{where}: expected one arena_bytes and one plan_time_ms:\n{out}")
    return text, json.loads(out)["arena_bytes"]


def plan_json(exe, map_path, mode):
    r = run(exe, ["--map", map_path, "--json", "--samples", mode])
    if r.returncode != 0:
        sys.exit(f"{map_path} --samples {mode}: exit {r.returncode}\n{r.stderr}")
    text, arena = strip(r.stdout, f"{map_path} --samples {mode}")
    return text, json.loads(text), arena


def text_lines(exe, map_path, mode):
    r = run(exe, ["--map", map_path, "--optimum", "--samples", mode])
    if r.returncode != 0:
        sys.exit(f"{map_path} --optimum --samples {mode}: exit {r.returncode}\n{r.stderr}")
    out = [l for l in r.stdout.splitlines()
           if not l.startswith("plan_time_ms") and not l.startswith("arena_bytes")]
    if not any(l.startswith("va_optimum_s") for l in out):
        sys.exit(f"{map_path} --samples {mode}: no va_optimum_s line:\n{r.stdout}")
    return out


def check_trajectory(j, where):
    if j["status"] != "ok" or "trajectory" not in j:
        sys.exit(f"{where}: no planned trajectory")
    dt = j["trajectory"]["dt"]
    s = j["trajectory"]["samples"]
    n = round(j["metrics"]["flight_time_s"] / dt) + 1
    if len(s) < 2 or len(s) != n:
        sys.exit(f"{where}: {len(s)} samples, the flight time needs {n}")
    for i, row in enumerate(s):
        if len(row) != 10 or abs(row[0] - i * dt) > 1e-9:
            sys.exit(f"{where}: sample {i} is {row}")
    return len(s)


def check_pieces(stored, pieces, where):
    """--samples pieces against the stored run (see the module comment)."""
    ms, mp = stored["metrics"], pieces["metrics"]
    fs, fp = stored["feasibility"], pieces["feasibility"]
    if abs(mp["energy"] - ms["energy"]) > 1e-3 * abs(ms["energy"]):
        sys.exit(f"{where}: pieces energy {mp['energy']} vs stored {ms['energy']}")
    for key in ("max_speed", "max_acc", "max_jerk"):
        if not fp[key] >= fs[key]:
            sys.exit(f"{where}: pieces {key} {fp[key]} below the samples' {fs[key]}")
    for key in ("min_clearance_m",):
        if not fp[key] <= fs[key]:
            sys.exit(f"{where}: pieces {key} {fp[key]} above the samples' {fs[key]}")
        if not mp[key] <= ms[key]:
            sys.exit(f"{where}: pieces metric {key} {mp[key]} above the stored one {ms[key]}")
    for key in ("energy", "min_clearance_m"):
        del mp[key], ms[key]
    for key in ("max_speed", "max_acc", "max_jerk", "min_turn_radius", "min_clearance_m"):
        del fp[key], fs[key]
    if pieces != stored:
        sys.exit(f"{where}: --samples pieces JSON differs from stored beyond its measures")
    return "pieces: same samples, bounds at or beyond the samples' measures"


def main():
    exe, maps = sys.argv[1], sys.argv[2:]
    if not maps:
        sys.exit("usage: check_samples_modes.py TDO_PLAN MAP [MAP ...]")
    for m in maps:
        a, stored, arena_stored = plan_json(exe, m, "stored")
        n = check_trajectory(stored, f"{m} stored")
        b, streamed, arena_streamed = plan_json(exe, m, "streamed")
        if a != b:
            ns = len(streamed.get("trajectory", {}).get("samples", []))
            sys.exit(f"{m}: stored and streamed JSON differ ({n} vs {ns} samples)")
        if not arena_streamed < arena_stored:
            sys.exit(f"{m}: streamed arena {arena_streamed} not below stored {arena_stored}: "
                     "--samples streamed did not take effect")
        if text_lines(exe, m, "stored") != text_lines(exe, m, "streamed"):
            sys.exit(f"{m}: stored and streamed text output (--optimum) differ")
        c, pj, _ = plan_json(exe, m, "pieces")
        pieces = check_pieces(stored, pj, m)
        print(f"{m}: {n} samples, stored = streamed ({len(a)} bytes of JSON; arena "
              f"{arena_stored} -> {arena_streamed} bytes); {pieces}")
    print("ok")


if __name__ == "__main__":
    main()
