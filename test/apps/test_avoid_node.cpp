// tdo-avoid's node in-process over memq:// (no network): state -> setpoint in lock-step and timed
// mode, a trajectory followed to its end, movers and the static map reaching the follower, and
// every kind of bad input counted in the heartbeat while the next valid state is served.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "avoid_node.h"
#include "node_test_util.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace {

using tdo_test::bytes_of;
using tdo_test::collect;
using tdo_test::heartbeat_reason;

constexpr int32_t kVehicle = 2;
constexpr int64_t kT0 = 1767225600000000;  // us, 2026-01-01
constexpr int64_t kStepUs = 20000;         // 50 Hz
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

tdo::vehicle_state_t state_at(int64_t utime, tdo_vec3 p, tdo_vec3 v = {0, 0, 0},
                              tdo_vec3 a = {0, 0, 0}) {
  tdo::vehicle_state_t m{};
  m.utime = utime;
  m.vehicle_id = kVehicle;
  const double pp[3] = {p.x, p.y, p.z}, vv[3] = {v.x, v.y, v.z}, aa[3] = {a.x, a.y, a.z};
  for (int i = 0; i < 3; ++i) {
    m.position[i] = pp[i];
    m.velocity[i] = vv[i];
    m.acceleration[i] = aa[i];
  }
  return m;
}

/** A rest-to-rest straight flight along x (quintic, minimum jerk), samples every 0.01 s. */
tdo::trajectory_t straight(int64_t request_id, tdo_vec3 from, double length, double duration) {
  tdo::trajectory_t m{};
  m.request_id = request_id;
  m.vehicle_id = kVehicle;
  m.map_id = -1;
  m.status_code = 0;
  m.status = "ok";
  m.reached = tdo::plan_request_t::DEPTH_TRAJECTORY;
  m.dt = 0.01;
  const int n = static_cast<int>(std::lround(duration / m.dt)) + 1;
  for (int i = 0; i < n; ++i) {
    const double t = i * m.dt, u = t / duration;
    const double s = length * (10 * std::pow(u, 3) - 15 * std::pow(u, 4) + 6 * std::pow(u, 5));
    const double v = length / duration * (30 * u * u - 60 * std::pow(u, 3) + 30 * std::pow(u, 4));
    const double a = length / (duration * duration) * (60 * u - 180 * u * u + 120 * std::pow(u, 3));
    m.samples.push_back({t, from.x + s, from.y, from.z, v, 0, 0, a, 0, 0});
  }
  m.n_samples = n;
  m.n_waypoints = 2;
  m.waypoints = {{from.x, from.y, from.z}, {from.x + length, from.y, from.z}};
  return m;
}

tdo::obstacles_t one_mover(int64_t utime, tdo_vec3 p, tdo_vec3 v, double r) {
  tdo::obstacles_t m{};
  m.utime = utime;
  m.vehicle_id = -1;
  m.n = 1;
  m.id = {7};
  m.position = {{p.x, p.y, p.z}};
  m.velocity = {{v.x, v.y, v.z}};
  m.radius = {r};
  return m;
}

/** 20 x 10 x 5 m at 0.5 m with a wall x = 6..7 m, y = 0..10, z = 0..5 (in boxes only). */
tdo::map_t wall_map(int64_t map_id) {
  tdo::map_t m{};
  EXPECT_TRUE(tdo_lcm::map_from_occupancy(tdo_grid_desc{40, 20, 10, 0.5, {0, 0, 0}}, {},
                                          {tdo_box{{6.0, 0.0, 0.0}, {7.0, 10.0, 5.0}}}, 0.25, &m)
                  .ok());
  m.map_id = map_id;
  return m;
}

double norm(tdo_vec3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }

class AvoidNodeTest : public tdo_test::NodeTest<tdo_lcm::AvoidNode, tdo_lcm::AvoidConfig, 10000> {
 protected:
  virtual bool lockstep() const { return true; }
  void SetUp() override { make(lockstep()); }

  void make(bool lockstep) {
    ASSERT_TRUE(bus_.good());
    cfg_.vehicle_id = kVehicle;
    cfg_.lockstep = lockstep;
    cfg_.max_nx = 48;
    cfg_.max_ny = 24;
    cfg_.max_nz = 12;
    cfg_.max_boxes = 8;
    cfg_.max_samples = 2000;
    cfg_.max_movers = 4;
    node_ = std::make_unique<tdo_lcm::AvoidNode>(&bus_, cfg_);
    std::string error;
    ASSERT_TRUE(node_->start(&error)) << error;
    ASSERT_TRUE(bus_.subscribe(cfg_.setpoint_channel, collect(&setpoints_)));
    ASSERT_TRUE(bus_.subscribe(cfg_.status_channel, collect(&status_)));
  }

