/**
 * @file avoid_node.h
 * @brief The tdo-avoid program minus its main(): the E-APF (or classical APF) follower of libtdo
 *        (apf.h) on LCM. TDO_TRAJECTORY + TDO_OBSTACLES + TDO_UAV_STATE + TDO_MAP -> TDO_SETPOINT,
 *        with TDO_STATUS heartbeats.
 *
 * Thin: decode (wire.h) -> adapter (adapters.h, vehicle.h) -> tdo_apf_run -> encode. Steps:
 *  - timed (default): tick() at the configured rate (poll() calls it), each with the latest state;
 *  - lock-step: one step per accepted vehicle state, at once (deterministic runs and tests).
 * Each step publishes one setpoint for the latest state. Before any state: nothing to publish.
 * Without a trajectory to follow (none yet, or the last one was refused by the library) the
 * setpoint brakes to a hover (tdo_motion_limit with a damping command, request_id -1).
 *
 * Inputs, and what happens to bad ones (never fatal; counted in the heartbeat by
 * "<what>.<reason>", what = trajectory, obstacles, state or map):
 *  - undecodable bytes (wrong fingerprint, truncated, bad counts): rejected;
 *  - a trajectory, state, obstacles or map for another vehicle: ignored (other_vehicle);
 *  - a trajectory answer with an error status or fewer than 2 samples: ignored (no_plan), the
 *    current task goes on;
 *  - a trajectory with bad samples (count, non-finite, times not increasing) or more samples than
 *    max_samples: rejected, the current task goes on; one the library refuses (tdo_apf_reset,
 *    e.g. non-uniform times): rejected (library_error), the follower holds until the next one;
 *  - a state with a non-finite number: rejected, the last good state stays;
 *  - obstacles with bad counts, non-finite numbers, radius <= 0 or more than max_movers:
 *    rejected, the last good obstacles stay;
 *  - a map that fails its checks (map_check against the grid's capacity): rejected, the previous
 *    map stays; a map the library refuses after the grid was reset: rejected, no static
 *    repulsion until the next good map.
 * Delivery: a request for this vehicle on the request channel, or a feasibility report for it,
 * promises a trajectory of the same request_id; one that has not arrived answer_timeout_s later
 * is counted as a rejected trajectory with reason "trajectory.missing" (heartbeat), once per
 * request (answer_watch.h). Those two channels are only watched: not counted in `received`,
 * undecodable messages on them are left to the planner. A trajectory may carry samples or only
 * the compact form (compact.h), which is sampled at its dt for the follower.
 * A new map (new map_id) is loaded into the grid and the current task is restarted on it with its
 * original time origin; the same map_id again is only counted as received. Map updates
 * (TDO_MAP_UPDATE, map_update.h) are applied to the grid the same way, in seq order; a gap or an
 * update that cannot be applied is counted ("update.gap", ...), makes the map stale
 * ("state.map_stale" in the heartbeat) and sends a map_request_t, as tdo-planner does.
 * Safety: after every map, update and trajectory the rest of the trajectory followed is checked
 * against the known obstacles (tdo_replan_check from the vehicle's place on it, exact, at the
 * vehicle radius; leaving the map's bounds counts as crossing). While the part still ahead
 * crosses one, the follower does not follow it: it brakes to a hover and every setpoint says
 * status "path_blocked" (status_code kStatusPathBlocked), counted as failed steps, with
 * "state.path_blocked" in the heartbeat, until a trajectory that is clear takes over.
 * Replanning (avoid_replan.cpp, docs/lcm.md "Replanning"): blocked, or the follower at a local
 * minimum or off the path, the node asks the planner for a plan (the goal and parameters of the
 * request followed) from the state its braking reaches at the takeover time, and follows the
 * answer from that time; no_path is a safe stop ("no_way_through"), max_replans unusable answers
 * one too ("replan_failed"); "replanning" while a plan the follower asked for is on its way.
 * Time: the follower's clock is seconds since the first accepted state's utime; movers are moved
 * on from their message's utime to the state's (at most max_mover_shift_s).
 * Single-threaded: the handlers run inside Bus::handle_timeout. Declare the bus before the node.
 */
