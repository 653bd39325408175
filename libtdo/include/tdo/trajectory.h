/**
 * @file trajectory.h
 * @brief Stage 5: time parameterisation, dynamic feasibility verification and refinement
 *        (docs/design.md s.5).
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

/**
 * One violation of a limit. A dynamic quantity violates when it misses its limit by more than 1 %
 * (speed, acceleration, jerk: value > 1.01 * limit; turn radius: 1.01 * value < limit), the
 * clearance when value < limit - 1e-9 m.
 */
typedef struct tdo_violation {
  double t;          /**< s, centre time of the finite-difference stencil (the sample time for
                          the clearance) */
  tdo_quantity what; /**< which limit */
  double value;      /**< measured value, unit of the quantity */
  double limit;      /**< the limit, same unit */
} tdo_violation;

/** m, tdo_feasibility.min_clearance is capped at the clearance + this. */
#define TDO_TRAJ_CLEARANCE_CAP_EXTRA 1.0

/**
 * Feasibility report of a sampled trajectory, computed from the sampled positions only (paper
 * eq. 15-19): v_i = (P_{i+1} - P_i)/dt, a_i = (v_{i+1} - v_i)/dt, j_i = (a_{i+1} - a_i)/dt as
 * vectors; the turn radius uses the centred velocity (v_i + v_{i+1})/2 of a_i.
 */
typedef struct tdo_feasibility {
  int ok;                          /**< 1 when no violation */
  double max_speed;                /**< m/s */
  double max_acc;                  /**< m/s^2 */
  double max_jerk;                 /**< m/s^3 */
  double min_turn_radius;          /**< m, minimum of |v|^2/|a_perp| (HUGE_VAL when straight) */
  double min_clearance;            /**< m, minimum exact distance of the samples to obstacles,
                                        capped at clearance + TDO_TRAJ_CLEARANCE_CAP_EXTRA;
                                        HUGE_VAL without a grid */
  uint32_t n_violations;           /**< violations listed */
  uint32_t n_violations_total;     /**< violations found (may exceed the listed ones: capacity) */
  const tdo_violation* violations; /**< the first n_violations */
} tdo_feasibility;

typedef struct tdo_traj tdo_traj;

/**
 * Constant-jerk pieces of the speed profile per path segment, at most (sizes max_profile): a
 * curved segment is flown as up to 4 equal parts ("plateaus", each with its own speed ceiling from
 * its own curvature) of at most 8 pieces each, a line as one. With less capacity (at least 8 per
 * segment + 1) curved segments get fewer parts: the same checks, a slower profile.
 */
#define TDO_TRAJ_PIECES_PER_SEGMENT 32u

/** Capacities. Every one sizes an arena array; see tdo_traj_footprint. */
typedef struct tdo_traj_config {
  uint32_t max_samples;     /**< samples at dt: flight time / dt + 1 (>= 2) */
  uint32_t max_segments;    /**< path segments (>= 1) */
  uint32_t max_profile;     /**< stations of the speed profile, i.e. its constant-jerk pieces:
                                 at most TDO_TRAJ_PIECES_PER_SEGMENT * segments + 1 (>= 1) */
  uint32_t max_violations;  /**< violations listed in the report (0: only counted) */
  uint32_t max_refinements; /**< refinement rounds before TDO_ERR_INFEASIBLE (0: none) */
  uint32_t stream_samples;  /**< 0: the samples are stored (84 bytes each, max_samples of them);
                                 1: not stored (0 bytes): verification and the energy evaluate them
                                 in streaming passes, with the same numbers, and
                                 tdo_traj_each_sample regenerates them on demand. max_samples still
                                 bounds their number (TDO_ERR_SAMPLE_CAPACITY) */
} tdo_traj_config;

/**
 * The motion a trajectory starts with: a plan from a moving vehicle (docs/design.md s.5, "Moving
 * start"). All zero: at rest, the trajectory as without it.
 */
