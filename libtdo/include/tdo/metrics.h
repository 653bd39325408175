/**
 * @file metrics.h
 * @brief Stage 6: trajectory quality metrics, identical for every planner (docs/design.md s.6).
 */
#ifndef TDO_METRICS_H
#define TDO_METRICS_H

#include "tdo/grid.h"
#include "tdo/path.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What the metrics are computed from. Any of path / samples may be absent (baselines). */
typedef struct tdo_metrics_input {
  const tdo_vec3* waypoints; /**< m, P2 or a baseline's raw path: turns are counted here */
  uint32_t n_waypoints;
  const tdo_path* path;      /**< final geometric path; NULL = the waypoint polyline, measured
                                  with its discrete curvature (turn angle theta_i at vertex i:
                                  integral |kappa| ds = sum theta_i, integral kappa^2 ds =
                                  sum theta_i^2 / mean length of the two adjacent segments) */
  const tdo_sample* samples; /**< time-parameterised trajectory; NULL = no energy / flight time */
  uint32_t n_samples;
  double dt;             /**< s, nominal sample period of `samples` (> 0 when samples are given);
                              the trapezoid rule uses the samples' own times t */
  const tdo_grid* grid;  /**< for min_clearance_m; NULL = not computed (HUGE_VAL) */
  double clearance_cap;  /**< m, > 0 with a grid; distances above it are reported as the cap */
  double clearance_hint; /**< m, optional (0 = none): a value just above the expected
                              min_clearance_m (the trajectory's minimum sample distance + 1e-9);
                              the distance queries start capped there; the result is the same */
} tdo_metrics_input;

/** The metric columns of docs/design.md s.6 (plan_time_ms is measured by the caller). */
typedef struct tdo_metrics {
  double length_m;          /**< m, arclength of the final path */
  uint32_t turns;           /**< interior waypoints with deflection > 1 degree */
  double total_turn_deg;    /**< deg, sum of those deflections */
  double min_clearance_m;   /**< m, min distance from the final path to obstacles: exact for
                                 lines; for curves a proven lower bound (chords of sagitta about
                                 1e-4 m: chord distance minus sagitta); HUGE_VAL without grid.
                                 tdo_planner_plan in the pieces mode: the proven clearance
                                 (tdo_traj_input.clearance_proven) */
  double avg_curvature;     /**< 1/m, (1/L) integral |kappa| ds */
  double smoothness;        /**< 1 / (1 + integral kappa^2 ds * 1 m), in (0, 1] */
  double energy;            /**< m^2/s^3, integral |a|^2 dt over the samples (trapezoid rule
                                 on the samples' a); 0 without samples */
  double flight_time_s;     /**< s, trajectory duration (last t - first t); 0 without samples */
  int curvature_continuous; /**< 1 when no junction of positive-length segments has a tangent
                                 kink above 1e-6 rad or a curvature-vector jump above 1e-4 1/m;
                                 for a polyline, 1 only when it has no turn at all */
} tdo_metrics;

/**
 * @brief Compute every metric. Allocates nothing; bounded work (curvature integrals: 4 panels of
 *        8-point Gauss-Legendre per curved segment; clearance: at most 256 chords per curve).
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers, fewer than 2 waypoints, non-finite points,
 *         an empty path, an unknown segment kind, a negative or non-finite length, samples with
 *         non-finite t or a or times not increasing, dt not > 0 with samples, clearance_cap not > 0
 *         with a grid; TDO_ERR_MAP_NOT_READY for an unfinished grid.
 */
tdo_status tdo_metrics_compute(const tdo_metrics_input* in, tdo_metrics* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_METRICS_H */
