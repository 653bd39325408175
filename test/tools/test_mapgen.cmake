# tdo-mapgen checks, run as: cmake -DEXE=tdo-mapgen -DMODE=... -DOUT=dir [-DMAPS=dir] -P test_mapgen.cmake
#   MODE=regenerate  regenerate map1..map6 into OUT and compare them byte for byte with MAPS/
#   MODE=random      two seeds, each generated twice into OUT: identical, solvable (--stats exit 0)
#   MODE=bad_args    bad command lines exit with status 2 and one "tdo-mapgen: error: ..." line
if(NOT DEFINED EXE OR NOT DEFINED MODE OR NOT DEFINED OUT)
  message(FATAL_ERROR "test_mapgen.cmake needs -DEXE -DMODE -DOUT")
endif()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

function(run_ok)
  execute_process(COMMAND ${EXE} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${EXE} ${ARGN}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

if(MODE STREQUAL "regenerate")
  if(NOT DEFINED MAPS)
    message(FATAL_ERROR "MODE=regenerate needs -DMAPS")
  endif()
  foreach(n 1 2 3 4 5 6)
    run_ok(--map map${n} -o ${OUT}/map${n}.tdomap)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${MAPS}/map${n}.tdomap
                            ${OUT}/map${n}.tdomap RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "maps/map${n}.tdomap differs from a fresh 'tdo-mapgen --map map${n}' "
                          "(${OUT}/map${n}.tdomap). If the generator or libtdo's grid changed on "
                          "purpose, regenerate the maps and update maps/README.md.")
    endif()
  endforeach()
elseif(MODE STREQUAL "random")
  foreach(seed 7 20240611)
    set(args --random --size 30 25 12 --columns 150 --footprint 1 3 --seed ${seed} --movers 3
             --mover-speed 0.4 1.2 --start 2 2 3 --goal 28 23 6)
    run_ok(${args} -o ${OUT}/a${seed}.tdomap)
    run_ok(${args} -o ${OUT}/b${seed}.tdomap)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/a${seed}.tdomap
                            ${OUT}/b${seed}.tdomap RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "seed ${seed}: two runs gave different files")
    endif()
    file(READ ${OUT}/a${seed}.tdomap text)
    string(REGEX MATCHALL "\nbox " boxes "${text}")
    string(REGEX MATCHALL "\nmover " movers "${text}")
    list(LENGTH boxes nb)
    list(LENGTH movers nm)
    if(NOT nb EQUAL 150 OR NOT nm EQUAL 3)
      message(FATAL_ERROR "seed ${seed}: expected 150 boxes and 3 movers, got ${nb} and ${nm}")
    endif()
    if(NOT text MATCHES "Regenerate \\(byte for byte\\): tdo-mapgen --random --size 30 25 12 --columns 150 --footprint 1 3 --seed ${seed} ")
      message(FATAL_ERROR "seed ${seed}: header lacks the regeneration command")
    endif()
    run_ok(--stats ${OUT}/a${seed}.tdomap --clearance 0.5)
  endforeach()
  file(READ ${OUT}/a7.tdomap a)
  file(READ ${OUT}/a20240611.tdomap b)
  if(a STREQUAL b)
    message(FATAL_ERROR "two different seeds gave the same map")
  endif()
elseif(MODE STREQUAL "bad_args")
  set(cases
      "--map|map7|-o|X"                                 "unknown map 'map7'"
      "--random|--columns|5|-o|X"                       "--random needs --size"
      "--random|--size|20|20|-o|X"                      "size"
      "--random|--size|20|20|20|--columns|5|--footprint|3|1|-o|X" "--footprint"
      "--random|--size|20|20|20|--columns|5|--footprint|1.25|2|-o|X" "steps of 0.1 m"
      "--random|--size|20|20|20|--columns|-4|-o|X"      "--columns must be in"
      "--random|--size|20|20|20|--columns|5|--goal|25|1|1|-o|X" "--goal must lie strictly inside"
      "--random|--size|20|20|20|--columns|5|--mover-speed|0|1|-o|X" "--mover-speed"
      "--random|--size|20|20|20|--columns|5|--seed|abc|-o|X" "seed"
      "--map|map1|--seed|3|-o|X"                        "excludes|--seed"
      "--map|map1"                                      "-o FILE is required"
      "--random|--size|20|20|20|--columns|5"            "-o FILE is required"
      "--frobnicate"                                    "frobnicate"
      "--stats|${OUT}/none.tdomap"                      "none.tdomap: cannot open"
      "--seed|3"                                        "give --map NAME")
  list(LENGTH cases n)
  math(EXPR last "${n} - 1")
  foreach(i RANGE 0 ${last} 2)
    list(GET cases ${i} joined)
    math(EXPR j "${i} + 1")
    list(GET cases ${j} want)
    string(REPLACE "|" ";" args "${joined}")
    string(REPLACE "X" "${OUT}/x.tdomap" args "${args}")
    execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 2 OR NOT err MATCHES "^tdo-mapgen: error: [^\n]+\n$" OR NOT err MATCHES "${want}")
      message(FATAL_ERROR "'${joined}': expected exit status 2 and one error line matching "
                          "'${want}'\nexit status: ${rc}\nstderr:\n${err}")
    endif()
    if(EXISTS ${OUT}/x.tdomap)
      message(FATAL_ERROR "'${joined}': wrote an output file despite the error")
    endif()
  endforeach()
else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
message(STATUS "ok: ${MODE}")
