#!/usr/bin/env python3
"""Issue 24's reproducers against their budget: each tool command must exit 2 with a one-line named
reason, and each hostile LCM message must be refused and counted by tdo-planner (exit 0, the
message in `rejected` with its reason); every run within 1 s and under 100 MB peak memory.

    python3 scripts/reproducers.py [--build DIR] [--scratch DIR] [--check]

Prints one row per reproducer: exit status, wall time (s) and peak RSS (MB, the child's own
getrusage ru_maxrss from wait4). The tools read the map files of test/tools/make_hostile_inputs.py
(written into --scratch, with geb079.bt at resolution 1e-9). tdo-planner reads its messages from
an LCM log (file:// URL, so no network) made of test/fuzz/regressions/fuzz_lcm and fuzz_replay.
With --check the exit status is 1 when any run has the wrong exit status or message, or peaks at
100 MB or more; the wall time is only printed (it depends on the machine's load).
"""
import argparse
import os
import re
import struct
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MEMORY_MB = 100.0


def write_lcmlog(path, events):
    """An LCM log file (the format of lcm-logger) of (channel, bytes) events."""
    with open(path, "wb") as f:
        for i, (channel, data) in enumerate(events):
            ch = channel.encode()
            f.write(struct.pack(">Iqqii", 0xEDA1DA01, i, 1000 * (i + 1), len(ch), len(data)))
            f.write(ch + data)


def fuzz_lcm_message(name):
    """The message bytes of a fuzz_lcm input (byte 0 is the type selector)."""
    with open(os.path.join(ROOT, "test", "fuzz", "regressions", "fuzz_lcm", name), "rb") as f:
        return f.read()[1:]


def run(argv):
    """(exit status, wall s, peak RSS MB, stdout + stderr) of one child process."""
    t0 = time.monotonic()
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = p.stdout.read()
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.monotonic() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, wall, usage.ru_maxrss / 1024.0, out.decode("utf-8", "replace")


def tool_cases(build, scratch):
    plan = os.path.join(build, "tools", "tdo-plan", "tdo-plan")
    h = os.path.join(scratch, "hostile")
    q = ["--start", "0", "0", "0", "--goal", "1", "1", "1"]
    simple = os.path.join(ROOT, "maps", "movingai", "Simple.3dmap")
    reg = os.path.join(ROOT, "test", "fuzz", "regressions")
    cases = [
        ("OcTree of inner nodes, 300 kB of 0xff", ["--map", f"{h}/all_inner_300k.bt"], "too_deep"),
        ("OcTree of inner nodes, 100 kB of 0xff", ["--map", f"{h}/all_inner_100k.bt"], "too_deep"),
        ("OcTree resolution 1e-6", ["--map", f"{h}/res_1e-6.bt"], "bad_resolution"),
        ("geb079 at resolution 1e-9", ["--map", f"{h}/geb079_res_1e-9.bt"], "bad_resolution"),
        ("OcTree resolution 1e300", ["--map", f"{h}/res_1e300.bt"], "bad_resolution"),
        ("ColorOcTree", ["--map", f"{h}/color.bt"], "wrong_tree_type"),
        (".ot header and garbage", ["--map", f"{h}/garbage.ot"], "corrupt OcTree"),
        ("a directory as --map", ["--map", f"{h}/directory.tdomap"], "is a directory"),
        ("one 10 MB token", ["--map", f"{h}/token_10mb.tdomap"], "10000000 bytes"),
        ("control characters", ["--map", f"{h}/control.tdomap"], r"unknown keyword 'bo\\x1b"),
        (".3dmap control characters", ["--map", f"{reg}/fuzz_3dmap/control.3dmap"], "error"),
        (".3dmap huge size", ["--map", f"{reg}/fuzz_3dmap/huge_size.3dmap"], "error"),
        (".tdomap resolution 1e-300", ["--map", f"{reg}/fuzz_tdomap/res_1e-300.tdomap"], "error"),
    ]
    rows = [(name, [plan] + args + q, 2, pattern) for name, args, pattern in cases]
    for c in ("1e4", "1e5", "1e12"):
        rows.append((f"Simple.3dmap clearance {c}",
                     [plan, "--map", simple, "--start", "0", "0", "0", "--goal", "100", "100",
                      "100", "--clearance", c], 2, "clearance_capacity"))
    return rows