  /** A valid state must still give one setpoint for it. */
  void expect_served(int64_t utime) {
    const std::size_t before = setpoints_.size();
    send(cfg_.state_channel, state_at(utime, tdo_vec3{2, 5, 2}));
    ASSERT_EQ(setpoints_.size(), before + 1);
    EXPECT_EQ(setpoints_.back().utime, utime);
  }

  std::vector<tdo::setpoint_t> setpoints_;
  std::vector<tdo::status_t> status_;
};

TEST_F(AvoidNodeTest, WithoutATrajectoryItBrakesToAHover) {
  send(cfg_.state_channel, state_at(kT0, tdo_vec3{2, 5, 2}, tdo_vec3{1, 0, 0}));
  ASSERT_EQ(setpoints_.size(), 1u);
  const tdo::setpoint_t& s = setpoints_[0];
  EXPECT_EQ(s.vehicle_id, kVehicle);
  EXPECT_EQ(s.request_id, -1);
  EXPECT_EQ(s.status, "ok");
  EXPECT_EQ(s.utime, kT0);
  // Braking: the acceleration opposes the velocity, within the jerk limit of one step.
  EXPECT_LT(s.acceleration[0], 0.0);
  EXPECT_GE(s.acceleration[0], -10.0 * 0.02 - 1e-12);
  EXPECT_LT(s.velocity[0], 1.0);
  EXPECT_NEAR(s.position[0], 2.0 + 0.02, 1e-3);
  EXPECT_EQ(node_->counters().holds, 1);
  EXPECT_EQ(node_->following(), -1);
}

TEST_F(AvoidNodeTest, FollowsATrajectoryToItsEnd) {
  const tdo_vec3 start{2, 5, 2};
  send(cfg_.trajectory_channel, straight(41, start, 6.0, 5.0));
  EXPECT_EQ(node_->counters().trajectories, 1);
  // Closed loop: the vehicle does exactly what the setpoint says, one step later.
  tdo::vehicle_state_t st = state_at(kT0, start);
  const int max_steps = 2000;  // 40 s for a 5 s flight
  int k = 0;
  for (; k < max_steps; ++k) {
    const std::size_t before = setpoints_.size();
    send(cfg_.state_channel, st);
    ASSERT_EQ(setpoints_.size(), before + 1);
    const tdo::setpoint_t& sp = setpoints_.back();
    ASSERT_EQ(sp.request_id, 41);
    ASSERT_EQ(sp.status, "ok");
    // Within the vehicle's limits.
    const tdo_vec3 v{sp.velocity[0], sp.velocity[1], sp.velocity[2]};
    const tdo_vec3 a{sp.acceleration[0], sp.acceleration[1], sp.acceleration[2]};
    ASSERT_LE(norm(v), cfg_.v_max + 1e-9);
    ASSERT_LE(norm(a), cfg_.a_max + 1e-9);
    st = state_at(st.utime + kStepUs, tdo_vec3{sp.position[0], sp.position[1], sp.position[2]}, v,
                  a);
    if (node_->last_output().mode == TDO_APF_MODE_ARRIVED) break;
  }
  ASSERT_LT(k, max_steps) << "did not arrive";
  EXPECT_EQ(node_->counters().goal_reached, 1);
  EXPECT_NEAR(st.position[0], 8.0, 0.2);
  EXPECT_NEAR(st.position[1], 5.0, 0.05);
  EXPECT_NEAR(st.position[2], 2.0, 0.05);
  // About on time: the reference is a 5 s flight.
  EXPECT_GT(k * 0.02, 4.0);
  EXPECT_LT(k * 0.02, 9.0);
  EXPECT_EQ(node_->counters().rejected, 0);
}

