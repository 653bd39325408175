/**
 * @file correct.h
 * @brief Stage 2: multi-scale inflection correction of the grid path (docs/design.md s.2).
 *
 * Every segment check is tdo_collision_segment_clear at the input clearance (exact, continuous).
 * 1. Every input segment is checked; one that fails makes the run TDO_ERR_NO_PATH.
 * 2. Repeated points and collinear interior points (turn < 1e-9 rad) are dropped; the merged
 *    segment of a collinear run is checked once (if it fails at the limit, the run's points stay).
 * 3. TDO_CORRECT_MULTISCALE: passes until one removes nothing; each pass runs the scales
 *    s = 3, 5, 7 in that order, and each scale two sweeps left to right over the windows of s
 *    consecutive points: sweep A tries only windows whose interior turns are all below
 *    turn_threshold, sweep B every window. A window's interior points are removed when the chord
 *    from its first to its last point is clear; the sweep then retries the same start, otherwise
 *    it moves one point on. Failed chords are remembered and not checked again.
 *    TDO_CORRECT_GREEDY_LOS: from the current point, the farthest later point with a clear chord
 *    (scanning from the goal backwards) is the next waypoint.
 *    TDO_CORRECT_NONE: step 2 only.
 * A removal that would break clearance is never made, so every output segment is a checked one.
 */
#ifndef TDO_CORRECT_H
#define TDO_CORRECT_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Correction variant. */
typedef enum tdo_correct_mode {
  TDO_CORRECT_MULTISCALE = 0, /**< scales 3, 5, 7 (TDO-MSF) */
  TDO_CORRECT_GREEDY_LOS = 1, /**< single-scale greedy line of sight (MSF-MTPO baseline) */
  TDO_CORRECT_NONE = 2        /**< collinear points dropped only */
} tdo_correct_mode;

typedef struct tdo_correct tdo_correct;

/** Capacities (61 bytes of arena per point). */
typedef struct tdo_correct_config {
  uint32_t max_points; /**< input and output points, > 0 (a run needs at least 2) */
  uint32_t max_checks; /**< segment clearance checks per run (budget), input checks included;
                            0 = no budget beyond the stage's own bound: every pass but the last
                            removes a point, so a run of n points makes O(n^2) checks at most */
} tdo_correct_config;

/** Input polyline: voxel centres with the exact start and goal at its ends. */
typedef struct tdo_correct_input {
  const tdo_grid* grid;   /**< finished grid */
  const tdo_vec3* points; /**< m, world frame */
  uint32_t n_points;      /**< >= 2 */
  tdo_correct_mode mode;  /**< variant */
  double clearance;       /**< m, every output segment keeps it */
  double turn_threshold;  /**< rad, finite, >= 0; windows whose interior turns are all below it
                               are tried first at each scale (sweep A) */
  int shorten;            /**< MULTISCALE only: 1 = after the scales, partial shortcuts (a
                               waypoint run is replaced by one point on a later segment whose
                               chord is verified at clearance), relocation towards the chord of
                               the neighbours, then small moves of each waypoint that keep the
                               turns, the corners' room and the segments' room from obstacles;
                               fewer or equal waypoints, shorter polyline. 0 = off (the paper's
                               correction alone) */
  int steps_proven;       /**< 0 (zero-initialised input): every input segment is checked.
                               1: the caller has proven that the segments between points[1] and
                               points[n_points - 2] keep the clearance with room to spare, and so
                               do the straight runs they form (tdo_planner_plan: grid steps at
                               clearance 0, whose swept voxels are all free, docs/design.md s.2);
                               those are not checked again but counted as checks, so budgets and
                               statuses stay those of checking. Other values:
                               TDO_ERR_INVALID_ARGUMENT */
} tdo_correct_input;

/** Output polyline P2; storage in the context, valid until the next run. */
typedef struct tdo_correct_output {
  const tdo_vec3* waypoints; /**< m, world frame; first = start, last = goal */
  uint32_t n_waypoints;
  uint32_t n_safety_critical; /**< interior waypoints whose removal (the chord between their
                                   neighbours) was checked and breaks clearance: all interior
                                   waypoints in MULTISCALE and GREEDY_LOS, 0 in NONE */
  uint32_t checks;            /**< segment checks done (also set on TDO_ERR_BUDGET) */
} tdo_correct_output;

/** @return arena bytes tdo_correct_init carves for `cfg`; 0 for a null or invalid cfg. */
size_t tdo_correct_footprint(const tdo_correct_config* cfg);
/**
 * @brief Carve a correction context from `arena`.
 * @return TDO_ERR_INVALID_ARGUMENT (null, max_points 0), TDO_ERR_ARENA_TOO_SMALL.
 */
tdo_status tdo_correct_init(tdo_correct** ctx, tdo_arena* arena, const tdo_correct_config* cfg);
/**
 * @brief Correct one polyline. Allocates nothing; deterministic.
 * @return TDO_ERR_INVALID_ARGUMENT (null, fewer than 2 or non-finite points, negative or
 *         non-finite clearance or turn_threshold, unknown mode), TDO_ERR_MAP_NOT_READY,
 *         TDO_ERR_PATH_CAPACITY (more than max_points), TDO_ERR_BUDGET (max_checks reached),
 *         TDO_ERR_NO_PATH when an input segment itself breaks clearance. On any error the output
 *         holds no waypoints.
 */
tdo_status tdo_correct_run(tdo_correct* ctx, const tdo_correct_input* in, tdo_correct_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_CORRECT_H */
