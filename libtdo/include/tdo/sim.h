/**
 * @file sim.h
 * @brief Deterministic simulator: a double-integrator vehicle with speed, acceleration and jerk
 *        limits at a fixed step, and moving spheres with constant velocity reflected at the map
 *        bounds. Same inputs, same run, bit for bit.
 *
 * One step of length dt from state (p, v, a) with setpoint acceleration a_sp (tdo_motion_limit):
 * - a_sp is pushed towards by at most j_max dt (jerk limit), clipped to |a| <= a_max;
 * - speed within the same jerk budget: when (v + a' dt, a') could no longer stop its speed at
 *   v_max with the jerk limit (|v'| + x^2 / j_max > v_max, x the acceleration along v', half the
 *   jerk budget kept for turning), a' moves towards the full braking step along v (bisection);
 * - v' = v + a' dt, clipped to |v'| <= v_max (the acceleration is then (v' - v)/dt; binds only
 *   from a state the rule above did not produce);
 * - p' = p + (v + v') dt / 2 (exact for constant acceleration);
 * - plus, when accel_noise > 0, a seeded disturbance acceleration (m/s^2, per axis, constant
 *   over the step; zero mean, standard deviation accel_noise, a sum of four uniform draws so no
 *   libm call is involved) added to a' before the speed limit (splitmix64 generator in the
 *   context, seeded by `seed`; no global state).
 * Stale or missing command: a setpoint whose t lies more than setpoint_max_age behind the
 * simulator's clock (state.t - setpoint.t > setpoint_max_age, when that is > 0; a NaN t too), or
 * a step without one (tdo_sim_hold), is not flown: the step brakes towards a hover in place,
 * command a = -brake_gain v through the same motion limits, and says so (tdo_sim_output.braked;
 * a stale setpoint also makes tdo_sim_run return TDO_ERR_SETPOINT_STALE, the step done).
 * Movers: q' = q + u dt; a centre that leaves the bounds on an axis is mirrored back into them and
 * that velocity component flips (at most 4 reflections per axis and step, then clamped).
 * Fixed memory from the caller's arena (the movers), no heap, bounded work per step.
 */
#ifndef TDO_SIM_H
#define TDO_SIM_H

#include "tdo/apf.h"
#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief The motion rule shared by the follower and the simulator: limit a desired acceleration
 *        and integrate one step.
 * @param[in] s state at the start of the step (s->a is the previous acceleration)
 * @param a_des m/s^2, desired acceleration (non-finite components count as 0)
 * @param v_max m/s, a_max m/s^2, j_max m/s^3, dt s: all > 0
 * @param[out] out t = s->t + dt, the limited acceleration a (|a| <= a_max,
 *             |a - s->a| <= j_max dt when s->a itself was within a_max and the state was
 *             speed-viable, as every state this rule produces is), v (|v| <= v_max) and p after
 *             the step.
 */
void tdo_motion_limit(const tdo_vehicle_state* s, tdo_vec3 a_des, double v_max, double a_max,
                      double j_max, double dt, tdo_setpoint* out);

/** Capacities. */
typedef struct tdo_sim_config {
  uint32_t max_movers; /**< moving spheres simulated (>= 1; 56 bytes each) */
} tdo_sim_config;

/** Parameters of one episode. */
typedef struct tdo_sim_params {
  double dt;               /**< s, step, > 0 (default 0.02 = 50 Hz) */
  double v_max;            /**< m/s, > 0 (default 3) */
  double a_max;            /**< m/s^2, > 0 (default 3) */
  double j_max;            /**< m/s^3, > 0 (default 10) */
  tdo_box bounds;          /**< m, world frame, movers are reflected at these (max > min) */
  double vehicle_radius;   /**< m, >= 0, for the collision flags (default 0.25) */
  double static_clearance; /**< m, >= 0: static collision when the vehicle centre comes closer
                                than this to the static geometry (default 0.25 = radius) */
  const tdo_grid* grid;    /**< finished grid for the static distance, or NULL (no static check);
                                must stay alive and unchanged while stepping */
  const tdo_box* boxes;    /**< m, world frame: the true world's boxes for the static distance
                                (tdo_sense_distance, exact), or NULL; may be given with a grid
                                (the smaller distance counts); must stay alive while stepping */
  uint32_t n_boxes;        /**< count of boxes (default 0) */
  uint64_t seed;           /**< seed of the disturbance generator (default 1) */
  double accel_noise;      /**< m/s^2, standard deviation of the disturbance, >= 0 (default 0) */
  double setpoint_max_age; /**< s, >= 0: a setpoint whose t lies more than this behind the
                                simulator's clock is stale and the step brakes instead; 0: no
                                age check (default 0: setpoints without a time; a caller whose
                                setpoints carry the time of the state they answer sets a few
                                steps, e.g. tdo-sim 3 dt) */
  double brake_gain;       /**< 1/s, >= 0: braking command a = -brake_gain v (default 2) */
} tdo_sim_params;

