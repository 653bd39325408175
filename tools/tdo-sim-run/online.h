/**
 * @file online.h
 * @brief One closed-loop episode in a world the vehicle discovers as it flies: a fraction of the
 *        columns hidden until the range sensor (tdo_sense_run) sees them, the revealed boxes
 *        applied to the planner's and the follower's grid (tdo_grid_apply_update), the active
 *        trajectory checked (tdo_replan_check) and replanned from the takeover state
 *        (tdo_replan_takeover, tdo_apf_switch) with libtdo's planner, the MSF-MTPO configuration
 *        of it, or not at all (E-APF only). Contacts are counted against the true world (every
 *        box), not the known map. Host tool code behind tdo-sim-run --unknown.
 */
#ifndef TDO_SIM_RUN_ONLINE_H
#define TDO_SIM_RUN_ONLINE_H

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "episode.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace tdo_online {

/** Who replans. */
enum class Replanner {
  None,   /**< no replanning: E-APF alone on the updated grid */
  Tdo,    /**< libtdo's planner (tdo_plan_params_default) */
  MsfMtpo /**< the MSF-MTPO baseline (tools/baselines "msf-mtpo": plain bidirectional search,
               greedy line-of-sight correction, arc corners, same trajectory stage) */
};

/** Stable name ("tdo", "none", "msf-mtpo"). */
const char* replanner_name(Replanner r);

/** Everything that determines an online episode besides the map. */
struct Options {
  Replanner replanner = Replanner::Tdo;
  double unknown = 0.0;         /**< fraction of the map's boxes hidden at the start, [0, 1] */
  uint64_t hide_seed = 1;       /**< seed of which boxes are hidden (tdo_sense_hide) */
  double sensor_range = 5.0;    /**< m, > 0 */
  double sense_period = 0.1;    /**< s, sensing (and checking) period, a multiple of the step */
  double horizon = 5.0;         /**< s, the active trajectory is checked this far ahead */
  double latency = 0.1;         /**< s, takeover time after the trigger (planning budget) */
  double check_slack = 0.01;    /**< m, the check's clearance is the planner's less this (chords) */
  double retry_period = 0.5;    /**< s, a failed replan is retried after this */
  double clearance = 0.5;       /**< m, planner clearance */
  double time_factor = 2.0;     /**< time limit = time_factor * first plan duration + time_extra */
  double time_extra = 20.0;     /**< s */
  double goal_tol = 0.2;        /**< m */
  double vehicle_radius = 0.25; /**< m */
  double static_clearance = 0.25; /**< m, static contact when the centre comes closer than this to
                                       a true box */
  bool movers = true;             /**< fly among the map's movers */
  double mover_margin = 0.5;      /**< m, a mover conflicts with the plan within its radius +
                                       vehicle_radius + this (the follower's default margin) */
  double mover_window = 1.0;      /**< s; > 0: a mover conflict triggers a replan round the
                                       region the mover's sphere (radius + vehicle_radius) sweeps
                                       over this window centred on the conflict time, set as
                                       temporary voxels and cleared after planning; 0: movers are
                                       left to the follower's evasion */
  double mover_period = 1.0;      /**< s, at most one mover replan per this period */
  double mover_keep_free = 2.5;   /**< m, no temporary voxel within this of the vehicle (the
                                       takeover start stays plannable) */
  uint32_t mover_cells = 40000;   /**< capacity of temporary voxels per mover replan (a larger
                                       region is not replanned round) */
  int32_t stream_samples = -1;    /**< planner's tdo_capacity.stream_samples (0 stored, 1 streamed,
                                       2 pieces); -1: as tdo_capacity_for_grid sets it */
};

/** Metrics of one online episode. */
struct Metrics {
  bool planned = false;              /**< the first plan succeeded */
  int plan_status = 0;               /**< tdo_status of the first plan */
  bool success = false;              /**< within goal_tol of the goal before the time limit */
  bool collision = false;            /**< collision_static || collision_mover */
  bool collision_static = false;     /**< closer than static_clearance to a true box */
  bool collision_mover = false;      /**< a mover gap below 0 */
  double min_true_static = HUGE_VAL; /**< m, smallest distance to the true boxes */
  double min_mover_gap = HUGE_VAL;   /**< m */
  uint32_t hidden = 0;               /**< boxes hidden at the start */
  uint32_t revealed = 0;             /**< of them revealed by the sensor */
  uint32_t triggers_blocked = 0;     /**< checks that found the active trajectory blocked */
  uint32_t triggers_stuck = 0;       /**< follower local-minimum reports that asked for a replan */
  uint32_t mover_conflicts = 0;      /**< checks (static clear) whose trajectory meets a mover's
                                          predicted position within the horizon (replanned
                                          round with mover_window > 0, else left to the
                                          follower's evasion) */
  uint32_t mover_replans = 0;        /**< of the replans, those round a mover (mover_window) */
  uint32_t mover_skipped = 0;        /**< mover conflicts not replanned: no free voxel in the
                                          region, or more than mover_cells */
  uint32_t replans = 0;              /**< new plans handed to the follower */
  uint32_t replan_failures = 0;      /**< replanning attempts without a plan (retried later) */
  std::vector<double> replan_ms;     /**< ms, wall time from trigger to new plan, per replan */
  std::vector<double> replan_cpu_ms; /**< ms, the same in thread CPU time */
  /** "takeover:<status>" / "vehicle:<status>" of every plan that failed (the takeover plan, then
   *  the plan from the vehicle's state) */
  std::vector<std::string> failure_statuses;
  uint32_t switches = 0;       /**< TDO_APF_EVENT_SWITCHED seen */
  uint32_t stale_switches = 0; /**< staged switches not taken in time (the reference held back
                                    while the vehicle was pushed off): replaced by a plan from the
                                    vehicle's state */
  bool escape_failed = false;  /**< the follower gave up at some point */
  double time = 0.0;           /**< s, arrival time or the time flown */
  double plan_duration = 0.0;  /**< s, first plan */
  double max_speed = 0.0, max_acc = 0.0, max_jerk = 0.0; /**< executed, finite differences */
  double v_limit = 0.0, a_limit = 0.0, j_limit = 0.0;    /**< the limits flown with */
  uint32_t steps = 0;
};

/**
 * @brief Fly one online episode on `map` (its start, goal, boxes and movers).
 * @return false with `error` for a set-up failure (capacity, bad options); an unplannable first
 *         query is `true` with planned = false.
 */
bool run(const tdo_io::Map& map, const Options& o, Metrics* out, std::string* error);

}  // namespace tdo_online

#endif  // TDO_SIM_RUN_ONLINE_H
