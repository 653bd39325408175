/**
 * @file trajectory.h
 * @brief Stage 5: time parameterisation, dynamic feasibility verification and refinement
 *        (pipeline.md s.5).
 */
#ifndef TDO_TRAJECTORY_H
#define TDO_TRAJECTORY_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/path.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** One trajectory sample. */
typedef struct tdo_sample {
  double t;   /**< s since the start */
  tdo_vec3 p; /**< m, world frame */
  tdo_vec3 v; /**< m/s */
  tdo_vec3 a; /**< m/s^2 */
} tdo_sample;

/** Quantity of a violation. */
typedef enum tdo_quantity {
  TDO_QUANTITY_SPEED = 0,        /**< |v| > v_max (m/s) */
  TDO_QUANTITY_ACCELERATION = 1, /**< |a| > a_max (m/s^2) */
  TDO_QUANTITY_JERK = 2,         /**< |j| > j_max (m/s^3) */
  TDO_QUANTITY_TURN_RADIUS = 3,  /**< r < v^2 / a_max (m) */
  TDO_QUANTITY_CLEARANCE = 4     /**< distance to obstacles < clearance (m) */
} tdo_quantity;

/** One violation of a limit. */
typedef struct tdo_violation {
  double t;          /**< s, sample time */
  tdo_quantity what; /**< which limit */
  double value;      /**< measured value, unit of the quantity */
  double limit;      /**< the limit, same unit */
} tdo_violation;

/** Feasibility report of a sampled trajectory (finite differences at dt, paper eq. 15-19). */
typedef struct tdo_feasibility {
  int ok;                          /**< 1 when no violation */
  double max_speed;                /**< m/s */
  double max_acc;                  /**< m/s^2 */
  double max_jerk;                 /**< m/s^3 */
  double min_turn_radius;          /**< m, minimum of |v|^2/|a_perp| (HUGE_VAL when straight) */
  double min_clearance;            /**< m, minimum exact distance of the samples to obstacles */
  uint32_t n_violations;           /**< violations listed */
  uint32_t n_violations_total;     /**< violations found (may exceed the listed ones: capacity) */
  const tdo_violation* violations; /**< the first n_violations */
} tdo_feasibility;

typedef struct tdo_traj tdo_traj;

/** Capacities. */
typedef struct tdo_traj_config {
  uint32_t max_samples;     /**< samples at dt: flight time / dt + 1 */
  uint32_t max_segments;    /**< path segments */
  uint32_t max_profile;     /**< arclength stations of the speed profile */
  uint32_t max_violations;  /**< violations listed in the report */
  uint32_t max_refinements; /**< refinement rounds before TDO_ERR_INFEASIBLE */
} tdo_traj_config;

/** Input. */
typedef struct tdo_traj_input {
  tdo_path path;        /**< geometric path (stage 3) */
  const tdo_grid* grid; /**< for the clearance column of the report (may be NULL: not checked) */
  double clearance;     /**< m */
  double v_max;         /**< m/s, > 0 */
  double a_max;         /**< m/s^2, > 0 */
  double j_max;         /**< m/s^3, > 0 */
  double a_lat_max;     /**< m/s^2, > 0, lateral limit used for curve speeds */
  double dt;            /**< s, sample period, > 0 */
} tdo_traj_input;

/** Output; storage in the context, valid until the next run. */
typedef struct tdo_traj_output {
  const tdo_sample* samples; /**< from t = 0 (at start, at rest) to the end (at goal, at rest) */
  uint32_t n_samples;
  double duration;        /**< s */
  uint32_t refinements;   /**< rounds used */
  tdo_feasibility report; /**< of the returned samples */
} tdo_traj_output;

size_t tdo_traj_footprint(const tdo_traj_config* cfg);
tdo_status tdo_traj_init(tdo_traj** ctx, tdo_arena* arena, const tdo_traj_config* cfg);
/**
 * @return TDO_OK only for a trajectory that passed every check; TDO_ERR_INFEASIBLE with the report
 *         of the last attempt otherwise; TDO_ERR_SAMPLE_CAPACITY; TDO_ERR_INVALID_ARGUMENT.
 */
tdo_status tdo_traj_run(tdo_traj* ctx, const tdo_traj_input* in, tdo_traj_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_TRAJECTORY_H */
