#!/usr/bin/env python3
"""CTest check of tdo-bench --test: the tables are produced and well-formed.

usage: check_bench_tables.py TDO_BENCH OUT_DIR

Runs the bench in test mode, then parses every CSV and Markdown table it wrote: headers, column
counts, numeric cells, planners and maps present, and recomputes the success counts of the
comparison table from runs.csv (independently of the bench's own aggregation).
"""
import csv
import json
import math
import os
import subprocess
import sys

PLANNERS = ["tdo", "msf-mtpo", "astar", "rrtconnect", "rrtconnect-simplify", "rrtstar",
            "rrtstar-simplify", "pso", "gwo"]
MODELS = ["model-a", "model-b", "model-c", "model-d", "model-e", "tdo"]
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)


def number(cell, what):
    if cell == "-":
        return math.nan
    try:
        return float(cell)
    except ValueError:
        failures.append(f"{what}: not a number: {cell!r}")
        return math.nan


def read_csv(path, header_start):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    check(len(rows) >= 2, f"{path}: no data rows")
    check(rows[0][:len(header_start)] == header_start, f"{path}: header {rows[0]}")
    for i, r in enumerate(rows[1:], 2):
        check(len(r) == len(rows[0]), f"{path}:{i}: {len(r)} cells, header has {len(rows[0])}")
    return [dict(zip(rows[0], r)) for r in rows[1:]]


def md_tables(path):
    """Every Markdown table in the file as a list of rows (lists of cells); checks the shape."""
    tables, cur = [], None
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("|"):
                check(line.endswith("|"), f"{path}:{n}: row does not end with |")
                cells = [c.strip() for c in line.strip("|").split("|")]
                if cur is None:
                    cur = [cells]
                else:
                    check(len(cells) == len(cur[0]), f"{path}:{n}: {len(cells)} cells, header {len(cur[0])}")
                    cur.append(cells)
            elif cur is not None:
                tables.append(cur)
                cur = None
    if cur is not None:
        tables.append(cur)
    for t in tables:
        check(len(t) >= 3, f"{path}: table without rows: {t[0]}")
        check(all(set(c) <= set("-:") and c for c in t[1]), f"{path}: bad separator {t[1]}")
    return tables


