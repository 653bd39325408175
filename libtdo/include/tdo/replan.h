/**
 * @file replan.h
 * @brief Replanning in flight (docs/design.md s.4, "Replanning"): is the active trajectory still
 *        clear on the current (updated) grid over a horizon, and from which state does the next
 *        plan start.
 *
 * The loop around it: after every map update (tdo_grid_apply_update) and obstacle message, call
 * tdo_replan_check from the follower's trajectory clock; when it reports the trajectory blocked
 * (or the follower reports a local minimum), take the state tdo_replan_takeover predicts at the
 * time the new plan will be ready, plan from it (tdo_plan_request.start = p, .state = state), and
 * hand the new plan to the follower with tdo_apf_switch at that time: the new plan starts with
 * exactly the old plan's position, velocity and acceleration there, and the follower's reference
 * passes from one to the other without a jump.
 * No memory of its own, no I/O, deterministic, every loop bounded by the sample and mover counts.
 */
#ifndef TDO_REPLAN_H
#define TDO_REPLAN_H

#include <stdint.h>

#include "tdo/apf.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Why a trajectory is blocked. */
typedef enum tdo_replan_cause {
  TDO_REPLAN_CLEAR = 0,  /**< not blocked within the horizon */
  TDO_REPLAN_STATIC = 1, /**< a piece comes closer than the clearance to the grid's geometry or
                              leaves the grid bounds */
  TDO_REPLAN_MOVER = 2   /**< a sample comes within a mover's radius + mover_clearance at the
                              mover's predicted position (constant velocity) */
} tdo_replan_cause;

/** What to check. */
typedef struct tdo_replan_check_input {
  const tdo_grid* grid;      /**< finished grid with every update applied */
  const tdo_sample* samples; /**< active trajectory: uniform dt from t = 0 (trajectory.h) */
  uint32_t n_samples;        /**< >= 2 */
  double t;                  /**< s, trajectory time to check from, >= 0: the follower's
                                  reference time (tdo_apf_output.ref_time) */
  double horizon;            /**< s, >= 0: the pieces from t to t + horizon are checked */
  double clearance;          /**< m, >= 0: each straight piece between consecutive samples must
                                  keep it (tdo_collision_segment_clear, exact). Use the plan's
                                  clearance less the chord's sagitta (1 cm covers 0.01 s samples
                                  at 3 m/s in any turn the limits allow) */
  const tdo_mover* movers;   /**< movers at trajectory time t (may be NULL when n_movers = 0) */
  uint32_t n_movers;         /**< count */
  double mover_clearance;    /**< m, >= 0: added to a mover's radius (vehicle radius and margin) */
} tdo_replan_check_input;

/** Result of a check. */
typedef struct tdo_replan_check_result {
  int blocked;             /**< 1 when blocked within the horizon */
  tdo_replan_cause cause;  /**< the first blocking cause in time */
  double t_blocked;        /**< s, trajectory time of the first blocked piece's start (or of
                                the blocked sample); HUGE_VAL when clear */
  uint32_t index;          /**< that sample's index */
  uint32_t mover_id;       /**< the mover's id (cause MOVER) */
  uint32_t pieces_checked; /**< straight pieces checked against the grid */
} tdo_replan_check_result;

/**
 * @brief Check the active trajectory from trajectory time t over the horizon: each straight piece
 *        between consecutive samples whose time interval meets [t, t + horizon] against the grid,
 *        and each sample in that interval against the movers' predicted positions. Pieces and
 *        samples in time order; the first failure is reported.
 * @return TDO_OK (blocked or not: see out->blocked); TDO_ERR_INVALID_ARGUMENT for null pointers,
 *         fewer than 2 samples, samples not uniform in time from 0 (1e-6 relative, first two and
 *         last), non-finite or negative t, horizon or clearances, a non-finite mover or a mover
 *         radius not > 0; TDO_ERR_MAP_NOT_READY for an unfinished grid.
 */
tdo_status tdo_replan_check(const tdo_replan_check_input* in, tdo_replan_check_result* out);

/** The state a new plan starts from. */
typedef struct tdo_replan_takeover_result {
  double t;              /**< s, trajectory time of the takeover on the active trajectory: the
                              first sample time at or after t + latency (its last sample's time
                              when later) */
  uint32_t index;        /**< that sample's index */
  tdo_vec3 p;            /**< m, position there: the new plan's start */
  tdo_start_state state; /**< m/s, m/s^2: velocity and acceleration there, for
                              tdo_plan_request.state */
} tdo_replan_takeover_result;

/**
 * @brief The predicted state on the active trajectory at the takeover time t + latency, rounded
 *        up to a sample so that the state is exactly one of the trajectory's (no interpolation).
 * @param t s, trajectory time now, >= 0: the follower's reference time (tdo_apf_output.ref_time),
 *        which is what tdo_apf_switch compares the switch time with
 * @param latency s, >= 0: time until the new plan is ready (planning and transport)
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers, fewer than 2 samples, samples not
 *         uniform from 0, a non-finite or negative t or latency.
 */
tdo_status tdo_replan_takeover(const tdo_sample* samples, uint32_t n_samples, double t,
                               double latency, tdo_replan_takeover_result* out);

/** Where a mover will be: the region it sweeps over a time window, as temporary voxels. */
typedef struct tdo_replan_mover_region {
  tdo_mover mover;    /**< the mover at time 0 of the window's clock (constant velocity) */
  double t0, t1;      /**< s, window on that clock, t0 <= t1: the centre moves from
                           p + v t0 to p + v t1 */
  double pad;         /**< m, >= 0: added to the mover's radius */
  tdo_vec3 keep_free; /**< m, world frame: no voxel whose centre is within keep_radius of this
                           point is listed (the vehicle and its takeover point) */
  double keep_radius; /**< m, >= 0 */
} tdo_replan_mover_region;

/**
 * @brief The voxels a mover occupies over a time window, for a replan that must route round
 *        where the mover will be (docs/design.md s.4, "Replanning", movers): every voxel inside
 *        the grid whose centre is within radius + pad of the segment the mover's centre sweeps
 *        over [t0, t1], that is not occupied already (tdo_grid_is_occupied) and whose centre is
 *        farther than keep_radius from keep_free; in index order (k, then j, then i).
 *        Apply them as `set` of a tdo_grid_update, plan, then apply the same list as `clear`:
 *        the grid is exactly as before (only voxels that were free were set).
 * @param out caller-owned, capacity voxels
 * @param[out] n_out voxels listed
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers, a non-finite mover or window,
 *         t1 < t0, a radius not > 0, a negative or non-finite pad or keep_radius;
 *         TDO_ERR_MAP_NOT_READY for an unfinished grid; TDO_ERR_MAP_CAPACITY when more than
 *         `capacity` voxels qualify (the first `capacity` are listed). Work: the voxels of the
 *         region's bounding box (bounded by the grid).
 */
tdo_status tdo_replan_mover_voxels(const tdo_grid* grid, const tdo_replan_mover_region* region,
                                   tdo_voxel* out, uint32_t capacity, uint32_t* n_out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_REPLAN_H */
