/**
 * @file planner.h
 * @brief The planner: one arena, one grid and every stage context, initialised once.
 */
#ifndef TDO_PLANNER_H
#define TDO_PLANNER_H

#include "tdo/config.h"
#include "tdo/grid.h"
#include "tdo/search.h"
#include "tdo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Opaque planner; lives at the start of the caller's arena. */
typedef struct tdo_planner tdo_planner;

/**
 * @brief Build a planner inside the caller's arena. The only place libtdo takes memory.
 * @param[out] out the planner (points into `arena`)
 * @param[in] arena caller-owned memory, at least tdo_planner_footprint(cfg) bytes, alive as long as
 *            the planner
 * @return TDO_ERR_INVALID_ARGUMENT for null or zero capacities, TDO_ERR_ARENA_TOO_SMALL.
 */
tdo_status tdo_planner_init(tdo_planner** out, void* arena, size_t arena_bytes,
                            const tdo_planner_config* cfg);

/** @return the planner's grid, to load a map with tdo_grid_reset / add / finish. */
tdo_grid* tdo_planner_grid(tdo_planner* planner);

/** @return the planner's search context. */
tdo_search* tdo_planner_search(tdo_planner* planner);

/** @return arena bytes carved at init (at most the footprint). */
size_t tdo_planner_arena_used(const tdo_planner* planner);

#ifdef __cplusplus
}
#endif

#endif /* TDO_PLANNER_H */
