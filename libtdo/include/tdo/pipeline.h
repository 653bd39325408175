/**
 * @file pipeline.h
 * @brief The whole TDO-MSF static pipeline in one call: search -> inflection correction ->
 *        smoothing -> time parameterisation and feasibility -> metrics.
 *
 * Every stage can be switched for the baselines and the ablation (tdo_plan_params).
 */
#ifndef TDO_PIPELINE_H
#define TDO_PIPELINE_H

#include "tdo/correct.h"
#include "tdo/metrics.h"
#include "tdo/path.h"
#include "tdo/planner.h"
#include "tdo/search.h"
#include "tdo/smooth.h"
#include "tdo/status.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How far the pipeline runs. */
typedef enum tdo_plan_depth {
  TDO_PLAN_SEARCH = 0,    /**< grid path only (the raw A* / bidir baselines) */
  TDO_PLAN_CORRECT = 1,   /**< plus inflection correction */
  TDO_PLAN_SMOOTH = 2,    /**< plus corner smoothing (geometric path) */
  TDO_PLAN_TRAJECTORY = 3 /**< plus time parameterisation and feasibility (default) */
} tdo_plan_depth;

/** Every parameter of the pipeline (names as in docs/design.md). Defaults, valid ranges and the
 *  stage that reads each: the table of params.h (`tdo-plan --list-params`, docs/design.md s.12). */
typedef struct tdo_plan_params {
  tdo_plan_depth depth;        /**< stages to run */
  tdo_search_kind search;      /**< bidirectional or A* */
  double lambda;               /**< m, turn penalty weight */
  double mu;                   /**< m, deviation weight */
  double theta_max;            /**< rad, direction constraint; 0 = off */
  double d_th;                 /**< deviation threshold in (0,1); 0 = off */
  double h_weight;             /**< heuristic weight >= 1 of the turn-penalised search */
  int first_meet;              /**< bidirectional: stop at the first meeting (the paper) */
  uint32_t max_expansions;     /**< search budget; 0 = the configured default */
  tdo_correct_mode correction; /**< multi-scale, greedy line of sight, none */
  int shorten;           /**< multi-scale: 1 = partial shortcuts after the scales (see correct.h and
                              docs/performance.md); 0 = the paper's correction alone */
  double turn_threshold; /**< rad, "straight" turns for the correction windows */
  tdo_smoothing smoothing; /**< g2, arc, none */
  int grid_first;   /**< a tdo_grid_first: what the search starts with (tdo_search_input.grid_first;
                         PLAIN and TERMS need cap.exact_heuristic) */
  double k;         /**< radius scale */
  double v_max;     /**< m/s */
  double a_max;     /**< m/s^2 */
  double j_max;     /**< m/s^3 */
  double a_lat_max; /**< m/s^2, lateral limit for corner radii */
  double v_cruise;  /**< m/s, speed that sets R_min = v_cruise^2 / a_lat_max */
  double stop_angle;  /**< rad, corners sharper than this stop */
  double dt;          /**< s, trajectory sample period */
  int states;         /**< a tdo_state_space: the turn-penalised search's states
                           (tdo_search_input.states) */
  double corner_time; /**< in [0, 1]: how far G2 corner shapes trade length for flight time
                           (tdo_smooth_input.corner_time; 0 = Yang-Sukkarieh corners) */
} tdo_plan_params;

/** Fill `p` with the defaults documented in tdo_plan_params. */
void tdo_plan_params_default(tdo_plan_params* p);

/** Fill the search fields of `in` from `p` as tdo_planner_plan does (kind, lambda, mu, theta_max,
 *  d_th, h_weight, first_meet, grid_first, states, max_expansions); grid, start and goal are left
 *  as they are. Nothing for NULL pointers. */
void tdo_plan_search_input(const tdo_plan_params* p, tdo_search_input* in);

/** The same for stage 2: mode (p->correction), turn_threshold and shorten; the rest is left. */
void tdo_plan_correct_input(const tdo_plan_params* p, tdo_correct_input* in);

/** The same for stage 3: mode (p->smoothing), k, v_cruise, v_max, a_lat_max, j_max, stop_angle
 *  and corner_time; the rest is left. */
void tdo_plan_smooth_input(const tdo_plan_params* p, tdo_smooth_input* in);

/** The same for stage 5: v_max, a_max, j_max, a_lat_max and dt; the rest is left. */
void tdo_plan_traj_input(const tdo_plan_params* p, tdo_traj_input* in);

/** The real-valued metrics of a plan (tdo_metrics) under the names the LCM trajectory and
 *  tdo-plan's JSON give them, in this order: length_m, total_turn_deg, min_clearance_m,
 *  avg_curvature, smoothness, energy, flight_time_s. */