/** The compact form only (no samples): one line from `from` along x, 3 m in 5 s, rest to rest. */
tdo::trajectory_t compact_line(int64_t request_id, tdo_vec3 from) {
  tdo::trajectory_t m{};
  m.request_id = request_id;
  m.vehicle_id = kVehicle;
  m.map_id = -1;
  m.status = "ok";
  m.reached = tdo::plan_request_t::DEPTH_TRAJECTORY;
  m.dt = 0.01;
  m.n_segments = 1;
  m.segment_kind = {tdo::trajectory_t::SEGMENT_LINE};
  m.segment_s0 = {0.0};
  m.segment_length = {3.0};
  m.n_segment_points = 12;
  m.segment_points = {from.x, from.y, from.z, from.x + 3.0, from.y, from.z, 0, 0, 0, 0, 0, 0};
  // Jerk +1, -1, 0, -1, +1 for 1 s each: 0 -> 1 m/s -> 0 over exactly 3 m.
  m.n_pieces = 5;
  m.piece_t0 = {0.0, 1.0, 2.0, 3.0, 4.0};
  m.piece_dur = {1.0, 1.0, 1.0, 1.0, 1.0};
  m.piece_s0 = {0.0, 1.0 / 6.0, 1.0, 2.0, 2.0 + 5.0 / 6.0};
  m.piece_v0 = {0.0, 0.5, 1.0, 1.0, 0.5};
  m.piece_a0 = {0.0, 1.0, 0.0, 0.0, -1.0};
  m.piece_j = {1.0, -1.0, 0.0, -1.0, 1.0};
  m.duration_s = 5.0;
  m.path_length_m = 3.0;
  m.sample_count = 501;
  return m;
}

TEST_F(AvoidNodeTest, GivenACompactOnlyTrajectoryThenItIsSampledAndFollowed) {
  const tdo_vec3 start{1, 5, 2};
  send(cfg_.trajectory_channel, compact_line(43, start));
  EXPECT_EQ(node_->counters().trajectories, 1);
  EXPECT_EQ(node_->counters().rejected, 0);
  tdo::vehicle_state_t st = state_at(kT0, start);
  int k = 0;
  for (; k < 1000; ++k) {
    send(cfg_.state_channel, st);
    ASSERT_FALSE(setpoints_.empty());
    const tdo::setpoint_t& sp = setpoints_.back();
    ASSERT_EQ(sp.request_id, 43);
    st = state_at(st.utime + kStepUs, tdo_vec3{sp.position[0], sp.position[1], sp.position[2]},
                  tdo_vec3{sp.velocity[0], sp.velocity[1], sp.velocity[2]},
                  tdo_vec3{sp.acceleration[0], sp.acceleration[1], sp.acceleration[2]});
    if (node_->last_output().mode == TDO_APF_MODE_ARRIVED) break;
  }
  ASSERT_LT(k, 1000) << "did not arrive";
  EXPECT_NEAR(st.position[0], 4.0, 0.2);
  // A compact form that does not check out is refused by name.
  tdo::trajectory_t bad = compact_line(44, start);
  bad.piece_dur[2] = -1.0;
  send(cfg_.trajectory_channel, bad);
  EXPECT_EQ(node_->counters().reasons.at("trajectory.out_of_range"), 1);
  bad = compact_line(45, start);
  bad.sample_count = 5000;  // over the capacity of 2000 samples
  send(cfg_.trajectory_channel, bad);
  EXPECT_EQ(node_->counters().reasons.at("trajectory.over_capacity"), 1);
}

TEST_F(AvoidNodeTest, GivenAPromisedTrajectoryThatNeverArrivesThenTrajectoryMissingIsReported) {
  const auto now = std::chrono::steady_clock::now();
  tdo::feasibility_t report{};  // the planner answered request 7 ...
  report.request_id = 7;
  report.vehicle_id = kVehicle;
  report.status = "ok";
  send(cfg_.feasibility_channel, report);  // ... but its trajectory was lost
  tdo::feasibility_t other = report;       // another vehicle's answer promises nothing here
  other.request_id = 8;
  other.vehicle_id = kVehicle + 1;
  send(cfg_.feasibility_channel, other);
  tdo::plan_request_t req{};  // request 9 is seen, and its trajectory arrives in time
  req.request_id = 9;
  req.vehicle_id = kVehicle;
  send(cfg_.request_channel, req);
  send(cfg_.trajectory_channel, straight(9, tdo_vec3{2, 5, 2}, 1.0, 2.0));
  send(cfg_.feasibility_channel, [] {
    tdo::feasibility_t f{};
    f.request_id = 9;
    f.vehicle_id = kVehicle;
    return f;
  }());  // its report after the trajectory: nothing pending
  EXPECT_LE(node_->next_due(), now + std::chrono::milliseconds(2100));  // woken for the deadline
  node_->poll(now + std::chrono::milliseconds(1500));
  EXPECT_EQ(node_->counters().missing, 0);
  node_->poll(now + std::chrono::milliseconds(2500));
  EXPECT_EQ(node_->counters().missing, 1);
  node_->poll(now + std::chrono::milliseconds(5000));  // reported once
  EXPECT_EQ(node_->counters().missing, 1);
  const tdo::status_t h = node_->status_message();
  bool named = false;
  for (int32_t i = 0; i < h.n_reasons; ++i)
    named |= h.reason[static_cast<std::size_t>(i)] == "trajectory.missing" &&
             h.reason_count[static_cast<std::size_t>(i)] == 1;
  EXPECT_TRUE(named);
  EXPECT_EQ(h.rejected, 1);
}