#ifndef TDO_AVOID_NODE_H
#define TDO_AVOID_NODE_H

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "answer_watch.h"
#include "tdo/tdo.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/grid_host.h"
#include "tdo_lcm/map_update.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** setpoint_t.status_code of a hover because the trajectory crosses a known obstacle. */
constexpr int32_t kStatusPathBlocked = -2;
/** setpoint_t.status_code while braking for a new plan the follower asked for (local minimum,
 *  too far off the path). */
constexpr int32_t kStatusReplanning = -3;
/** setpoint_t.status_code of the safe stop after the planner found no way through (no_path). */
constexpr int32_t kStatusNoWayThrough = -4;
/** setpoint_t.status_code of the safe stop after max_replans requests brought no usable plan. */
constexpr int32_t kStatusReplanFailed = -5;

/** Configuration of a follower node (tdo-avoid's command line). */
struct AvoidConfig {
  int32_t vehicle_id = 0;                               /**< vehicle served */
  std::string trajectory_channel = kChannelTrajectory;  /**< trajectories in */
  std::string obstacles_channel = kChannelObstacles;    /**< moving obstacles in */
  std::string state_channel = kChannelVehicleState;     /**< vehicle states in */
  std::string map_channel = kChannelMap;                /**< static maps in */
  std::string map_update_channel = kChannelMapUpdate;   /**< map updates in */
  std::string map_request_channel = kChannelMapRequest; /**< requests for a whole map out */
  std::string setpoint_channel = kChannelSetpoint;      /**< setpoints out */
  std::string status_channel = kChannelStatus;          /**< heartbeats out */
  std::string request_channel = kChannelPlanRequest;    /**< requests seen (promise a trajectory) */
  std::string feasibility_channel = kChannelFeasibility; /**< reports seen (promise one too) */
  double answer_timeout_s = 2.0; /**< s: a promised trajectory missing this long is reported */
  tdo_follower_kind kind = TDO_FOLLOWER_EAPF; /**< E-APF or classical APF */
  double rate_hz = 50.0;            /**< Hz, steps per second; the follower's dt = 1 / rate */
  bool lockstep = false;            /**< one step per received state instead of the timer */
  double v_max = 3.0;               /**< m/s, speed limit of the setpoints */
  double a_max = 3.0;               /**< m/s^2 */
  double j_max = 10.0;              /**< m/s^3 */
  double vehicle_radius = 0.25;     /**< m */
  int32_t max_nx = 128;             /**< voxels along x of the largest map (sizes the grid) */
  int32_t max_ny = 128;             /**< voxels along y */
  int32_t max_nz = 64;              /**< voxels along z */
  uint32_t max_boxes = 4096;        /**< obstacle boxes of one map */
  double max_clearance_ratio = 4.0; /**< largest map clearance / resolution */
  uint32_t max_samples = 100000;    /**< trajectory samples (1000 s at 0.01 s) */
  uint32_t max_movers = 256;        /**< moving obstacles per message */
  uint32_t nearest_window = 200;    /**< samples searched each way per step for the nearest point
                                         (2 s at the planner's default 0.01 s) */
  double max_mover_shift_s = 1.0; /**< s, movers are moved on to the state's time by at most this */
  double heartbeat_period_s = 1.0; /**< s between TDO_STATUS messages; <= 0: none from poll() */
  // replanning (avoid_replan.cpp)
  bool replan = true;               /**< send plan requests from the predicted state when needed */
  double replan_lead_s = 0.5;       /**< s from the trigger to the takeover of the new plan */
  uint32_t max_replans = 3;         /**< requests per trigger without a usable plan, then a stop */
  uint32_t max_replans_total = 200; /**< requests over the node's life, then a stop */
  double replan_deviation_m = 2.0;  /**< m off the path for replan_deviation_s: replan */
  double replan_deviation_s = 1.0;  /**< s */
  int64_t replan_id_base = 1000000000; /**< request_id of the k-th replan: base + k */
};