uint32_t tdo_metric_count(void);
/** Name of metric i, NULL for i >= tdo_metric_count(). */
const char* tdo_metric_name(uint32_t i);
/** Value of metric i in `m`; NaN for i >= tdo_metric_count() or NULL. */
double tdo_metric_value(const tdo_metrics* m, uint32_t i);

/** One planning request. Zero-initialise it: a zero `state` is a start at rest. */
typedef struct tdo_plan_request {
  tdo_vec3 start;         /**< m, world frame */
  tdo_vec3 goal;          /**< m, world frame */
  tdo_plan_params params; /**< parameters */
  tdo_start_state state;  /**< m/s and m/s^2 at `start`: the vehicle's motion (trajectory.h).
                               Zero: at rest, the plan exactly as without it. Non-zero: the
                               trajectory begins with exactly this velocity and acceleration
                               (docs/design.md s.5, "Moving start"); needs depth TRAJECTORY */
} tdo_plan_request;

/** Everything a plan produced. Arrays point into the planner arena, valid until the next plan. */
typedef struct tdo_plan_result {
  tdo_status status;         /**< overall status (TDO_OK only when every stage run passed) */
  tdo_plan_depth reached;    /**< last stage that produced output */
  tdo_search_output search;  /**< stage 1 */
  const tdo_vec3* grid_path; /**< m, voxel centres with the exact start and goal at the ends
                                  (with a moving start: the search start, at the entry's end);
                                  the start (goal) voxel's centre stays as well when the segment
                                  from the start to the next centre (from the previous centre to
                                  the goal) would not keep the clearance */
  uint32_t n_grid_path;
  const tdo_vec3* waypoints; /**< m, polyline P2 (stage 2); with a moving start it begins with
                                  the entry points (the end of the ramp, the end of the braking
                                  line) before the corrected path from the search start */
  uint32_t n_waypoints;
  uint32_t n_safety_critical; /**< waypoints kept for clearance */
  tdo_path path;              /**< stage 3 */
  const tdo_sample* samples;  /**< stage 5, every dt; NULL when the planner streams them
                                  (tdo_capacity.stream_samples): tdo_planner_each_sample */
  uint32_t n_samples;
  tdo_feasibility feasibility; /**< stage 5 report (also when infeasible) */
  uint32_t refinements;        /**< feasibility refinement rounds */
  tdo_metrics metrics;         /**< stage 6, of the deepest output */
  uint32_t sample_passes;      /**< trajectory rounds verified over the samples (every round when
                                    stored or streamed; with tdo_capacity.stream_samples
                                    TDO_TRAJ_SAMPLES_PIECES only those whose closed-form check
                                    failed: tdo_traj_output.sample_passes), summed as refinements */
} tdo_plan_result;

/**
 * @brief Plan on the planner's finished grid (its clearance applies). Allocates nothing.
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers or a parameter outside its valid
 *         range in the table of params.h (tdo_plan_params_check: `depth`, then the rows of the
 *         stages `depth` runs; 0 is valid for lambda, mu, theta_max and d_th: no penalty, no
 *         constraint, threshold off);
 *         the search statuses; TDO_ERR_START_BLOCKED / TDO_ERR_GOAL_BLOCKED also when the start
 *         or goal point itself (not only its voxel's centre) is closer than the clearance to an
 *         obstacle, at every depth (docs/design.md s.0: every point of the output keeps it);
 * TDO_ERR_INFEASIBLE (with the report) when no trajectory meets the limits; capacity and budget
 * statuses. A moving start (req->state non-zero): TDO_ERR_STATE_NOT_FINITE (at every depth),
 * TDO_ERR_INVALID_ARGUMENT below depth TRAJECTORY, TDO_ERR_STATE_TOO_FAST,
 * TDO_ERR_STATE_OVER_LIMITS (tdo_traj_entry_plan), TDO_ERR_START_OUT_OF_BOUNDS /
 * TDO_ERR_START_BLOCKED for the start point, TDO_ERR_STATE_CANNOT_STOP when the ramp or the
 * braking line along the velocity leaves the bounds or the clearance, or the braking line ends in
 * a blocked voxel.
 */
tdo_status tdo_planner_plan(tdo_planner* planner, const tdo_plan_request* req,
                            tdo_plan_result* out);

/**
 * @brief Hand every sample of the last plan's trajectory to `fn` in order (stored, or regenerated
 *        bit for bit when the planner streams samples). Allocates nothing; n_samples calls.
 * @return TDO_ERR_NOT_CONFIGURED without a trajectory stage; TDO_ERR_INVALID_ARGUMENT for null
 *         pointers or when the last plan returned no trajectory (not TDO_OK, or not that deep).
 */
tdo_status tdo_planner_each_sample(const tdo_planner* planner, tdo_sample_fn fn, void* user);

#ifdef __cplusplus
}
#endif

#endif /* TDO_PIPELINE_H */
