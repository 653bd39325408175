# tdo-sim-run --samples: episodes do not depend on whether the planner stores its trajectory
# samples (tdo_capacity.stream_samples).
#   cmake -DEXE=tdo-sim-run -DMAPS=maps -DDATA=test/data -DOUT=dir -P test_sim_samples.cmake
# 1. Map6 (E-APF among 12 movers): the episode JSON of --samples stored and --samples streamed is
#    byte-identical and carries the plan (its sample positions) and the flown steps.
# 2. Online replanning round a hidden wall (every replan reads the new plan's samples): the same
#    summary line in both modes, with at least one replan and switch.
# 3. --samples pieces: the same episode once the library accepts it, else exit 2 with one
#    "tdo-sim-run: error: planner init: <status name>" line.
foreach(v EXE MAPS DATA OUT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "test_sim_samples.cmake needs -D${v}")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

foreach(mode stored streamed)
  execute_process(COMMAND ${EXE} --map ${MAPS}/map6.tdomap --samples ${mode} -o ${OUT}/${mode}.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^eapf: plan ok, 12 movers")
    message(FATAL_ERROR "Map6 --samples ${mode} (exit ${rc}):\n${out}\n${err}")
  endif()
  file(READ ${OUT}/${mode}.json json_${mode})
  if(NOT json_${mode} MATCHES "\"plan\": *\\[[ \n]*\\[" OR NOT json_${mode} MATCHES "\"steps\": *\\[[ \n]*{")
    message(FATAL_ERROR "Map6 --samples ${mode}: the episode has no plan or no steps")
  endif()
endforeach()
if(NOT json_stored STREQUAL json_streamed)
  message(FATAL_ERROR "Map6: --samples stored and streamed give different episodes; see ${OUT}")
endif()
string(LENGTH "${json_stored}" len)
message(STATUS "ok: Map6 episode identical with samples stored and streamed (${len} bytes)")

set(wall ${DATA}/hidden_wall.tdomap)
foreach(mode stored streamed)
  execute_process(COMMAND ${EXE} --map ${wall} --unknown 1 --sensor-range 5 --replanner tdo
                          --samples ${mode}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE online_${mode} ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT online_${mode} MATCHES "^online tdo: plan ok, hidden 1 revealed 1, success yes"
     OR NOT online_${mode} MATCHES "replans [1-9][0-9]* \\(" OR NOT online_${mode} MATCHES "switches [1-9]")
    message(FATAL_ERROR "hidden wall --samples ${mode} (exit ${rc}):\n${online_${mode}}\n${err}")
  endif()
endforeach()
if(NOT online_stored STREQUAL online_streamed)
  message(FATAL_ERROR "hidden wall: stored and streamed differ:\n${online_stored}${online_streamed}")
endif()
message(STATUS "ok: online replanning identical with samples stored and streamed")

execute_process(COMMAND ${EXE} --map ${MAPS}/map6.tdomap --samples pieces -o ${OUT}/pieces.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  file(READ ${OUT}/pieces.json json_pieces)
  if(NOT json_pieces STREQUAL json_stored)
    message(FATAL_ERROR "Map6: --samples pieces gives another episode than stored")
  endif()
  message(STATUS "ok: --samples pieces gives the same episode")
elseif(rc EQUAL 2 AND err MATCHES "^tdo-sim-run: error: planner init: [a-z_]+\n$")
  message(STATUS "ok: --samples pieces refused: ${err}")
else()
  message(FATAL_ERROR "--samples pieces: exit ${rc}, expected 0 or 2 naming a status:\n${out}\n${err}")
endif()
