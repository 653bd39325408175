/**
 * @file node_status.h
 * @brief Start-up, clock and heartbeat (TDO_STATUS) code shared by the LCM nodes (tdo-avoid,
 * tdo-sim, tdo-planner): each node fills its own counters, these fill and send the rest.
 */
#ifndef TDO_LCM_NODE_STATUS_H
#define TDO_LCM_NODE_STATUS_H

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "tdo_lcm/bus.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** @return us since the Unix epoch (system clock), the utime of messages the nodes send. */
int64_t wall_utime();

/** @return `s` seconds as a steady-clock duration. */
std::chrono::steady_clock::duration steady_seconds(double s);

/**
 * @brief Move a periodic deadline one `period` on; when that is still not after `now` (the node
 * fell behind), the next one is `now + period`: no burst of catch-up events.
 */
void advance_deadline(std::chrono::steady_clock::time_point* next,
                      std::chrono::steady_clock::time_point now,
                      std::chrono::steady_clock::duration period);

/** @return false, after storing `msg` in `*error` when `error` is not null: a failed start(). */
bool fail_start(std::string* error, const std::string& msg);

/**
 * @return why a node cannot start: the bus is missing or not good, the node is `already_started`,
 *         or its `rate_hz` is not finite and > 0; "" when it can.
 */
const char* start_problem(const Bus* bus, bool already_started, double rate_hz);

/**
 * @brief Allocate a node's library arena: `bytes` rounded up to whole std::max_align_t.
 * @return the bytes allocated; 0 when the allocation failed (`*error`, when not null, says so)
 */
std::size_t alloc_node_arena(std::unique_ptr<std::max_align_t[]>* arena, std::size_t bytes,
                             std::string* error);

/**
 * @brief Fill a heartbeat's header (utime now, seq, program, vehicle_id, uptime since `started`)
 * and its reason lists from `reasons`; the node fills the counters.
 */
void fill_status(tdo::status_t* s, const char* program, int64_t seq, int32_t vehicle_id,
                 std::chrono::steady_clock::time_point started,
                 const std::map<std::string, int64_t>& reasons);

/**
 * @brief start() `node`; on failure print "PROG: error: WHY" on stderr.
 * @return whether the node started
 */
template <class Node>
bool start_node(const char* prog, Node* node) {
  std::string error;
  if (node->start(&error)) return true;
  std::fprintf(stderr, "%s: error: %s\n", prog, error.c_str());
  return false;
}

/**
 * @brief Count a refused message in a node's counters (fields `ignored`, `rejected`, `reasons`):
 * ignored when `on_purpose` (e.g. for another vehicle), else rejected, and by "WHAT.REASON".
 */
template <class Counters>
void count_refusal(Counters* c, const std::string& what, Reason reason, bool on_purpose) {
  if (on_purpose)
    ++c->ignored;
  else
    ++c->rejected;
  ++c->reasons[what + "." + reason_str(reason)];
}

/** A node's own counters of one heartbeat (their meaning: lcmtypes/status_t.lcm). */
struct StatusCounts {
  int64_t map_id = -1;       /**< map in use; -1 = none */
  int64_t received = 0;      /**< messages received */
  int64_t maps_loaded = 0;   /**< maps accepted and loaded */
  int64_t answered = 0;      /**< requests answered (or steps taken) */
  int64_t succeeded = 0;     /**< answers with status ok */
  int64_t failed = 0;        /**< answers with a failure status */
  int64_t rejected = 0;      /**< messages refused by a check */
  int64_t ignored = 0;       /**< messages ignored on purpose */
  double last_plan_ms = 0.0; /**< ms, wall time of the last library call */
};

/** @return a heartbeat: header and reasons as fill_status, then the counters `c`. */
tdo::status_t make_status(const char* program, int64_t seq, int32_t vehicle_id,
                          std::chrono::steady_clock::time_point started,
                          const std::map<std::string, int64_t>& reasons, const StatusCounts& c);

/**
 * @brief Send heartbeat `s` on `channel` when its counts are consistent (check_counts), then
 * advance `*seq`; the bus fills queue_capacity and dropped (Bus::dropped). Nothing is sent and
 * `*seq` stays when the counts are not.
 */
void send_status(Bus* bus, const std::string& channel, const tdo::status_t& s, int64_t* seq);

}  // namespace tdo_lcm

#endif  // TDO_LCM_NODE_STATUS_H
