/**
 * @file sim_node.h
 * @brief The tdo-sim program minus its main(): libtdo's deterministic simulator (sim.h) on LCM.
 *        TDO_SETPOINT -> TDO_UAV_STATE + TDO_OBSTACLES at a fixed rate; optionally a map file
 *        (.tdomap, .3dmap, .bt, .ot, read by mapio) published on TDO_MAP, whose moving spheres
 *        are the simulated movers and whose geometry is the static collision check.
 *
 * Thin: decode (wire.h) -> adapter (vehicle.h) -> tdo_sim_run -> encode. Steps:
 *  - timed (default): one step per tick at the configured rate (poll() calls it). A step flies
 *    only the setpoint that answers the current state (its utime is the state's): the follower's
 *    command, and its safety filter's braking roll-out, hold for the state it was computed from
 *    (apf.h). When that answer has not come at the tick, the step waits for it (the simulated
 *    clock waits) up to setpoint_wait_s of wall clock; if it is still missing the step is late:
 *    the vehicle brakes (the library's braking, sim.h: a = -brake_gain v through the motion
 *    limits; by default the braking of the follower's roll-out) instead of flying an older
 *    command on a state it was not computed for. A late step is counted as "step.setpoint_late"
 *    in the heartbeat and logged when lateness starts and ends; an answer that arrives after its
 *    state was passed is never flown ("setpoint.late"). With setpoint_wait_s 0 the step flies the
 *    latest setpoint whatever state it answers, unless it is stale (its utime more than
 *    setpoint_max_age_steps steps behind the simulated clock: "step.setpoint_stale", braking).
 *    When no setpoint came for setpoint_timeout_s (wall clock) the vehicle brakes at once;
 *  - lock-step: one step per accepted setpoint, at once, and nothing else (deterministic runs).
 * Every step publishes the state and the movers, both stamped with the simulated clock:
 * utime = the start utime + steps * dt. start() publishes the map and the initial state and movers.
 * The map is published again every map_period_s (timed mode) for programs that start later.
 * For demos, request_goal sends one TDO_PLAN_REQUEST (request_id 1) from the vehicle's position to
 * the goal request_delay_s after start (timed mode; lock-step: in start()).
 *
 * Bad input is never fatal; counted in the heartbeat by "setpoint.<reason>":
 *  - undecodable bytes: rejected; a setpoint for another vehicle: ignored (other_vehicle);
 *  - a setpoint with a non-finite number: rejected, the last good one stays (no step in lock-step).
 * Single-threaded: the handlers run inside Bus::handle_timeout. Declare the bus before the node.
 */
