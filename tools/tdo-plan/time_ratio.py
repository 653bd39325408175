#!/usr/bin/env python3
"""Flight time against the v/a time optimum along each plan's own path (tdo-plan --optimum).

    time_ratio.py TDO_PLAN [--forest N] [--max-median R] [--max-median-forest R]
                  [extra tdo-plan options...]

Plans Map1-Map5 and the first N forest_gen queries of forests 0-2 (default 10 each, 30 pairs;
0: none) with `tdo-plan --json --optimum`, prints one markdown table per set and the summary lines
(median and worst ratio, total flight time, violations of the finite-difference check).
--max-median R: exit status 1 unless every plan is ok without violations and the median ratio of
each set is at most R (a regression check for CTest). --max-median-forest R: the forest set's
bound instead (default: --max-median's).
"""
import csv
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def plan(exe, args, extra):
    out = subprocess.run([exe, "--json", "--optimum"] + args + extra, capture_output=True,
                         text=True, check=False)
    if out.returncode == 2 or not out.stdout.strip():
        raise SystemExit("tdo-plan failed: " + " ".join(args) + ": " + out.stderr.strip())
    return json.loads(out.stdout)


def row(name, j):
    m = j.get("metrics", {})
    f = j.get("feasibility", {})
    o = j.get("va_optimum", {})
    return {"name": name, "status": j["status"], "flight": m.get("flight_time_s", float("nan")),
            "opt": o.get("time_s", float("nan")), "ratio": o.get("ratio", float("nan")),
            "bound": o.get("jerk_bound_s", float("nan")),
            "length": m.get("length_m", float("nan")), "turns": m.get("turns", -1),
            "viol": f.get("violations_total", -1), "energy": m.get("energy", float("nan")),
            "smooth": m.get("smoothness", float("nan")),
            "plan_ms": m.get("plan_time_ms", float("nan")), "refine": o.get("refinements", -1)}


def table(rows):
    print("| query | status | flight s | v/a optimum s | ratio | jerk bound s | bound / optimum "
          "| length m | turns | FD violations | energy m^2/s^3 | smoothness |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['name']} | {r['status']} | {r['flight']:.2f} | {r['opt']:.2f} | "
              f"{r['ratio']:.3f} | {r['bound']:.2f} | {r['bound'] / r['opt']:.3f} | "
              f"{r['length']:.2f} | {r['turns']} | {r['viol']} | "
              f"{r['energy']:.2f} | {r['smooth']:.3f} |")
    ok = [r for r in rows if r["status"] == "ok"]
    ratios = [r["ratio"] for r in ok] or [float("nan")]
    print()
    bounds = [r["bound"] / r["opt"] for r in ok] or [float("nan")]
    print(f"{len(ok)}/{len(rows)} ok; ratio median {statistics.median(ratios):.3f}, "
          f"worst {max(ratios):.3f}; jerk bound / optimum median "
          f"{statistics.median(bounds):.3f}; total flight {sum(r['flight'] for r in ok):.2f} s "
          f"(optimum {sum(r['opt'] for r in ok):.2f} s); total length "
          f"{sum(r['length'] for r in ok):.2f} m; turns {sum(r['turns'] for r in ok)}; "
          f"FD violations {sum(max(r['viol'], 0) for r in rows)}; refinement rounds "
          f"{sum(max(r['refine'], 0) for r in rows)}")
    print()
    bad = len(ok) != len(rows) or any(r["viol"] != 0 for r in rows)
    return bad, statistics.median(ratios)


def main():
    argv = sys.argv[1:]
    if not argv:
        raise SystemExit(__doc__)
    exe = argv.pop(0)
    n_forest = 10
    max_median = None
    max_forest = None
    while argv[:1] in (["--forest"], ["--max-median"], ["--max-median-forest"]):
        if argv[0] == "--forest":
            n_forest = int(argv[1])
        elif argv[0] == "--max-median":
            max_median = float(argv[1])
        else:
            max_forest = float(argv[1])
        argv = argv[2:]
    if max_forest is None:
        max_forest = max_median
    maps = []
    for i in range(1, 6):
        j = plan(exe, ["--map", os.path.join(ROOT, "maps", f"map{i}.tdomap")], argv)
        maps.append(row(f"map{i}", j))
    print("**Map1-Map5**\n")
    results = [table(maps)]
    forest = []
    with open(os.path.join(ROOT, "maps", "forest_gen", "start_and_end.csv")) as fh:
        queries = [q for q in csv.reader(fh) if q and not q[0].startswith("#")]
    for fid in range(3):
        qs = [q for q in queries if int(q[1]) == fid][:n_forest]
        for q in qs:
            j = plan(exe, ["--map", os.path.join(ROOT, "maps", "forest_gen", f"forest{fid}.bt"),
                           "--start", q[2], q[3], q[4], "--goal", q[5], q[6], q[7]], argv)
            forest.append(row(f"forest{fid} #{q[0]}", j))
    if forest:
        print(f"**forest_gen: the first {n_forest} queries of forests 0-2**\n")
        results.append(table(forest))
    limits = [max_median, max_forest]
    for (bad, median), limit in zip(results, limits):
        if limit is not None and (bad or not median <= limit):
            print(f"FAIL: a plan failed or violated a limit, or median {median:.3f} > {limit}")
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