def app_cases(build, scratch):
    planner = os.path.join(build, "apps", "tdo-planner", "tdo-planner")
    corpus = os.path.join(ROOT, "test", "fuzz", "corpus", "fuzz_lcm")
    with open(os.path.join(corpus, "0_tdo_map_3"), "rb") as f:
        good_map = f.read()[1:]
    logs = {
        "map_t with the OcTree of inner nodes": (
            [("TDO_MAP", fuzz_lcm_message("0_octree_all_inner"))], r"map\.bad_encoding 1"),
        "map_t with clearance hint 1e300": (
            [("TDO_MAP", fuzz_lcm_message("0_clearance_hint_1e300"))], r"map\.map_capacity 1"),
        "request with clearance 5e5 m": (
            [("TDO_MAP", good_map), ("TDO_PLAN_REQUEST", fuzz_lcm_message("1_clearance_5e5"))],
            r"request\.map_capacity 1"),
    }
    rows = []
    for name, (events, pattern) in logs.items():
        path = os.path.join(scratch, re.sub(r"[^a-z0-9]+", "_", name.lower()) + ".lcmlog")
        write_lcmlog(path, events)
        rows.append((name, [planner, "--lcm-url", f"file://{path}?speed=0", "--duration", "30"], 0,
                     r"stopped: .* [1-9][0-9]* rejected.*" + pattern))
    hostile = os.path.join(ROOT, "test", "fuzz", "regressions", "fuzz_replay", "hostile.lcmlog")
    rows.append(("log of both (fuzz_replay)",
                 [planner, "--lcm-url", f"file://{hostile}?speed=0", "--duration", "30"], 0,
                 r"stopped: .* 2 rejected.*map\.bad_encoding 1.*request\.no_map 1"))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scratch", default=None)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    scratch = a.scratch or tempfile.mkdtemp(prefix="tdo-reproducers-")
    os.makedirs(scratch, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(ROOT, "test", "tools", "make_hostile_inputs.py"),
                    os.path.join(scratch, "hostile"), os.path.join(ROOT, "maps")], check=True)
    with open(os.path.join(ROOT, "maps", "octomap", "geb079.bt"), "rb") as f:
        geb = f.read()
    with open(os.path.join(scratch, "hostile", "geb079_res_1e-9.bt"), "wb") as f:
        f.write(geb.replace(b"\nres 0.08\n", b"\nres 1e-9\n", 1))

    rows = [("tdo-plan",) + r for r in tool_cases(a.build, scratch)]
    rows += [("tdo-planner",) + r for r in app_cases(a.build, scratch)]
    bad = 0
    print("| program | reproducer | exit | wall (s) | peak RSS (MB) | outcome |")
    print("|---|---|---|---|---|---|")
    for program, name, argv, want_code, pattern in rows:
        code, wall, rss, out = run(argv)
        lines = [line for line in out.splitlines() if line.strip()]
        if program == "tdo-plan":
            said = lines[-1] if lines else "(nothing)"
        else:
            stop = [line for line in lines if "stopped:" in line]
            counts = re.findall(r"\d+ received, \d+ answered|\d+ rejected", stop[-1] if stop else "")
            reasons = [line.split(":", 1)[1].strip() for line in lines
                       if line.startswith("tdo-planner:   ")]
            said = ", ".join(counts) + (": " + ", ".join(reasons) if reasons else "")
        good = code == want_code and re.search(pattern, out, re.S) is not None and rss < MEMORY_MB
        if not good:
            bad += 1
        said = said.replace(scratch + "/hostile/", "").replace(ROOT + "/", "")
        said = said if len(said) <= 110 else said[:107] + "..."
        print(f"| {program} | {name} | {code} | {wall:.2f} | {rss:.1f} | "
              f"{'' if good else 'FAILED: '}{said.replace('|', '/')} |")
    print(f"{len(rows) - bad} of {len(rows)} within the budget (exit status, named reason, "
          f"< {MEMORY_MB:.0f} MB); load average {os.getloadavg()[0]:.1f}")
    return 1 if a.check and bad else 0


if __name__ == "__main__":
    sys.exit(main())