#ifndef TDO_SIM_NODE_H
#define TDO_SIM_NODE_H

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/grid_host.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** Configuration of a simulator node (tdo-sim's command line). */
struct SimConfig {
  int32_t vehicle_id = 0;                               /**< vehicle simulated */
  std::string setpoint_channel = kChannelSetpoint;      /**< setpoints in */
  std::string state_channel = kChannelVehicleState;     /**< states out */
  std::string obstacles_channel = kChannelObstacles;    /**< movers out */
  std::string map_channel = kChannelMap;                /**< the map file out */
  std::string status_channel = kChannelStatus;          /**< heartbeats out */
  std::string request_channel = kChannelPlanRequest;    /**< the demo request out (request_goal) */
  std::string map_update_channel = kChannelMapUpdate;   /**< revealed boxes out (sensing) */
  std::string map_request_channel = kChannelMapRequest; /**< requests for the whole map in */
  double rate_hz = 50.0;        /**< Hz, steps per second; the simulator's dt = 1 / rate */
  bool lockstep = false;        /**< one step per received setpoint instead of the timer */
  std::string map_file;         /**< map to publish and simulate in; empty: none */
  double map_resolution = 0.0;  /**< m, voxel edge for OcTrees (0 = the tree's) */
  double map_clearance = 0.5;   /**< m, clearance hint sent with the map (the planner's) */
  int64_t map_id = 1;           /**< map_id of the published map (>= 0) */
  double map_period_s = 1.0;    /**< s between re-publications of the map; <= 0: only at start */
  bool movers = true;           /**< simulate the map file's moving spheres */
  bool has_start = false;       /**< start given (else the map's start, else the bounds' centre) */
  tdo_vec3 start{};             /**< m, world frame, initial position (at rest) */
  bool has_bounds = false;      /**< bounds given (else the map's, else 0..50 x 0..50 x 0..20) */
  tdo_box bounds{};             /**< m, movers are reflected at these */
  double v_max = 3.0;           /**< m/s */
  double a_max = 3.0;           /**< m/s^2 */
  double j_max = 10.0;          /**< m/s^3 */
  double vehicle_radius = 0.25; /**< m, for the mover collision flag */
  double static_clearance = 0.25;  /**< m, static collision when the centre comes closer */
  uint64_t seed = 1;               /**< seed of the disturbance and the hidden boxes */
  double accel_noise = 0.0;        /**< m/s^2, standard deviation of the disturbance */
  double setpoint_timeout_s = 0.5; /**< s, timed mode: brake when no setpoint came for this long */
  double brake_gain = -1.0;        /**< 1/s, braking command a = -gain v; < 0: 2 j_max / a_max,
                                        the braking of the follower's safety roll-out (apf.h: a_max
                                        against v, proportional below a_max^2 / (2 j_max)) */
  double setpoint_wait_s = 0.1;    /**< s, timed mode: wall time a step waits past its tick for
                                        the setpoint answering the current state, then brakes
                                        (setpoint_late); 0: fly the latest setpoint (age check) */
  double setpoint_max_age_steps = 3.0; /**< timed mode: a setpoint more than this many steps
                                            (1 / rate) older than the simulated clock is stale:
                                            brake; 0: no age check */
  bool log = false;                    /**< stale-setpoint transitions to stderr (tdo-sim: unless
                                            --quiet) */
  int64_t start_utime = 0;             /**< us, utime of the initial state; 0 = the wall clock */
  uint32_t max_movers = 256;           /**< capacity: movers simulated */
  bool request_goal = false;       /**< demo: send one plan request, start -> goal, with libtdo's
                                        default parameters (as a ground station would) */
  bool has_goal = false;           /**< goal given (else the map's goal) */
  tdo_vec3 goal{};                 /**< m, world frame */
  double request_delay_s = 1.0;    /**< s after start (timed mode) before the request goes out */
  double heartbeat_period_s = 1.0; /**< s between TDO_STATUS messages; <= 0: none from poll() */
  double unknown_fraction = 0.0;   /**< in [0, 1]: share of the map's boxes hidden until sensed
                                        (tdo_sense_hide with `seed`); 0: whole map known */
  double sensor_range = 5.0;       /**< m, > 0: reach of the range sensor (tdo_sense_run) */
};

/** Counters, also sent in each heartbeat (status_t). */
struct SimCounters {
  int64_t received = 0;          /**< messages on the setpoint channel */
  int64_t setpoints = 0;         /**< setpoints accepted */
  int64_t steps = 0;             /**< simulator steps (heartbeat: answered) */
  int64_t brakes = 0;            /**< steps without a fresh setpoint (braking) */
  int64_t stale_steps = 0;       /**< of them, steps whose setpoint was stale (setpoint_stale) */
  int64_t late_steps = 0;        /**< of them, steps whose answer did not come (setpoint_late) */
  int64_t late_setpoints = 0;    /**< answers that came after their state was passed (not flown) */
  int64_t waits = 0;             /**< ticks that waited for the answer to the current state */
  int64_t collision_steps = 0;   /**< steps ending in a collision (heartbeat: failed) */
  int64_t mover_collisions = 0;  /**< steps with a mover gap below 0 */
  int64_t static_collisions = 0; /**< steps closer than static_clearance to the map */
  double min_mover_gap = 0.0;    /**< m, smallest mover gap over the run (HUGE_VAL: none) */
  double min_static_dist = 0.0;  /**< m, smallest static distance over the run (capped at 10 m) */
  int64_t maps_published = 0;    /**< map messages sent */
  int64_t boxes_hidden = 0;      /**< boxes hidden at start (sensing) */
  int64_t boxes_revealed = 0;    /**< of them revealed by the sensor */
  int64_t updates_published = 0; /**< map_update_t sent (one per step that revealed boxes) */
  int64_t rejected = 0;          /**< messages refused by a check */
  int64_t ignored = 0;           /**< messages for another vehicle */
  double last_step_ms = 0.0;     /**< ms, wall time of the last simulator call */
  std::map<std::string, int64_t> reasons; /**< "setpoint.<reason>" */
};

class SimNode {
 public:
  SimNode(Bus* bus, SimConfig cfg);
  SimNode(const SimNode&) = delete;
  SimNode& operator=(const SimNode&) = delete;

  /**
   * @brief Read the map file, allocate (once), reset the simulator, subscribe, and publish the map
   *        and the initial state and movers.
   * @param[out] error why not (may be null)
   */
  bool start(std::string* error);

  /** @brief Timed mode: step when a tick is due, map when due; both modes: heartbeat when due. */
  void poll(std::chrono::steady_clock::time_point now);

  /** @return when poll() next has something to do. */
  std::chrono::steady_clock::time_point next_due() const;

  /** @brief One step now with the latest setpoint (or braking), then publish. */
  void step();

  /** @brief Publish the current state and movers (again). */
  void publish_state();

  /** @brief Publish the map (when there is one). */
  void publish_map();

  /** @brief Publish the demo plan request (request_goal) now. @return false without a goal. */
  bool publish_request();

  /** @brief Publish a heartbeat now. */
  void publish_status();

  /** @return the heartbeat message as it would be sent now. */
  tdo::status_t status_message() const;

  const SimCounters& counters() const { return counters_; }
  /** @return the simulator's current output (state, movers, distances). */
  tdo_sim_output current() const;
  /** @return the map's default goal, when the map file gave one. */
  bool goal(tdo_vec3* out) const;
  /** @return the map message (empty when no map file). */
  const tdo::map_t& map_message() const { return map_msg_; }
  bool has_map() const { return has_map_; }
  int64_t start_utime() const { return utime0_; }
  std::size_t arena_bytes() const { return arena_bytes_ + grid_.arena_bytes(); }

  /** @return the map_id of the map published now (a new one after each map request). */
  int64_t map_id() const { return map_id_; }
  /** @return the true world's boxes and which of them the vehicle knows (1) or not yet (0). */
  const std::vector<tdo_box>& true_boxes() const { return true_boxes_; }
  const std::vector<uint8_t>& known() const { return known_; }

  /** Handler of the raw bytes of one setpoint (what start() subscribes). */
  void on_setpoint(const void* data, std::size_t size);
  /** Handler of a map request: the known map under a new map_id (sensing only). */
  void on_map_request(const void* data, std::size_t size);

 private:
  void refuse(const std::string& what, const Check& c);
  void step_at(std::chrono::steady_clock::time_point now);
  void note_stale(bool stale, const tdo_sim_output& out);
  void note_late(bool late, const tdo_sim_output& out);
  bool follower_alive(std::chrono::steady_clock::time_point now) const;
  bool answered() const { return have_setpoint_ && setpoint_utime_ == state_utime_; }
  // Timed steps fly only the answer to their state (setpoint_wait_s > 0).
  bool waits_for_answers() const { return !cfg_.lockstep && cfg_.setpoint_wait_s > 0.0; }
  bool start_sensing(const tdo_io::Map& map, std::string* error);
  void sense(bool publish = true);
  Check known_map_msg();

  Bus* bus_;
  SimConfig cfg_;
  GridHost grid_;
  std::unique_ptr<std::max_align_t[]> arena_;
  std::size_t arena_bytes_ = 0;
  tdo_sim* sim_ = nullptr;

  bool has_map_ = false;
  tdo::map_t map_msg_{};
  int64_t map_id_ = -1;
  // sensing (sim_sensing.cpp): the map file (the true world), its boxes and what is known
  bool sensing_ = false;
  tdo_io::Map map_;
  std::vector<tdo_box> true_boxes_;  // the map file's boxes: the static check and the sensor
  bool has_voxels_ = false;          // the map file has voxels: the grid joins the static check
  std::vector<uint8_t> known_;
  std::vector<uint32_t> revealed_;
  int64_t update_seq_ = 0;
  bool has_goal_ = false;
  tdo_vec3 goal_{};

  int64_t utime0_ = 0; /**< us, utime of simulated t = 0 */
  bool have_setpoint_ = false;
  bool stale_ = false;           // the last step's setpoint was stale (for the log's transitions)
  bool late_ = false;            // the last step was late (for the log's transitions)
  int64_t state_utime_ = 0;      // utime of the state published last (the current one)
  int64_t setpoint_utime_ = -1;  // utime of the state the latest setpoint answers
  bool waiting_ = false;         // the due tick waits for the answer to the current state
  std::chrono::steady_clock::time_point wait_until_;
  tdo_setpoint setpoint_{};
  double yaw_ = 0.0;
  std::chrono::steady_clock::time_point setpoint_wall_;

  SimCounters counters_;
  int64_t state_seq_ = 0;
  int64_t obstacles_seq_ = 0;
  int64_t status_seq_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_status_;
  std::chrono::steady_clock::time_point next_tick_;
  std::chrono::steady_clock::time_point next_map_;
  std::chrono::steady_clock::time_point request_at_;
  bool requested_ = false;
};

}  // namespace tdo_lcm

#endif  // TDO_SIM_NODE_H