typedef struct tdo_start_state {
  tdo_vec3 v; /**< m/s, world frame: velocity at the start (|v| <= v_max) */
  tdo_vec3 a; /**< m/s^2, world frame: acceleration at the start (|a| <= a_max) */
} tdo_start_state;

/**
 * How a moving start enters its path (tdo_traj_entry_plan): a ramp of one or two constant-jerk
 * pieces brings the acceleration to zero, then the path begins with a straight line along the
 * velocity left, at least `brake` long, so that the vehicle can always stop on it within the
 * limits. One piece (jerk -a / ramp) when its speed stays within v_max; otherwise two, through a
 * middle acceleration that brakes along the velocity (docs/design.md s.5, "Moving start").
 */
typedef struct tdo_traj_entry {
  double ramp;     /**< s, duration of the whole ramp (0 when the start acceleration is zero) */
  double knot;     /**< s, duration of its first piece (= ramp when it has one piece) */
  tdo_vec3 jerk;   /**< m/s^3, the first piece's constant jerk; one piece: -a / ramp */
  tdo_vec3 jerk2;  /**< m/s^3, the second piece's constant jerk (zero with one piece) */
  tdo_vec3 knot_p; /**< m, position at the end of the first piece */
  tdo_vec3 knot_v; /**< m/s, velocity there */
  tdo_vec3 knot_a; /**< m/s^2, acceleration there (zero with one piece) */
  tdo_vec3 p;      /**< m, position at the end of the ramp: where the path must begin */
  tdo_vec3 v;      /**< m/s, velocity there (acceleration zero): the path's initial tangent */
  double speed;    /**< m/s, |v|, at most v_max */
  double brake;    /**< m, the path's first line must be at least this long: the distance in which
                        the speed profile's straight-line limits (0.99 a_max, 0.6 j_max) stop from
                        `speed`, plus 1e-6 relative and 1e-9 m */
} tdo_traj_entry;

/**
 * @brief The entry of the state (p0, s): the acceleration ramp and the braking line. On the ramp
 *        |v| <= v_max, |a| <= a_max and |j| <= 0.995 j_max throughout. Bounded work (at most
 *        2 x 153 candidate two-piece ramps), no allocation, deterministic.
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers, non-finite p0 or limits not > 0;
 *         TDO_ERR_STATE_NOT_FINITE (a NaN or infinity in s); TDO_ERR_STATE_TOO_FAST (|v| above
 *         v_max); TDO_ERR_STATE_OVER_LIMITS for |a| above a_max, and for a state speeding up
 *         (a_t = a.v / |v| > 0) for which no candidate ramp keeps |v| <= v_max: every state with
 *         |v| + a_t^2 / (2 j_max) > v_max (its speed must rise above v_max whatever the jerk,
 *         since d a_t / dt >= -j_max), and a band below that bound, less than 1.25 w^2 / (2 v_max)
 *         wide with w = a_max^2 / (1.9 j_max) (0.047 m/s at 3 m/s, 3 m/s^2, 10 m/s^3).
 *         A state not speeding up (a_t <= 0) is accepted when a_max^2 <= 0.9 j_max v_max
 *         (docs/design.md s.5 says how both statements are tested). Each limit allows 1e-9
 *         relative for rounding (a state sampled at v_max); the entry's speed is then v_max.
 */
tdo_status tdo_traj_entry_plan(tdo_vec3 p0, const tdo_start_state* s, double v_max, double a_max,
                               double j_max, tdo_traj_entry* out);

/** Input. */
typedef struct tdo_traj_input {
  tdo_path path;         /**< geometric path (stage 3); each segment's `length` as path.h says */
  const tdo_grid* grid;  /**< for the clearance column of the report (may be NULL: not checked);
                              when given it must be finished */
  double clearance;      /**< m, >= 0; every sample keeps it (checked only with a grid) */
  double v_max;          /**< m/s, > 0 */
  double a_max;          /**< m/s^2, > 0 */
  double j_max;          /**< m/s^3, > 0 */
  double a_lat_max;      /**< m/s^2, > 0, lateral limit used for curve speeds (at most 0.9 a_max
                              is used; the tangential acceleration gets the rest of 0.98 a_max) */
  double dt;             /**< s, sample period, > 0 (default 0.01) */
  tdo_vec3 start_p;      /**< m, where a moving start begins (unused when `start` is zero) */
  tdo_start_state start; /**< zero (zero-initialised input): start at rest at the path's first
                              point. Otherwise the samples begin at start_p with exactly this
                              velocity and acceleration: the ramp of tdo_traj_entry_plan, then the
                              path, which must begin at the entry's p (within 1e-6 m) with a line
                              along its v (within 1e-3 rad) at least `brake` long */
} tdo_traj_input;

