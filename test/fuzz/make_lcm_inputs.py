#!/usr/bin/env python3
"""The LCM inputs of the fuzz targets, made from the committed replay log with the current types.

    .venv/bin/python test/fuzz/make_lcm_inputs.py PYDIR            # rewrite them
    .venv/bin/python test/fuzz/make_lcm_inputs.py PYDIR --check    # exit 1: a stale fingerprint

PYDIR holds the generated Python types (build/lcmtypes/python); the lcm wheel must import. Every
LCM message starts with its type's 8-byte fingerprint, and a message of an older version of the
type is refused at once (bad_fingerprint): a seed or regression input made before a type changed
no longer reaches the code it was made for. So this rewrites, from test/data/map6_run.lcmlog:
  corpus/fuzz_lcm/<kind>_<channel>_<event>  the type selector byte of fuzz_lcm.cpp + one message;
  corpus/fuzz_replay/map1.lcmlog            the log's first 12 events (Map1's requests);
  regressions/fuzz_lcm/1_clearance_5e5      a valid request on fuzz_lcm's fixed map, clearance 5e5 m;
  regressions/fuzz_replay/hostile.lcmlog    the map of 0_octree_all_inner, then that request.
The other inputs (maps, vehicle states, setpoints, obstacles) are kept; --check covers them all.
"""
import glob
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
LOG = os.path.join(ROOT, "test", "data", "map6_run.lcmlog")
# fuzz_lcm.cpp's selector byte -> type name; the replay log's channels -> type name.
KINDS = {0: "map_t", 1: "plan_request_t", 2: "trajectory_t", 3: "vehicle_state_t",
         4: "setpoint_t", 5: "obstacles_t", 6: "feasibility_t", 7: "status_t"}
CHANNELS = {"TDO_MAP": "map_t", "TDO_PLAN_REQUEST": "plan_request_t",
            "TDO_TRAJECTORY": "trajectory_t", "TDO_FEASIBILITY": "feasibility_t",
            "TDO_STATUS": "status_t"}
# Events of map6_run.lcmlog taken as fuzz_lcm seeds: the maps of Map1 and Map6, requests, answers
# (an error answer, compact ones of a few kB; not the 115 kB sampled one), reports, a heartbeat.
SEEDS = {3: "map_t", 12: "map_t", 0: "plan_request_t", 4: "plan_request_t", 7: "plan_request_t",
         1: "trajectory_t", 9: "trajectory_t", 17: "trajectory_t", 2: "feasibility_t",
         6: "feasibility_t", 10: "feasibility_t", 25: "status_t"}


def fingerprint(tdo, type_name):
    return getattr(tdo, type_name)().encode()[:8]


def check(tdo, lcm):
    stale = []
    for path in sorted(glob.glob(os.path.join(HERE, "*", "fuzz_lcm", "*"))):
        data = open(path, "rb").read()
        if len(data) >= 9 and data[1:9] != fingerprint(tdo, KINDS[data[0] % 8]):
            stale.append(f"{path}: not a {KINDS[data[0] % 8]} of the current type")
    for path in sorted(glob.glob(os.path.join(HERE, "*", "fuzz_replay", "*.lcmlog"))):
        for ev in lcm.EventLog(path, "r"):
            if ev.channel in CHANNELS and ev.data[:8] != fingerprint(tdo, CHANNELS[ev.channel]):
                stale.append(f"{path}: event {ev.eventnum} on {ev.channel} is of an older type")
    for line in stale:
        print("STALE " + line)
    if stale:
        script = os.path.relpath(__file__, ROOT)
        print(f"regenerate: .venv/bin/python {script} build/lcmtypes/python")
        return 1
    print("every fuzz_lcm and fuzz_replay input has its type's current fingerprint")
    return 0


def clearance_request(tdo, template):
    """A request fuzz_lcm's fixed map (16 x 16 x 8 voxels of 0.5 m) could answer, but for its
    clearance of 5e5 m (the stencil check used to scan (2 clearance / res)^2 cells: hours)."""
    r = tdo.plan_request_t.decode(template)
    r.request_id, r.vehicle_id, r.map_id, r.seq = 5, 0, -1, 5
    r.start, r.goal = [1.25, 1.25, 1.25], [6.75, 1.25, 1.25]
    r.clearance = 5e5
    r.use_defaults &= ~tdo.plan_request_t.USE_DEFAULT_CLEARANCE
    return r.encode()


def write(tdo, lcm):
    events = list(lcm.EventLog(LOG, "r"))
    corpus = os.path.join(HERE, "corpus", "fuzz_lcm")
    kind_of = {name: kind for kind, name in KINDS.items()}
    for name in set(SEEDS.values()):
        for old in glob.glob(os.path.join(corpus, f"{kind_of[name]}_tdo_{name[:-2]}_*")):
            os.remove(old)
    for i, name in SEEDS.items():
        ev = events[i]
        if CHANNELS.get(ev.channel) != name:
            raise SystemExit(f"{LOG}: event {i} is on {ev.channel}, not a {name}: update SEEDS")
        with open(os.path.join(corpus, f"{kind_of[name]}_tdo_{name[:-2]}_{i}"), "wb") as f:
            f.write(bytes([kind_of[name]]) + ev.data)

    def write_log(path, evs):
        log = lcm.EventLog(path, "w", overwrite=True)
        for channel, data, utime in evs:
            log.write_event(utime, channel, data)
        log.close()

    write_log(os.path.join(HERE, "corpus", "fuzz_replay", "map1.lcmlog"),
              [(e.channel, e.data, e.timestamp) for e in events[:12]])
    template = next(e.data for e in events if e.channel == "TDO_PLAN_REQUEST")
    request = clearance_request(tdo, template)
    with open(os.path.join(HERE, "regressions", "fuzz_lcm", "1_clearance_5e5"), "wb") as f:
        f.write(bytes([1]) + request)
    octree_map = open(os.path.join(HERE, "regressions", "fuzz_lcm", "0_octree_all_inner"),
                      "rb").read()[1:]
    write_log(os.path.join(HERE, "regressions", "fuzz_replay", "hostile.lcmlog"),
              [("TDO_MAP", octree_map, 1000), ("TDO_PLAN_REQUEST", request, 2000)])
    return check(tdo, lcm)


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--check"):
        print(__doc__)
        return 2
    sys.path.insert(0, sys.argv[1])
    import lcm  # noqa: E402  (the wheel)
    import tdo  # noqa: E402  (generated)
    return check(tdo, lcm) if len(sys.argv) == 3 else write(tdo, lcm)


if __name__ == "__main__":
    sys.exit(main())
