"""Cross-language check: messages written by the wheel's Python bindings with the generated Python
types are decoded and answered by tdo-planner (C++), through a file:// log (no network).

    python py_interop.py TDO_PLANNER GENERATED_PYTHON_DIR SCRATCH_DIR
"""
import math
import os
import subprocess
import sys

planner, pydir, scratch = sys.argv[1:4]
sys.path.insert(0, pydir)
import lcm  # noqa: E402  (the wheel)
import tdo  # noqa: E402  (generated: every type must import)

for name in ("map_t", "obstacles_t", "plan_request_t", "trajectory_t", "feasibility_t",
             "vehicle_state_t", "setpoint_t", "status_t"):
    getattr(tdo, name)()

os.makedirs(scratch, exist_ok=True)
path = os.path.join(scratch, "interop.lcmlog")
log = lcm.EventLog(path, "w", overwrite=True)

m = tdo.map_t()
m.map_id, m.vehicle_id, m.resolution = 1, -1, 0.5
m.origin, m.size, m.clearance = [0.0, 0.0, 0.0], [20, 20, 10], 0.25
m.encoding = tdo.map_t.ENCODING_RLE
m.runs = [19, 1, 3980]  # one occupied voxel in a corner
m.n_runs = len(m.runs)
m.boxes = [[4.5, 0.0, 0.0, 5.5, 7.0, 5.0]]  # a wall, open above y = 7 m
m.n_boxes = len(m.boxes)
log.write_event(1000, "TDO_MAP", m.encode())

r = tdo.plan_request_t()
r.request_id, r.vehicle_id, r.map_id = 7, 0, -1
r.start, r.goal, r.clearance = [1.25, 1.25, 1.25], [8.75, 1.25, 1.25], -1.0
r.depth, r.search = tdo.plan_request_t.DEPTH_TRAJECTORY, tdo.plan_request_t.SEARCH_BIDIR
r.lambda_turn, r.mu, r.theta_max, r.d_th, r.h_weight, r.first_meet = 50.0, 20.0, math.pi / 4, 0.0, 1.0, True
r.max_expansions, r.correction, r.turn_threshold = 0, tdo.plan_request_t.CORRECT_MULTISCALE, math.radians(10)
r.shorten = True
r.smoothing, r.k = tdo.plan_request_t.SMOOTHING_G2, 1.0
r.v_max, r.a_max, r.j_max, r.a_lat_max, r.v_cruise = 3.0, 3.0, 10.0, 3.0, 3.0
r.stop_angle, r.dt, r.corner_time = math.radians(150), 0.01, 1.0
log.write_event(2000, "TDO_PLAN_REQUEST", r.encode())
bad = tdo.plan_request_t.decode(r.encode())  # and one with a NaN goal: answered, counted
bad.request_id, bad.goal = 8, [float("nan"), 1.25, 1.25]
log.write_event(3000, "TDO_PLAN_REQUEST", bad.encode())
log.close()

out = subprocess.run([planner, "--lcm-url", "file://" + path + "?speed=0", "--duration", "30"],
                     capture_output=True, text=True, timeout=60)
print(out.stderr)
want = "stopped: 3 received, 2 answered (1 ok, 0 failed), 1 rejected"
if out.returncode != 0 or want not in out.stderr or "request.non_finite 1" not in out.stderr:
    print(f"FAILED: exit status {out.returncode}, expected 0 and '{want}'")
    sys.exit(1)
print("python -> tdo-planner interop ok")
