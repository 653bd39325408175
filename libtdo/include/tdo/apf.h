/**
 * @file apf.h
 * @brief Online follower (docs/design.md s.4, paper eq. 10-14): the trajectory-guided enhanced APF
 *        (E-APF) and the classical APF baseline in one module, run at a fixed rate.
 *
 * Every force is an acceleration (unit mass), m/s^2, world frame (z up). Per step, at vehicle
 * position p with velocity v:
 * - attraction  U_att = 1/2 k_a d_g^2, d_g = |p - p_ref|. E-APF: p_ref = trajectory point at the
 *   trajectory clock tau plus `lookahead`; classical APF: p_ref = goal. Beyond `att_dist` the
 *   potential grows linearly (conic), so |F_att| <= k_a * att_dist.
 * - repulsion   U_rep = 1/2 k_r (1/d - 1/d_0)^2 for d < d_0, summed over
 *   the static map: d = exact distance to the obstacle geometry (collision.h) - vehicle_radius,
 *     with its own gain k_r_static and influence distance d_0_static (the planned trajectory
 *     already keeps the planner's clearance, so this acts only when the vehicle is pushed
 *     towards a wall), and
 *   each moving sphere: d = |r*| - radius - vehicle_radius - mover_margin, r* = predicted closest
 *     relative position within `horizon` (r = p - q, w = v - u, t* = clamp(-r.w/|w|^2, 0,
 *     horizon), r* = r + w t*), gradient taken at fixed v. d is floored at `d_min`.
 * - guidance    U_guide = k_g d_p^2 (E-APF only), d_p = distance to the nearest point of the
 *   planned trajectory (polyline through the samples), F_guide = 2 k_g (p_near - p).
 * - command     a_des = -grad U_total - k_d (v - v_ref) (+ a_ref feed-forward for E-APF, where
 *   v_ref, a_ref are the trajectory's at the reference time; classical APF: v_ref = 0, no
 *   feed-forward), then limited by tdo_motion_limit (sim.h: jerk |a - a_prev| <= j_max dt,
 *   |a| <= a_max, and |v| <= v_max reached without exceeding the jerk limit; the simulator applies
 *   the same rule). Wall terms (classical APF always; E-APF only when more than 0.2 m off the plan,
 *   or escaping: on the plan the plan vouches for the clearance): within 1 m of the static
 *   geometry (beyond vehicle_radius) the component of the command minus the E-APF feed-forward
 *   that points into the geometry fades linearly to zero at contact, so the field moves the
 *   vehicle along or away from a wall, never into it (the reported terms are the unmodified
 *   gradients); within 2 m a braking term n v_n^2 / (2 max(d - v_n a_max / j_max, d_min)) is
 *   added (n the unit normal away from the geometry, v_n the approach speed, d the distance
 *   beyond vehicle_radius, also probed 0.2-0.8 s ahead along v): the deceleration that stops
 *   before contact.
 * - static safety filter (E-APF, `safety` = 1; the classical APF baseline keeps the plain field):
 *   the limited command is kept only when a braking roll-out from the state it leads to (same
 *   v/a/j rule, braking against v at a_max) stays at least vehicle_radius + safety_margin from the
 *   static geometry; otherwise the applied acceleration moves towards braking just enough
 *   (bisection), event TDO_APF_EVENT_SAFETY. Braking is safe whenever the previous step's command
 *   was, so, from a safe start and without disturbance, the vehicle never comes closer than that.
 * - mover evasion (E-APF with `safety` = 1): while the field predicts a mover within
 *   mover_margin (predicted gap d < 0), the desired acceleration (at most a_max) is held in a 2 s
 *   look-ahead (same v/a/j rule, movers at constant velocity); if the smallest predicted gap to
 *   the movers or to the static geometry (less vehicle_radius + safety_margin) stays >=
 *   mover_margin it is kept, else the best of a_max along 18 fixed directions replaces it (event
 *   TDO_APF_EVENT_EVADE). The static safety filter then still has the last word.
 * - trajectory clock tau: advances with the vehicle time (state.t), but is held while the
 *   vehicle is more than `hold_dist` from the trajectory point at tau (pushed away by a mover),
 *   so the reference waits; while the vehicle is more than hold_dist / 2 from that point,
 *   tau + lookahead never lags the time of the last nearest trajectory point (a vehicle that
 *   rejoins the plan further along is not pulled back).
 * - local minimum: every `lm_window` seconds the progress is compared with the window's start
 *   (E-APF: arclength of the nearest trajectory point; APF: best distance to the goal). Detected
 *   when the progress is below `lm_progress`, the vehicle is farther than `lm_goal_dist` from the
 *   goal, and the force is small (|F_total| < lm_force, now or averaged over the window) or the
 *   vehicle slow (|v| < lm_speed, now or as net displacement over the window: oscillations count).
 *   Escape: for `escape_time` the attraction and guidance are replaced by a tangential term of
 *   magnitude k_t, perpendicular to the repulsion normal, turning about an axis fixed at the
 *   detection. After `max_escapes` detections without progress in between the follower gives up:
 *   TDO_ERR_LOCAL_MINIMUM, event TDO_APF_EVENT_ESCAPE_FAILED, and from then on it brakes to a
 *   hover (a valid, limited setpoint every step) until the next tdo_apf_reset.
 * Fixed memory from the caller's arena, no heap, bounded work per step (nearest-point search over
 * at most `nearest_window` samples, one distance query per static-gradient probe, one pass over
 * the movers; the safety filter's roll-outs and the evasion's 19 look-aheads have fixed step
 * counts), bit-identical results for identical inputs.
 */
