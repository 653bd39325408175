/**
 * @file map_publisher.h
 * @brief tdo-publish-map minus its main(): publishes a map on TDO_MAP, its updates (boxes added)
 *        on TDO_MAP_UPDATE with consecutive seq, and answers a map_request_t on TDO_MAP_REQUEST
 *        with the whole current map (the file's obstacles plus every box published since) under a
 *        new map_id, after which the updates continue with seq 1 of that id (docs/lcm.md). Every
 *        whole map sent after an update gets a new map_id (also with --period).
 */
#ifndef TDO_MAP_PUBLISHER_H
#define TDO_MAP_PUBLISHER_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo/types.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** Channels and identity of a map publisher. */
struct MapPublisherConfig {
  std::string map_channel = kChannelMap;                /**< maps out */
  std::string map_update_channel = kChannelMapUpdate;   /**< updates out */
  std::string map_request_channel = kChannelMapRequest; /**< requests for a whole map in */
  int32_t vehicle_id = -1; /**< vehicle the map is for (-1 = every vehicle) */
};

class MapPublisher {
 public:
  /** @param map the map to publish (its map_id is the first id; later ids count up from it) */
  MapPublisher(Bus* bus, MapPublisherConfig cfg, tdo::map_t map);
  MapPublisher(const MapPublisher&) = delete;
  MapPublisher& operator=(const MapPublisher&) = delete;

  /** @brief Subscribe to the map requests. */
  bool start(std::string* error);

  /** @brief Publish the current map (utime now); after updates under a new map_id. */
  bool publish_map();

  /** @brief Publish an update adding `boxes` (next seq of the current map) and keep them. */
  bool publish_boxes(const std::vector<tdo_box>& boxes);

  /** Handler of a map_request_t: a whole map under a new map_id (requests for other vehicles and
   *  undecodable ones are counted and left). */
  void on_map_request(const void* data, std::size_t size);

  int64_t map_id() const { return map_.map_id; }
  int64_t seq() const { return seq_; }
  int64_t requests_answered() const { return answered_; }
  int64_t requests_refused() const { return refused_; }
  const tdo::map_t& map() const { return map_; }

 private:
  Bus* bus_;
  MapPublisherConfig cfg_;
  tdo::map_t map_;
  int64_t seq_ = 0; /**< last update seq of the current map_id */
  int64_t answered_ = 0;
  int64_t refused_ = 0;
};

}  // namespace tdo_lcm

#endif  // TDO_MAP_PUBLISHER_H
