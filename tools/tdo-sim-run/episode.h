/**
 * @file episode.h
 * @brief One dynamic episode: plan with tdo_planner_plan, fly it in the libtdo simulator with the
 *        E-APF or classical APF follower, measure. Host tool code (allocation, exceptions allowed
 *        outside libtdo); behind tdo-sim-run and its tests.
 */
#ifndef TDO_SIM_RUN_EPISODE_H
#define TDO_SIM_RUN_EPISODE_H

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace tdo_episode {

/** Everything that determines an episode besides the map. */
struct Options {
  tdo_follower_kind follower = TDO_FOLLOWER_EAPF; /**< E-APF or classical APF */
  bool movers = true;             /**< false: ignore the map's movers (no-mover case) */
  double clearance = 0.5;         /**< m, planner clearance */
  double time_factor = 2.0;       /**< time limit = time_factor * planned duration + time_extra */
  double time_extra = 20.0;       /**< s */
  double goal_tol = 0.2;          /**< m, success when the vehicle comes this close to the goal */
  double vehicle_radius = 0.25;   /**< m, mover collision when centre gap < radius + this */
  double static_clearance = 0.25; /**< m, static collision when closer than this to geometry */
  uint64_t seed = 1;              /**< simulator disturbance seed */
  double accel_noise = 0.0;       /**< m/s^2, simulator disturbance (0: none) */
  bool keep_samples = true;       /**< keep the per-step record (JSON); false for benches */
  int32_t stream_samples = -1;    /**< planner's tdo_capacity.stream_samples (0 stored, 1 streamed,
                                       2 pieces); -1: as tdo_capacity_for_grid sets it */
  std::vector<std::pair<std::string, double>> params; /**< follower parameter overrides by name
                                                           (see set_param) */
};

/**
 * @brief Set the follower parameter `name` (a field of tdo_apf_params: k_a, att_dist, k_r,
 * k_r_static, d_0, d_0_static, d_min, k_g, k_d, lookahead, hold_dist, horizon, mover_margin,
 * lm_window, lm_progress, lm_force, lm_speed, lm_goal_dist, k_t, escape_time, max_escapes).
 * @return false for an unknown name.
 */
bool set_param(tdo_apf_params* p, const std::string& name, double value);

/** One simulator step as recorded. */
struct Step {
  double t;           /**< s */
  tdo_vec3 p, v, a;   /**< m, m/s, m/s^2 */
  double mover_gap;   /**< m, smallest surface gap to a mover (HUGE_VAL: none) */
  double static_dist; /**< m, distance to static geometry (capped at 10 m) */
  double deviation;   /**< m, distance to the planned path */
  uint32_t events;    /**< TDO_APF_EVENT_* of the follower step that led here */
  int mode;           /**< tdo_apf_mode after that step */
  tdo_vec3 a_des;     /**< m/s^2, the follower's unlimited command of that step */
};

/** Metrics of one episode (issue 4). */
struct Metrics {
  bool planned = false;          /**< the planner returned a trajectory */
  int plan_status = 0;           /**< tdo_status of the plan */
  bool success = false;          /**< within goal_tol of the goal before the time limit */
  bool collision = false;        /**< collision_mover || collision_static */
  bool collision_mover = false;  /**< a mover gap below 0 */
  bool collision_static = false; /**< static distance below static_clearance */
  double min_mover_sep = 0.0;    /**< m, smallest surface gap |p-q| - R - r_v (HUGE_VAL: none) */
  double min_static_dist = 0.0;  /**< m */
  double max_deviation = 0.0;    /**< m, from the planned path (polyline of the plan samples) */
  double mean_deviation = 0.0;   /**< m, mean over the steps until arrival */
  double plan_duration = 0.0;    /**< s */
  double time = 0.0;             /**< s, arrival time (or the time flown when not arrived) */
  double time_overhead = 0.0;    /**< s, time - plan_duration (arrived episodes) */
  uint32_t lm_events = 0;        /**< local minima detected */
  uint32_t escapes = 0;          /**< escapes started */
  bool escape_failed = false;    /**< the follower gave up (TDO_ERR_LOCAL_MINIMUM) */
  double max_speed = 0.0;        /**< m/s, finite differences of the executed positions */
  double max_acc = 0.0;          /**< m/s^2 */
  double max_jerk = 0.0;         /**< m/s^3 */
  double v_limit = 0.0;          /**< m/s, the limits flown with (the planner's) */
  double a_limit = 0.0;          /**< m/s^2 */
  double j_limit = 0.0;          /**< m/s^3 */
  uint32_t steps = 0;            /**< simulator steps */
  uint32_t safety_steps = 0;     /**< steps where the static safety filter changed the command */
  uint32_t evade_steps = 0;      /**< steps where the mover evasion replaced the command */
  uint32_t movers = 0;           /**< movers in the episode */
};

/** A whole episode. */
struct Episode {
  Metrics m;
  std::vector<tdo_sample> plan;              /**< planned samples */
  std::vector<Step> steps;                   /**< executed (when keep_samples) */
  std::vector<std::vector<tdo_vec3>> tracks; /**< per mover: centre at each step (keep_samples) */
  std::vector<double> radii;                 /**< per mover, m */
  std::vector<std::string> events;           /**< "t=...: name" lines */
  tdo_apf_params params{};                   /**< follower parameters used */
};

/**
 * @brief Plan on `map` (its start and goal) and fly the episode.
 * @return false with `error` for a map that cannot be loaded into a planner or bad options; an
 *         unplannable query is `true` with m.planned = false.
 */
bool run(const tdo_io::Map& map, const Options& o, Episode* out, std::string* error);

/** The episode as JSON text (metrics, plan, steps, movers' tracks, events). */
std::string to_json(const Episode& e, const tdo_io::Map& map, const Options& o);

/**
 * @brief Executed speed, acceleration and jerk maxima by finite differences of positions taken
 *        every dt (paper eq. 15-17); each maximum is raised, never lowered (start them at 0).
 */
void executed_vaj(const std::vector<tdo_vec3>& pos, double dt, double* max_v, double* max_a,
                  double* max_j);

/** Stable name of a follower ("eapf" / "apf"). */
const char* follower_name(tdo_follower_kind k);

}  // namespace tdo_episode

#endif  // TDO_SIM_RUN_EPISODE_H
