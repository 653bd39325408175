/**
 * @file correct.h
 * @brief Stage 2: multi-scale inflection correction of the grid path (pipeline.md s.2).
 */
#ifndef TDO_CORRECT_H
#define TDO_CORRECT_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Correction variant. */
typedef enum tdo_correct_mode {
  TDO_CORRECT_MULTISCALE = 0, /**< scales 3, 5, 7 (TDO-MSF) */
  TDO_CORRECT_GREEDY_LOS = 1, /**< single-scale greedy line of sight (MSF-MTPO baseline) */
  TDO_CORRECT_NONE = 2        /**< collinear points dropped only */
} tdo_correct_mode;

typedef struct tdo_correct tdo_correct;

/** Capacities. */
typedef struct tdo_correct_config {
  uint32_t max_points; /**< input and output points */
  uint32_t max_checks; /**< segment clearance checks per run (budget) */
} tdo_correct_config;

/** Input polyline: voxel centres with the exact start and goal at its ends. */
typedef struct tdo_correct_input {
  const tdo_grid* grid;   /**< finished grid */
  const tdo_vec3* points; /**< m, world frame */
  uint32_t n_points;      /**< >= 2 */
  tdo_correct_mode mode;  /**< variant */
  double clearance;       /**< m, every output segment keeps it */
  double turn_threshold;  /**< rad; interior turns below it count as "straight" in a window */
} tdo_correct_input;

/** Output polyline P2; storage in the context, valid until the next run. */
typedef struct tdo_correct_output {
  const tdo_vec3* waypoints; /**< m, world frame; first = start, last = goal */
  uint32_t n_waypoints;
  uint32_t n_safety_critical; /**< points kept because their removal would break clearance */
  uint32_t checks;            /**< segment checks done */
} tdo_correct_output;

size_t tdo_correct_footprint(const tdo_correct_config* cfg);
tdo_status tdo_correct_init(tdo_correct** ctx, tdo_arena* arena, const tdo_correct_config* cfg);
/**
 * @return TDO_ERR_INVALID_ARGUMENT, TDO_ERR_PATH_CAPACITY (too many points), TDO_ERR_BUDGET,
 *         TDO_ERR_NO_PATH when an input segment itself breaks clearance.
 */
tdo_status tdo_correct_run(tdo_correct* ctx, const tdo_correct_input* in, tdo_correct_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_CORRECT_H */
