// The path's distance to the obstacles as the metrics measure it (internal; metrics.cpp): lines
// exact, curves a proven chord lower bound. tdo_metrics_compute reports it as min_clearance_m, and
// the trajectory's pieces check (trajectory.cpp) takes the same value for its report.
#ifndef TDO_SRC_PATH_CLEARANCE_H
#define TDO_SRC_PATH_CLEARANCE_H

#include <stdint.h>

#include "tdo/grid.h"
#include "tdo/path.h"
#include "tdo/types.h"

namespace tdo_internal {

/** m, min(cap, distance) of `path` (or, when it is NULL, of the polyline w[0..n)) to the obstacles
 *  of a finished grid; 0 when touching. `hint` (0 = none): a value just above the expected result;
 *  the queries start capped there and the result is the same whatever the hint. cap > 0. */
double path_min_clearance(const tdo_grid* grid, const tdo_path* path, const tdo_vec3* w, uint32_t n,
                          double cap, double hint);

}  // namespace tdo_internal

#endif  // TDO_SRC_PATH_CLEARANCE_H