TEST_F(AvoidNodeTest, MoversAreMovedOnToTheStateTimeAndRepel) {
  const tdo_vec3 p{2, 5, 2};
  send(cfg_.trajectory_channel, straight(42, p, 6.0, 5.0));
  // A sphere seen 0.5 s before the state, 1 m/s towards -x: then at x = 4.5, now at x = 4.0.
  send(cfg_.obstacles_channel,
       one_mover(kT0 - 500000, tdo_vec3{4.5, 5, 2}, tdo_vec3{-1, 0, 0}, 0.5));
  send(cfg_.state_channel, state_at(kT0, p));
  ASSERT_EQ(setpoints_.size(), 1u);
  const tdo_apf_terms& t = node_->last_output().terms;
  // |p - q| - R - vehicle radius, with q = (4, 5, 2).
  EXPECT_NEAR(t.mover_gap, 2.0 - 0.5 - cfg_.vehicle_radius, 1e-9);
  EXPECT_LT(t.f_rep_movers.x, 0.0);  // pushed away from it, along -x
  EXPECT_NE(node_->last_output().events & TDO_APF_EVENT_REPULSED, 0u);
  // No obstacles any more: an empty message clears them.
  tdo::obstacles_t none{};
  none.utime = kT0;
  none.vehicle_id = kVehicle;
  send(cfg_.obstacles_channel, none);
  send(cfg_.state_channel, state_at(kT0 + kStepUs, p));
  EXPECT_EQ(node_->last_output().terms.mover_gap, HUGE_VAL);
}

TEST_F(AvoidNodeTest, TheMapGivesStaticRepulsion) {
  const tdo_vec3 p{5.6, 5, 2};  // 0.4 m from the wall at x = 6
  send(cfg_.trajectory_channel, straight(43, tdo_vec3{5.6, 5, 2}, -3.0, 3.0));
  send(cfg_.state_channel, state_at(kT0, p));
  EXPECT_EQ(node_->last_output().terms.static_dist, HUGE_VAL);  // no map yet
  send(cfg_.map_channel, wall_map(3));
  EXPECT_EQ(node_->map_id(), 3);
  EXPECT_EQ(node_->counters().maps_loaded, 1);
  EXPECT_EQ(node_->following(), 43);  // the task was restarted on the new grid
  send(cfg_.state_channel, state_at(kT0 + kStepUs, p));
  const tdo_apf_terms& t = node_->last_output().terms;
  EXPECT_NEAR(t.static_dist, 0.4, 1e-9);
  EXPECT_LT(t.f_rep_static.x, 0.0);  // away from the wall
  // The same map again is not reloaded.
  send(cfg_.map_channel, wall_map(3));
  EXPECT_EQ(node_->counters().maps_loaded, 1);
}

class AvoidNodeTimedTest : public AvoidNodeTest {
 protected:
  bool lockstep() const override { return false; }
};

TEST_F(AvoidNodeTimedTest, StepsAtTheRate) {
  send(cfg_.state_channel, state_at(kT0, tdo_vec3{2, 5, 2}));
  EXPECT_TRUE(setpoints_.empty());  // only the timer steps
  const auto t0 = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  node_->poll(t0);
  pump();
  EXPECT_EQ(setpoints_.size(), 1u);
  node_->poll(t0 + std::chrono::milliseconds(10));
  pump();
  EXPECT_EQ(setpoints_.size(), 1u);
  node_->poll(t0 + std::chrono::milliseconds(20));
  pump();
  EXPECT_EQ(setpoints_.size(), 2u);
}