/** Fill `p` with the defaults documented in tdo_sim_params (bounds 0..1 m: set them). */
void tdo_sim_params_default(tdo_sim_params* p);

/** Opaque simulator; carved from the caller's arena. */
typedef struct tdo_sim tdo_sim;

/** Input of one step. */
typedef struct tdo_sim_input {
  tdo_setpoint setpoint; /**< command; its acceleration is applied through tdo_motion_limit;
                              its t (s, the simulator's clock) for the age check */
} tdo_sim_input;

/** State after one step (or after the reset, for tdo_sim_get). */
typedef struct tdo_sim_output {
  tdo_vehicle_state state; /**< vehicle after the step */
  const tdo_mover* movers; /**< movers after the step (storage in the context, valid until the
                                next step or reset) */
  uint32_t n_movers;       /**< count */
  uint32_t steps;          /**< steps since the reset */
  double mover_gap;        /**< m, smallest |p - q| - radius - vehicle_radius (HUGE_VAL none) */
  uint32_t nearest_mover;  /**< id of the mover with that gap (0 when none) */
  double static_dist;      /**< m, exact distance to the static geometry (the grid's voxels and
                                the boxes) capped at 10 m (HUGE_VAL without a grid or boxes) */
  int collision_mover;     /**< 1 when mover_gap < 0 */
  int collision_static;    /**< 1 when static_dist < static_clearance */
  int braked;              /**< 1 when the step braked instead of flying a setpoint
                                (tdo_sim_hold, or a stale setpoint) */
  double setpoint_age;     /**< s, clock at the step's start - setpoint.t (0 after a reset or
                                tdo_sim_hold) */
} tdo_sim_output;

/** @return arena bytes tdo_sim_init carves for `cfg`; 0 for an invalid configuration. */
size_t tdo_sim_footprint(const tdo_sim_config* cfg);

/**
 * @brief Carve a simulator from `arena`.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or max_movers 0;
 *         TDO_ERR_ARENA_TOO_SMALL when the arena has no room.
 */
tdo_status tdo_sim_init(tdo_sim** ctx, tdo_arena* arena, const tdo_sim_config* cfg);

/**
 * @brief Start an episode: parameters, initial vehicle state, movers at state.t (copied).
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers, parameters outside their ranges, a
 *         non-finite state or mover, a mover radius not > 0; TDO_ERR_OBSTACLE_CAPACITY for more
 *         than max_movers movers; TDO_ERR_MAP_NOT_READY for an unfinished grid;
 *         TDO_ERR_INVALID_BOX for a box with max < min or a non-finite corner. On error steps
 *         return TDO_ERR_NOT_CONFIGURED.
 */
tdo_status tdo_sim_reset(tdo_sim* ctx, const tdo_sim_params* params,
                         const tdo_vehicle_state* initial, const tdo_mover* movers,
                         uint32_t n_movers);

/**
 * @brief Advance one dt with the setpoint's acceleration (braking instead when it is stale).
 * @return TDO_OK; TDO_ERR_SETPOINT_STALE when the setpoint was stale (the step was done, braking;
 *         `out` filled); TDO_ERR_INVALID_ARGUMENT for null pointers (nothing advanced);
 *         TDO_ERR_NOT_CONFIGURED before a successful reset.
 */
tdo_status tdo_sim_run(tdo_sim* ctx, const tdo_sim_input* in, tdo_sim_output* out);

/**
 * @brief Advance one dt without a command (none came, or the caller timed it out): brake towards
 *        a hover (a = -brake_gain v through the motion limits), out->braked = 1.
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers; TDO_ERR_NOT_CONFIGURED before a
 *         successful reset.
 */
tdo_status tdo_sim_hold(tdo_sim* ctx, tdo_sim_output* out);

/** @brief tdo_sim_run with only the vehicle state out (`state` may be NULL). */
tdo_status tdo_sim_step(tdo_sim* ctx, const tdo_setpoint* setpoint, tdo_vehicle_state* state);

/** @brief Current state, movers and distances without stepping. */
tdo_status tdo_sim_get(const tdo_sim* ctx, tdo_sim_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SIM_H */
