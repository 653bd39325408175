# Find LCM 1.5 (the official wheel, installed into <repo>/.venv by scripts/setup.sh) for the apps.
#
# Where it looks, in order: lcm_DIR (scripts/build.sh passes the venv's lcm/cmake directory),
# CMAKE_PREFIX_PATH, then <repo>/.venv/lib/python3*/site-packages/lib/lcm/cmake (any Python).
#
# Defines, before find_package(lcm):
#   GLib2::glib   imported target for the system libglib-2.0. The wheel's exported lcm-static
#                 target links GLib2::glib but its config never defines it (known 1.5.x trap).
# After it: the imported targets lcm, lcm-static, lcm-coretypes, lcm-gen, lcm-java and the
# functions of lcmUtilities.cmake (lcm_wrap_types, lcm_add_library).
#   TDO_LCM_PREFIX  the wheel's prefix (site-packages), with bin/lcm-gen, share/java/lcm.jar

include_guard(GLOBAL)

# ---- GLib2::glib ---------------------------------------------------------------------------------
if(NOT TARGET GLib2::glib)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(TDO_GLIB QUIET IMPORTED_TARGET glib-2.0)
  endif()
  if(TARGET PkgConfig::TDO_GLIB)
    add_library(GLib2::glib INTERFACE IMPORTED)
    set_target_properties(GLib2::glib PROPERTIES INTERFACE_LINK_LIBRARIES PkgConfig::TDO_GLIB)
    set(_tdo_glib_what "pkg-config glib-2.0 ${TDO_GLIB_VERSION}")
  else()
    # No libglib2.0-dev: the run-time library alone is enough to link (lcm needs no GLib header).
    find_library(TDO_GLIB_LIBRARY NAMES glib-2.0 libglib-2.0.so.0)
    if(NOT TDO_GLIB_LIBRARY)
      message(FATAL_ERROR "LCM needs the system GLib (libglib-2.0): run bash scripts/setup.sh "
                          "(apt package libglib2.0-dev), or configure with -DTDO_BUILD_APPS=OFF")
    endif()
    add_library(GLib2::glib UNKNOWN IMPORTED)
    set_target_properties(GLib2::glib PROPERTIES IMPORTED_LOCATION "${TDO_GLIB_LIBRARY}")
    set(_tdo_glib_what "${TDO_GLIB_LIBRARY}")
  endif()
endif()

# ---- lcm -----------------------------------------------------------------------------------------
set(_tdo_lcm_hints "")
file(GLOB _tdo_lcm_venv_dirs LIST_DIRECTORIES true
     "${PROJECT_SOURCE_DIR}/.venv/lib/python3*/site-packages/lib/lcm/cmake")
if(_tdo_lcm_venv_dirs)
  list(APPEND _tdo_lcm_hints ${_tdo_lcm_venv_dirs})
endif()
find_package(lcm 1.5 CONFIG HINTS ${_tdo_lcm_hints})
if(NOT lcm_FOUND)
  message(FATAL_ERROR
    "LCM 1.5 not found (TDO_BUILD_APPS=ON). Run: bash scripts/setup.sh (installs the lcm wheel into "
    "${PROJECT_SOURCE_DIR}/.venv), then bash scripts/build.sh, which passes -Dlcm_DIR=<the venv's "
    "lcm/cmake directory>. Or configure with -DTDO_BUILD_APPS=OFF.")
endif()
include(${LCM_USE_FILE})
get_filename_component(TDO_LCM_PREFIX "${lcm_DIR}/../../.." ABSOLUTE)
message(STATUS "LCM ${LCM_VERSION}: ${lcm_DIR} (GLib2::glib: ${_tdo_glib_what})")