/** Message counters, also sent in each heartbeat (status_t). */
struct AvoidCounters {
  int64_t received = 0;        /**< messages on the four input channels */
  int64_t missing = 0;         /**< promised trajectories that did not arrive in time (rejected) */
  int64_t maps_loaded = 0;     /**< maps loaded into the grid */
  int64_t trajectories = 0;    /**< trajectories accepted (follower reset) */
  int64_t setpoints = 0;       /**< setpoints published (heartbeat: answered) */
  int64_t steps_ok = 0;        /**< follower steps with TDO_OK (heartbeat: succeeded) */
  int64_t steps_failed = 0;    /**< follower steps with a failure, e.g. local_minimum (failed) */
  int64_t holds = 0;           /**< hover setpoints without a task */
  int64_t blocked_holds = 0;   /**< hover setpoints because the trajectory crosses an obstacle */
  int64_t updates_applied = 0; /**< map updates applied to the grid */
  int64_t rejected = 0;        /**< messages refused by a check */
  int64_t ignored = 0;         /**< messages not for this vehicle or without a plan */
  int64_t goal_reached = 0;    /**< GOAL_REACHED events */
  int64_t lm_detections = 0;   /**< local minima detected (over every task) */
  int64_t replans = 0;         /**< plan requests sent from a predicted state */
  int64_t replan_switches = 0; /**< new plans taken over at their takeover time */
  int64_t replan_refused = 0;  /**< answers to them not taken (error, blocked, late) */
  int64_t safe_stops = 0;      /**< stops: no_way_through or replan_failed */
  int64_t unsafe_brakes = 0;   /**< hold steps whose straight braking would touch a known
                                    obstacle: the follower's step was sent instead */
  double last_step_ms = 0.0;   /**< ms, wall time of the last follower call */
  std::map<std::string, int64_t> reasons; /**< "trajectory.<reason>", "state.<reason>", ... */
};

class AvoidNode {
 public:
  AvoidNode(Bus* bus, AvoidConfig cfg);
  AvoidNode(const AvoidNode&) = delete;
  AvoidNode& operator=(const AvoidNode&) = delete;

  /**
   * @brief Allocate the grid and the follower arena (once), initialise, subscribe.
   * @param[out] error why not (may be null)
   */
  bool start(std::string* error);

  /** @brief Timed mode: step when a tick is due; both modes: heartbeat when due. */
  void poll(std::chrono::steady_clock::time_point now);

  /** @brief One step now with the latest state (nothing before any state). @return published. */
  bool tick();

  /** @return when poll() next has something to do (a tick or a heartbeat). */
  std::chrono::steady_clock::time_point next_due() const;

  /** @brief Publish a heartbeat now. */
  void publish_status();

  /** @return the heartbeat message as it would be sent now. */
  tdo::status_t status_message() const;

  const AvoidCounters& counters() const { return counters_; }
  /** @return the trajectory followed (request_id), -1 when holding. */
  int64_t following() const { return task_ready_ ? request_id_ : -1; }
  int64_t map_id() const { return have_map_ ? map_id_ : -1; }
  /** @return true while the rest of the trajectory followed crosses a known obstacle. */
  bool path_blocked() const;
  bool map_stale() const { return updates_.stale(); }
  /** @return the setpoint status while not following ("" when following or holding idle). */
  const char* stop_status() const;
  /** @return true while a replan is asked for and its plan has not taken over. */
  bool replanning() const { return replan_.phase != ReplanPhase::idle; }
  /** @return the last follower output (mode, terms, events). */
  const tdo_apf_output& last_output() const { return last_out_; }
  std::size_t arena_bytes() const { return arena_bytes_ + grid_.arena_bytes(); }
  const tdo_apf_params& params() const { return params_; }

  /** Handlers of the raw bytes of one message (what start() subscribes). */
  void on_trajectory(const void* data, std::size_t size);
  void on_obstacles(const void* data, std::size_t size);
  void on_state(const void* data, std::size_t size);
  void on_map(const void* data, std::size_t size);
  void on_request(const void* data, std::size_t size);
  void on_feasibility(const void* data, std::size_t size);
  void on_map_update(const void* data, std::size_t size);

