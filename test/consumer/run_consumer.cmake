# cmake -P script behind the install_consumer test.
#   -DTDO_BUILD_DIR=     the libtdo build tree to install
#   -DCONSUMER_SOURCE_DIR= the consumer project
#   -DWORK_DIR=          scratch directory (emptied first): prefix/ and build/ go here
#   -DGENERATOR= -DC_COMPILER= -DCXX_COMPILER= -DBUILD_TYPE= as the parent build
#   -DEXTRA_FLAGS=       compile and link flags for the consumer (sanitizer runtimes)
cmake_minimum_required(VERSION 3.20)

foreach(var TDO_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: -D${var}= is required")
  endif()
endforeach()

# Run a command, show it, and fail the test when it fails.
function(run_step what)
  message(STATUS "[consumer] ${what}: ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[consumer] ${what} failed (${rc})")
  endif()
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${prefix}" "${build}")

run_step("install" "${CMAKE_COMMAND}" --install "${TDO_BUILD_DIR}" --prefix "${prefix}")

set(configure "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${build}" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}")
foreach(pair "C_COMPILER;CMAKE_C_COMPILER" "CXX_COMPILER;CMAKE_CXX_COMPILER"
             "BUILD_TYPE;CMAKE_BUILD_TYPE")
  list(GET pair 0 in)
  list(GET pair 1 out)
  if(NOT "${${in}}" STREQUAL "")
    list(APPEND configure "-D${out}=${${in}}")
  endif()
endforeach()
if(NOT "${EXTRA_FLAGS}" STREQUAL "")
  list(APPEND configure "-DCMAKE_C_FLAGS=${EXTRA_FLAGS}" "-DCMAKE_CXX_FLAGS=${EXTRA_FLAGS}"
       "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}")
endif()
run_step("configure" ${configure})
run_step("build" "${CMAKE_COMMAND}" --build "${build}")
run_step("run" "${build}/tdo_consumer")
