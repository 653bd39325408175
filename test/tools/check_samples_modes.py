#!/usr/bin/env python3
"""tdo-plan --samples: the output does not depend on whether the library stores the samples.

    check_samples_modes.py TDO_PLAN MAP [MAP ...]

For each map: `--json --samples stored` and `--json --samples streamed` must give the same bytes
once the two fields that may differ are removed: plan_time_ms (wall time) and arena_bytes (the
streamed arena holds no samples, so it must be smaller, which also shows the mode took effect).
The stored run must carry a trajectory of samples every dt ending at the flight time, so a
consumer that drops or truncates the streamed samples fails the comparison. The text output (with
the v/a optimum, read from the samples) must match the same way.

`--samples pieces` (tdo_capacity.stream_samples 2): either the library accepts it and the output
matches as well, or tdo-plan exits 2 with one "tdo-plan: error: <status name>: ..." line.
"""
import json
import re
import subprocess
import sys

STATUS = re.compile(r"^tdo-plan: error: ([a-z_]+): .*\(--samples pieces\)\n$")


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
        r = run(exe, ["--map", m, "--json", "--samples", "pieces"])
        if r.returncode == 0:
            if strip(r.stdout, f"{m} --samples pieces")[0] != a:
                sys.exit(f"{m}: --samples pieces JSON differs from stored")
            pieces = "pieces same"
        else:
            if r.returncode != 2 or r.stdout or not STATUS.match(r.stderr):
                sys.exit(f"{m}: --samples pieces: exit {r.returncode}, expected 0 or 2 with a "
                         f"named status:\n{r.stdout}{r.stderr}")
            pieces = "pieces refused (" + STATUS.match(r.stderr).group(1) + ", exit 2)"
        print(f"{m}: {n} samples, stored = streamed ({len(a)} bytes of JSON; arena "
              f"{arena_stored} -> {arena_streamed} bytes); {pieces}")
    print("ok")


if __name__ == "__main__":
    main()
