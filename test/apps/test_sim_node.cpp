// tdo-sim's node in-process over memq:// (no network): Map6 published with its movers, one step
// per setpoint in lock-step (checked against the motion rule of sim.h), timed steps and braking,
// seeded determinism, collision counting, and bad setpoints counted while the next one is served.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "node_test_util.h"
#include "sim_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/grid_host.h"
#include "tdo_lcm/wire.h"

namespace {

using tdo_test::bytes_of;
using tdo_test::collect;
using tdo_test::heartbeat_reason;

constexpr int32_t kVehicle = 1;
constexpr int64_t kT0 = 1767225600000000;  // us, 2026-01-01
const std::string kMap6 = std::string(TDO_MAPS_DIR) + "/map6.tdomap";

/** The `mover` lines of a .tdomap file, read here independently of mapio. */
struct FileMover {
  int id;
  double p[3], v[3], r;
};
std::vector<FileMover> movers_in(const std::string& path) {
  std::vector<FileMover> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string kw;
    ss >> kw;
    if (kw != "mover") continue;
    FileMover m{};
    ss >> m.id >> m.p[0] >> m.p[1] >> m.p[2] >> m.v[0] >> m.v[1] >> m.v[2] >> m.r;
    out.push_back(m);
  }
  return out;
}

tdo::setpoint_t setpoint(int64_t seq, double ax, double ay, double az) {
  tdo::setpoint_t m{};
  m.utime = kT0 + seq * 20000;
  m.seq = seq;
  m.vehicle_id = kVehicle;
  m.request_id = 5;
  m.acceleration[0] = ax;
  m.acceleration[1] = ay;
  m.acceleration[2] = az;
  m.yaw = 0.5;
  m.status = "ok";
  return m;
}

class SimNodeTest : public tdo_test::NodeTest<tdo_lcm::SimNode, tdo_lcm::SimConfig, 10000> {
 protected:
  virtual bool lockstep() const { return true; }
  void SetUp() override {
    ASSERT_TRUE(bus_.good());
    ASSERT_TRUE(bus_.subscribe(cfg_.state_channel, collect(&states_)));
    ASSERT_TRUE(bus_.subscribe(cfg_.obstacles_channel, collect(&obstacles_)));
    ASSERT_TRUE(bus_.subscribe(cfg_.map_channel, collect(&maps_)));
    ASSERT_TRUE(bus_.subscribe(cfg_.status_channel, collect(&status_)));
    cfg_.vehicle_id = kVehicle;
    cfg_.lockstep = lockstep();
    cfg_.map_file = kMap6;
    cfg_.start_utime = kT0;
    node_ = std::make_unique<tdo_lcm::SimNode>(&bus_, cfg_);
    std::string error;
    ASSERT_TRUE(node_->start(&error)) << error;
    pump();
  }

  std::vector<tdo::vehicle_state_t> states_;
  std::vector<tdo::obstacles_t> obstacles_;
  std::vector<tdo::map_t> maps_;
  std::vector<tdo::status_t> status_;
};

TEST_F(SimNodeTest, StartPublishesTheMapTheStateAndTheMovers) {
  ASSERT_EQ(maps_.size(), 1u);
  const tdo::map_t& m = maps_[0];
  EXPECT_EQ(m.map_id, 1);
  EXPECT_EQ(m.vehicle_id, -1);
  EXPECT_EQ(m.size[0], 50);
  EXPECT_EQ(m.size[1], 50);
  EXPECT_EQ(m.size[2], 20);
  EXPECT_EQ(m.resolution, 1.0);
  EXPECT_EQ(m.clearance, 0.5);
  EXPECT_EQ(m.n_boxes, 500);  // Map6's columns, as boxes
  EXPECT_EQ(m.boxes[0], (std::vector<double>{21, 5, 0, 22, 6, 5.4}));
  ASSERT_EQ(states_.size(), 1u);
  EXPECT_EQ(states_[0].utime, kT0);
  EXPECT_EQ(states_[0].vehicle_id, kVehicle);
  EXPECT_EQ(states_[0].position[0], 2.0);  // the map's start
  EXPECT_EQ(states_[0].position[1], 2.0);
  EXPECT_EQ(states_[0].position[2], 3.0);
  ASSERT_EQ(obstacles_.size(), 1u);
  const std::vector<FileMover> file = movers_in(kMap6);
  ASSERT_EQ(file.size(), 12u);
  const tdo::obstacles_t& o = obstacles_[0];
  EXPECT_EQ(o.utime, kT0);
  ASSERT_EQ(o.n, 12);
  for (std::size_t i = 0; i < file.size(); ++i) {
    EXPECT_EQ(o.id[i], file[i].id);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(o.position[i][a], file[i].p[a]);
      EXPECT_EQ(o.velocity[i][a], file[i].v[a]);
    }
    EXPECT_EQ(o.radius[i], file[i].r);
  }
}

