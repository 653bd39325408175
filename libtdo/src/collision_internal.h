// Internal collision queries shared by the stages (not part of the public API).
#ifndef TDO_SRC_COLLISION_INTERNAL_H
#define TDO_SRC_COLLISION_INTERNAL_H

#include <stdint.h>

#include "tdo/collision.h"

namespace tdo_internal {

/**
 * tdo_collision_segment_clear with a hint for runs of similar queries: *hint (1 + the index of
 * the box that failed the last query, 0 for none) is tested first against the whole segment, and
 * the query stops as "not clear" when that box is certainly closer than the clearance (by more
 * than a rounding margin, so the full query would fail too); otherwise the full query runs and a
 * box that fails it becomes the hint. Same answer as tdo_collision_segment_clear, always.
 */
int segment_clear_hinted(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                         uint32_t* hint);

}  // namespace tdo_internal

#endif  // TDO_SRC_COLLISION_INTERNAL_H
