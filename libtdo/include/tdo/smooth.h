/**
 * @file smooth.h
 * @brief Stage 3: curvature-constrained adaptive-radius corner smoothing (docs/design.md s.3).
 *
 * Each interior waypoint with deflection theta gets a corner curve tangent to both segments, in
 * their plane, with radius r = k * theta / (2 sin(theta/2)) * R_min, R_min = v_cruise^2 /
 * a_lat_max (paper eq. 8).
 *
 * G2 mode (default) uses the analytic G2 cubic Bezier spiral corner of Yang and Sukkarieh (IEEE
 * T-RO 2010): two cubic Beziers, curvature 0 where they meet the lines, curvature continuous (and
 * flat, dkappa/ds = 0) at their junction on the bisector, peak curvature exactly 1/r there. The
 * radius is the larger of the eq. 8 radius and the jerk radius sqrt(v_c^3 * F(theta) / j_max), with
 * v_c = min(v_cruise, v_max) and F = max|dkappa/ds| * r^2 of the corner shape, so that the lateral
 * jerk v_c^3 * dkappa/ds stays within j_max at the design speed (docs/design.md s.3: "curvature
 * rate chosen so that lateral jerk v^3 dkappa/ds <= j_max"). ARC mode uses the paper's circular
 * arcs of the eq. 8 radius (curvature jumps where they meet the lines). NONE mode returns the
 * polyline with a stop point at every corner.
 *
 * Fit: a corner's tangent length may use at most max(L/2, L - T_nb) of each adjacent segment of
 * length L, T_nb being the neighbour corner's desired tangent length (0 at start, goal, stop points
 * and straight waypoints, so corners there get the whole segment). A corner that does not fit is
 * shrunk to fit and slowed (v_limit <= sqrt(a_lat_max * r)). Clearance: each corner curve must
 * pass tdo_collision_bezier_clear (arcs: chords checked at clearance + sagitta) or it is shrunk
 * (radius x 0.6) at most max_shrinks times. A corner deflecting more than stop_angle, or one that
 * would need a radius below min_radius, becomes a stop point: the polyline corner itself, with the
 * incoming line flagged stop_at_end. The straight lines are sub-segments of the input segments,
 * which stage 2 has verified at the clearance, so they are not checked again.
 *
 * Speed caps (v_limit): lines v_max; corner curves min(v_max, sqrt(a_lat_max * r),
 * (j_max / max|dkappa/ds|)^(1/3)) (arcs have no curvature-rate term: dkappa/ds = 0 inside).
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
  uint32_t max_waypoints; /**< input waypoints (>= 2) */
  uint32_t max_segments;  /**< output segments (>= 1): n_waypoints - 1 lines plus 2 (g2) or 1 (arc)
                               per corner, so 3 * max_waypoints always suffices */
  uint32_t max_shrinks;   /**< clearance shrink steps per corner (radius x 0.6 each) before it
                               becomes a stop point; 0 = none */
} tdo_smooth_config;

/** Input. */
typedef struct tdo_smooth_input {
  const tdo_grid* grid;      /**< finished grid, for clearance checks; NULL = geometry only, no
                                  clearance check (tests and tools) */
  const tdo_vec3* waypoints; /**< m, world frame, polyline P2 */
  uint32_t n_waypoints;      /**< >= 2 */
  tdo_smoothing mode;        /**< curve family */
  double clearance;          /**< m, >= 0, every curve keeps it */
  double k;                  /**< radius scale, > 0 (default 1) */
  double v_cruise;           /**< m/s, speed used for R_min, > 0 */
  double v_max;              /**< m/s, speed cap, > 0 */
  double a_lat_max;          /**< m/s^2, lateral acceleration limit, > 0 */
  double j_max;              /**< m/s^3, > 0, bounds the curvature rate: v^3 dkappa/ds <= j_max */
  double stop_angle;         /**< rad, > 0; corners deflecting more than this become stop points */
  double min_radius;         /**< m, >= 0; corners that fit only with a smaller radius become stop
                                  points; 0 = default 0.05 * R_min */
} tdo_smooth_input;

/** Output path; storage in the context, valid until the next run. */
typedef struct tdo_smooth_output {
  tdo_path path;           /**< lines and corner curves from start to goal, lengths filled */
  uint32_t n_corners;      /**< corners filleted with a curve */
  uint32_t n_shrunk;       /**< filleted corners whose radius was reduced (no room or clearance) */
  uint32_t n_stops;        /**< stop points */
  uint32_t n_clear_checks; /**< curve clearance queries made */
} tdo_smooth_output;

/** @return arena bytes tdo_smooth_init carves for `cfg` (0 for an invalid configuration). */
size_t tdo_smooth_footprint(const tdo_smooth_config* cfg);

/**
 * @brief Carve a smoothing context from `arena`.
 * @return TDO_ERR_INVALID_ARGUMENT for null pointers or zero capacities, TDO_ERR_ARENA_TOO_SMALL.
 */
tdo_status tdo_smooth_init(tdo_smooth** ctx, tdo_arena* arena, const tdo_smooth_config* cfg);

/**
 * @brief Smooth the polyline. Allocates nothing; bounded work. Consecutive duplicate waypoints
 *        (closer than 1e-9 m) are merged, keeping the exact start and goal.
 * @return TDO_ERR_INVALID_ARGUMENT (null pointers, fewer than 2 distinct waypoints, non-finite
 *         waypoints, non-positive or non-finite k, speeds, limits or stop_angle, negative or
 *         non-finite clearance or min_radius, unknown mode), TDO_ERR_PATH_CAPACITY (more waypoints
 *         than max_waypoints or more segments than max_segments; no partial path is returned).
 */
tdo_status tdo_smooth_run(tdo_smooth* ctx, const tdo_smooth_input* in, tdo_smooth_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SMOOTH_H */