TEST_F(SimNodeTest, LockStepOneStepPerSetpointFollowingTheMotionRule) {
  send(cfg_.setpoint_channel, setpoint(0, 3.0, 0.0, -1.0));
  ASSERT_EQ(states_.size(), 2u);
  ASSERT_EQ(obstacles_.size(), 2u);
  const tdo::vehicle_state_t& s = states_[1];
  const double dt = 0.02;
  EXPECT_EQ(s.utime, kT0 + 20000);
  EXPECT_EQ(s.seq, 1);
  // Jerk limit from rest: |a' - 0| <= j_max dt = 0.2 m/s^2, along the command (3, 0, -1).
  const double n = std::sqrt(10.0);
  const double ax = 0.2 * 3.0 / n, az = -0.2 / n;
  EXPECT_NEAR(s.acceleration[0], ax, 1e-12);
  EXPECT_NEAR(s.acceleration[2], az, 1e-12);
  EXPECT_NEAR(s.velocity[0], ax * dt, 1e-12);
  EXPECT_NEAR(s.position[0], 2.0 + 0.5 * ax * dt * dt, 1e-12);
  EXPECT_NEAR(s.position[2], 3.0 + 0.5 * az * dt * dt, 1e-12);
  EXPECT_EQ(s.yaw, 0.5);  // the commanded heading
  // Movers: q' = q + u dt (none is at a bound in the first step).
  const std::vector<FileMover> file = movers_in(kMap6);
  for (std::size_t i = 0; i < file.size(); ++i)
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(obstacles_[1].position[i][a], file[i].p[a] + file[i].v[a] * dt, 1e-12);
  EXPECT_EQ(obstacles_[1].utime, s.utime);
  EXPECT_EQ(node_->counters().steps, 1);
  EXPECT_EQ(node_->counters().brakes, 0);
}