TEST_F(AvoidNodeTest, MalformedBytesAreCountedAndServingGoesOn) {
  expect_served(kT0);
  // Wrong fingerprint on every channel: a setpoint where something else is expected.
  tdo::setpoint_t sp{};
  sp.status = "x";
  for (const std::string& ch :
       {cfg_.state_channel, cfg_.trajectory_channel, cfg_.obstacles_channel, cfg_.map_channel})
    send_raw(ch, bytes_of(sp));
  // Truncated and overlong messages.
  std::vector<uint8_t> b = bytes_of(state_at(kT0, tdo_vec3{1, 1, 1}));
  send_raw(cfg_.state_channel, std::vector<uint8_t>(b.begin(), b.end() - 3));
  b.push_back(0);
  send_raw(cfg_.state_channel, b);
  std::vector<uint8_t> tb = bytes_of(straight(1, tdo_vec3{1, 1, 1}, 2.0, 2.0));
  send_raw(cfg_.trajectory_channel, std::vector<uint8_t>(tb.begin(), tb.begin() + 40));
  // An obstacles message whose count is negative on the wire (offset: 8 fingerprint + 8 utime +
  // 8 seq + 4 vehicle_id).
  std::vector<uint8_t> ob = bytes_of(one_mover(kT0, tdo_vec3{1, 1, 1}, tdo_vec3{}, 1.0));
  for (std::size_t i = 28; i < 32; ++i) ob[i] = 0xFF;
  send_raw(cfg_.obstacles_channel, ob);
  EXPECT_EQ(reason("state.bad_fingerprint"), 1);
  EXPECT_EQ(reason("trajectory.bad_fingerprint"), 1);
  EXPECT_EQ(reason("obstacles.bad_fingerprint"), 1);
  EXPECT_EQ(reason("map.bad_fingerprint"), 1);
  EXPECT_EQ(reason("state.truncated"), 1);
  EXPECT_EQ(reason("state.trailing_bytes"), 1);
  EXPECT_EQ(reason("trajectory.truncated"), 1);
  EXPECT_EQ(reason("obstacles.negative_count"), 1);
  EXPECT_EQ(node_->counters().rejected, 8);
  EXPECT_EQ(setpoints_.size(), 1u);  // nothing was answered
  expect_served(kT0 + kStepUs);
}

