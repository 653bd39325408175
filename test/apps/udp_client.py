"""The client side of netns_udp.sh, over real UDP multicast: waits for tdo-planner's heartbeat,
has tdo-publish-map (another process) publish Map6, then sends plan requests (valid, NaN, another
vehicle, valid) and checks every answer and the heartbeat counters.

    python udp_client.py URL GENERATED_PYTHON_DIR TDO_PUBLISH_MAP MAP6
"""
import math
import subprocess
import sys
import time

url, pydir, publish_map, map_path = sys.argv[1:5]
sys.path.insert(0, pydir)
import lcm  # noqa: E402
import tdo  # noqa: E402

lc = lcm.LCM(url)
got = {"status": [], "traj": {}, "feas": {}}
lc.subscribe("TDO_STATUS", lambda ch, d: got["status"].append(tdo.status_t.decode(d)))
lc.subscribe("TDO_TRAJECTORY", lambda ch, d: got["traj"].setdefault(
    tdo.trajectory_t.decode(d).request_id, tdo.trajectory_t.decode(d)))
lc.subscribe("TDO_FEASIBILITY", lambda ch, d: got["feas"].setdefault(
    tdo.feasibility_t.decode(d).request_id, tdo.feasibility_t.decode(d)))


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def wait_for(pred, seconds, what):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if pred():
            return
        lc.handle_timeout(100)
    fail(f"timed out after {seconds} s waiting for {what}")


wait_for(lambda: got["status"], 20, "the planner's first heartbeat")
# The map from another process; again until the heartbeat says it is loaded (UDP may drop).
for attempt in range(5):
    subprocess.run([publish_map, map_path, "--lcm-url", url, "--map-id", "6"], check=True)
    try:
        wait_for(lambda: got["status"] and got["status"][-1].map_id == 6, 3, "map 6 loaded")
        break
    except SystemExit:
        if attempt == 4:
            raise

start, goal = None, None
for line in open(map_path):
    f = line.split()
    if f[:1] == ["start"]:
        start = [float(v) for v in f[1:4]]
    if f[:1] == ["goal"]:
        goal = [float(v) for v in f[1:4]]


def request(rid, vehicle=0):
    r = tdo.plan_request_t()
    r.utime, r.request_id, r.vehicle_id, r.map_id = int(time.time() * 1e6), rid, vehicle, -1
    r.start, r.goal, r.clearance = list(start), list(goal), -1.0
    r.depth, r.search = tdo.plan_request_t.DEPTH_TRAJECTORY, tdo.plan_request_t.SEARCH_BIDIR
    r.lambda_turn, r.mu, r.theta_max, r.d_th, r.h_weight = 50.0, 20.0, math.pi / 4, 0.0, 1.0
    r.first_meet, r.max_expansions = True, 0
    r.correction, r.shorten, r.turn_threshold = tdo.plan_request_t.CORRECT_MULTISCALE, True, math.radians(10)
    r.smoothing, r.k = tdo.plan_request_t.SMOOTHING_G2, 1.0
    r.v_max, r.a_max, r.j_max, r.a_lat_max, r.v_cruise = 3.0, 3.0, 10.0, 3.0, 3.0
    r.stop_angle, r.dt, r.corner_time = math.radians(150), 0.01, 1.0
    r.seq, r.samples = rid, tdo.plan_request_t.SAMPLES_ON  # the checks below read the samples
    return r


bad = request(2)
bad.goal = [float("nan"), 49.0, 15.0]
for r in (request(1), bad, request(3, vehicle=5), request(4)):
    lc.publish("TDO_PLAN_REQUEST", r.encode())
wait_for(lambda: all(i in got["traj"] and i in got["feas"] for i in (1, 2, 4)), 60,
         "answers to requests 1, 2 and 4")
for i in (1, 4):
    t, f = got["traj"][i], got["feas"][i]
    if t.status != "ok" or not f.ok or t.n_samples < 2 or t.map_id != 6:
        fail(f"request {i}: status {t.status!r} feasible {f.ok} samples {t.n_samples}")
    end = t.samples[-1][1:4]
    if max(abs(a - b) for a, b in zip(end, goal)) > 1e-6:
        fail(f"request {i}: ends at {end}, goal {goal}")
if got["traj"][2].status != "non_finite" or got["traj"][2].status_code != -1:
    fail(f"request 2: {got['traj'][2].status!r}, expected non_finite")
if got["traj"][1].samples != got["traj"][4].samples:
    fail("the same request planned twice gave different samples")
n = len(got["status"])
wait_for(lambda: len(got["status"]) > n, 5, "a heartbeat after the answers")
s = got["status"][-1]
if 3 in got["traj"] or s.ignored != 1 or s.rejected != 1 or s.succeeded != 2 or s.answered != 3:
    fail(f"heartbeat: answered {s.answered} ok {s.succeeded} rejected {s.rejected} "
         f"ignored {s.ignored}; request 3 answered: {3 in got['traj']}")
print(f"udp client: 3 answers ({len(got['traj'][1].samples)} samples), heartbeat "
      f"{dict(zip(s.reason, s.reason_count))}")
