// Layout of tdo_planner. Internal to libtdo.
#ifndef TDO_SRC_PLANNER_INTERNAL_H
#define TDO_SRC_PLANNER_INTERNAL_H

#include <stddef.h>

#include "guide.h"
#include "tdo/arena.h"
#include "tdo/config.h"
#include "tdo/correct.h"
#include "tdo/grid.h"
#include "tdo/search.h"
#include "tdo/smooth.h"
#include "tdo/trajectory.h"

struct tdo_planner {
  tdo_planner_config cfg;
  tdo_arena arena;
  tdo_grid* grid;
  tdo_search* search;
  tdo_internal::Guide* guide;  // nullptr without tdo_capacity.guide_shift
  tdo_correct* correct;
  tdo_smooth* smooth;
  tdo_traj* traj;
  tdo_vec3* grid_path;  // max_path + 2 world points of the last plan
  uint32_t n_grid_path;
  tdo_vec3* waypoints;  // max_waypoints: a moving start's entry points + the correction's output
  int have_samples;     // 1 when the last plan returned a trajectory (tdo_planner_each_sample)
};

namespace tdo_internal {
size_t planner_footprint(const tdo_planner_config* cfg);
size_t pipeline_footprint(const tdo_planner_config* cfg);
tdo_status pipeline_init(tdo_planner* planner, tdo_arena* arena);
}  // namespace tdo_internal

#endif  // TDO_SRC_PLANNER_INTERNAL_H