#ifndef TDO_APF_H
#define TDO_APF_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A moving obstacle: a sphere with constant velocity. */
typedef struct tdo_mover {
  uint32_t id;   /**< caller's identifier (not interpreted) */
  tdo_vec3 p;    /**< m, world frame, centre at the time of the vehicle state */
  tdo_vec3 v;    /**< m/s, world frame, velocity */
  double radius; /**< m, > 0 */
} tdo_mover;

/** State of the vehicle (measured, or the simulator's). */
typedef struct tdo_vehicle_state {
  double t;   /**< s, time of the state (episode or system clock, monotonic) */
  tdo_vec3 p; /**< m, world frame, position */
  tdo_vec3 v; /**< m/s, world frame, velocity */
  tdo_vec3 a; /**< m/s^2, world frame, acceleration (the last command applied) */
} tdo_vehicle_state;

/** Command for the next step: the state the vehicle should reach one step dt later. */
typedef struct tdo_setpoint {
  double t;   /**< s, time the setpoint refers to (state.t + dt) */
  tdo_vec3 p; /**< m, world frame, position after one step */
  tdo_vec3 v; /**< m/s, world frame, velocity after one step (|v| <= v_max) */
  tdo_vec3 a; /**< m/s^2, world frame, acceleration to hold over the step (|a| <= a_max,
                   |a - state.a| <= j_max dt) */
} tdo_setpoint;

/** Which follower. */
typedef enum tdo_follower_kind {
  TDO_FOLLOWER_EAPF = 0, /**< trajectory-guided enhanced APF (default) */
  TDO_FOLLOWER_APF = 1   /**< classical APF: attraction to the goal, no guidance (baseline) */
} tdo_follower_kind;

