# Determinism of tdo-plan: run the same command twice and require bit-identical JSON.
#   cmake -DEXE=tdo-plan "-DARGS=--map|m.tdomap|--json" -P test_determinism.cmake
# The only field allowed to differ is "plan_time_ms" (wall time): it is removed from both outputs
# before the comparison. The run must have planned (status "ok") and given a trajectory.
if(NOT DEFINED EXE OR NOT DEFINED ARGS)
  message(FATAL_ERROR "test_determinism.cmake needs -DEXE and -DARGS")
endif()
string(REPLACE "|" ";" args "${ARGS}")
foreach(run 1 2)
  execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out${run}
                  ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "run ${run}: exit status ${rc}\nstderr:\n${err}")
  endif()
  if(NOT out${run} MATCHES "^{\"arena_bytes\"" OR NOT out${run} MATCHES "\"status\":\"ok\"" OR
     NOT out${run} MATCHES "\"samples\":\\[\\[")
    message(FATAL_ERROR "run ${run}: not a planned JSON trajectory:\n${out${run}}")
  endif()
  string(REGEX MATCHALL "\"plan_time_ms\":" fields "${out${run}}")
  list(LENGTH fields n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "run ${run}: expected one plan_time_ms field, found ${n}")
  endif()
  string(REGEX REPLACE "\"plan_time_ms\":[-+.0-9eE]+,?" "" stripped${run} "${out${run}}")
endforeach()
if(NOT stripped1 STREQUAL stripped2)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/determinism_run1.json "${stripped1}")
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/determinism_run2.json "${stripped2}")
  message(FATAL_ERROR "the two runs differ (plan_time_ms removed); see determinism_run1.json and "
                      "determinism_run2.json in ${CMAKE_CURRENT_BINARY_DIR}")
endif()
string(LENGTH "${stripped1}" len)
message(STATUS "ok: two runs give the same ${len} bytes of JSON (plan_time_ms removed)")
