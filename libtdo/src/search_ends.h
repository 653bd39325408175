// The ends of a search query (docs/design.md s.1, "Search ends"): the one check of start and goal
// that tdo_search_run and the pipeline's direct route both make, so the two cannot disagree on
// what is plannable.
#ifndef TDO_SEARCH_ENDS_H
#define TDO_SEARCH_ENDS_H

#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

namespace tdo_internal {

/**
 * Whether start and goal make a search query on `g` (a finished grid), in this order: the start
 * inside the grid's half-open bounds (TDO_ERR_START_OUT_OF_BOUNDS: outside, on a max face or not
 * finite), the goal too (TDO_ERR_GOAL_OUT_OF_BOUNDS), two distinct points
 * (TDO_ERR_START_EQUALS_GOAL), the start voxel free at the grid's clearance, the centre rule of
 * s.0 (TDO_ERR_START_BLOCKED), the goal voxel too (TDO_ERR_GOAL_BLOCKED). TDO_OK: both voxels are
 * in ends[0] (start) and ends[1] (goal); otherwise ends is unspecified.
 */
inline tdo_status search_ends_ok(const tdo_grid* g, tdo_vec3 start, tdo_vec3 goal,
                                 tdo_voxel ends[2]) {
  if (!tdo_grid_world_to_voxel(g, start, &ends[0])) return TDO_ERR_START_OUT_OF_BOUNDS;
  if (!tdo_grid_world_to_voxel(g, goal, &ends[1])) return TDO_ERR_GOAL_OUT_OF_BOUNDS;
  if (!(start.x < goal.x || start.x > goal.x || start.y < goal.y || start.y > goal.y ||
        start.z < goal.z || start.z > goal.z))
    return TDO_ERR_START_EQUALS_GOAL;
  if (tdo_grid_is_blocked(g, ends[0])) return TDO_ERR_START_BLOCKED;
  if (tdo_grid_is_blocked(g, ends[1])) return TDO_ERR_GOAL_BLOCKED;
  return TDO_OK;
}

}  // namespace tdo_internal

#endif  // TDO_SEARCH_ENDS_H