TEST_F(SimNodeTest, BadSetpointsAreCountedAndDoNotStep) {
  tdo::vehicle_state_t wrong{};  // wrong fingerprint
  send_raw(cfg_.setpoint_channel, bytes_of(wrong));
  std::vector<uint8_t> b = bytes_of(setpoint(0, 1, 0, 0));
  send_raw(cfg_.setpoint_channel, std::vector<uint8_t>(b.begin(), b.end() - 1));
  b.push_back(7);
  send_raw(cfg_.setpoint_channel, b);
  // The status string's length on the wire claims more bytes than there are.
  b = bytes_of(setpoint(0, 1, 0, 0));
  b[b.size() - 4 - 3] = 0x7F;
  send_raw(cfg_.setpoint_channel, b);
  tdo::setpoint_t sp = setpoint(0, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  send(cfg_.setpoint_channel, sp);
  sp = setpoint(0, 1, 0, 0);
  sp.position[1] = std::numeric_limits<double>::infinity();
  send(cfg_.setpoint_channel, sp);
  sp = setpoint(0, 1, 0, 0);
  sp.vehicle_id = kVehicle + 1;
  send(cfg_.setpoint_channel, sp);
  EXPECT_EQ(reason("setpoint.bad_fingerprint"), 1);
  EXPECT_EQ(reason("setpoint.truncated"), 2);
  EXPECT_EQ(reason("setpoint.trailing_bytes"), 1);
  EXPECT_EQ(reason("setpoint.non_finite"), 2);
  EXPECT_EQ(reason("setpoint.other_vehicle"), 1);
  EXPECT_EQ(node_->counters().rejected, 6);
  EXPECT_EQ(node_->counters().ignored, 1);
  EXPECT_EQ(node_->counters().steps, 0);
  EXPECT_EQ(states_.size(), 1u);
  send(cfg_.setpoint_channel, setpoint(1, 1, 0, 0));
  EXPECT_EQ(node_->counters().steps, 1);
  EXPECT_EQ(states_.size(), 2u);
}

TEST_F(SimNodeTest, SameSeedSameRunDifferentSeedDifferentRun) {
  // Two more simulators with disturbance on their own buses: same seed -> identical states.
  auto run = [](uint64_t seed) {
    tdo_lcm::Bus bus("memq://");
    std::vector<tdo::vehicle_state_t> out;
    tdo_lcm::SimConfig cfg;
    cfg.vehicle_id = kVehicle;
    cfg.lockstep = true;
    cfg.map_file = kMap6;
    cfg.start_utime = kT0;
    cfg.accel_noise = 0.5;
    cfg.seed = seed;
    EXPECT_TRUE(bus.subscribe(cfg.state_channel, collect(&out)));
    tdo_lcm::SimNode node(&bus, cfg);
    std::string error;
    EXPECT_TRUE(node.start(&error)) << error;
    for (int k = 0; k < 50; ++k) {
      EXPECT_TRUE(bus.publish(cfg.setpoint_channel, setpoint(k, 1.0, 0.5, 0.0)));
      while (bus.handle_timeout(0) > 0) {
      }
    }
    return out;
  };
  const auto a = run(7), b = run(7), c = run(8);
  ASSERT_EQ(a.size(), 51u);
  ASSERT_EQ(b.size(), 51u);
  ASSERT_EQ(c.size(), 51u);
  bool differ = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(a[k].position[i], b[k].position[i]);
      EXPECT_EQ(a[k].velocity[i], b[k].velocity[i]);
      differ = differ || std::fabs(a[k].position[i] - c[k].position[i]) > 0.0;
    }
  }
  EXPECT_TRUE(differ);
}

TEST_F(SimNodeTest, HeartbeatsCarryTheCounters) {
  send(cfg_.setpoint_channel, setpoint(0, 1, 0, 0));
  tdo::setpoint_t sp = setpoint(1, 1, 0, 0);
  sp.yaw = std::numeric_limits<double>::quiet_NaN();
  send(cfg_.setpoint_channel, sp);
  node_->poll(std::chrono::steady_clock::now() + std::chrono::seconds(1));
  pump();
  ASSERT_EQ(status_.size(), 1u);
  const tdo::status_t& h = status_[0];
  EXPECT_EQ(h.program, "tdo-sim");
  EXPECT_EQ(h.vehicle_id, kVehicle);
  EXPECT_EQ(h.map_id, 1);
  EXPECT_EQ(h.maps_loaded, 1);
  EXPECT_EQ(h.received, 2);
  EXPECT_EQ(h.answered, 1);
  EXPECT_EQ(h.succeeded, 1);
  EXPECT_EQ(h.failed, 0);
  EXPECT_EQ(h.rejected, 1);
  ASSERT_EQ(h.n_reasons, 1);
  EXPECT_EQ(h.reason[0], "setpoint.non_finite");
  EXPECT_EQ(h.reason_count[0], 1);
}

class SimNodeTimedTest : public SimNodeTest {
 protected:
  bool lockstep() const override { return false; }
};