/** Parameters; tdo_apf_params_default gives the documented defaults per kind. */
typedef struct tdo_apf_params {
  tdo_follower_kind kind; /**< E-APF or classical APF */
  double dt;              /**< s, step period, > 0 (default 0.02 = 50 Hz) */
  double k_a;             /**< 1/s^2, attraction gain, > 0 (E-APF 4, APF 1) */
  double att_dist;        /**< m, attraction is conic beyond this distance, > 0 (E-APF 2,
                               APF 4: cruise k_a att_dist / k_d = 2 m/s) */
  double k_r;             /**< m^4/s^2, repulsion gain, >= 0 (default 1.5) */
  double d_0;             /**< m, influence distance of movers, > 0 (default 2.5) */
  double d_0_static;      /**< m, influence distance of the static map, > 0 (E-APF 0.25,
                               APF 2) */
  double d_min;           /**< m, floor of the repulsion distance, > 0 (default 0.05) */
  double k_g;             /**< 1/s^2, guidance gain, >= 0 (E-APF 2, ignored by APF) */
  double k_d;             /**< 1/s, damping, > 0 (E-APF 4, APF 2: both critically damped) */
  double lookahead;       /**< s, reference time ahead of the clock, >= 0 (default 0.1) */
  double hold_dist;       /**< m, the clock holds while farther than this from its point, > 0
                               (default 1) */
  double horizon;         /**< s, closest-approach prediction horizon, >= 0 (default 2.5) */
  double vehicle_radius;  /**< m, >= 0 (default 0.25) */
  double mover_margin;    /**< m, extra gap kept from movers, >= 0 (default 0.5) */
  double v_max;           /**< m/s, > 0 (default 3) */
  double a_max;           /**< m/s^2, > 0 (default 3) */
  double j_max;           /**< m/s^3, > 0 (default 10) */
  double goal_tol;        /**< m, arrived within this of the goal at speed < 0.1 m/s, > 0
                               (default 0.2) */
  double lm_window;       /**< s, progress window of the local-minimum detector, > 0 (default 2) */
  double lm_progress;     /**< m, progress below this over a window counts as none, > 0
                               (default 0.3) */
  double lm_force;        /**< m/s^2, "small force" threshold, > 0 (default 0.5) */
  double lm_speed;        /**< m/s, "slow" threshold, > 0 (default 0.2) */
  double lm_goal_dist;    /**< m, no detection within this of the goal, > 0 (default 1) */
  double k_t;             /**< m/s^2, tangential escape magnitude, >= 0 (default 2) */
  double escape_time;     /**< s, duration of one escape, > 0 (default 3) */
  uint32_t max_escapes;   /**< escapes without progress before giving up (default 3) */
  double k_r_static;      /**< m^4/s^2, repulsion gain of the static map, >= 0 (E-APF 0.0025:
                               gentle, the planned trajectory already keeps the clearance and a
                               stiff wall term would shake the vehicle off it; APF 1.5 = k_r) */
  uint32_t safety;        /**< 1: static safety filter on the command (E-APF default), 0: off
                               (APF default: the baseline stays the plain field) */
  double safety_margin;   /**< m, the filter keeps the braking roll-out this far beyond
                               vehicle_radius from the static geometry, >= 0 (default 0.05) */
} tdo_apf_params;

/** Fill `p` with the defaults of `kind` (see tdo_apf_params). */
void tdo_apf_params_default(tdo_apf_params* p, tdo_follower_kind kind);

/** Capacities; every one sizes an arena array or bounds a loop, see tdo_apf_footprint. */
typedef struct tdo_apf_config {
  uint32_t max_samples;    /**< trajectory samples kept (>= 2; 88 bytes each: the sample and
                                its arclength) */
  uint32_t max_movers;     /**< moving obstacles accepted per step (>= 1; no storage, bounds the
                                per-step work) */
  uint32_t nearest_window; /**< samples searched per step for the nearest trajectory point,
                                forward and backward of the last one (>= 1; e.g. 2 s / sample dt) */
  uint32_t switching;      /**< 1: room for a staged next plan of max_samples (tdo_apf_switch;
                                doubles the sample storage); 0: none (switch refused) */
} tdo_apf_config;

/** Opaque follower context; carved from the caller's arena. */
typedef struct tdo_apf tdo_apf;

/** What the follower is to do; read by tdo_apf_reset, the arrays are copied. */
typedef struct tdo_apf_task {
  const tdo_sample* samples; /**< planned trajectory (trajectory.h), uniform dt, t from 0;
                                  required for E-APF, may be NULL for APF */
  uint32_t n_samples;        /**< count (E-APF: >= 2; at most max_samples) */
  tdo_vec3 goal;             /**< m, world frame; E-APF ignores it and uses the last sample */
  const tdo_grid* grid;      /**< finished grid of the static map, or NULL for no static
                                  repulsion; must stay alive while stepping. It is read at every
                                  step, so changes made between steps by tdo_grid_apply_update
                                  (obstacles that arrived by map updates) are seen by the
                                  repulsion, the wall terms and the safety filter from the next
                                  step on */
  double t0;                 /**< s, vehicle-clock time that corresponds to trajectory t = 0 */
} tdo_apf_task;

/** Follower mode. */
typedef enum tdo_apf_mode {
  TDO_APF_MODE_TRACK = 0,  /**< normal: potential-field command */
  TDO_APF_MODE_ESCAPE = 1, /**< escaping a local minimum (tangential term) */
  TDO_APF_MODE_STUCK = 2,  /**< escape failed: braking to hover, TDO_ERR_LOCAL_MINIMUM */
  TDO_APF_MODE_ARRIVED = 3 /**< at the goal: holding it */
} tdo_apf_mode;