def main():
    exe, out = sys.argv[1], sys.argv[2]
    proc = subprocess.run([exe, "--test", "--out", out, "--no-progress"], capture_output=True,
                          text=True, timeout=1500)
    if proc.returncode != 0:
        print(proc.stdout, proc.stderr)
        print(f"tdo-bench exited with {proc.returncode}")
        return 1

    runs = read_csv(os.path.join(out, "runs.csv"), ["set", "map", "query", "planner", "seed", "ok"])
    for r in runs:
        check(r["ok"] in ("0", "1"), f"runs.csv: ok = {r['ok']}")
        if r["ok"] == "1":
            check(r["status"].startswith("ok"), f"runs.csv: ok run with status {r['status']}")
            for k in ("length_m", "turns", "min_clearance_m", "plan_time_ms"):
                check(number(r[k], k) >= 0, f"runs.csv: {k} = {r[k]}")
            check(number(r["min_clearance_m"], "clearance") >= 0.5 - 1e-9,
                  f"runs.csv: {r['planner']} on {r['map']} below the clearance: {r['min_clearance_m']}")
        else:
            check(not r["status"].startswith("ok"), f"runs.csv: failed run with status {r['status']}")
    sets = {r["set"] for r in runs}
    check(sets == {"paper", "random", "forest"}, f"runs.csv: sets {sets}")

    comp = read_csv(os.path.join(out, "table_compare.csv"), ["map", "planner", "runs", "ok", "success"])
    check([r["planner"] for r in comp] == PLANNERS, f"table_compare.csv planners {[r['planner'] for r in comp]}")
    for row in comp:
        mine = [r for r in runs if r["map"] == row["map"] and r["planner"] == row["planner"]]
        ok = sum(r["ok"] == "1" for r in mine)
        check(int(row["runs"]) == len(mine) and int(row["ok"]) == ok,
              f"table_compare.csv {row['planner']}: runs/ok {row['runs']}/{row['ok']}, runs.csv {len(mine)}/{ok}")
        check(abs(number(row["success"], "success") - ok / max(1, len(mine))) < 1e-4, "success rate")
        if ok:
            lens = sorted(float(r["length_m"]) for r in mine if r["ok"] == "1")
            med = lens[len(lens) // 2] if len(lens) % 2 else 0.5 * (lens[len(lens) // 2 - 1] + lens[len(lens) // 2])
            check(abs(number(row["length_m"], "length") - med) <= 1e-4 * max(1, med),
                  f"{row['planner']}: median length {row['length_m']} vs {med}")
    # tdo and A* are deterministic and must solve map1.
    for p in ("tdo", "astar", "msf-mtpo"):
        check(any(r["planner"] == p and r["ok"] == "1" for r in comp), f"{p} failed on map1")

    t = md_tables(os.path.join(out, "table_compare.md"))
    check(len(t) == 1 and [r[0] for r in t[0][2:]] == PLANNERS, "table_compare.md rows")
    check("success" in t[0][0] and "plan time (ms)" in t[0][0] and "energy (m^2/s^3)" in t[0][0],
          f"table_compare.md header {t[0][0]}")

    abl = read_csv(os.path.join(out, "table_ablation.csv"), ["map", "model"])
    check([r["model"] for r in abl] == MODELS, f"table_ablation.csv models {[r['model'] for r in abl]}")
    t = md_tables(os.path.join(out, "table_ablation.md"))
    check(len(t) == 2 and all(len(x) == 2 + len(MODELS) for x in t), "table_ablation.md shape")

    sens = read_csv(os.path.join(out, "table_sensitivity.csv"), ["lambda", "mu"])
    check([(r["lambda"], r["mu"]) for r in sens] == [("10", "5"), ("10", "20"), ("50", "5"), ("50", "20")],
          f"table_sensitivity.csv grid {[(r['lambda'], r['mu']) for r in sens]}")
    t = md_tables(os.path.join(out, "table_sensitivity.md"))
    check(len(t) == 1 and len(t[0]) == 2 + 4, "table_sensitivity.md shape")

    forest = read_csv(os.path.join(out, "table_forest.csv"), ["forest", "planner", "queries"])
    check({r["planner"] for r in forest} == {"astar", "tdo", "msf-mtpo", "rrtconnect-simplify"},
          "table_forest.csv planners")
    check(all(r["queries"] == "2" for r in forest), "table_forest.csv: 2 queries")
    rnd = read_csv(os.path.join(out, "table_random.csv"), ["planner", "maps"])
    check(all(r["maps"] == "1" for r in rnd), "table_random.csv: 1 map")
    md_tables(os.path.join(out, "table_forest.md"))
    md_tables(os.path.join(out, "table_random.md"))
    md_tables(os.path.join(out, "claims.md"))

    with open(os.path.join(out, "goals.md")) as f:
        goals = f.read()
    for i in range(1, 5):
        check(f"\n{i}. **" in goals, f"goals.md: goal {i} missing")
    check(goals.count("**met**") + goals.count("**not met**") + goals.count("not measured") >= 4,
          "goals.md: verdicts")

    with open(os.path.join(out, "paths", "map1.json")) as f:
        paths = json.load(f)
    check(os.path.exists(paths["map"]), "paths: map file")
    names = [p["planner"] for p in paths["planners"]]
    check(names == PLANNERS, f"paths/map1.json planners {names}")
    for p in paths["planners"]:
        if p["ok"]:
            check(len(p["curve"]) >= 2 and p["curve"][0] == paths["start"] and p["curve"][-1] == paths["goal"],
                  f"paths/map1.json {p['planner']}: curve ends")

    for msg in failures:
        print("FAIL:", msg)
    print(f"checked {len(runs)} runs; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
