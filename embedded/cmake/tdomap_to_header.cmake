# Turn a .tdomap file (maps/README.md) into a C header, so a firmware image carries the map as
# constant data. Run as a script:
#
#   cmake -DIN=maps/map1.tdomap -DOUT=tdo_demo_map.h -DNAME=map1 -P tdomap_to_header.cmake
#
# Numbers are copied as written (decimal text), so the compiler rounds them exactly as the host's
# strtod does. Only 'bounds', 'resolution', 'start', 'goal' and 'box' lines are accepted; anything
# else (voxels, movers) stops the build with the line number.
cmake_policy(VERSION 3.20)

foreach(var IN ITEMS IN OUT NAME)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "tdomap_to_header: -D${var}=... is required")
  endif()
endforeach()

file(STRINGS "${IN}" lines)
set(num "[-+]?[0-9]+(\\.[0-9]*)?([eE][-+]?[0-9]+)?")
set(boxes "")
set(n_boxes 0)
set(line_no 0)
foreach(line IN LISTS lines)
  math(EXPR line_no "${line_no} + 1")
  string(REGEX REPLACE "#.*$" "" line "${line}")
  string(STRIP "${line}" line)
  if(line STREQUAL "")
    continue()
  endif()
  string(REGEX REPLACE "[ \t]+" ";" tok "${line}")
  list(GET tok 0 kw)
  list(REMOVE_AT tok 0)
  list(LENGTH tok n)
  foreach(t IN LISTS tok)
    if(NOT kw STREQUAL "tdomap" AND NOT t MATCHES "^${num}$")
      message(FATAL_ERROR "${IN}:${line_no}: '${t}' is not a number")
    endif()
  endforeach()
  string(REPLACE ";" ", " args "${tok}")
  if(kw STREQUAL "tdomap")
    if(NOT tok STREQUAL "1")
      message(FATAL_ERROR "${IN}:${line_no}: only 'tdomap 1' is supported")
    endif()
  elseif(kw STREQUAL "bounds" AND n EQUAL 6)
    set(bounds "${args}")
  elseif(kw STREQUAL "resolution" AND n EQUAL 1)
    set(res "${args}")
  elseif(kw STREQUAL "start" AND n EQUAL 3)
    set(start "${args}")
  elseif(kw STREQUAL "goal" AND n EQUAL 3)
    set(goal "${args}")
  elseif(kw STREQUAL "box" AND n EQUAL 6)
    list(SUBLIST tok 0 3 lo)
    list(SUBLIST tok 3 3 hi)
    string(REPLACE ";" ", " lo "${lo}")
    string(REPLACE ";" ", " hi "${hi}")
    string(APPEND boxes "    {{${lo}}, {${hi}}},\n")
    math(EXPR n_boxes "${n_boxes} + 1")
  else()
    message(FATAL_ERROR "${IN}:${line_no}: unsupported line for the firmware: '${line}'")
  endif()
endforeach()
foreach(var IN ITEMS bounds res start goal)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${IN}: no '${var}' line")
  endif()
endforeach()
if(n_boxes EQUAL 0)
  message(FATAL_ERROR "${IN}: no 'box' line")
endif()

get_filename_component(in_name "${IN}" NAME)
set(text "/* Generated from ${in_name} by embedded/cmake/tdomap_to_header.cmake; do not edit. */
#ifndef TDO_DEMO_MAP_H
#define TDO_DEMO_MAP_H

#include \"tdo/types.h\"

#define TDO_DEMO_MAP_NAME \"${NAME}\"
#define TDO_DEMO_MAP_FILE \"${in_name}\"
#define TDO_DEMO_MAP_BOXES ${n_boxes}u

/* m, world frame: min x, y, z then max x, y, z */
static const double tdo_demo_map_bounds[6] = {${bounds}};
/* m, voxel edge */
static const double tdo_demo_map_res = ${res};
/* m, world frame */
static const tdo_vec3 tdo_demo_map_start = {${start}};
static const tdo_vec3 tdo_demo_map_goal = {${goal}};
/* m, world frame: axis-aligned obstacle boxes {min}, {max} */
static const tdo_box tdo_demo_map_boxes[TDO_DEMO_MAP_BOXES] = {
${boxes}};

#endif /* TDO_DEMO_MAP_H */
")
# Write only on change, so an unchanged map does not rebuild the firmware.
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
  if(old STREQUAL text)
    return()
  endif()
endif()
file(WRITE "${OUT}" "${text}")
