// tdo-sim's range sensor (sim_node.h, docs/lcm.md "Sensing"): a seeded share of the map's boxes is
// hidden; after every step the boxes the vehicle sees (tdo_sense_run) are published as one
// map_update_t of the map in use. The published map holds the known boxes only; the collision
// check always uses the whole map file (the true world: every box, tdo_sim_params.boxes).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim_node.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {
bool SimNode::start_sensing(const tdo_io::Map& map, std::string* error) {
  auto fail_with = [&](const std::string& msg) {
    if (error != nullptr) *error = msg;
    return false;
  };
  if (!(cfg_.unknown_fraction >= 0.0 && cfg_.unknown_fraction <= 1.0))
    return fail_with("the unknown fraction must be in [0, 1]");
  if (!(cfg_.sensor_range > 0.0) || !std::isfinite(cfg_.sensor_range))
    return fail_with("the sensor range must be finite and > 0");
  if (!(cfg_.unknown_fraction > 0.0)) return true;
  if (!has_map_ || map.boxes.empty())
    return fail_with("hidden obstacles (--unknown) need a map file with boxes (.tdomap)");
  sensing_ = true;
  map_ = map;
  const std::size_t n = true_boxes_.size();
  known_.assign(n, 1);
  revealed_.assign(n, 0);
  // The seeded choice shared with tdo-sim-run (tdo_sense_hide): the same seed hides the same boxes.
  if (tdo_sense_hide(static_cast<uint32_t>(n), cfg_.unknown_fraction, cfg_.seed, known_.data()) !=
      TDO_OK)
    return fail_with("the unknown fraction must be in [0, 1]");
  std::size_t hide = 0;
  for (uint8_t k : known_) hide += k == 0u;
  counters_.boxes_hidden = static_cast<int64_t>(hide);
  sense(false);  // what the vehicle sees at its start is in the first map
  const Check c = known_map_msg();
  return c.ok() ? true : fail_with(std::string("the known map: ") + reason_str(c.reason));
}

// map_msg_ = the known boxes (and any voxels of the file) under map_id_.
Check SimNode::known_map_msg() {
  tdo_io::Map known = map_;
  known.boxes.clear();
  for (std::size_t k = 0; k < true_boxes_.size(); ++k)
    if (known_[k] != 0) known.boxes.push_back(true_boxes_[k]);
  const Check c = map_msg_from_map(known, cfg_.map_clearance, &map_msg_);
  map_msg_.map_id = map_id_;
  map_msg_.vehicle_id = -1;
  return c;
}

// Reveal what the vehicle sees now; publish it as the next update of the map in use.
void SimNode::sense(bool publish) {
  const tdo_sim_output now = current();
  tdo_sense_input in{};
  in.p = now.state.p;
  in.range = cfg_.sensor_range;
  in.boxes = true_boxes_.data();
  in.n_boxes = static_cast<uint32_t>(true_boxes_.size());
  in.known = known_.data();
  in.revealed = revealed_.data();
  in.max_revealed = static_cast<uint32_t>(revealed_.size());
  tdo_sense_output out{};
  const tdo_status st = tdo_sense_run(&in, &out);
  if (st != TDO_OK) {  // the boxes were checked when the map was loaded: count, keep serving
    ++counters_.reasons[std::string("sense.") + tdo_status_str(st)];
    return;
  }
  if (out.n_revealed == 0) return;
  counters_.boxes_revealed += out.n_revealed;
  if (!publish) return;
  tdo::map_update_t u{};
  u.utime = utime_at(utime0_, now.state.t);
  u.map_id = map_id_;
  u.seq = ++update_seq_;
  u.vehicle_id = -1;
  for (uint32_t k = 0; k < out.n_revealed; ++k) {
    const tdo_box& b = true_boxes_[revealed_[k]];
    u.boxes.push_back({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z});
  }
  u.n_boxes = static_cast<int32_t>(u.boxes.size());
  bus_->publish(cfg_.map_update_channel, u);
  ++counters_.updates_published;
}

// A program's map is stale: a request naming the map in use gets the known map under a new
// map_id (its updates start again at seq 1); one naming an older map gets the current map again.
void SimNode::on_map_request(const void* data, std::size_t size) {
  tdo::map_request_t r{};
  const Check c = decode(data, size, &r);
  if (!c.ok()) {
    refuse("map_request", c);
    return;
  }
  if (r.map_id == map_id_) {
    ++map_id_;
    update_seq_ = 0;
    if (!known_map_msg().ok()) return;
  }
  publish_map();
}

}  // namespace tdo_lcm
