/**
 * @file traj_profile.h
 * @brief Read-only view of a computed trajectory as the library represents it: the geometric
 *        path (tdo_path, path.h) and a speed profile of constant-jerk pieces over its arclength.
 *
 * Piece k covers t in [t0, t0 + dur) (s); inside it the path arclength is the exact cubic
 *   s(t) = s0 + v0 tau + a0 tau^2 / 2 + j tau^3 / 6,  tau = t - t0,
 * and the position is the path point at s. The pieces follow each other without gaps in time
 * (t0 of a piece is t0 + dur of the one before; the first starts at 0, or with a moving start at
 * the end of its acceleration ramp, tdo_traj_entry.ramp, whose samples lie off the path and are
 * no piece). How many pieces a path
 * segment gets is the time parameterisation's business and may vary: readers take n_pieces as
 * given. Sample i of the trajectory (tdo_traj_output.samples) lies at t = i * dt, and the last one,
 * at t = (n_samples - 1) * dt, is exactly the goal at rest.
 *
 * Everything here copies values out of a context; nothing allocates, nothing changes the context.
 */
#ifndef TDO_TRAJ_PROFILE_H
#define TDO_TRAJ_PROFILE_H

#include "tdo/planner.h"
#include "tdo/status.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** One constant-jerk piece of the speed profile. */
typedef struct tdo_traj_piece {
  double t0;  /**< s, start time */
  double dur; /**< s, duration (> 0) */
  double s0;  /**< m, path arclength at t0 */
  double v0;  /**< m/s, path speed ds/dt at t0 */
  double a0;  /**< m/s^2, path acceleration at t0 */
  double j;   /**< m/s^3, path jerk, constant over the piece */
} tdo_traj_piece;

/** Summary of the last run's profile. */
typedef struct tdo_traj_profile_info {
  uint32_t n_pieces;  /**< constant-jerk pieces (tdo_traj_piece_at 0 .. n_pieces - 1) */
  uint32_t n_samples; /**< samples at dt (as tdo_traj_output.n_samples) */
  double dt;          /**< s, sample period */
  double duration;    /**< s, time of the last sample, (n_samples - 1) * dt */
  double length;      /**< m, path arclength (sum of the segments' lengths) */
} tdo_traj_profile_info;

/**
 * @brief Summary of the profile of the last tdo_traj_run that produced samples.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or when that run produced no samples.
 */
tdo_status tdo_traj_profile(const tdo_traj* ctx, tdo_traj_profile_info* out);

/**
 * @brief Piece `index` (< n_pieces) of the last run's profile.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers, no samples or an index out of range.
 */
tdo_status tdo_traj_piece_at(const tdo_traj* ctx, uint32_t index, tdo_traj_piece* out);

/**
 * @return the planner's trajectory context when its last plan returned a usable trajectory (the
 *         samples tdo_planner_each_sample hands out), NULL otherwise (no plan yet, not that deep,
 *         infeasible, a failure, or a planner without a trajectory stage).
 */
const tdo_traj* tdo_planner_trajectory(const tdo_planner* planner);

#ifdef __cplusplus
}
#endif

#endif /* TDO_TRAJ_PROFILE_H */