TEST_F(SimNodeTimedTest, StepsAtTheRateAndBrakesWithoutSetpoints) {
  EXPECT_EQ(states_.size(), 1u);
  send(cfg_.setpoint_channel, setpoint(0, 1, 0, 0));
  EXPECT_EQ(states_.size(), 1u);  // only the timer steps
  const auto t0 = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  for (int k = 0; k < 5; ++k) node_->poll(t0 + std::chrono::milliseconds(20 * k));
  pump();
  EXPECT_EQ(node_->counters().steps, 5);
  EXPECT_EQ(states_.size(), 6u);
  EXPECT_EQ(states_.back().utime, kT0 + 5 * 20000);
  // The setpoint is older than its timeout (0.5 s) at t0 + 5 s: every step braked, at rest.
  EXPECT_EQ(node_->counters().brakes, 5);
  EXPECT_EQ(states_.back().position[0], 2.0);
  // The map went out again (its period is 1 s).
  EXPECT_EQ(maps_.size(), 2u);
}

// The state a message describes, and one step of the motion rule (sim.h) from it.
tdo_vehicle_state state_of(const tdo::vehicle_state_t& m) {
  tdo_vehicle_state s{};
  s.p = tdo_vec3{m.position[0], m.position[1], m.position[2]};
  s.v = tdo_vec3{m.velocity[0], m.velocity[1], m.velocity[2]};
  s.a = tdo_vec3{m.acceleration[0], m.acceleration[1], m.acceleration[2]};
  return s;
}
void expect_step(const tdo::vehicle_state_t& from, tdo_vec3 a_cmd, const tdo::vehicle_state_t& to) {
  const tdo_vehicle_state s = state_of(from);
  tdo_setpoint next{};
  tdo_motion_limit(&s, a_cmd, 3.0, 3.0, 10.0, 0.02, &next);
  EXPECT_NEAR(to.position[0], next.p.x, 1e-12);
  EXPECT_NEAR(to.position[1], next.p.y, 1e-12);
  EXPECT_NEAR(to.position[2], next.p.z, 1e-12);
  EXPECT_NEAR(to.velocity[0], next.v.x, 1e-12);
  EXPECT_NEAR(to.velocity[1], next.v.y, 1e-12);
  EXPECT_NEAR(to.velocity[2], next.v.z, 1e-12);
}

// GIVEN timed steps and a follower whose answers (setpoint utime = the state it answers) come
// late WHEN a tick is due without the answer to the current state THEN the step waits for it (no
// state goes out), flies it on that state as soon as it comes, never flies an answer to a state
// already passed ("setpoint.late"), and after the wait (0.1 s) brakes as the follower's safety
// roll-out does (apf.h: a_max against v, proportional below a_max^2 / (2 j_max)), named
// "step.setpoint_late" in the heartbeat.
TEST_F(SimNodeTimedTest, LateAnswersAreNeverFlownTheStepWaitsThenBrakesNamedLate) {
  // Within the setpoint timeout (0.5 s) of the wall clock: the follower counts as alive.
  const auto t0 = std::chrono::steady_clock::now() + std::chrono::milliseconds(30);
  const auto ms = [](int n) { return std::chrono::milliseconds(n); };
  send(cfg_.setpoint_channel, setpoint(0, 2, 1, 0));  // answers state 0
  node_->poll(t0);
  pump();
  ASSERT_EQ(states_.size(), 2u);
  expect_step(states_[0], tdo_vec3{2, 1, 0}, states_[1]);
  send(cfg_.setpoint_channel, setpoint(0, -3, 0, 0));  // state 0 again: passed, never flown
  EXPECT_EQ(node_->counters().late_setpoints, 1);
  node_->poll(t0 + ms(20));  // due, no answer to state 1: waits
  node_->poll(t0 + ms(60));
  pump();
  EXPECT_EQ(states_.size(), 2u);
  EXPECT_EQ(node_->counters().waits, 1);
  EXPECT_LE(node_->next_due(), t0 + ms(120));         // no later than the end of the tick's wait
  send(cfg_.setpoint_channel, setpoint(1, 2, 1, 0));  // the answer to state 1
  node_->poll(t0 + ms(61));
  pump();
  ASSERT_EQ(states_.size(), 3u);
  expect_step(states_[1], tdo_vec3{2, 1, 0}, states_[2]);
  node_->poll(t0 + ms(81));  // due; the answer to state 2 never comes
  node_->poll(t0 + ms(180));
  pump();
  EXPECT_EQ(states_.size(), 3u);
  node_->poll(t0 + ms(181));  // the wait is over: a late step, braking
  pump();
  ASSERT_EQ(states_.size(), 4u);
  const tdo_vehicle_state s2 = state_of(states_[2]);
  const double speed = std::sqrt(s2.v.x * s2.v.x + s2.v.y * s2.v.y + s2.v.z * s2.v.z);
  const double k = 3.0 / std::max(speed, 3.0 * 3.0 / (2.0 * 10.0));  // a_max / max(|v|, v_lin)
  expect_step(states_[2], tdo_vec3{-k * s2.v.x, -k * s2.v.y, -k * s2.v.z}, states_[3]);
  const tdo_lcm::SimCounters& c = node_->counters();
  EXPECT_EQ(c.steps, 3);
  EXPECT_EQ(c.late_steps, 1);
  EXPECT_EQ(c.brakes, 1);
  EXPECT_EQ(c.stale_steps, 0);
  node_->publish_status();
  pump();
  ASSERT_FALSE(status_.empty());
  EXPECT_EQ(heartbeat_reason(status_.back(), "step.setpoint_late"), 1);
  EXPECT_EQ(heartbeat_reason(status_.back(), "setpoint.late"), 1);
}

