// Layout of tdo_planner. Internal to libtdo.
#ifndef TDO_SRC_PLANNER_INTERNAL_H
#define TDO_SRC_PLANNER_INTERNAL_H

#include <stddef.h>

#include "tdo/arena.h"
#include "tdo/config.h"
#include "tdo/grid.h"
#include "tdo/search.h"

struct tdo_planner {
  tdo_planner_config cfg;
  tdo_arena arena;
  tdo_grid* grid;
  tdo_search* search;
};

namespace tdo_internal {
size_t planner_footprint(const tdo_planner_config* cfg);
}  // namespace tdo_internal

#endif  // TDO_SRC_PLANNER_INTERNAL_H