TEST_F(AvoidNodeTest, BadContentIsRefusedByNameAndTheLastGoodInputStays) {
  send(cfg_.trajectory_channel, straight(50, tdo_vec3{2, 5, 2}, 6.0, 5.0));
  send(cfg_.obstacles_channel, one_mover(kT0, tdo_vec3{2, 8, 2}, tdo_vec3{}, 0.5));
  expect_served(kT0);
  EXPECT_EQ(setpoints_.back().request_id, 50);
  const double gap = node_->last_output().terms.mover_gap;
  EXPECT_NEAR(gap, 3.0 - 0.5 - cfg_.vehicle_radius, 1e-9);

  // Non-finite numbers.
  tdo::vehicle_state_t s = state_at(kT0 + kStepUs, tdo_vec3{2, 5, 2});
  s.velocity[1] = kNaN;
  send(cfg_.state_channel, s);
  tdo::obstacles_t o = one_mover(kT0, tdo_vec3{2, 6, 2}, tdo_vec3{}, 0.5);
  o.position[0][0] = kNaN;
  send(cfg_.obstacles_channel, o);
  tdo::trajectory_t t = straight(51, tdo_vec3{2, 5, 2}, 6.0, 5.0);
  t.samples[3][5] = std::numeric_limits<double>::infinity();
  send(cfg_.trajectory_channel, t);
  // Array counts that do not match the arrays: on the wire the count is one less than the
  // elements sent (a count mismatch in a C++ message cannot be encoded at all; the adapters'
  // unit tests cover that case).
  std::vector<uint8_t> ob = bytes_of(one_mover(kT0, tdo_vec3{2, 6, 2}, tdo_vec3{}, 0.5));
  ob[31] = 0;  // n: 1 -> 0 (offset 8 fingerprint + 8 utime + 8 seq + 4 vehicle_id, big endian)
  send_raw(cfg_.obstacles_channel, ob);
  t = straight(52, tdo_vec3{2, 5, 2}, 6.0, 5.0);
  std::vector<uint8_t> tb = bytes_of(t);
  const std::size_t n_samples_at = 8 + 8 + 8 + 4 + 8 + 4 + (4 + t.status.size() + 1) +
                                   (4 + t.detail.size() + 1) + 1 + 4 + 24 * t.grid_path.size() + 4 +
                                   24 * t.waypoints.size() + 8;
  ASSERT_EQ(tb[n_samples_at + 3], static_cast<uint8_t>(t.n_samples & 0xFF));
  tb[n_samples_at + 3] = static_cast<uint8_t>(tb[n_samples_at + 3] - 1);
  send_raw(cfg_.trajectory_channel, tb);
  // More than the capacity: movers and samples.
  o = one_mover(kT0, tdo_vec3{2, 6, 2}, tdo_vec3{}, 0.5);
  for (int i = 0; i < 4; ++i) {
    o.id.push_back(20 + i);
    o.position.push_back({2, 6, 2});
    o.velocity.push_back({0, 0, 0});
    o.radius.push_back(0.5);
  }
  o.n = 5;
  send(cfg_.obstacles_channel, o);
  send(cfg_.trajectory_channel, straight(53, tdo_vec3{2, 5, 2}, 6.0, 30.0));  // 3001 samples
  // A map larger than the grid's capacity.
  tdo::map_t big{};
  ASSERT_TRUE(
      tdo_lcm::map_from_occupancy(tdo_grid_desc{100, 100, 10, 0.1, {0, 0, 0}}, {}, {}, 0.0, &big)
          .ok());
  big.map_id = 9;
  send(cfg_.map_channel, big);
  // Radius 0.
  o = one_mover(kT0, tdo_vec3{2, 6, 2}, tdo_vec3{}, 0.0);
  send(cfg_.obstacles_channel, o);

  EXPECT_EQ(reason("state.non_finite"), 1);
  EXPECT_EQ(reason("obstacles.non_finite"), 1);
  EXPECT_EQ(reason("trajectory.non_finite"), 1);
  EXPECT_EQ(reason("obstacles.trailing_bytes"), 1);
  EXPECT_EQ(reason("trajectory.trailing_bytes"), 1);
  EXPECT_EQ(reason("obstacles.over_capacity"), 1);
  EXPECT_EQ(reason("trajectory.over_capacity"), 1);
  EXPECT_EQ(reason("map.map_capacity"), 1);
  EXPECT_EQ(reason("obstacles.out_of_range"), 1);
  EXPECT_EQ(node_->counters().rejected, 9);
  EXPECT_EQ(node_->map_id(), -1);
  EXPECT_EQ(setpoints_.size(), 1u);  // the bad state was not answered

  // Still following request 50 around the same mover.
  expect_served(kT0 + 2 * kStepUs);
  EXPECT_EQ(setpoints_.back().request_id, 50);
  EXPECT_NEAR(node_->last_output().terms.mover_gap, gap, 1e-9);
}

TEST_F(AvoidNodeTest, OtherVehiclesAndFailedPlansAreIgnored) {
  send(cfg_.trajectory_channel, straight(60, tdo_vec3{2, 5, 2}, 6.0, 5.0));
  tdo::trajectory_t t = straight(61, tdo_vec3{2, 5, 2}, 6.0, 5.0);
  t.vehicle_id = kVehicle + 1;
  send(cfg_.trajectory_channel, t);
  tdo::trajectory_t failed{};
  failed.request_id = 62;
  failed.vehicle_id = kVehicle;
  failed.status_code = TDO_ERR_NO_PATH;
  failed.status = "no_path";
  failed.reached = -1;
  send(cfg_.trajectory_channel, failed);
  tdo::vehicle_state_t s = state_at(kT0, tdo_vec3{9, 9, 9});
  s.vehicle_id = kVehicle + 1;
  send(cfg_.state_channel, s);
  tdo::obstacles_t o = one_mover(kT0, tdo_vec3{2, 6, 2}, tdo_vec3{}, 0.5);
  o.vehicle_id = kVehicle + 1;
  send(cfg_.obstacles_channel, o);
  tdo::map_t m = wall_map(4);
  m.vehicle_id = kVehicle + 1;
  send(cfg_.map_channel, m);
  EXPECT_EQ(reason("trajectory.other_vehicle"), 1);
  EXPECT_EQ(reason("trajectory.no_plan"), 1);
  EXPECT_EQ(reason("state.other_vehicle"), 1);
  EXPECT_EQ(reason("obstacles.other_vehicle"), 1);
  EXPECT_EQ(reason("map.other_vehicle"), 1);
  EXPECT_EQ(node_->counters().ignored, 5);
  EXPECT_EQ(node_->counters().rejected, 0);
  EXPECT_TRUE(setpoints_.empty());
  expect_served(kT0);
  EXPECT_EQ(setpoints_.back().request_id, 60);
  EXPECT_EQ(node_->last_output().terms.mover_gap, HUGE_VAL);
}