// GIVEN a follower that always answers one state late (within the age bound of 3 steps), asking
// for 2 m/s^2 towards Map1's wall (x = 6 .. 7, ahead of the start (2, 2, 3)) WHEN the simulator
// waits for answers (the default) THEN none is flown: every step is late, braking, the vehicle
// stays at rest with no contact. Flying the latest setpoint instead (setpoint wait 0: the old
// command on a newer state) takes the vehicle into the wall.
struct Lagging {
  tdo_lcm::SimCounters counters;
  double moved = 0.0;
};

// A timed simulator of kVehicle on Map1 from kT0: the map sent once, the follower never timed out.
tdo_lcm::SimConfig timed_map1_config() {
  tdo_lcm::SimConfig cfg;
  cfg.vehicle_id = kVehicle;
  cfg.map_file = std::string(TDO_MAPS_DIR) + "/map1.tdomap";
  cfg.start_utime = kT0;
  cfg.map_period_s = 0.0;
  cfg.setpoint_timeout_s = 1e6;
  return cfg;
}

// Deliver the messages queued on `bus` (at most 10,000).
void drain(tdo_lcm::Bus& bus) {
  for (int i = 0; i < 10000 && bus.handle_timeout(0) > 0; ++i) {
  }
}

Lagging lagging_follower(double wait_s) {
  tdo_lcm::Bus bus("memq://");
  tdo_lcm::SimConfig cfg = timed_map1_config();
  cfg.setpoint_wait_s = wait_s;
  tdo_lcm::SimNode node(&bus, cfg);
  std::string error;
  EXPECT_TRUE(node.start(&error)) << error;
  const tdo_vec3 p0 = node.current().state.p;
  auto pump = [&bus] { drain(bus); };
  pump();
  auto t = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  EXPECT_TRUE(bus.publish(cfg.setpoint_channel, setpoint(0, 2.0, 0.0, 0.0)));
  pump();
  node.poll(t);  // state 0 answered: the first step flies it
  for (int k = 1; k < 200; ++k) {
    EXPECT_TRUE(bus.publish(cfg.setpoint_channel, setpoint(k - 1, 2.0, 0.0, 0.0)));
    pump();
    t += std::chrono::milliseconds(20);
    node.poll(t);
    if (wait_s > 0.0) {
      t += std::chrono::milliseconds(100);
      node.poll(t);  // past the wait
    }
    pump();
  }
  Lagging r;
  r.counters = node.counters();
  const tdo_vec3 p = node.current().state.p;
  r.moved = std::sqrt((p.x - p0.x) * (p.x - p0.x) + (p.y - p0.y) * (p.y - p0.y) +
                      (p.z - p0.z) * (p.z - p0.z));
  EXPECT_EQ(r.counters.steps, 200);
  return r;
}

