/**
 * @file metrics.h
 * @brief Stage 6: trajectory quality metrics, identical for every planner (pipeline.md s.6).
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
  const tdo_path* path;      /**< final geometric path; NULL = the waypoint polyline */
  const tdo_sample* samples; /**< time-parameterised trajectory; NULL = no energy / flight time */
  uint32_t n_samples;
  double dt;            /**< s, sample period of `samples` */
  const tdo_grid* grid; /**< for min_clearance_m; NULL = not computed (HUGE_VAL) */
  double clearance_cap; /**< m, distances above it are reported as the cap */
} tdo_metrics_input;

/** The metric columns of pipeline.md s.6 (plan_time_ms is measured by the caller). */
typedef struct tdo_metrics {
  double length_m;          /**< m, arclength of the final path */
  uint32_t turns;           /**< interior waypoints with deflection > 1 degree */
  double total_turn_deg;    /**< deg, sum of those deflections */
  double min_clearance_m;   /**< m, min exact distance from the final path to obstacles */
  double avg_curvature;     /**< 1/m, (1/L) integral |kappa| ds */
  double smoothness;        /**< 1 / (1 + integral kappa^2 ds * 1 m), in (0, 1] */
  double energy;            /**< m^2/s^3, integral |a|^2 dt over the samples; 0 without samples */
  double flight_time_s;     /**< s, trajectory duration; 0 without samples */
  int curvature_continuous; /**< 1 when curvature has no jump along the path */
} tdo_metrics;

/** @return TDO_ERR_INVALID_ARGUMENT for null pointers or fewer than 2 waypoints. Bounded work. */
tdo_status tdo_metrics_compute(const tdo_metrics_input* in, tdo_metrics* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_METRICS_H */
