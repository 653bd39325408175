// The coarse guide of the turn-penalised search (docs/design.md s.1, "The coarse guide"): the same
// search on a grid of coarse cells (2^shift voxels per edge, a cell free when any of its voxels
// is), then the fine search confined to a corridor around the coarse path, and the whole grid only
// when the corridor holds no path. Internal to libtdo.
#ifndef TDO_SRC_GUIDE_H
#define TDO_SRC_GUIDE_H

#include <stddef.h>
#include <stdint.h>

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/search.h"
#include "tdo/status.h"

namespace tdo_internal {

struct Guide;

struct GuideCapacity {
  uint32_t max_cells;  // coarse cells of the largest coarse grid
  uint32_t max_nodes;  // coarse search states per direction
  uint32_t max_path;   // cells of a coarse path
  int32_t shift;       // log2 of the coarse cell edge in voxels, 1..7
};

// The guide's capacity for a planner of max_voxels voxels and a cell edge of 2^shift voxels.
GuideCapacity guide_capacity(uint32_t max_voxels, int32_t shift);
size_t guide_footprint(const GuideCapacity& cap);
tdo_status guide_init(Guide** out, tdo_arena* arena, const GuideCapacity& cap);

// What the guide did for one query.
struct GuideReport {
  uint32_t used;         // 0: no guide (grid too small or too large for it), 1: the corridor's
                         // search found the path, 2: the corridor's search found no path and the
                         // whole grid was searched, 3: a short query's whole-grid search answered
  uint32_t expansions;   // a short query's spent try, coarse search and corridor search (the
                         // search that returned excluded)
  uint32_t corridor;     // coarse cells in the corridor
  uint32_t coarse_path;  // cells of the coarse path
};

// The search of `in` through the guide; `out` as tdo_search_run's for the fine search that found
// the path (or the whole-grid search's status).
tdo_status guide_search(Guide* gd, tdo_search* fine, const tdo_search_input* in,
                        tdo_search_output* out, GuideReport* report);

}  // namespace tdo_internal

#endif  // TDO_SRC_GUIDE_H