TEST(SimNodeStandalone, AFollowerOneStateLateIsNeverFlownIntoTheWall) {
  const Lagging r = lagging_follower(0.1);
  EXPECT_EQ(r.counters.late_steps, 199);
  EXPECT_EQ(r.counters.late_setpoints, 199);
  EXPECT_EQ(r.counters.stale_steps, 0);
  EXPECT_EQ(r.counters.collision_steps, 0);
  EXPECT_LT(r.moved, 0.01);  // one step of 2 m/s^2, then braking to rest

  const Lagging old = lagging_follower(0.0);
  EXPECT_EQ(old.counters.late_steps, 0);
  EXPECT_EQ(old.counters.stale_steps, 0);  // one step behind: within the age bound
  EXPECT_GT(old.counters.static_collisions, 0) << "the late commands no longer reach the wall";
}

TEST(SimNodeStandalone, VoxelMapFilesArePublishedRunLengthEncoded) {
  // MovingAI (.3dmap: a header line "voxel 105 132 105", then 512 distinct voxels) and OctoMap
  // (.bt): the occupied voxels go out run-length encoded, and the planner's adapter loads them
  // back into a grid with the same voxels occupied (the planner side of the same message).
  for (const char* file : {"movingai/Simple.3dmap", "octomap/geb079.bt"}) {
    SCOPED_TRACE(file);
    tdo_lcm::Bus bus("memq://");
    std::vector<tdo::map_t> maps;
    tdo_lcm::SimConfig cfg;
    cfg.lockstep = true;
    cfg.map_file = std::string(TDO_MAPS_DIR) + "/" + file;
    cfg.map_clearance = 0.0;
    cfg.map_resolution = 0.4;  // OcTree at 0.4 m instead of its 0.05 m: a small, fast grid
    ASSERT_TRUE(bus.subscribe(cfg.map_channel, collect(&maps)));
    tdo_lcm::SimNode node(&bus, cfg);
    std::string error;
    ASSERT_TRUE(node.start(&error)) << error;
    while (bus.handle_timeout(0) > 0) {
    }
    ASSERT_EQ(maps.size(), 1u);
    const tdo::map_t& m = maps[0];
    EXPECT_EQ(m.encoding, tdo::map_t::ENCODING_RLE);
    EXPECT_EQ(m.n_boxes, 0);
    ASSERT_GT(m.n_runs, 1);
    int64_t occupied = 0, total = 0;
    for (int32_t i = 0; i < m.n_runs; ++i) {
      if (i % 2 == 1) occupied += m.runs[i];
      total += m.runs[i];
    }
    EXPECT_EQ(total, int64_t{m.size[0]} * m.size[1] * m.size[2]);
    if (std::string(file).find("3dmap") != std::string::npos) {
      EXPECT_EQ(m.size[0], 105);
      EXPECT_EQ(m.size[1], 132);
      EXPECT_EQ(m.size[2], 105);
      EXPECT_EQ(occupied, 512);  // one voxel per line after the header
    } else {
      EXPECT_GT(occupied, 1000);
    }
    tdo_lcm::GridHost host;
    ASSERT_TRUE(host.start(m.size[0], m.size[1], m.size[2], 1, 1.0, &error)) << error;
    ASSERT_TRUE(tdo_lcm::map_to_grid(m, host.capacity(), -1.0, host.grid()).ok());
    int64_t in_grid = 0;
    for (int32_t k = 0; k < m.size[2]; ++k)
      for (int32_t j = 0; j < m.size[1]; ++j)
        for (int32_t i = 0; i < m.size[0]; ++i)
          in_grid += tdo_grid_is_occupied(host.grid(), tdo_voxel{i, j, k}) ? 1 : 0;
    EXPECT_EQ(in_grid, occupied);
  }
}