TEST_F(AvoidNodeTest, ATrajectoryTheLibraryRefusesMeansHover) {
  send(cfg_.trajectory_channel, straight(70, tdo_vec3{2, 5, 2}, 6.0, 5.0));
  expect_served(kT0);
  EXPECT_EQ(setpoints_.back().request_id, 70);
  // Increasing but not uniform sample times: the adapter passes them, tdo_apf_reset does not.
  tdo::trajectory_t t = straight(71, tdo_vec3{2, 5, 2}, 6.0, 5.0);
  t.samples[10][0] += 0.004;
  send(cfg_.trajectory_channel, t);
  EXPECT_EQ(reason("trajectory.library_error"), 1);
  expect_served(kT0 + kStepUs);
  EXPECT_EQ(setpoints_.back().request_id, -1);
  // The next good trajectory is followed again.
  send(cfg_.trajectory_channel, straight(72, tdo_vec3{2, 5, 2}, 6.0, 5.0));
  expect_served(kT0 + 2 * kStepUs);
  EXPECT_EQ(setpoints_.back().request_id, 72);
}

TEST_F(AvoidNodeTest, HeartbeatsCarryTheCounters) {
  send(cfg_.trajectory_channel, straight(80, tdo_vec3{2, 5, 2}, 6.0, 5.0));
  expect_served(kT0);
  tdo::vehicle_state_t s = state_at(kT0, tdo_vec3{2, 5, 2});
  s.yaw = kNaN;
  send(cfg_.state_channel, s);
  s.vehicle_id = 99;
  send(cfg_.state_channel, s);
  const auto t0 = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  node_->poll(t0);
  pump();
  ASSERT_EQ(status_.size(), 1u);
  const tdo::status_t& h = status_.back();
  EXPECT_EQ(h.program, "tdo-avoid");
  EXPECT_EQ(h.vehicle_id, kVehicle);
  EXPECT_EQ(h.map_id, -1);
  EXPECT_EQ(h.received, 4);
  EXPECT_EQ(h.answered, 1);
  EXPECT_EQ(h.succeeded, 1);
  EXPECT_EQ(h.failed, 0);
  EXPECT_EQ(h.rejected, 1);
  EXPECT_EQ(h.ignored, 1);
  int64_t sum = 0;
  for (int64_t n : h.reason_count) sum += n;
  EXPECT_EQ(sum, h.rejected + h.ignored);
  ASSERT_EQ(h.n_reasons, 2);
  EXPECT_EQ(h.reason[0], "state.non_finite");
  EXPECT_EQ(h.reason[1], "state.other_vehicle");
}

TEST(AvoidNodeConfig, KindRateAndCapacitiesAreChecked) {
  tdo_lcm::AvoidConfig cfg;
  cfg.max_nx = cfg.max_ny = cfg.max_nz = 8;
  cfg.kind = TDO_FOLLOWER_APF;
  cfg.rate_hz = 100.0;
  {
    tdo_lcm::Bus bus("memq://");
    tdo_lcm::AvoidNode node(&bus, cfg);
    std::string error;
    ASSERT_TRUE(node.start(&error)) << error;
    EXPECT_EQ(node.params().kind, TDO_FOLLOWER_APF);
    EXPECT_EQ(node.params().dt, 0.01);
    tdo_apf_params def;
    tdo_apf_params_default(&def, TDO_FOLLOWER_APF);
    EXPECT_EQ(node.params().k_a, def.k_a);
  }
  for (int bad = 0; bad < 4; ++bad) {
    tdo_lcm::AvoidConfig c = cfg;
    if (bad == 0) c.rate_hz = 0.0;
    if (bad == 1) c.v_max = -1.0;
    if (bad == 2) c.max_movers = 0;
    if (bad == 3) c.max_nx = 0;
    tdo_lcm::Bus bus("memq://");
    tdo_lcm::AvoidNode node(&bus, c);
    std::string error;
    EXPECT_FALSE(node.start(&error)) << bad;
    EXPECT_FALSE(error.empty());
  }
}

}  // namespace