/** Event bits raised in one step (tdo_apf_output.events). */
#define TDO_APF_EVENT_LM_DETECTED 0x01u   /**< local minimum detected */
#define TDO_APF_EVENT_ESCAPE_START 0x02u  /**< escape started */
#define TDO_APF_EVENT_ESCAPE_OK 0x04u     /**< progress resumed after an escape */
#define TDO_APF_EVENT_ESCAPE_FAILED 0x08u /**< gave up: TDO_ERR_LOCAL_MINIMUM from now on */
#define TDO_APF_EVENT_GOAL_REACHED 0x10u  /**< arrived at the goal (once) */
#define TDO_APF_EVENT_CLOCK_HELD 0x20u    /**< trajectory clock held (vehicle pushed away) */
#define TDO_APF_EVENT_REPULSED 0x40u      /**< a mover is within its influence distance */
#define TDO_APF_EVENT_SAFETY 0x80u        /**< the static safety filter changed the command */
#define TDO_APF_EVENT_EVADE 0x100u        /**< mover evasion replaced the field's command */
#define TDO_APF_EVENT_SWITCHED 0x200u     /**< the staged plan took over (tdo_apf_switch) */

/** The potential-field terms at one state (tdo_apf_eval, and part of every step's output). */
typedef struct tdo_apf_terms {
  tdo_vec3 f_att;        /**< m/s^2, -grad U_att */
  tdo_vec3 f_rep_static; /**< m/s^2, -grad U_rep of the static map */
  tdo_vec3 f_rep_movers; /**< m/s^2, -grad U_rep summed over the movers */
  tdo_vec3 f_guide;      /**< m/s^2, -grad U_guide (zero for APF) */
  tdo_vec3 f_total;      /**< m/s^2, sum of the four above */
  double u_att;          /**< m^2/s^2, U_att */
  double u_rep_static;   /**< m^2/s^2, U_rep of the static map */
  double u_rep_movers;   /**< m^2/s^2, U_rep summed over the movers */
  double u_guide;        /**< m^2/s^2, U_guide */
  double u_total;        /**< m^2/s^2, sum */
  tdo_vec3 ref;          /**< m, attraction point (trajectory reference or goal) */
  tdo_vec3 nearest;      /**< m, nearest point of the planned trajectory (the goal for APF) */
  double deviation;      /**< m, |p - nearest| (E-APF); 0 for APF */
  double static_dist;    /**< m, exact distance to the static geometry, capped at
                              vehicle_radius + max(d_0_static, 2) + 0.5 (HUGE_VAL without a
                              grid) */
  double mover_gap;      /**< m, smallest current surface gap |p - q| - radius - vehicle_radius
                              over the movers (HUGE_VAL without movers) */
  double mover_pred_gap; /**< m, smallest predicted gap d over the movers (HUGE_VAL none) */
} tdo_apf_terms;

/** Input of one step. */
typedef struct tdo_apf_input {
  tdo_vehicle_state state; /**< current vehicle state (state.t is the vehicle clock) */
  const tdo_mover* movers; /**< moving obstacles at state.t (may be NULL when n_movers = 0) */
  uint32_t n_movers;       /**< count, at most max_movers */
} tdo_apf_input;

/** Output of one step. */
typedef struct tdo_apf_output {
  tdo_setpoint setpoint;  /**< command for the next dt (valid also with TDO_ERR_LOCAL_MINIMUM) */
  tdo_apf_terms terms;    /**< the field at the input state */
  tdo_vec3 a_des;         /**< m/s^2, unlimited command (field + damping + feed-forward) */
  double ref_time;        /**< s, trajectory time of the reference point (tau + lookahead) */
  double progress;        /**< m, E-APF: arclength of the nearest trajectory point; APF: initial
                               minus best distance to the goal */
  tdo_apf_mode mode;      /**< mode after this step */
  uint32_t events;        /**< TDO_APF_EVENT_* bits raised in this step */
  uint32_t lm_detections; /**< local minima detected since the reset */
  uint32_t escapes;       /**< escapes started since the reset */
  uint32_t steps;         /**< steps since the reset */
} tdo_apf_output;

/** @return arena bytes tdo_apf_init carves for `cfg`; 0 for an invalid configuration. */
size_t tdo_apf_footprint(const tdo_apf_config* cfg);

