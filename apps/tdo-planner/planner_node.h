/**
 * @file planner_node.h
 * @brief The tdo-planner program minus its main(): keeps the latest map from TDO_MAP, answers each
 *        TDO_PLAN_REQUEST with TDO_TRAJECTORY + TDO_FEASIBILITY, publishes TDO_STATUS heartbeats.
 *
 * Thin: decode (wire.h) -> adapter (adapters.h) -> tdo_planner_plan -> encode. It never dies on a
 * bad message. What happens to each kind of input:
 *  - undecodable (wrong fingerprint, truncated, bad counts): counted, not answered (no request id);
 *  - a map that fails its checks: counted, the previous map stays; an ENCODING_OCTOMAP_BT map is
 *    rasterised onto its grid first (map_file.h; builds with OctoMap, else unsupported_encoding);
 *  - a map the library refuses after the grid was reset (rare: checks mirror the library): counted,
 *    the planner has no map until the next good one;
 *  - a request for another vehicle (or a map for another vehicle): counted as ignored, no answer;
 *  - any other bad request, a request before any map or for another map id: counted as rejected
 *    and answered with status_code STATUS_REJECTED and the reason as status; the feasibility
 *    answer names the field at fault and why (refused_field, refused_reason), and the heartbeat
 *    counts it by field too ("field.<name>", not part of the rejected + ignored sum);
 *  - parameters whose use_defaults bit is set get libtdo's defaults (adapters.h); the answers
 *    carry the request's seq (request_seq); samples only for SAMPLES_ON, the compact form always
 *    for a usable trajectory (compact.h);
 *  - a map update (TDO_MAP_UPDATE, map_update.h): applied to the grid when it is the next one of
 *    the loaded map (time proportional to the update); refused by reason ("update.gap",
 *    "update.stale_update", "update.other_map", "update.contradictory", "update.out_of_range",
 *    ...). A gap, or an update that cannot be applied, makes the map stale: the node sends a
 *    map_request_t on TDO_MAP_REQUEST (again every heartbeat period while stale), answers every
 *    request with status "map_stale" instead of planning, and its heartbeat carries
 *    "state.map_stale" (1; outside the rejected + ignored sum) until a whole map arrives;
 *  - a valid request: answered with the library's status (ok, no_path, infeasible, ...).
 * Single-threaded: the handlers run inside Bus::handle_timeout, like poll(). The node subscribes
 * on its bus in start(); the bus must not dispatch after the node is gone (declare the bus first).
 */
#ifndef TDO_PLANNER_NODE_H
#define TDO_PLANNER_NODE_H

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/map_update.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** Configuration of a planner node (tdo-planner's command line). */
struct PlannerConfig {
  int32_t vehicle_id = 0;                                /**< vehicle served */
  std::string map_channel = kChannelMap;                 /**< maps in */
  std::string map_update_channel = kChannelMapUpdate;    /**< map updates in */
  std::string map_request_channel = kChannelMapRequest;  /**< requests for a whole map out */
  std::string request_channel = kChannelPlanRequest;     /**< requests in */
  std::string trajectory_channel = kChannelTrajectory;   /**< answers out */
  std::string feasibility_channel = kChannelFeasibility; /**< reports out */
  std::string status_channel = kChannelStatus;           /**< heartbeats out */
  int32_t max_nx = 128;             /**< voxels along x of the largest map (sizes the arena) */
  int32_t max_ny = 128;             /**< voxels along y */
  int32_t max_nz = 64;              /**< voxels along z */
  uint32_t max_nodes = 2000000;     /**< search states per direction */
  uint32_t max_boxes = 4096;        /**< obstacle boxes of one map */
  double max_clearance_ratio = 4.0; /**< largest clearance / resolution the stencil fits */
  double heartbeat_period_s = 1.0;  /**< s between TDO_STATUS messages; <= 0: none from poll() */
  int32_t stream_samples = -1;      /**< tdo_capacity.stream_samples: 0 stored, 1 streamed,
                                         2 pieces; -1: as tdo_capacity_for_grid sets it. The
                                         answers are the same in every mode */
};

/** Message counters, also sent in each heartbeat. */
struct PlannerCounters {
  int64_t received = 0;        /**< messages on the map and request channels */
  int64_t maps_loaded = 0;     /**< maps loaded into the grid */
  int64_t updates_applied = 0; /**< map updates applied to the grid */
  int64_t map_requests = 0;    /**< map_request_t sent */
  int64_t answered = 0;        /**< requests answered (also with an error status) */
  int64_t succeeded = 0;       /**< answers with status ok */
  int64_t failed = 0;          /**< answers with a libtdo failure status */
  int64_t rejected = 0;        /**< messages refused by a check */
  int64_t ignored = 0;         /**< messages for another vehicle */
  double last_plan_ms = 0.0;   /**< ms, wall time of the last library call */
  std::map<std::string, int64_t>
      reasons; /**< "map.<reason>", "request.<reason>", "result.<reason>" */
};

class PlannerNode {
 public:
  PlannerNode(Bus* bus, PlannerConfig cfg);
  PlannerNode(const PlannerNode&) = delete;
  PlannerNode& operator=(const PlannerNode&) = delete;

  /**
   * @brief Allocate the arena (once; the footprint of the configured capacities), initialise the
   *        planner and subscribe to the map and request channels.
   * @param[out] error why not (may be null)
   */
  bool start(std::string* error);

  /** @brief Publish a heartbeat when one is due (call after each handleTimeout). */
  void poll(std::chrono::steady_clock::time_point now);

  /** @brief Publish a heartbeat now. */
  void publish_status();

  /** @return the heartbeat message as it would be sent now. */
  tdo::status_t status_message() const;

  const PlannerCounters& counters() const { return counters_; }
  const tdo_capacity& capacity() const { return cfg_tdo_.cap; }
  std::size_t arena_bytes() const { return arena_bytes_; }
  int64_t map_id() const { return have_map_ ? map_id_ : -1; }
  /** @return true while the map is known to be stale (a whole map was asked for). */
  bool map_stale() const { return updates_.stale(); }

  /** Handlers of the raw bytes of one message (what start() subscribes). */
  void on_map(const void* data, std::size_t size);
  void on_request(const void* data, std::size_t size);
  void on_map_update(const void* data, std::size_t size);

 private:
  void refuse(const std::string& what, const Check& c);
  void answer(const tdo::trajectory_t& traj, const tdo::feasibility_t& feas);
  void answer_error(const AnswerIds& ids, const std::string& what, const Check& c);
  bool set_clearance(double clearance, Check* why);
  void request_map(const char* why);

  Bus* bus_;
  PlannerConfig cfg_;
  tdo_planner_config cfg_tdo_{};
  std::unique_ptr<std::max_align_t[]> arena_;
  std::size_t arena_bytes_ = 0;
  tdo_planner* planner_ = nullptr;

  bool have_map_ = false;
  int64_t map_id_ = -1;
  double map_res_ = 0.0;       /**< m, resolution of the loaded map */
  double map_clearance_ = 0.0; /**< m, clearance hint of the loaded map */
  MapUpdateSeq updates_;       /**< the updates of the loaded map */
  std::string stale_why_;      /**< why the map is stale (map_request_t.reason) */
  int64_t map_request_seq_ = 0;
  std::chrono::steady_clock::time_point next_map_request_;

  PlannerCounters counters_;
  int64_t status_seq_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_status_;
};

}  // namespace tdo_lcm

#endif  // TDO_PLANNER_NODE_H
