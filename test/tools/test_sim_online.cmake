# tdo-sim-run online checks (issue 20): cmake -DEXE=tdo-sim-run -DDATA=test/data -P test_sim_online.cmake
# 1. A wall across the route, hidden until the range sensor sees it: with tdo replanning the vehicle
#    goes round it and arrives without contact (--check exit 0, at least one replan and switch);
#    without replanning (E-APF only) it does not arrive (--check exit 1); with the wall known from
#    the start, E-APF alone arrives (so the hiding is what the replanning answers).
# 2. A small bench prints the table with the three rows side by side and the summary line in
#    exactly its form.
# 3. Bad online options: exit status 2 with one "tdo-sim-run: error: ..." line.
foreach(v EXE DATA)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "test_sim_online.cmake needs -D${v}")
  endif()
endforeach()
set(wall ${DATA}/hidden_wall.tdomap)

execute_process(COMMAND ${EXE} --map ${wall} --unknown 1 --sensor-range 5 --replanner tdo --check
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^online tdo: plan ok, hidden 1 revealed 1, success yes, collision no"
   OR NOT out MATCHES "replans [1-9][0-9]* \\(" OR NOT out MATCHES "switches [1-9]")
  message(FATAL_ERROR "tdo replanning round the hidden wall failed (exit ${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${EXE} --map ${wall} --unknown 1 --sensor-range 5 --replanner none --check
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT out MATCHES "^online none: plan ok, hidden 1 revealed 1, success no")
  message(FATAL_ERROR "E-APF alone should not get round the hidden wall (exit ${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${EXE} --map ${wall} --unknown 0 --replanner none --check
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^online none: plan ok, hidden 0 revealed 0, success yes, collision no")
  message(FATAL_ERROR "with the wall known E-APF alone should arrive (exit ${rc}):\n${out}\n${err}")
endif()
message(STATUS "ok: hidden wall: replanning arrives without contact, E-APF alone does not")

execute_process(COMMAND ${EXE} --bench 3 --seed 5 --size 20 20 10 --columns 25 --movers 2
                        --unknown 0.5 --sensor-range 5
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "online bench failed (exit ${rc}):\n${out}\n${err}")
endif()
if(NOT out MATCHES "\n +tdo replan +E-APF only +MSF-MTPO replan\n")
  message(FATAL_ERROR "online bench: the three rows are not side by side:\n${out}")
endif()
if(NOT out MATCHES "\nonline: episodes=3 success=[0-3] collisions=[0-3] replans=[0-9]+ replan_p99_ms=[0-9]+\\.[0-9][0-9] over_limits=[0-3]\n$")
  message(FATAL_ERROR "online bench: summary line not in its form:\n${out}")
endif()
message(STATUS "ok: online bench table and summary line")
# Movers blocking the plan trigger replans round their swept region (default --mover-replan 1);
# with --mover-replan 0 they are left to the E-APF (conflicts counted, no mover replan).
if(NOT out MATCHES "\nmover conflicts / replans \\(skipped\\) +[0-9]+ / [1-9][0-9]* \\(")
  message(FATAL_ERROR "online bench: no replan round a blocking mover:\n${out}")
endif()
execute_process(COMMAND ${EXE} --bench 3 --seed 5 --size 20 20 10 --columns 25 --movers 2
                        --unknown 0.5 --sensor-range 5 --mover-replan 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "left to the E-APF"
   OR NOT out MATCHES "\nmover conflicts / replans \\(skipped\\) +[1-9][0-9]* / 0 \\(0\\)")
  message(FATAL_ERROR "online bench --mover-replan 0: expected conflicts without replans:\n${out}")
endif()
message(STATUS "ok: movers trigger replans, and not with --mover-replan 0")

foreach(c "--unknown;1.5" "--unknown;0.5;--sensor-range;0" "--unknown;0.5;--replanner;foo"
          "--unknown;0.5;--latency;-1" "--unknown;0.5;--noise;0.1" "--unknown;0.5;--mover-replan;-1"
          "--unknown;0.5;--mover-replan;nan")
  execute_process(COMMAND ${EXE} --map ${wall} ${c} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^tdo-sim-run: error: [^\n]+\n$")
    message(FATAL_ERROR "expected exit 2 and one 'tdo-sim-run: error:' line for '${c}', got ${rc}:\n${err}")
  endif()
endforeach()
message(STATUS "ok: bad online options are refused")