/**
 * @brief Carve a follower from `arena` (the only memory it ever uses).
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or capacities below their minimum;
 *         TDO_ERR_ARENA_TOO_SMALL when the arena has no room.
 */
tdo_status tdo_apf_init(tdo_apf** ctx, tdo_arena* arena, const tdo_apf_config* cfg);

/**
 * @brief Start a new task: set the parameters, copy the trajectory, clear the detector.
 * @return TDO_ERR_INVALID_ARGUMENT for a null pointer, a parameter outside its range, non-finite
 *         values, E-APF with fewer than 2 samples or samples whose times are not uniform (1e-6
 *         relative) from 0; TDO_ERR_SAMPLE_CAPACITY for more than max_samples samples;
 *         TDO_ERR_MAP_NOT_READY for an unfinished grid. On error the follower is not ready and
 *         steps return TDO_ERR_NOT_CONFIGURED.
 */
tdo_status tdo_apf_reset(tdo_apf* ctx, const tdo_apf_params* params, const tdo_apf_task* task);

/**
 * @brief Stage a new plan that takes over from the active one without a jump in the reference
 *        (docs/design.md s.4, "Replanning"): the new plan's t = 0 is aligned with the active
 *        plan's trajectory time `t_switch`. The follower keeps its state (vehicle clock, mode
 *        counters, the last command) and tracks the active plan until the step whose reference
 *        time (clock + lookahead) reaches t_switch (or the active plan's end, if earlier); from
 *        that step on the clock runs on the new plan at clock - t_switch, so the reference passes
 *        from the active plan at t_switch to the new plan at 0. When the new plan starts with
 *        the active plan's position, velocity and acceleration at t_switch (a plan from
 *        tdo_replan_takeover's state), the reference p, v and a are continuous across the
 *        switch. At the switch the nearest-point search restarts at the new plan's start, the
 *        local-minimum window restarts, an escape or a stuck follower returns to tracking (the
 *        new plan is the way out), the goal becomes the new plan's last sample and the grid
 *        the task's; event TDO_APF_EVENT_SWITCHED. A t_switch already passed switches at the
 *        next step (a plan from the vehicle's own state: the reference then starts at its t = 0
 *        plus the time passed). A second call before the switch replaces the staged plan.
 *        task->t0 and task->goal are not used.
 * @return TDO_OK; TDO_ERR_NOT_CONFIGURED before a successful reset or without
 *         tdo_apf_config.switching; TDO_ERR_INVALID_ARGUMENT for null pointers, a follower that
 *         is not E-APF, a non-finite or negative t_switch, or samples as tdo_apf_reset refuses
 *         them; TDO_ERR_SAMPLE_CAPACITY for more than max_samples; TDO_ERR_MAP_NOT_READY for an
 *         unfinished grid. On error the staged plan (if any) and the active one are unchanged.
 */
tdo_status tdo_apf_switch(tdo_apf* ctx, const tdo_apf_task* task, double t_switch);

/**
 * @brief One step: field at the input state, limited command for the next dt.
 * @return TDO_OK; TDO_ERR_LOCAL_MINIMUM once the escape failed (the setpoint brakes to hover);
 *         TDO_ERR_OBSTACLE_CAPACITY for more than max_movers movers (nothing advanced);
 *         TDO_ERR_INVALID_ARGUMENT for null pointers, a non-finite state or mover, a mover radius
 *         not > 0 (nothing advanced); TDO_ERR_NOT_CONFIGURED before a successful reset.
 */
tdo_status tdo_apf_run(tdo_apf* ctx, const tdo_apf_input* in, tdo_apf_output* out);

/** @brief tdo_apf_run without the diagnostics: state and movers in, setpoint out. */
tdo_status tdo_apf_step(tdo_apf* ctx, const tdo_vehicle_state* state, const tdo_mover* movers,
                        uint32_t n_movers, tdo_setpoint* setpoint);

/**
 * @brief Evaluate the potentials and forces at `state` without changing the follower (the clock,
 *        the detector and the nearest-point index stay). For tests and plots.
 * @return as tdo_apf_run, without TDO_ERR_LOCAL_MINIMUM.
 */
tdo_status tdo_apf_eval(const tdo_apf* ctx, const tdo_vehicle_state* state, const tdo_mover* movers,
                        uint32_t n_movers, tdo_apf_terms* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_APF_H */
