// libFuzzer target of the LCM decoders and adapters, through tdo-planner's node and the vehicle
// adapters. Byte 0 picks the message type, the rest are the message bytes:
//   0 map_t -> PlannerNode::on_map (wire check, decode, OcTree check and rasterising, map checks,
//     grid), then a fixed valid request on whatever map the node holds;
//   1 plan_request_t -> PlannerNode::on_request on a fixed valid map (planned when it is valid);
//   2 trajectory_t -> samples_from_msg; 3 vehicle_state_t -> vehicle_state_from_msg;
//   4 setpoint_t -> setpoint_from_msg; 5 obstacles_t -> movers_from_msg;
//   6 feasibility_t, 7 status_t -> decode + check_counts.
// Every input starts from the same state (the fixed map is loaded first), so a finding reproduces
// alone. The node must survive anything: no crash, no hang, no sanitizer report.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "planner_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace {

template <class Msg>
std::vector<uint8_t> bytes_of(const Msg& m) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

struct Fixture {
  tdo_lcm::Bus bus{"memq://"};
  std::unique_ptr<tdo_lcm::PlannerNode> node;
  std::vector<uint8_t> map_bytes;
  std::vector<uint8_t> request_bytes;

  Fixture() {
    tdo_lcm::PlannerConfig cfg;
    cfg.max_nx = 16;
    cfg.max_ny = 16;
    cfg.max_nz = 8;
    cfg.max_nodes = 20000;
    cfg.max_boxes = 16;
    cfg.heartbeat_period_s = 0.0;
    node = std::make_unique<tdo_lcm::PlannerNode>(&bus, cfg);
    std::string error;
    if (!node->start(&error)) __builtin_trap();
    const tdo_grid_desc d{16, 16, 8, 0.5, {0.0, 0.0, 0.0}};
    const std::vector<tdo_box> boxes = {tdo_box{{3.5, 0.0, 0.0}, {4.5, 5.0, 4.0}}};
    tdo::map_t m{};
    if (!tdo_lcm::map_from_occupancy(d, {}, boxes, 0.25, &m).ok()) __builtin_trap();
    m.map_id = 1;
    m.vehicle_id = -1;
    map_bytes = bytes_of(m);
    tdo_plan_request r{};
    tdo_plan_params_default(&r.params);
    r.start = tdo_vec3{1.25, 1.25, 1.25};
    r.goal = tdo_vec3{6.75, 1.25, 1.25};
    tdo::plan_request_t q{};
    tdo_lcm::plan_request_to_msg(r, -1.0, &q);
    q.request_id = 1;
    q.vehicle_id = 0;
    q.map_id = -1;
    request_bytes = bytes_of(q);
  }
};

template <class Msg>
bool decoded(const uint8_t* data, std::size_t size, Msg* m) {
  return tdo_lcm::decode(data, size, m).ok();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Fixture fx;
  if (size < 1 || size > (1u << 20)) return 0;
  const uint8_t kind = data[0] % 8;
  const uint8_t* body = data + 1;
  const std::size_t n = size - 1;
  fx.node->on_map(fx.map_bytes.data(), fx.map_bytes.size());
  if (kind == 0) {
    fx.node->on_map(body, n);
    fx.node->on_request(fx.request_bytes.data(), fx.request_bytes.size());
  } else if (kind == 1) {
    fx.node->on_request(body, n);
  } else if (kind == 2) {
    tdo::trajectory_t m{};
    std::vector<tdo_sample> samples;
    if (decoded(body, n, &m)) (void)tdo_lcm::samples_from_msg(m, &samples);
  } else if (kind == 3) {
    tdo::vehicle_state_t m{};
    tdo_vehicle_state s{};
    if (decoded(body, n, &m)) (void)tdo_lcm::vehicle_state_from_msg(m, 0, m.utime, &s);
  } else if (kind == 4) {
    tdo::setpoint_t m{};
    tdo_setpoint s{};
    if (decoded(body, n, &m)) (void)tdo_lcm::setpoint_from_msg(m, 0, m.utime, &s);
  } else if (kind == 5) {
    tdo::obstacles_t m{};
    std::vector<tdo_mover> movers;
    if (decoded(body, n, &m)) (void)tdo_lcm::movers_from_msg(m, 0, 64, &movers);
  } else if (kind == 6) {
    tdo::feasibility_t m{};
    if (decoded(body, n, &m)) (void)tdo_lcm::check_counts(m);
  } else {
    tdo::status_t m{};
    if (decoded(body, n, &m)) (void)tdo_lcm::check_counts(m);
  }
  return 0;
}
