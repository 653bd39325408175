#!/usr/bin/env bash
# The closed loop of docs/lcm.md ("Closed loop in five commands"), run as written inside a private
# network namespace made here (no packet can leave it), on the apps' default URL: tdo-sim (Map6,
# vehicle, movers), tdo-planner, tdo-avoid, lcm-logger, and tdo-request --wait. Then 200 more
# requests, each of which must be answered (tdo-request exit 0), with no trajectory.missing in
# tdo-avoid's counters, the vehicle moving and no contact with a column or a mover (tdo-sim's
# counters); then the log lcm-logger recorded must hold every answer and tools/plot/tdo_plot_log.py
# must draw the executed path, the movers and the replans.
# Exit 77 (CTest SKIP_RETURN_CODE) when namespaces are not available.
#
#   netns_closed_loop.sh REPO BUILD_DIR VENV_PYTHON PYDIR SCRATCH [N_REQUESTS]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/netns_enter.sh" "$0" "$@"
shift
repo="$1" build="$2" python="$3" pydir="$4" scratch="$5" n="${6:-200}"
mkdir -p "$scratch"
rm -f "$scratch"/*.lcmlog "$scratch"/*.err
cd "$repo"
doc="$repo/docs/lcm.md"
pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

# The commands as docs/lcm.md shows them (checked verbatim below), with BUILD and the log path
# of this test.
sim=(build/apps/tdo-sim/tdo-sim --map maps/map6.tdomap)
planner=(build/apps/tdo-planner/tdo-planner)
avoid=(build/apps/tdo-avoid/tdo-avoid)
request=(build/apps/tdo-request/tdo-request --start 2 2 3 --goal 49 49 15 --wait)
for c in "${sim[*]} &" "${planner[*]} &" "${avoid[*]} &" "scripts/lcm-logger run.lcmlog &" \
         "${request[*]}"; do
  grep -qF -- "$c" "$doc" || { echo "FAILED: docs/lcm.md does not show the command: $c"; exit 1; }
done
run() { local exe="$1"; shift; "$build/${exe#build/}" "$@"; }
bin() { echo "$build/${1#build/}"; }

"$(bin "${sim[0]}")" "${sim[@]:1}" 2>"$scratch/sim.err" &
sim_pid=$!
pids+=($sim_pid)
"$(bin "${planner[0]}")" "${planner[@]:1}" 2>"$scratch/planner.err" &
planner_pid=$!
pids+=($planner_pid)
"$(bin "${avoid[0]}")" "${avoid[@]:1}" 2>"$scratch/avoid.err" &
avoid_pid=$!
pids+=($avoid_pid)
LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304" \
  scripts/lcm-logger --quiet --force "$scratch/run.lcmlog" &
logger_pid=$!
sleep 1.5  # the planner has a map (tdo-sim publishes it every second)

rc=0
out=$(run "${request[@]}") || { echo "$out"; echo "FAILED: the documented tdo-request"; rc=1; }
echo "$out"
grep -q "^status           ok" <<<"$out" || { echo "FAILED: not ok"; rc=1; }

# Delivery: N requests one after another, each answered (trajectory and report) within 10 s.
ok=0
t0=$(date +%s.%N)
for ((i = 1; i <= n; i++)); do
  if run "${request[@]:0:${#request[@]}-1}" --wait --timeout 10 --request-id "$((1000 + i))" \
        >/dev/null 2>>"$scratch/request.err"; then
    ok=$((ok + 1))
  fi
done
echo "closed loop: $ok of $n requests answered in $(echo "$(date +%s.%N) - $t0" | bc) s"
[[ $ok -eq $n ]] || rc=1
sleep 4  # past tdo-avoid's answer timeout (2 s): a lost trajectory would be counted by now

kill -TERM "$sim_pid"
wait "$sim_pid" || { echo "tdo-sim exit status $?"; rc=1; }
kill -TERM "$avoid_pid" "$planner_pid"
wait "$avoid_pid" || { echo "tdo-avoid exit status $?"; rc=1; }
wait "$planner_pid" || { echo "tdo-planner exit status $?"; rc=1; }
kill -INT "$logger_pid"  # scripts/lcm-logger is the logger itself: SIGINT ends it
wait "$logger_pid" || { echo "FAILED: lcm-logger exit status $? on SIGINT"; rc=1; }
cat "$scratch/sim.err" "$scratch/avoid.err" "$scratch/planner.err"
# No contact with a column or a mover over the whole run (tdo-sim checks every step against the
# map file and the movers it simulates).
grep -Eq "tdo-sim: stopped: .* 0 in collision: 0 static, 0 mover" "$scratch/sim.err" ||
  { echo "FAILED: tdo-sim counted a contact"; rc=1; }
if grep -q "trajectory.missing" "$scratch/avoid.err"; then
  echo "FAILED: tdo-avoid was promised trajectories that never arrived"
  rc=1
fi
grep -q "tdo-avoid: stopped:" "$scratch/avoid.err" || { echo "FAILED: tdo-avoid did not stop cleanly"; rc=1; }
# Every answer is in the log lcm-logger recorded, and the vehicle moved.
"$python" - "$scratch/run.lcmlog" "$pydir" "$((n + 1))" <<'PY' || rc=1
import sys
import lcm
sys.path.insert(0, sys.argv[2])
import tdo
ids, xs = set(), []
for ev in lcm.EventLog(sys.argv[1], "r"):
    if ev.channel == "TDO_TRAJECTORY":
        t = tdo.trajectory_t.decode(ev.data)
        if t.status == "ok" and t.n_pieces > 0:
            ids.add(t.request_id)
    elif ev.channel == "TDO_UAV_STATE":
        xs.append(tdo.vehicle_state_t.decode(ev.data).position[0])
want = int(sys.argv[3])
moved = max(xs) - min(xs) if xs else 0.0
print(f"log: {len(ids)} compact trajectories of {want} requests, vehicle moved {moved:.2f} m in x")
sys.exit(0 if len(ids) >= want and moved > 0.2 else 1)
PY
# The log plot draws the plan, the executed path and the movers' tracks (docs/lcm.md).
plot=$("$python" tools/plot/tdo_plot_log.py "$scratch/run.lcmlog" --types "$pydir" \
  -o "$scratch/run.png") || { echo "FAILED: tdo_plot_log.py"; rc=1; }
echo "$plot"
grep -Eq "[1-9][0-9]* states, 12 movers, [1-9][0-9]* other plans" <<<"$plot" ||
  { echo "FAILED: the plot lacks the executed path, the movers or the replans"; rc=1; }
exit "$rc"