 private:
  enum class ReplanPhase { idle, waiting, pending, stopped };
  enum class Hold { idle, blocked, replanning, no_way_through, replan_failed };
  /** Replanning state (avoid_replan.cpp). */
  struct Replan {
    ReplanPhase phase = ReplanPhase::idle;
    Hold stop = Hold::idle;          /**< why stopped (phase stopped) */
    bool wanted = false;             /**< the follower asked for a new plan */
    int64_t request_id = -1;         /**< the request waited for */
    double t_take = 0.0;             /**< s, follower clock of the takeover */
    uint32_t attempts = 0;           /**< requests since the last trigger was resolved */
    double off_since = -1.0;         /**< s, follower clock since off the path (-1: on it) */
    double clearance = -1.0;         /**< m, request clearance; < 0: the followed request's */
    double start_speed = 0.0;        /**< m/s, of the predicted state asked from */
    double rest_since = -1.0;        /**< s, follower clock since at rest after a stop */
    std::vector<tdo_sample> samples; /**< the answer, waiting for its takeover */
  };
  bool have_template() const;
  void remember_request(const tdo::plan_request_t& m);
  bool follower_wants_replan(tdo_status st);
  void request_replan();
  void on_replan_answer(const tdo::trajectory_t& m);
  void replan_refused(const std::string& why);
  void replan_stop(Hold why);
  bool at_rest_since(double s);
  bool replan_tick();
  void switch_to_pending();
  void resume_after_map();
  tdo_setpoint brake_step(const tdo_vehicle_state& s) const;
  bool brake_is_safe();
  Check trajectory_samples(const tdo::trajectory_t& m, std::vector<tdo_sample>* out) const;
  void check_blocked();
  bool samples_blocked(const std::vector<tdo_sample>& samples, double from, double* blocked_to);
  void request_map(const std::string& why);
  void hold(Hold why);
  void track_nearest();
  void refuse(const std::string& what, const Check& c);
  void reset_task();
  void publish_setpoint(const tdo_setpoint& sp, tdo_status st, int64_t request_id,
                        Hold why = Hold::idle);

  Bus* bus_;
  AvoidConfig cfg_;
  GridHost grid_;
  std::unique_ptr<std::max_align_t[]> arena_;
  std::size_t arena_bytes_ = 0;
  tdo_apf* apf_ = nullptr;
  tdo_apf_params params_{};

  // map
  bool have_map_ = false;
  int64_t map_id_ = -1;
  MapUpdateSeq updates_;
  int64_t map_request_seq_ = 0;
  // the task crosses a known obstacle (blocked_), the last time it does: blocked_to_ (s, trajectory
  // time of the end of the last blocked segment)
  bool blocked_ = false;
  double blocked_to_ = 0.0;
  std::size_t near_idx_ = 0; /**< sample of the task nearest to the vehicle (track_nearest) */
  // task
  std::vector<tdo_sample> samples_;
  int64_t request_id_ = -1;
  bool have_task_ = false;   /**< a trajectory was accepted */
  bool task_ready_ = false;  /**< the follower was reset with it */
  bool task_t0_set_ = false; /**< its time origin is fixed (the first state after it) */
  double task_t0_ = 0.0;     /**< s, follower clock at trajectory t = 0 */
  // state and movers
  bool have_state_ = false;
  bool utime_ref_set_ = false;
  int64_t utime_ref_ = 0; /**< us, follower clock origin */
  int64_t state_utime_ = 0;
  tdo_vehicle_state state_{};
  std::vector<tdo_mover> movers_;
  int64_t movers_utime_ = 0; /**< us, time of movers_ */
  std::vector<tdo_mover> movers_now_;
  double yaw_ = 0.0;

  AnswerWatch watch_;
  // replanning: the requests seen for this vehicle (the last kMaxTemplates, their parameters and
  // goal are reused), the one whose trajectory is followed, the replan in progress
  static constexpr std::size_t kMaxTemplates = 16;
  std::vector<tdo::plan_request_t> requests_;
  tdo::plan_request_t template_{};
  bool template_set_ = false;
  Replan replan_;
  int64_t replan_seq_ = 0;

  tdo_apf_output last_out_{};
  AvoidCounters counters_;
  int64_t setpoint_seq_ = 0;
  int64_t status_seq_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_status_;
  std::chrono::steady_clock::time_point next_tick_;
};

}  // namespace tdo_lcm

#endif  // TDO_AVOID_NODE_H
