#!/usr/bin/env python3
"""Run tdo-plan --json and check that stdout is one JSON object with the keys interfaces.md names.

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
                "smoothing", "seed", "max_expansions", "max_nodes"):
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
    if abs(length - m["length_m"]) > 1e-9 * max(1.0, length):
        fail(f"length_m {m['length_m']} is not the polyline length {length}", proc)
    if m["turns"] < 0 or m["total_turn_deg"] < 0 or m["expansions"] <= 0:
        fail("metrics out of range", proc)
    print("ok:", doc["planner"], doc["status"], f"{len(path)} points, {m['length_m']:.3f} m")


if __name__ == "__main__":
    main()
