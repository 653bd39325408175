# cmake -P script behind the install_consumer test.
#   -DTDO_BUILD_DIR=     the libtdo build tree to install
#   -DCONSUMER_SOURCE_DIR= the consumer project
#   -DWORK_DIR=          scratch directory (emptied first): prefix/ and build/ go here
#   -DGENERATOR= -DC_COMPILER= -DCXX_COMPILER= -DBUILD_TYPE= as the parent build
#   -DEXTRA_FLAGS=       compile and link flags for the consumer (sanitizer runtimes)
#   -DREADME=            README.md: its ```c block must be project/readme_example.c and its first
#                        ```text block after it that program's output
#   -DEXPECT_LCMTYPES=ON the build has the LCM apps: the message types must be installed and the
#                        consumer's LCM node (tdo::lcmtypes alone) must build and run
cmake_minimum_required(VERSION 3.20)

foreach(var TDO_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR README)
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
if(EXPECT_LCMTYPES)
  list(APPEND configure "-DTDO_EXPECT_LCMTYPES=ON")
endif()
run_step("configure" ${configure})
run_step("build" "${CMAKE_COMMAND}" --build "${build}")
run_step("run" "${build}/tdo_consumer")
if(EXPECT_LCMTYPES)
  run_step("run the LCM node" "${build}/tdo_lcm_node")
  foreach(f share/tdo/lcmtypes/tdo_trajectory_t.lcm include/tdo_lcmtypes/tdo_trajectory_t.h
            include/tdo_lcmtypes/tdo/trajectory_t.hpp include/tdo_lcmtypes/tdo_traj_eval.h
            share/tdo/python/tdo/trajectory_t.py)
    if(NOT EXISTS "${prefix}/${f}")
      message(FATAL_ERROR "[consumer] not installed: ${f}")
    endif()
  endforeach()
endif()

# The README's example: the source it shows, and the output it shows, byte for byte.
function(readme_block fence from out_text out_end)
  file(READ "${README}" text)
  string(SUBSTRING "${text}" ${from} -1 text)
  string(FIND "${text}" "\n```${fence}\n" begin)
  if(begin EQUAL -1)
    message(FATAL_ERROR "[consumer] README.md has no ```${fence} block")
  endif()
  string(LENGTH "\n```${fence}\n" fence_len)
  math(EXPR begin "${begin} + ${fence_len}")
  string(SUBSTRING "${text}" ${begin} -1 text)
  string(FIND "${text}" "```\n" end)
  string(SUBSTRING "${text}" 0 ${end} block)
  math(EXPR end "${from} + ${begin} + ${end}")
  set(${out_text} "${block}" PARENT_SCOPE)
  set(${out_end} ${end} PARENT_SCOPE)
endfunction()

readme_block("c" 0 shown_source source_end)
file(READ "${CONSUMER_SOURCE_DIR}/readme_example.c" source)
if(NOT shown_source STREQUAL source)
  message(FATAL_ERROR "[consumer] README.md's ```c block differs from project/readme_example.c")
endif()
readme_block("text" ${source_end} shown_output output_end)
message(STATUS "[consumer] run: ${build}/tdo_readme_example")
execute_process(COMMAND "${build}/tdo_readme_example" RESULT_VARIABLE rc OUTPUT_VARIABLE output)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "[consumer] the README example failed (${rc}):\n${output}")
endif()
if(NOT output STREQUAL shown_output)
  message(FATAL_ERROR "[consumer] the README example printed\n${output}\nREADME.md shows\n"
                      "${shown_output}")
endif()
