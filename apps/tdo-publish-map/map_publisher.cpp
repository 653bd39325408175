// tdo-publish-map's node (map_publisher.h).
#include "map_publisher.h"

#include <utility>

#include "tdo_lcm/node_status.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {

MapPublisher::MapPublisher(Bus* bus, MapPublisherConfig cfg, tdo::map_t map)
    : bus_(bus), cfg_(std::move(cfg)), map_(std::move(map)) {
  map_.vehicle_id = cfg_.vehicle_id;
}

bool MapPublisher::start(std::string* error) {
  if (bus_ == nullptr || !bus_->good()) {
    if (error != nullptr) *error = "LCM is not initialised";
    return false;
  }
  const bool ok = bus_->subscribe(
      cfg_.map_request_channel,
      [this](const void* d, std::size_t n, const std::string&) { on_map_request(d, n); });
  if (!ok && error != nullptr) *error = "cannot subscribe to " + cfg_.map_request_channel;
  return ok;
}

bool MapPublisher::publish_map() {
  // A whole map holds every update of its id sent before it; once updates went out it is a new
  // map (a new id, updates from seq 1), so no receiver mistakes it for the map without them.
  if (seq_ > 0) {
    ++map_.map_id;
    seq_ = 0;
  }
  map_.utime = wall_utime();
  return bus_->publish(cfg_.map_channel, map_);
}

bool MapPublisher::publish_boxes(const std::vector<tdo_box>& boxes) {
  tdo::map_update_t u{};
  u.utime = wall_utime();
  u.map_id = map_.map_id;
  u.seq = seq_ + 1;
  u.vehicle_id = cfg_.vehicle_id;
  for (const tdo_box& b : boxes)
    u.boxes.push_back({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z});
  u.n_boxes = static_cast<int32_t>(u.boxes.size());
  if (!bus_->publish(cfg_.map_update_channel, u)) return false;
  seq_ = u.seq;
  for (const auto& b : u.boxes) map_.boxes.push_back(b);  // the whole map includes it from now
  map_.n_boxes = static_cast<int32_t>(map_.boxes.size());
  return true;
}

void MapPublisher::on_map_request(const void* data, std::size_t size) {
  tdo::map_request_t r{};
  const Check c = decode(data, size, &r);
  if (!c.ok() || (cfg_.vehicle_id != -1 && r.vehicle_id != cfg_.vehicle_id)) {
    ++refused_;
    return;
  }
  // Always answered: the requester may have missed a whole map sent meanwhile. Without updates
  // since, the same id goes out again (a receiver reloads the same map).
  if (publish_map()) ++answered_;
}

}  // namespace tdo_lcm