TEST(SimNodeStandalone, DemoRequestFromTheStartToTheMapsGoal) {
  tdo_lcm::Bus bus("memq://");
  std::vector<tdo::plan_request_t> requests;
  tdo_lcm::SimConfig cfg;
  cfg.vehicle_id = kVehicle;
  cfg.lockstep = true;  // lock-step: the request goes out in start()
  cfg.request_goal = true;
  ASSERT_TRUE(bus.subscribe(cfg.request_channel, collect(&requests)));
  {
    tdo_lcm::SimNode node(&bus, cfg);  // no map, no --goal: refused
    std::string error;
    EXPECT_FALSE(node.start(&error));
    EXPECT_NE(error.find("goal"), std::string::npos) << error;
  }
  cfg.map_file = kMap6;
  tdo_lcm::SimNode node(&bus, cfg);
  std::string error;
  ASSERT_TRUE(node.start(&error)) << error;
  while (bus.handle_timeout(0) > 0) {
  }
  ASSERT_EQ(requests.size(), 1u);
  const tdo::plan_request_t& r = requests[0];
  EXPECT_EQ(r.request_id, 1);
  EXPECT_EQ(r.vehicle_id, kVehicle);
  EXPECT_EQ(r.map_id, 1);
  EXPECT_EQ(r.clearance, -1.0);  // the map's hint
  EXPECT_EQ(r.start[0], 2.0);    // Map6's start and goal
  EXPECT_EQ(r.start[2], 3.0);
  EXPECT_EQ(r.goal[0], 49.0);
  EXPECT_EQ(r.goal[1], 49.0);
  EXPECT_EQ(r.goal[2], 15.0);
  EXPECT_EQ(r.depth, tdo::plan_request_t::DEPTH_TRAJECTORY);
}

TEST(SimNodeStandalone, CollisionsAreCountedAndWithoutAMapTheBoundsAreUsed) {
  tdo_lcm::Bus bus("memq://");
  std::vector<tdo::map_t> maps;
  std::vector<tdo::vehicle_state_t> states;
  tdo_lcm::SimConfig cfg;
  cfg.lockstep = true;
  ASSERT_TRUE(bus.subscribe(cfg.map_channel, collect(&maps)));
  ASSERT_TRUE(bus.subscribe(cfg.state_channel, collect(&states)));
  {
    // Map6 with the vehicle started inside its first column (21..22, 5..6, 0..5.4).
    tdo_lcm::SimConfig c = cfg;
    c.map_file = kMap6;
    c.has_start = true;
    c.start = tdo_vec3{21.5, 5.5, 1.0};
    tdo_lcm::SimNode node(&bus, c);
    std::string error;
    ASSERT_TRUE(node.start(&error)) << error;
    node.step();
    node.step();
    EXPECT_EQ(node.counters().static_collisions, 2);
    EXPECT_EQ(node.counters().collision_steps, 2);
    EXPECT_EQ(node.counters().min_static_dist, 0.0);
    EXPECT_EQ(node.status_message().failed, 2);
  }
  while (bus.handle_timeout(0) > 0) {
  }
  maps.clear();
  states.clear();
  {
    tdo_lcm::SimNode node(&bus, cfg);
    std::string error;
    ASSERT_TRUE(node.start(&error)) << error;
    EXPECT_FALSE(node.has_map());
    while (bus.handle_timeout(0) > 0) {
    }
    EXPECT_TRUE(maps.empty());
    ASSERT_EQ(states.size(), 1u);
    EXPECT_EQ(states[0].position[0], 25.0);  // centre of the default 50 x 50 x 20 m bounds
    EXPECT_EQ(states[0].position[2], 10.0);
    EXPECT_EQ(node.status_message().map_id, -1);
  }
  tdo_lcm::SimConfig bad = cfg;
  bad.map_file = std::string(TDO_MAPS_DIR) + "/no_such_map.tdomap";
  tdo_lcm::SimNode node(&bus, bad);
  std::string error;
  EXPECT_FALSE(node.start(&error));
  EXPECT_NE(error.find("no_such_map"), std::string::npos) << error;
}