/** Output; storage in the context, valid until the next run. */
typedef struct tdo_traj_output {
  const tdo_sample* samples; /**< every dt from t = 0 (at start, at rest or in the start state)
                                  to the end (exactly at the goal, at rest); a sample falls on
                                  every stop point. NULL
                                  with stream_samples (n_samples still counts them) */
  uint32_t n_samples;
  double duration;        /**< s, (n_samples - 1) * dt */
  uint32_t refinements;   /**< refinement rounds used (0: the first profile passed) */
  tdo_feasibility report; /**< of the returned samples */
  double energy;          /**< m^2/s^3, integral |a|^2 dt over the samples by the trapezoid rule on
                               their a, as tdo_metrics_compute computes it from `samples` */
} tdo_traj_output;

/** Receives sample `index` (0 first) of a trajectory; `user` is the caller's pointer. */
typedef void (*tdo_sample_fn)(void* user, uint32_t index, const tdo_sample* sample);

/** @return arena bytes tdo_traj_init carves for `cfg`; 0 for an invalid configuration. */
size_t tdo_traj_footprint(const tdo_traj_config* cfg);

/**
 * @brief Carve a trajectory context from `arena`.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or capacities below their minimum;
 *         TDO_ERR_ARENA_TOO_SMALL when the arena has no room.
 */
tdo_status tdo_traj_init(tdo_traj** ctx, tdo_arena* arena, const tdo_traj_config* cfg);

/**
 * @brief Time-parameterise the path rest to rest (also at rest at every stop point and tangent
 *        kink), sample it every dt, verify the samples and refine: lower the speed, acceleration
 *        and jerk limits (x0.8) of the segments around each violation, at most max_refinements
 *        times. Allocates nothing; bounded work.
 * @return TDO_OK only for a trajectory that passed every check;
 *         TDO_ERR_INFEASIBLE with the samples and report of the last attempt otherwise (clearance
 *         violations stop the refinement at once: flying slower does not move the path);
 *         TDO_ERR_SAMPLE_CAPACITY when the samples or the profile pieces do not fit (during a
 *         refinement round `out` keeps the previous, failed attempt);
 *         TDO_ERR_PATH_CAPACITY for more than max_segments segments;
 *         TDO_ERR_MAP_NOT_READY for an unfinished grid;
 *         TDO_ERR_INVALID_ARGUMENT for null pointers, a limit or dt zero, negative or non-finite, a
 *         negative or non-finite clearance, an empty or zero-length path, an unknown segment kind,
 *         non-finite points, curvature or lengths, a negative length, a v_limit not > 0, or
 *         consecutive segments whose end points are more than 1e-6 m apart, or a path that does not
 *         begin as a moving start needs; the statuses of tdo_traj_entry_plan for a bad start.
 */
tdo_status tdo_traj_run(tdo_traj* ctx, const tdo_traj_input* in, tdo_traj_output* out);

/**
 * @brief Hand every sample of the last run's trajectory to `fn`, in order: the stored samples, or
 *        with stream_samples the same samples (same bits) regenerated from the profile. Needs the
 *        path given to that run unchanged. Allocates nothing; at most max_samples calls.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or when the last run produced no samples
 *         (an error before sampling, or no run yet).
 */
tdo_status tdo_traj_each_sample(const tdo_traj* ctx, tdo_sample_fn fn, void* user);

#ifdef __cplusplus
}
#endif

#endif /* TDO_TRAJECTORY_H */
