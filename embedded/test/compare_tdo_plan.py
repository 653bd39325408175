#!/usr/bin/env python3
"""Check the demo's host twin against an independent program: tdo-plan --json on the same map.

tdo-plan reads the .tdomap file itself, sizes the planner with its own (default) capacities and
prints with printf/JSON; the demo uses the compiled-in map header, the firmware's tighter
capacities and its own number formatting. Both use the default TDO-MSF parameters and clearance
0.5 m, so status, expansions, grid path length, waypoints and metrics must agree to the demo's
9 printed decimals.

usage: compare_tdo_plan.py TDO_PLAN DEMO MAP
"""
import json
import subprocess
import sys


def main() -> int:
    tdo_plan, demo, map_path = sys.argv[1:4]
    ref = json.loads(subprocess.run([tdo_plan, "--map", map_path, "--json", "--retry", "off"], check=True,
                                    capture_output=True, text=True).stdout)
    out = subprocess.run([demo], check=True, capture_output=True, text=True).stdout
    lines = [l for l in out.splitlines() if not l.startswith("@")]
    kv = {}
    wps = []
    for l in lines:
        parts = l.split()
        if parts[:1] == ["wp"]:
            wps.append([float(x) for x in parts[2:5]])
        elif len(parts) >= 2:
            kv.setdefault(parts[0], parts[1])

    errors = []

    def same(name, got, want, tol=5.1e-10):
        if isinstance(want, str) or isinstance(want, bool):
            ok = got == want
        else:
            ok = abs(float(got) - float(want)) <= tol * max(1.0, abs(float(want)))
        print(f"{'ok ' if ok else 'BAD'} {name}: demo {got}  tdo-plan {want}")
        if not ok:
            errors.append(name)

    m = ref["metrics"]
    same("status", kv.get("status"), ref["status"])
    same("expansions", int(kv["expansions"]), m["expansions"], 0)
    same("search_cost_m", kv["search_cost_m"], ref["search_cost"])
    same("grid_path voxels", int(kv["grid_path"]), len(ref["grid_path"]), 0)
    same("waypoints", len(wps), len(ref["waypoints"]), 0)
    for i, (a, b) in enumerate(zip(wps, ref["waypoints"])):
        for axis in range(3):
            same(f"waypoint {i}[{axis}]", a[axis], b[axis])
    for key in ("length_m", "total_turn_deg", "min_clearance_m", "smoothness", "energy",
                "flight_time_s"):
        demo_key = {"energy": "energy_m2ps3"}.get(key, key)
        same(key, kv[demo_key], m[key])
    same("turns", int(kv["turns"]), m["turns"], 0)
    same("avg_curvature", kv["avg_curvature_1pm"], m["avg_curvature"])
    same("samples", int(kv["samples"]), len(ref["trajectory"]["samples"]), 0)
    same("feasible", kv["feasible"] == "1", ref["feasibility"]["ok"] in (True, 1))
    if errors:
        print(f"demo and tdo-plan disagree on: {', '.join(errors)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