// A follower starved of CPU (the netns runs under load: 799 setpoints for 1,081 steps) stops
// answering while the simulator's timer keeps stepping. Map1's wall (x = 6 .. 7) lies ahead of
// its start (2, 2, 3); the follower asks for 2 m/s^2 towards it for 1 s, each setpoint stamped
// with the state it answers, then falls silent; the wall-clock timeout is set far out (as when
// late setpoints keep trickling in). Returns the node's counters and last heartbeat.
struct Starved {
  tdo_lcm::SimCounters counters;
  tdo::status_t heartbeat{};
  double final_speed = 0.0;
};

Starved starve(double max_age_steps) {
  tdo_lcm::Bus bus("memq://");
  std::vector<tdo::vehicle_state_t> states;
  std::vector<tdo::status_t> status;
  tdo_lcm::SimConfig cfg = timed_map1_config();
  cfg.setpoint_max_age_steps = max_age_steps;
  cfg.setpoint_wait_s = 0.0;  // the age check of the latest setpoint, not the wait for answers
  EXPECT_TRUE(bus.subscribe(cfg.state_channel, collect(&states)));
  EXPECT_TRUE(bus.subscribe(cfg.status_channel, collect(&status)));
  tdo_lcm::SimNode node(&bus, cfg);
  std::string error;
  EXPECT_TRUE(node.start(&error)) << error;
  auto pump = [&bus] { drain(bus); };
  pump();
  const auto t0 = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  for (int k = 0; k < 300; ++k) {  // 6 s at 50 Hz
    if (k < 50) {
      EXPECT_EQ(states.size(), static_cast<std::size_t>(k + 1));
      EXPECT_TRUE(bus.publish(cfg.setpoint_channel, setpoint(k, 2.0, 0.0, 0.0)));
      pump();
    }
    node.poll(t0 + std::chrono::milliseconds(20 * k));
    pump();
  }
  node.publish_status();
  pump();
  Starved r;
  r.counters = node.counters();
  if (!status.empty()) r.heartbeat = status.back();
  const tdo_vehicle_state s = node.current().state;
  r.final_speed = std::sqrt(s.v.x * s.v.x + s.v.y * s.v.y + s.v.z * s.v.z);
  EXPECT_EQ(r.counters.steps, 300);
  EXPECT_EQ(r.counters.setpoints, 50);
  return r;
}

// GIVEN the starved follower WHEN its last setpoint is more than 3 steps old THEN tdo-sim names
// setpoint_stale in its heartbeat, brakes and hovers short of the wall; with the age check off
// (0 steps) the vehicle flies the old command into the wall.
TEST(SimNodeStandalone, StarvedSetpointStreamIsNamedStaleAndTheVehicleBrakesShortOfTheWall) {
  const Starved r = starve(3.0);
  EXPECT_GT(r.counters.stale_steps, 200);  // the 250 silent steps but the first 3
  EXPECT_EQ(heartbeat_reason(r.heartbeat, "step.setpoint_stale"), r.counters.stale_steps);
  EXPECT_EQ(r.counters.brakes, r.counters.stale_steps);
  EXPECT_EQ(r.counters.collision_steps, 0);
  EXPECT_GE(r.counters.min_static_dist, 0.25);  // the simulator's static clearance
  EXPECT_LT(r.final_speed, 0.01);

  const Starved blind = starve(0.0);
  EXPECT_EQ(blind.counters.stale_steps, 0);
  EXPECT_EQ(heartbeat_reason(blind.heartbeat, "step.setpoint_stale"), 0);
  EXPECT_GT(blind.counters.static_collisions, 0) << "the old command no longer reaches the wall";
}

}  // namespace
