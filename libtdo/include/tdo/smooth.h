/**
 * @file smooth.h
 * @brief Stage 3: curvature-constrained adaptive-radius corner smoothing (pipeline.md s.3).
 *
 * Each interior waypoint with deflection theta gets a corner curve tangent to both segments, in
 * their plane, with radius r = k * theta / (2 sin(theta/2)) * R_min, R_min = v_cruise^2 /
 * a_lat_max. G2 mode uses two cubic Bezier spirals (Yang and Sukkarieh 2010) whose peak curvature
 * is 1/r and whose curvature is zero where they meet the lines; ARC mode uses the paper's circular
 * arcs.
 */
#ifndef TDO_SMOOTH_H
#define TDO_SMOOTH_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/path.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Corner curve family. */
typedef enum tdo_smoothing {
  TDO_SMOOTHING_G2 = 0,  /**< curvature-continuous Bezier spiral corners (default) */
  TDO_SMOOTHING_ARC = 1, /**< circular arcs (curvature jumps at the junctions) */
  TDO_SMOOTHING_NONE = 2 /**< the polyline itself, a stop point at every corner */
} tdo_smoothing;

typedef struct tdo_smooth tdo_smooth;

/** Capacities. */
typedef struct tdo_smooth_config {
  uint32_t max_waypoints; /**< input waypoints */
  uint32_t max_segments;  /**< output segments: at most 3 per waypoint */
  uint32_t max_shrinks;   /**< shrink steps per corner when it does not fit or keep clearance */
} tdo_smooth_config;

/** Input. */
typedef struct tdo_smooth_input {
  const tdo_grid* grid;      /**< finished grid, for clearance checks */
  const tdo_vec3* waypoints; /**< m, world frame, polyline P2 */
  uint32_t n_waypoints;      /**< >= 2 */
  tdo_smoothing mode;        /**< curve family */
  double clearance;          /**< m, every curve keeps it */
  double k;                  /**< radius scale, > 0 (default 1) */
  double v_cruise;           /**< m/s, speed used for R_min, > 0 */
  double v_max;              /**< m/s, speed cap, > 0 */
  double a_lat_max;          /**< m/s^2, lateral acceleration limit, > 0 */
  double j_max;              /**< m/s^3, bounds the curvature rate: v^3 dkappa/ds <= j_max */
  double stop_angle;         /**< rad; corners deflecting more than this become stop points */
} tdo_smooth_input;

/** Output path; storage in the context, valid until the next run. */
typedef struct tdo_smooth_output {
  tdo_path path;      /**< lines and corner curves from start to goal */
  uint32_t n_corners; /**< corners filleted */
  uint32_t n_shrunk;  /**< corners whose radius was reduced (no room or clearance) */
  uint32_t n_stops;   /**< stop points */
} tdo_smooth_output;

size_t tdo_smooth_footprint(const tdo_smooth_config* cfg);
tdo_status tdo_smooth_init(tdo_smooth** ctx, tdo_arena* arena, const tdo_smooth_config* cfg);
/** @return TDO_ERR_INVALID_ARGUMENT (non-positive or non-finite k, speeds, limits),
 * TDO_ERR_PATH_CAPACITY. */
tdo_status tdo_smooth_run(tdo_smooth* ctx, const tdo_smooth_input* in, tdo_smooth_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SMOOTH_H */
