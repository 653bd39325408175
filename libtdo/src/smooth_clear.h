// Cheap verdicts on the smoothing's corner curves (smooth.cpp, docs/design.md s.3), internal: a
// certificate that tdo_collision_bezier_clear passes a curve, and one that it fails it. Each
// claims only what the exact check would answer, so the smoothing runs that check only when
// neither decides.
#ifndef TDO_SRC_SMOOTH_CLEAR_H
#define TDO_SRC_SMOOTH_CLEAR_H

#include "tdo/grid.h"
#include "tdo/types.h"

namespace tdo_internal {

/**
 * 1 when tdo_collision_bezier_clear(grid, c, clearance, tolerance) is surely 1 (tolerance >=
 * 1e-9): no voxel within clearance + tolerance of the box of the control points is occupied
 * (block_clear) and that box lies in the bounds. 0: no claim (also for margins of 1.5 voxel
 * edges or more, which block_clear never decides).
 */
int bezier_surely_clear(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                        double tolerance);

/**
 * 1 when tdo_collision_bezier_clear(grid, c, clearance, any tolerance) is surely 0: a point of
 * the curve lies inside a voxel cube (by 1e-6 voxel edges). Tried only below a clearance of one
 * voxel edge, on points from c[3] (from_end 1) or c[0] (from_end 0), where the corner curve comes
 * nearest to the obstacle it wraps. 0: no claim.
 */
int bezier_surely_blocked(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                          int from_end);

}  // namespace tdo_internal

#endif  // TDO_SRC_SMOOTH_CLEAR_H
