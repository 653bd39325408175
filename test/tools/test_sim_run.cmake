# tdo-sim-run checks: cmake -DEXE=tdo-sim-run -DMAPS=maps -DOUT=dir [-DPYTHON=python3 -DPLOT=script]
#                           -P test_sim_run.cmake
# 1. Map6 with the default seed and E-APF: planned, goal reached, no collision (--check exit 0),
#    and the episode JSON carries the metrics and per-step records (checked by Python if given).
# 2. Determinism: the same episode twice gives byte-identical JSON.
# 3. Bad input: exit status 2 with one "tdo-sim-run: error: ..." line.
# 4. The plot script draws the episode (a PNG of non-trivial size).
foreach(v EXE MAPS OUT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "test_sim_run.cmake needs -D${v}")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(map6 ${MAPS}/map6.tdomap)

foreach(i 1 2)
  execute_process(COMMAND ${EXE} --map ${map6} --check -o ${OUT}/ep${i}.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "Map6 E-APF episode failed its goal (exit ${rc}):\n${out}\n${err}")
  endif()
  if(NOT out MATCHES "eapf: plan ok, 12 movers, success yes, collision no")
    message(FATAL_ERROR "unexpected summary:\n${out}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/ep1.json ${OUT}/ep2.json RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "the same episode gave different JSON: not deterministic")
endif()
message(STATUS "ok: Map6 collision-free and deterministic")

if(DEFINED PYTHON)
  execute_process(COMMAND ${PYTHON} -c "
import json, math, sys
e = json.load(open(sys.argv[1]))
m = e['metrics']
assert m['success'] and not m['collision'], m
assert m['movers'] == 12 and len(e['movers']) == 12
st = e['steps']
assert len(st) == m['steps'] and len(e['movers'][0]['track']) == len(st)
# Independent recomputation of the separation from the recorded tracks.
rv = e['params']['vehicle_radius']
sep = min(math.dist(s['p'], mv['track'][k]) - mv['radius'] - rv
          for k, s in enumerate(st) for mv in e['movers'])
assert abs(sep - m['min_mover_separation_m']) < 1e-9, (sep, m['min_mover_separation_m'])
assert sep > 0.0
assert math.dist(st[-1]['p'], e['goal']) <= e['params']['goal_tol'] + 1e-12
dt = e['params']['dt']
for k in range(1, len(st)):
    assert abs(st[k]['t'] - st[k-1]['t'] - dt) < 1e-9
    assert math.hypot(*st[k]['v']) <= e['params']['v_max'] * (1 + 1e-12)
    assert math.hypot(*st[k]['a']) <= e['params']['a_max'] * (1 + 1e-12)
print('json ok')
" ${OUT}/ep1.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "episode JSON check failed:\n${out}\n${err}")
  endif()
  if(DEFINED PLOT)
    execute_process(COMMAND ${PYTHON} ${PLOT} ${OUT}/ep1.json -o ${OUT}/ep1.png
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0 OR NOT EXISTS ${OUT}/ep1.png)
      message(FATAL_ERROR "plot_episode.py failed (${rc}):\n${out}\n${err}")
    endif()
    file(SIZE ${OUT}/ep1.png size)
    if(size LESS 30000)
      message(FATAL_ERROR "episode PNG of only ${size} bytes")
    endif()
    execute_process(COMMAND ${PYTHON} ${PLOT} ${OUT}/none.json -o ${OUT}/x.png
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 2 OR NOT err MATCHES "^plot_episode: error: [^\n]+\n$")
      message(FATAL_ERROR "plot of a missing file: expected exit 2 and one error line, got ${rc}:\n${err}")
    endif()
  endif()
endif()

# Arguments separated by '|' (a CMake list would split the cases themselves).
set(cases
    "--map|${OUT}/none.tdomap"
    "--map|${map6}|--follower|rrt"
    "--map|${map6}|--param|frobnicate=1"
    "--map|${map6}|--param|k_a=-1"
    "--map|${map6}|--param|k_r"
    "--map|${map6}|--noise|-1"
    "--random|--movers=-3"
    "--bench|5|--mover-speed|0|1")
foreach(c IN LISTS cases)
  string(REPLACE "|" ";" args "${c}")
  execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^tdo-sim-run: error: [^\n]+\n$")
    message(FATAL_ERROR "expected exit 2 and one 'tdo-sim-run: error:' line for '${c}', got ${rc}:\n${err}")
  endif()
endforeach()
message(STATUS "ok: bad input exits with status 2")