namespace {

/** 20 x 10 x 5 m at 0.5 m, free (boxes arrive by map updates). */
tdo::map_t open_map(int64_t map_id) {
  tdo::map_t m{};
  EXPECT_TRUE(
      tdo_lcm::map_from_occupancy(tdo_grid_desc{40, 20, 10, 0.5, {0, 0, 0}}, {}, {}, 0.25, &m)
          .ok());
  m.map_id = map_id;
  m.vehicle_id = -1;
  return m;
}

tdo::map_update_t wall_update(int64_t map_id, int64_t seq) {
  tdo::map_update_t u{};
  u.map_id = map_id;
  u.seq = seq;
  u.vehicle_id = -1;
  u.boxes = {{9.0, -1.0, -1.0, 10.0, 11.0, 6.0}};  // across the whole map at x = 9..10 m
  u.n_boxes = 1;
  return u;
}

TEST_F(AvoidNodeTest, GivenAFollowedPlan_WhenAnUpdatePutsAWallAcrossIt_ThenBrakesAndNeverOk) {
  std::vector<tdo::map_request_t> requests;
  ASSERT_TRUE(bus_.subscribe(cfg_.map_request_channel, collect(&requests)));
  send(cfg_.map_channel, open_map(5));
  send(cfg_.trajectory_channel, straight(50, tdo_vec3{2, 5, 2}, 14.0, 7.0));  // through x = 9..10
  int64_t t = kT0;
  tdo_vec3 p{2, 5, 2}, v{0, 0, 0}, a{0, 0, 0};
  // The vehicle does what it is told: the next state is the setpoint.
  auto take = [&](const tdo::setpoint_t& s) {
    p = tdo_vec3{s.position[0], s.position[1], s.position[2]};
    v = tdo_vec3{s.velocity[0], s.velocity[1], s.velocity[2]};
    a = tdo_vec3{s.acceleration[0], s.acceleration[1], s.acceleration[2]};
  };
  for (int k = 0; k < 120; ++k, t += kStepUs) {  // 2.4 s of following: ok
    send(cfg_.state_channel, state_at(t, p, v, a));
    ASSERT_EQ(setpoints_.back().status, "ok");
    take(setpoints_.back());
  }
  EXPECT_FALSE(node_->path_blocked());
  ASSERT_GT(v.x, 2.9) << p.x;  // at full speed, 3.5 m before the wall
  const double x_update = p.x;

  send(cfg_.map_update_channel, wall_update(5, 1));
  EXPECT_EQ(node_->counters().updates_applied, 1);
  EXPECT_TRUE(node_->path_blocked());
  const int64_t failed_before = node_->counters().steps_failed;
  for (int k = 0; k < 200; ++k, t += kStepUs) {  // 4 s: the vehicle stops, never told ok
    send(cfg_.state_channel, state_at(t, p, v, a));
    const tdo::setpoint_t& s = setpoints_.back();
    ASSERT_EQ(s.status, "path_blocked");
    ASSERT_EQ(s.status_code, tdo_lcm::kStatusPathBlocked);
    take(s);
  }
  EXPECT_LT(p.x + 0.25, 9.0) << "stopped before the wall (vehicle radius 0.25 m)";
  EXPECT_GT(p.x, x_update) << "braked from speed, not from rest";
  EXPECT_LT(norm(v), 0.05);
  EXPECT_EQ(node_->counters().steps_failed - failed_before, 200);
  const tdo::status_t hb = node_->status_message();
  EXPECT_EQ(heartbeat_reason(hb, "state.path_blocked"), 1);
  EXPECT_GE(hb.failed, 200);

  // A trajectory that stays clear of the wall is followed again (ok).
  send(cfg_.trajectory_channel, straight(51, p, -3.0, 3.0));  // back, away from it
  EXPECT_FALSE(node_->path_blocked());
  send(cfg_.state_channel, state_at(t, p, v, a));
  EXPECT_EQ(setpoints_.back().status, "ok");
  EXPECT_EQ(setpoints_.back().request_id, 51);
  EXPECT_EQ(heartbeat_reason(node_->status_message(), "state.path_blocked"), 0);

  // A gap: counted, the map is stale and the whole map is asked for.
  send(cfg_.map_update_channel, wall_update(5, 3));
  EXPECT_TRUE(node_->map_stale());
  EXPECT_EQ(heartbeat_reason(node_->status_message(), "update.gap"), 1);
  EXPECT_EQ(heartbeat_reason(node_->status_message(), "state.map_stale"), 1);
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].program, "tdo-avoid");
  EXPECT_EQ(requests[0].last_seq, 1);
}

}  // namespace
