/**
 * @file node_status.h
 * @brief Clock and heartbeat (TDO_STATUS) code shared by the LCM nodes (tdo-avoid, tdo-sim,
 * tdo-planner): each node fills its own counters, these fill and send the rest.
 */
#ifndef TDO_LCM_NODE_STATUS_H
#define TDO_LCM_NODE_STATUS_H

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

#include "tdo_lcm/bus.h"
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

/**
 * @brief Fill a heartbeat's header (utime now, seq, program, vehicle_id, uptime since `started`)
 * and its reason lists from `reasons`; the node fills the counters.
 */
void fill_status(tdo::status_t* s, const char* program, int64_t seq, int32_t vehicle_id,
                 std::chrono::steady_clock::time_point started,
                 const std::map<std::string, int64_t>& reasons);

/**
 * @brief Send heartbeat `s` on `channel` when its counts are consistent (check_counts), then
 * advance `*seq`; the bus fills queue_capacity and dropped (Bus::dropped). Nothing is sent and
 * `*seq` stays when the counts are not.
 */
void send_status(Bus* bus, const std::string& channel, const tdo::status_t& s, int64_t* seq);

}  // namespace tdo_lcm

#endif  // TDO_LCM_NODE_STATUS_H
