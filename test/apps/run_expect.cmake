# Run a program and check its exact exit status and (optionally) a regex on stdout + stderr.
#   cmake -DEXE=prog "-DARGS=a|b|c" -DCODE=0 [-DOUTPUT_REGEX=re] -P run_expect.cmake
if(NOT DEFINED EXE OR NOT DEFINED CODE)
  message(FATAL_ERROR "run_expect.cmake needs -DEXE and -DCODE")
endif()
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 60)
set(report "command: ${EXE} ${args}\nexit status: ${rc}\nstdout:\n${out}\nstderr:\n${err}")
if(NOT rc STREQUAL "${CODE}")
  message(FATAL_ERROR "expected exit status ${CODE}\n${report}")
endif()
if(DEFINED OUTPUT_REGEX AND NOT "${out}${err}" MATCHES "${OUTPUT_REGEX}")
  message(FATAL_ERROR "output does not match '${OUTPUT_REGEX}'\n${report}")
endif()
message(STATUS "ok: exit status ${rc}")
