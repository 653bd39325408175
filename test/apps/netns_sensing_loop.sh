#!/usr/bin/env bash
# The closed loop in a world being discovered (docs/lcm.md "Replanning"), over real UDP multicast
# inside a private network namespace made here: tdo-sim on Map6 with 30 % of the columns hidden
# until its range sensor sees them (revealed ones go out as map updates), tdo-planner, tdo-avoid
# (replanning), lcm-logger. tdo-sim sends the flight's request. The vehicle must reach the goal
# with no contact against the true world (tdo-sim's counters, every box of the map file), tdo-avoid
# must have replanned at least once, and tdo-replay must reproduce every answer of the recorded
# log bit for bit, the replans included. Exit 77 (CTest SKIP_RETURN_CODE) without namespaces.
#
#   netns_sensing_loop.sh REPO BUILD_DIR VENV_PYTHON PYDIR SCRATCH [SEED]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/netns_enter.sh" "$0" "$@"
shift
repo="$1" build="$2" python="$3" pydir="$4" scratch="$5" seed="${6:-1}"
mkdir -p "$scratch"
rm -f "$scratch"/*.lcmlog "$scratch"/*.err
cd "$repo"
pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
scripts/lcm-logger --quiet --force "$scratch/run.lcmlog" &
logger_pid=$!
pids+=($logger_pid)
"$build/apps/tdo-planner/tdo-planner" 2>"$scratch/planner.err" &
planner_pid=$!
pids+=($planner_pid)
"$build/apps/tdo-avoid/tdo-avoid" 2>"$scratch/avoid.err" &
avoid_pid=$!
pids+=($avoid_pid)
sleep 0.5
"$build/apps/tdo-sim/tdo-sim" --map maps/map6.tdomap --unknown 0.3 --sensor-range 5 \
  --seed "$seed" --request-goal --request-delay 1.5 2>"$scratch/sim.err" &
sim_pid=$!
pids+=($sim_pid)

# Until the vehicle is within 0.25 m of the goal (at most 120 s).
rc=0
"$python" - "$pydir" <<'PY' || { echo "FAILED: the goal was not reached"; rc=1; }
import math, select, sys, time
import lcm
sys.path.insert(0, sys.argv[1])
import tdo
goal, best, done = (49.0, 49.0, 15.0), [1e9], [False]
def on_state(channel, data):
    p = tdo.vehicle_state_t.decode(data).position
    best[0] = min(best[0], math.dist(p, goal))
    done[0] = done[0] or best[0] < 0.25
lc = lcm.LCM()
lc.subscribe("TDO_UAV_STATE", on_state)
end = time.time() + 120
while not done[0] and time.time() < end:
    if select.select([lc.fileno()], [], [], 0.5)[0]:
        lc.handle()
print(f"closest to the goal: {best[0]:.3f} m")
sys.exit(0 if done[0] else 1)
PY

kill -TERM "$sim_pid"
wait "$sim_pid" || { echo "tdo-sim exit status $?"; rc=1; }
sleep 0.5
kill -TERM "$avoid_pid" "$planner_pid"
wait "$avoid_pid" || { echo "tdo-avoid exit status $?"; rc=1; }
wait "$planner_pid" || { echo "tdo-planner exit status $?"; rc=1; }
kill -INT "$logger_pid"
wait "$logger_pid" || { echo "FAILED: lcm-logger exit status $? on SIGINT"; rc=1; }
cat "$scratch/sim.err" "$scratch/avoid.err" "$scratch/planner.err"
grep -Eq "tdo-sim: stopped: .* 0 in collision: 0 static, 0 mover" "$scratch/sim.err" ||
  { echo "FAILED: tdo-sim counted a contact with the true world"; rc=1; }
grep -Eq "tdo-avoid: stopped: .* [1-9][0-9]* replans \([1-9][0-9]* taken over\), 0 safe stops" \
  "$scratch/avoid.err" || { echo "FAILED: tdo-avoid did not replan, or stopped"; rc=1; }
grep -Eq "[1-9][0-9]* of [1-9][0-9]* hidden boxes revealed" "$scratch/sim.err" ||
  { echo "FAILED: nothing was hidden and revealed"; rc=1; }

# The log: map updates, and at least one replan answered ok (tdo-avoid's request ids from 1e9).
"$python" - "$scratch/run.lcmlog" "$pydir" <<'PY' || rc=1
import sys
import lcm
sys.path.insert(0, sys.argv[2])
import tdo
updates, replans = 0, set()
for ev in lcm.EventLog(sys.argv[1], "r"):
    if ev.channel == "TDO_MAP_UPDATE":
        updates += 1
    elif ev.channel == "TDO_TRAJECTORY":
        t = tdo.trajectory_t.decode(ev.data)
        if t.request_id >= 1000000000 and t.status == "ok":
            replans.add(t.request_id)
print(f"log: {updates} map updates, {len(replans)} replans answered ok")
if updates == 0 or not replans:
    print("FAILED: no map update or no replan in the log")
    sys.exit(1)
PY
# tdo-replay: every recorded answer again, bit for bit.
"$build/apps/tdo-replay/tdo-replay" "$scratch/run.lcmlog" || { echo "FAILED: tdo-replay"; rc=1; }
exit "$rc"
