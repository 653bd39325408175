#!/usr/bin/env python3
"""Run tdo-plan --json and check that stdout is one JSON object with the keys of docs/design.md
s.10.

usage: check_plan_json.py TDO_PLAN ARGS...   (the script adds --json)
"""
import json
import math
import subprocess
import sys


def fail(msg, proc=None):
    print("FAIL:", msg)
    if proc is not None:
        print("stdout:", proc.stdout)
        print("stderr:", proc.stderr)
    sys.exit(1)


def check_pipeline(doc, path, grid_length, proc):
    """The full pipeline: waypoints, trajectory and feasibility (docs/design.md s.10)."""
    for key in ("waypoints", "trajectory", "feasibility"):
        if key not in doc:
            fail(f"missing key '{key}'", proc)
    m = doc["metrics"]
    for key in ("min_clearance_m", "avg_curvature", "smoothness", "energy", "flight_time_s"):
        if key not in m or not isinstance(m[key], (int, float)):
            fail(f"missing or non-numeric metrics.{key}", proc)
    wp = doc["waypoints"]
    if wp[0] != path[0] or wp[-1] != path[-1]:
        fail("waypoints do not begin and end at the grid path's exact start and goal", proc)
    wp_length = sum(math.dist(a, b) for a, b in zip(wp, wp[1:]))
    # Shortcuts and corner curves only shorten: path <= waypoint polyline <= grid polyline.
    if wp_length > grid_length + 1e-9 or m["length_m"] > wp_length + 1e-9:
        fail(f"lengths grow: grid {grid_length}, waypoints {wp_length}, path {m['length_m']}",
             proc)
    samples = doc["trajectory"]["samples"]
    if len(samples) < 2 or any(len(q) != 10 for q in samples):
        fail("trajectory.samples must be [t, x, y, z, vx, vy, vz, ax, ay, az] rows", proc)
    if samples[0][1:4] != path[0] or samples[-1][1:4] != path[-1]:
        fail("trajectory does not begin and end exactly at start and goal", proc)
    f = doc["feasibility"]
    for key in ("ok", "max_speed", "max_acc", "max_jerk", "min_turn_radius", "min_clearance_m",
                "violations"):
        if key not in f:
            fail(f"missing feasibility.{key}", proc)
    if f["ok"] is not True or f["violations"]:
        fail("status ok but the feasibility report is not clean", proc)
    if abs(m["flight_time_s"] - samples[-1][0]) > 1e-9:
        fail("flight_time_s is not the last sample's time", proc)


def main():
    cmd = sys.argv[1:] + ["--json"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if proc.returncode != 0:
        fail(f"exit status {proc.returncode}", proc)
    try:
        doc = json.loads(proc.stdout)
    except json.JSONDecodeError as e:
        fail(f"stdout is not JSON: {e}", proc)
    if not isinstance(doc, dict):
        fail("stdout is not a JSON object", proc)
    for key in ("status", "planner", "params", "grid_path", "metrics"):
        if key not in doc:
            fail(f"missing key '{key}'", proc)
    if doc["status"] != "ok":
        fail(f"status {doc['status']!r}", proc)
    for key in ("lambda", "mu", "theta_max_deg", "clearance", "v_max", "a_max", "j_max", "k", "dt",
                "smoothing", "seed", "max_expansions", "max_nodes", "retry"):
        if key not in doc["params"]:
            fail(f"missing params.{key}", proc)
    m = doc["metrics"]
    for key in ("length_m", "turns", "total_turn_deg", "plan_time_ms", "expansions"):
        if key not in m or not isinstance(m[key], (int, float)):
            fail(f"missing or non-numeric metrics.{key}", proc)
    path = doc["grid_path"]
    if len(path) < 2 or any(len(p) != 3 for p in path):
        fail("grid_path must hold at least two [x, y, z] points", proc)
    if "--start" in cmd:
        i = cmd.index("--start")
        start = [float(v) for v in cmd[i + 1:i + 4]]
        if path[0] != start:
            fail(f"grid_path starts at {path[0]}, not at the exact start {start}", proc)
    if "--goal" in cmd:
        i = cmd.index("--goal")
        goal = [float(v) for v in cmd[i + 1:i + 4]]
        if path[-1] != goal:
            fail(f"grid_path ends at {path[-1]}, not at the exact goal {goal}", proc)
    length = sum(math.dist(a, b) for a, b in zip(path, path[1:]))
    if doc["planner"] in ("astar", "bidir"):
        if abs(length - m["length_m"]) > 1e-9 * max(1.0, length):
            fail(f"length_m {m['length_m']} is not the polyline length {length}", proc)
    else:
        check_pipeline(doc, path, length, proc)
    if m["turns"] < 0 or m["total_turn_deg"] < 0 or m["expansions"] <= 0:
        fail("metrics out of range", proc)
    print("ok:", doc["planner"], doc["status"], f"{len(path)} points, {m['length_m']:.3f} m")


if __name__ == "__main__":
    main()
