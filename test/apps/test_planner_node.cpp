// tdo-planner's node in-process over memq:// (no network): map + request -> trajectory + report,
// and every kind of bad input counted in the heartbeat while the next valid request is served.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "node_test_util.h"
#include "planner_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/wire.h"
#if TDO_LCM_HAVE_OCTOMAP
#include "tdo_io/map_io.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/rle.h"
#endif

namespace {

using tdo_test::bytes_of;
using tdo_test::collect;

constexpr int32_t kVehicle = 3;

/** Collects what the node publishes. */
struct Inbox {
  std::vector<tdo::trajectory_t> traj;
  std::vector<tdo::feasibility_t> feas;
  std::vector<tdo::status_t> status;
};

/** 10 x 10 x 5 m at 0.5 m with a wall at x = 4.5..5.5 m, open above y = 7 m. */
tdo::map_t wall_map(int64_t map_id) {
  const tdo_grid_desc d{20, 20, 10, 0.5, {0.0, 0.0, 0.0}};
  const std::vector<tdo_box> boxes = {tdo_box{{4.5, 0.0, 0.0}, {5.5, 7.0, 5.0}}};
  std::vector<uint8_t> occ(20u * 20u * 10u, 0u);
  occ[19] = 1;  // one run-length voxel in a corner, away from the path
  tdo::map_t m{};
  EXPECT_TRUE(tdo_lcm::map_from_occupancy(d, occ, boxes, 0.25, &m).ok());
  m.map_id = map_id;
  m.vehicle_id = -1;
  return m;
}

tdo::plan_request_t request(int64_t id) {
  tdo_plan_request r{};
  tdo_plan_params_default(&r.params);
  r.start = tdo_vec3{1.25, 1.25, 1.25};
  r.goal = tdo_vec3{8.75, 1.25, 1.25};
  tdo::plan_request_t m{};
  tdo_lcm::plan_request_to_msg(r, -1.0, &m);
  m.request_id = id;
  m.seq = 100 + id;
  m.vehicle_id = kVehicle;
  m.map_id = -1;
  m.samples = tdo::plan_request_t::SAMPLES_ON;  // these tests read the samples
  return m;
}

class PlannerNodeTest
    : public tdo_test::NodeTest<tdo_lcm::PlannerNode, tdo_lcm::PlannerConfig, 1000> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(bus_.good());
    cfg_.vehicle_id = kVehicle;
    cfg_.max_nx = 24;
    cfg_.max_ny = 24;
    cfg_.max_nz = 12;
    cfg_.max_nodes = 400000;
    cfg_.max_boxes = 8;
    cfg_.max_clearance_ratio = 2.0;
    cfg_.heartbeat_period_s = 1.0;
    node_ = std::make_unique<tdo_lcm::PlannerNode>(&bus_, cfg_);
    std::string error;
    ASSERT_TRUE(node_->start(&error)) << error;
    ASSERT_TRUE(bus_.subscribe(cfg_.trajectory_channel, collect(&inbox_.traj)));
    ASSERT_TRUE(bus_.subscribe(cfg_.feasibility_channel, collect(&inbox_.feas)));
    ASSERT_TRUE(bus_.subscribe(cfg_.status_channel, collect(&inbox_.status)));
  }

  /** @return the count of `key` in the heartbeat the node would send now (0 when absent). */
  int64_t heartbeat_reason(const std::string& key) const {
    const tdo::status_t s = node_->status_message();
    for (int32_t i = 0; i < s.n_reasons; ++i)
      if (s.reason[static_cast<std::size_t>(i)] == key)
        return s.reason_count[static_cast<std::size_t>(i)];
    return 0;
  }
  /** The last answer must be a feasible trajectory for request `id`. */
  void expect_planned(int64_t id) {
    ASSERT_FALSE(inbox_.traj.empty());
    ASSERT_FALSE(inbox_.feas.empty());
    const tdo::trajectory_t& t = inbox_.traj.back();
    EXPECT_EQ(t.request_id, id);
    EXPECT_EQ(t.status, "ok") << t.detail;
    EXPECT_EQ(t.status_code, 0);
    EXPECT_GT(t.n_samples, 2);
    EXPECT_EQ(t.sample_count, t.n_samples);
    EXPECT_GT(t.n_segments, 0);
    EXPECT_GT(t.n_pieces, 0);
    EXPECT_EQ(t.request_seq, 100 + id);
    EXPECT_GE(t.n_waypoints, 2);
    EXPECT_EQ(inbox_.feas.back().request_id, id);
    EXPECT_EQ(inbox_.feas.back().request_seq, 100 + id);
    EXPECT_TRUE(inbox_.feas.back().checked);
    EXPECT_TRUE(inbox_.feas.back().ok);
  }

  Inbox inbox_;
};

TEST_F(PlannerNodeTest, MapThenRequestGivesTrajectoryAndFeasibility) {
  send(cfg_.map_channel, wall_map(5));
  EXPECT_EQ(node_->map_id(), 5);
  send(cfg_.request_channel, request(1));
  ASSERT_EQ(inbox_.traj.size(), 1u);
  ASSERT_EQ(inbox_.feas.size(), 1u);
  expect_planned(1);
  const tdo::trajectory_t& t = inbox_.traj[0];
  EXPECT_EQ(t.vehicle_id, kVehicle);
  EXPECT_EQ(t.map_id, 5);
  EXPECT_EQ(t.reached, tdo::plan_request_t::DEPTH_TRAJECTORY);
  EXPECT_EQ(t.samples.front()[1], 1.25);  // starts at the start, at rest
  EXPECT_EQ(t.samples.front()[4], 0.0);
  EXPECT_NEAR(t.samples.back()[1], 8.75, 1e-9);  // ends at the goal
  EXPECT_GT(t.length_m, 7.5);                    // around the wall
  EXPECT_GT(t.flight_time_s, 0.0);
  EXPECT_EQ(inbox_.feas[0].clearance, 0.25);  // the map's hint
  // The samples go around the wall: over y = 7 m while crossing x = 5 m.
  bool crossed_above = false;
  for (const auto& s : t.samples)
    if (std::fabs(s[1] - 5.0) < 0.1) crossed_above = crossed_above || s[2] > 7.0;
  EXPECT_TRUE(crossed_above);
  const auto& c = node_->counters();
  EXPECT_EQ(c.received, 2);
  EXPECT_EQ(c.maps_loaded, 1);
  EXPECT_EQ(c.answered, 1);
  EXPECT_EQ(c.succeeded, 1);
  EXPECT_EQ(c.rejected, 0);
}

TEST_F(PlannerNodeTest, RequestBeforeAnyMapIsAnsweredNoMap) {
  send(cfg_.request_channel, request(9));
  ASSERT_EQ(inbox_.traj.size(), 1u);
  EXPECT_EQ(inbox_.traj[0].request_id, 9);
  EXPECT_EQ(inbox_.traj[0].status, "no_map");
  EXPECT_EQ(inbox_.traj[0].status_code, tdo::trajectory_t::STATUS_REJECTED);
  EXPECT_EQ(inbox_.traj[0].map_id, -1);
  EXPECT_EQ(inbox_.feas[0].status, "no_map");
  EXPECT_EQ(reason("request.no_map"), 1);
  // Then a map arrives and the same request is served.
  send(cfg_.map_channel, wall_map(1));
  send(cfg_.request_channel, request(10));
  expect_planned(10);
}

TEST_F(PlannerNodeTest, RequestForAnotherVehicleIsIgnored) {
  send(cfg_.map_channel, wall_map(1));
  tdo::plan_request_t r = request(2);
  r.vehicle_id = kVehicle + 1;
  send(cfg_.request_channel, r);
  EXPECT_TRUE(inbox_.traj.empty());
  EXPECT_EQ(node_->counters().ignored, 1);
  EXPECT_EQ(reason("request.other_vehicle"), 1);
  // A map for another vehicle is ignored too, and the current map stays.
  tdo::map_t m = wall_map(2);
  m.vehicle_id = kVehicle + 1;
  send(cfg_.map_channel, m);
  EXPECT_EQ(node_->map_id(), 1);
  EXPECT_EQ(reason("map.other_vehicle"), 1);
  send(cfg_.request_channel, request(3));
  expect_planned(3);
}

TEST_F(PlannerNodeTest, MalformedBytesAreCountedAndServingGoesOn) {
  send(cfg_.map_channel, wall_map(1));
  // Wrong fingerprint: a status message on the request channel.
  tdo::status_t s{};
  s.program = "x";
  send_raw(cfg_.request_channel, bytes_of(s));
  // Truncated request; request with bytes after its end.
  std::vector<uint8_t> b = bytes_of(request(4));
  send_raw(cfg_.request_channel, std::vector<uint8_t>(b.begin(), b.end() - 5));
  b.push_back(0);
  send_raw(cfg_.request_channel, b);
  // A map whose run count is negative on the wire (offset of n_runs: 8 fingerprint + 8 utime +
  // 8 map_id + 4 vehicle_id + 8 resolution + 24 origin + 12 size + 8 clearance + 1 encoding).
  std::vector<uint8_t> mb = bytes_of(wall_map(2));
  for (std::size_t i = 81; i < 85; ++i) mb[i] = 0xFF;
  send_raw(cfg_.map_channel, mb);
  EXPECT_TRUE(inbox_.traj.empty());  // nothing to answer to
  EXPECT_EQ(reason("request.bad_fingerprint"), 1);
  EXPECT_EQ(reason("request.truncated"), 1);
  EXPECT_EQ(reason("request.trailing_bytes"), 1);
  EXPECT_EQ(reason("map.negative_count"), 1);
  EXPECT_EQ(node_->counters().rejected, 4);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(5));
  expect_planned(5);
}

TEST_F(PlannerNodeTest, BadRequestsAreAnsweredWithTheirReason) {
  send(cfg_.map_channel, wall_map(1));
  tdo::plan_request_t r = request(6);
  r.start[1] = std::numeric_limits<double>::quiet_NaN();
  send(cfg_.request_channel, r);
  r = request(7);
  r.smoothing = 7;
  send(cfg_.request_channel, r);
  r = request(8);
  r.map_id = 99;
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.traj.size(), 3u);
  EXPECT_EQ(inbox_.traj[0].request_id, 6);
  EXPECT_EQ(inbox_.traj[0].status, "non_finite");
  EXPECT_NE(inbox_.traj[0].detail.find("start[1]"), std::string::npos);
  EXPECT_EQ(inbox_.traj[1].status, "bad_enum");
  EXPECT_EQ(inbox_.traj[2].status, "unknown_map");
  for (const auto& t : inbox_.traj) EXPECT_EQ(t.status_code, tdo::trajectory_t::STATUS_REJECTED);
  EXPECT_EQ(node_->counters().rejected, 3);
  EXPECT_EQ(node_->counters().answered, 3);
  send(cfg_.request_channel, request(9));
  expect_planned(9);
}

TEST_F(PlannerNodeTest, LibraryFailuresAreAnsweredWithTheLibraryStatus) {
  send(cfg_.map_channel, wall_map(1));
  tdo::plan_request_t r = request(11);
  r.goal[0] = 5.0;  // inside the wall
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.traj.size(), 1u);
  EXPECT_EQ(inbox_.traj[0].status, "goal_blocked");
  EXPECT_EQ(inbox_.traj[0].status_code, TDO_ERR_GOAL_BLOCKED);
  EXPECT_EQ(inbox_.traj[0].n_samples, 0);
  EXPECT_FALSE(inbox_.feas[0].ok);
  EXPECT_EQ(node_->counters().failed, 1);
  EXPECT_EQ(node_->counters().rejected, 0);
}

TEST_F(PlannerNodeTest, MapLargerThanTheCapacityKeepsThePreviousMap) {
  send(cfg_.map_channel, wall_map(1));
  tdo::map_t big{};
  ASSERT_TRUE(
      tdo_lcm::map_from_occupancy(tdo_grid_desc{100, 100, 100, 0.1, {0, 0, 0}}, {}, {}, 0.0, &big)
          .ok());
  big.map_id = 2;
  send(cfg_.map_channel, big);
  EXPECT_EQ(reason("map.map_capacity"), 1);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(12));
  expect_planned(12);
  EXPECT_EQ(inbox_.traj.back().map_id, 1);
}

TEST_F(PlannerNodeTest, RequestedClearance) {
  send(cfg_.map_channel, wall_map(1));
  tdo::plan_request_t r = request(13);
  r.clearance = 0.5;
  send(cfg_.request_channel, r);
  expect_planned(13);
  EXPECT_EQ(inbox_.feas.back().clearance, 0.5);
  EXPECT_GE(inbox_.feas.back().min_clearance, 0.5 - 1e-9);
  // More than the stencil capacity (2 voxels): refused, the map stays usable.
  r = request(14);
  r.clearance = 3.0;
  send(cfg_.request_channel, r);
  EXPECT_EQ(inbox_.traj.back().status, "map_capacity");
  send(cfg_.request_channel, request(15));
  expect_planned(15);
  EXPECT_EQ(inbox_.feas.back().clearance, 0.25);
}

// A clearance whose stencil would span (2 * 5e5 / 0.5)^3 cells: refused before any loop (the check
// used to scan the stencil's bounding box first and blocked the node for hours), answered, counted;
// the same for a map's clearance hint; the next valid request is served.
TEST_F(PlannerNodeTest, GivenHugeClearanceWhenRequestedOrHintedThenRefusedAndServingGoesOn) {
  send(cfg_.map_channel, wall_map(5));
  tdo::plan_request_t huge = request(7);
  huge.clearance = 5e5;
  send(cfg_.request_channel, huge);
  ASSERT_EQ(inbox_.traj.size(), 1u);
  EXPECT_EQ(inbox_.traj[0].status, "map_capacity") << inbox_.traj[0].detail;
  EXPECT_EQ(inbox_.traj[0].status_code, tdo::trajectory_t::STATUS_REJECTED);
  tdo::map_t hinted = wall_map(6);
  hinted.clearance = 1e300;
  send(cfg_.map_channel, hinted);
  EXPECT_EQ(node_->map_id(), 5);
  EXPECT_EQ(heartbeat_reason("request.map_capacity"), 1);
  EXPECT_EQ(heartbeat_reason("map.map_capacity"), 1);
  send(cfg_.request_channel, request(8));
  ASSERT_EQ(inbox_.traj.size(), 2u);
  expect_planned(8);
}

TEST_F(PlannerNodeTest, HeartbeatsCarryTheCounters) {
  const auto t0 = std::chrono::steady_clock::now();
  node_->poll(t0);
  node_->poll(t0 + std::chrono::milliseconds(500));  // not due yet
  pump();
  ASSERT_EQ(inbox_.status.size(), 1u);
  send(cfg_.request_channel, request(1));  // no map: rejected
  tdo::plan_request_t other = request(2);
  other.vehicle_id = 99;
  send(cfg_.request_channel, other);  // ignored
  node_->poll(t0 + std::chrono::milliseconds(1100));
  pump();
  ASSERT_EQ(inbox_.status.size(), 2u);
  const tdo::status_t& s = inbox_.status.back();
  EXPECT_EQ(s.program, "tdo-planner");
  EXPECT_EQ(s.vehicle_id, kVehicle);
  EXPECT_EQ(s.seq, 1);
  EXPECT_EQ(s.map_id, -1);
  EXPECT_EQ(s.received, 2);
  EXPECT_EQ(s.answered, 1);
  EXPECT_EQ(s.rejected, 1);
  EXPECT_EQ(s.ignored, 1);
  int64_t sum = 0;
  for (int64_t n : s.reason_count) sum += n;
  EXPECT_EQ(sum, s.rejected + s.ignored);
  ASSERT_EQ(s.n_reasons, 2);
  EXPECT_EQ(s.reason[0], "request.no_map");
  EXPECT_EQ(s.reason[1], "request.other_vehicle");
}

// ---- Malformed input, one test per kind (issue 5). Each: refused with a named reason, counted in
// the heartbeat, and the next valid request is still served on the map in place.

// Offsets in the encoded wall_map (big-endian): 8 fingerprint, 8 utime, 8 map_id, 4 vehicle_id,
// 8 resolution, 24 origin, 12 size, 8 clearance, 1 encoding, then n_runs at 81, its 3 runs, n_bytes
// at 97 (0), n_boxes at 101 (1), the box (48 bytes) at 105.
constexpr std::size_t kMapNBoxesOffset = 101;

void put_be32(std::vector<uint8_t>* b, std::size_t at, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i)
    (*b)[at + static_cast<std::size_t>(i)] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

TEST_F(PlannerNodeTest, WrongFingerprintIsCountedAndNotAnswered) {
  send(cfg_.map_channel, wall_map(1));
  tdo::status_t s{};
  s.program = "x";
  send_raw(cfg_.request_channel, bytes_of(s));       // a status_t on the request channel
  send_raw(cfg_.map_channel, bytes_of(request(1)));  // a request on the map channel
  EXPECT_TRUE(inbox_.traj.empty());                  // no request id to answer to
  EXPECT_EQ(heartbeat_reason("request.bad_fingerprint"), 1);
  EXPECT_EQ(heartbeat_reason("map.bad_fingerprint"), 1);
  EXPECT_EQ(node_->status_message().rejected, 2);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(2));
  expect_planned(2);
}

TEST_F(PlannerNodeTest, TruncatedMessagesAreCountedAndNotAnswered) {
  send(cfg_.map_channel, wall_map(1));
  const std::vector<uint8_t> r = bytes_of(request(1));
  for (std::size_t keep : {std::size_t{0}, std::size_t{7}, std::size_t{20}, r.size() - 1})
    send_raw(cfg_.request_channel, std::vector<uint8_t>(r.begin(), r.begin() + keep));
  const std::vector<uint8_t> m = bytes_of(wall_map(2));
  send_raw(cfg_.map_channel, std::vector<uint8_t>(m.begin(), m.end() - 1));
  EXPECT_TRUE(inbox_.traj.empty());
  EXPECT_EQ(heartbeat_reason("request.truncated"), 4);
  EXPECT_EQ(heartbeat_reason("map.truncated"), 1);
  EXPECT_EQ(node_->map_id(), 1);  // the truncated map 2 did not replace map 1
  send(cfg_.request_channel, request(2));
  expect_planned(2);
  EXPECT_EQ(inbox_.traj.back().map_id, 1);
}

TEST_F(PlannerNodeTest, NonFiniteNumbersAreRefused) {
  send(cfg_.map_channel, wall_map(1));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  tdo::plan_request_t r = request(1);
  r.goal[2] = inf;
  send(cfg_.request_channel, r);
  r = request(2);
  r.v_max = nan;
  send(cfg_.request_channel, r);
  tdo::map_t m = wall_map(2);
  m.resolution = nan;
  send(cfg_.map_channel, m);
  m = wall_map(3);
  m.boxes[0][4] = inf;
  send(cfg_.map_channel, m);
  ASSERT_EQ(inbox_.traj.size(), 2u);  // requests are answered, with the field named
  EXPECT_EQ(inbox_.traj[0].status, "non_finite");
  EXPECT_NE(inbox_.traj[0].detail.find("goal[2]"), std::string::npos) << inbox_.traj[0].detail;
  EXPECT_EQ(inbox_.traj[1].status, "non_finite");
  EXPECT_NE(inbox_.traj[1].detail.find("v_max"), std::string::npos) << inbox_.traj[1].detail;
  EXPECT_EQ(inbox_.feas[1].status, "non_finite");
  EXPECT_EQ(heartbeat_reason("request.non_finite"), 2);
  EXPECT_EQ(heartbeat_reason("map.non_finite"), 2);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(3));
  expect_planned(3);
}

TEST_F(PlannerNodeTest, ArrayCountsThatDoNotMatchAreRefused) {
  send(cfg_.map_channel, wall_map(1));
  const std::vector<uint8_t> good = bytes_of(wall_map(2));
  ASSERT_EQ(good.size(), kMapNBoxesOffset + 4 + 48);
  std::vector<uint8_t> b = good;
  put_be32(&b, kMapNBoxesOffset, 2);  // two boxes announced, one sent
  send_raw(cfg_.map_channel, b);
  b = good;
  put_be32(&b, kMapNBoxesOffset, 0);  // no box announced, one sent
  send_raw(cfg_.map_channel, b);
  // Counts consistent on the wire but the runs do not cover the 4000 voxels of the size.
  tdo::map_t m = wall_map(3);
  m.runs.back() -= 1;
  send(cfg_.map_channel, m);
  m = wall_map(4);
  m.size[2] = 11;  // one more layer than the runs describe
  send(cfg_.map_channel, m);
  EXPECT_EQ(heartbeat_reason("map.truncated"), 1);
  EXPECT_EQ(heartbeat_reason("map.trailing_bytes"), 1);
  EXPECT_EQ(heartbeat_reason("map.rle_mismatch"), 2);
  EXPECT_EQ(node_->status_message().rejected, 4);
  EXPECT_EQ(node_->status_message().maps_loaded, 1);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(5));
  expect_planned(5);
}

TEST_F(PlannerNodeTest, MapLargerThanTheCapacityIsCountedInTheHeartbeat) {
  send(cfg_.map_channel, wall_map(1));
  tdo::map_t m = wall_map(2);
  m.boxes.assign(9, m.boxes[0]);  // capacity: 8 boxes
  m.n_boxes = 9;
  send(cfg_.map_channel, m);
  tdo::map_t big{};
  ASSERT_TRUE(
      tdo_lcm::map_from_occupancy(tdo_grid_desc{25, 24, 12, 0.5, {0, 0, 0}}, {}, {}, 0.0, &big)
          .ok());  // one voxel row more than 24 x 24 x 12
  big.map_id = 3;
  send(cfg_.map_channel, big);
  EXPECT_EQ(heartbeat_reason("map.map_capacity"), 2);
  EXPECT_EQ(node_->map_id(), 1);
  send(cfg_.request_channel, request(6));
  expect_planned(6);
}

TEST_F(PlannerNodeTest, RequestBeforeAnyMapAndForAnotherVehicleInTheHeartbeat) {
  send(cfg_.request_channel, request(1));
  tdo::plan_request_t other = request(2);
  other.vehicle_id = kVehicle + 1;
  send(cfg_.request_channel, other);
  ASSERT_EQ(inbox_.traj.size(), 1u);  // no_map answered, the other vehicle's request not
  EXPECT_EQ(inbox_.traj[0].request_id, 1);
  const tdo::status_t s = node_->status_message();
  EXPECT_EQ(s.rejected, 1);
  EXPECT_EQ(s.ignored, 1);
  EXPECT_EQ(heartbeat_reason("request.no_map"), 1);
  EXPECT_EQ(heartbeat_reason("request.other_vehicle"), 1);
  send(cfg_.map_channel, wall_map(1));
  send(cfg_.request_channel, request(3));
  expect_planned(3);
}

TEST_F(PlannerNodeTest, GivenSamplesOffWhenPlannedThenOnlyTheCompactFormTravels) {
  send(cfg_.map_channel, wall_map(5));
  tdo::plan_request_t r = request(1);
  r.samples = tdo::plan_request_t::SAMPLES_OFF;
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.traj.size(), 1u);
  const tdo::trajectory_t& t = inbox_.traj[0];
  EXPECT_EQ(t.status, "ok") << t.detail;
  EXPECT_EQ(t.n_samples, 0);
  EXPECT_TRUE(t.samples.empty());
  EXPECT_GT(t.sample_count, 2);
  EXPECT_GT(t.n_pieces, 0);
  EXPECT_EQ(t.n_segment_points, 12 * t.n_segments);
  EXPECT_EQ(t.request_seq, 101);
  r.samples = 2;  // neither SAMPLES_OFF nor SAMPLES_ON
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.feas.size(), 2u);
  EXPECT_EQ(inbox_.traj[1].status, "bad_enum");
  EXPECT_EQ(inbox_.feas[1].refused_field, "samples");
}

TEST_F(PlannerNodeTest, GivenAMovingStart_WhenRequested_ThenTheTrajectoryBeginsInThatState) {
  // GIVEN a vehicle flying +y at 1 m/s and accelerating +x, asking without samples
  send(cfg_.map_channel, wall_map(5));
  tdo::plan_request_t r = request(1);
  r.samples = tdo::plan_request_t::SAMPLES_OFF;
  r.start_vel[1] = 1.0;
  r.start_acc[0] = 0.5;
  send(cfg_.request_channel, r);
  // THEN a plan whose first sample is that state; its acceleration ramp is no piece of the
  // compact form, so it travels as samples
  ASSERT_EQ(inbox_.traj.size(), 1u);
  const tdo::trajectory_t& t = inbox_.traj[0];
  ASSERT_EQ(t.status, "ok") << t.detail;
  ASSERT_GT(t.n_samples, 2);
  EXPECT_EQ(t.n_pieces, 0);
  EXPECT_EQ(t.samples.front()[1], 1.25);
  EXPECT_EQ(t.samples.front()[4], 0.0);
  EXPECT_EQ(t.samples.front()[5], 1.0);
  EXPECT_EQ(t.samples.front()[7], 0.5);
  EXPECT_TRUE(inbox_.feas[0].ok);
  // AND bad states are refused naming the field, or answered with the library's named status
  r = request(2);
  r.start_vel[0] = std::numeric_limits<double>::quiet_NaN();
  send(cfg_.request_channel, r);
  r = request(3);
  r.start_vel[0] = 3.5;  // above v_max
  send(cfg_.request_channel, r);
  r = request(4);
  r.start[0] = 3.25;  // 0.5 m before the wall's clearance, flying at it at 3 m/s
  r.start_vel[0] = 3.0;
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.traj.size(), 4u);
  EXPECT_EQ(inbox_.traj[1].status, "non_finite");
  EXPECT_EQ(inbox_.feas[1].refused_field, "start_vel[0]");
  EXPECT_EQ(inbox_.traj[2].status, "out_of_range");
  EXPECT_EQ(inbox_.feas[2].refused_field, "start_vel");
  EXPECT_EQ(inbox_.traj[3].status, "state_cannot_stop");
  EXPECT_EQ(inbox_.traj[3].status_code, TDO_ERR_STATE_CANNOT_STOP);
  EXPECT_EQ(inbox_.traj[3].n_samples, 0);
  // AND the node keeps serving
  send(cfg_.request_channel, request(5));
  expect_planned(5);
}

TEST_F(PlannerNodeTest, GivenACornerTimeOutsideZeroToOneThenRefusedNamingTheField) {
  send(cfg_.map_channel, wall_map(5));
  tdo::plan_request_t r = request(1);
  r.corner_time = 1.5;
  send(cfg_.request_channel, r);
  ASSERT_EQ(inbox_.feas.size(), 1u);
  EXPECT_EQ(inbox_.traj[0].status, "out_of_range");
  EXPECT_EQ(inbox_.feas[0].refused_field, "corner_time");
  EXPECT_EQ(heartbeat_reason("field.corner_time"), 1);
  r.corner_time = 0.0;  // the previous corner shapes: valid
  send(cfg_.request_channel, r);
  expect_planned(1);
}

TEST_F(PlannerNodeTest, GivenOnlyStartAndGoalWithUseDefaultsThenPlannedWithTheLibrarysDefaults) {
  send(cfg_.map_channel, wall_map(5));
  tdo::plan_request_t bare{};  // every parameter zero
  bare.request_id = 1;
  bare.seq = 101;
  bare.vehicle_id = kVehicle;
  bare.map_id = -1;
  bare.start[0] = bare.start[1] = bare.start[2] = 1.25;
  bare.goal[0] = 8.75;
  bare.goal[1] = bare.goal[2] = 1.25;
  send(cfg_.request_channel, bare);  // zeros are not defaults: refused, naming a field
  ASSERT_EQ(inbox_.feas.size(), 1u);
  EXPECT_EQ(inbox_.traj[0].status, "out_of_range");
  EXPECT_EQ(inbox_.feas[0].refused_field, "h_weight");
  EXPECT_NE(inbox_.feas[0].refused_reason.find("must be >= 1"), std::string::npos)
      << inbox_.feas[0].refused_reason;
  EXPECT_EQ(heartbeat_reason("request.out_of_range"), 1);
  EXPECT_EQ(heartbeat_reason("field.h_weight"), 1);
  bare.use_defaults = tdo::plan_request_t::USE_DEFAULT_ALL;
  bare.samples = tdo::plan_request_t::SAMPLES_ON;
  send(cfg_.request_channel, bare);
  expect_planned(1);
  const tdo::trajectory_t with_defaults = inbox_.traj.back();
  send(cfg_.request_channel, request(1));  // every default written out: the same plan
  expect_planned(1);
  EXPECT_EQ(inbox_.traj.back().samples, with_defaults.samples);
  // One field given, the rest defaulted: v_max 1 m/s flies slower.
  bare.use_defaults =
      tdo::plan_request_t::USE_DEFAULT_ALL & ~tdo::plan_request_t::USE_DEFAULT_V_MAX;
  bare.v_max = 1.0;
  send(cfg_.request_channel, bare);
  expect_planned(1);
  EXPECT_GT(inbox_.traj.back().flight_time_s, with_defaults.flight_time_s);
  // Bits beyond USE_DEFAULT_ALL and a refused v_max name their fields.
  bare.use_defaults = tdo::plan_request_t::USE_DEFAULT_ALL + 1;
  send(cfg_.request_channel, bare);
  EXPECT_EQ(inbox_.feas.back().refused_field, "use_defaults");
  bare.use_defaults =
      tdo::plan_request_t::USE_DEFAULT_ALL & ~tdo::plan_request_t::USE_DEFAULT_V_MAX;
  bare.v_max = 0.0;
  send(cfg_.request_channel, bare);
  EXPECT_EQ(inbox_.traj.back().status_code, tdo::trajectory_t::STATUS_REJECTED);
  EXPECT_EQ(inbox_.feas.back().refused_field, "v_max");
  EXPECT_EQ(heartbeat_reason("field.v_max"), 1);
}

}  // namespace

namespace {

// ---- samples stored or regenerated (tdo_capacity.stream_samples): the same answers -----------

/** What a node planning with `stream_samples` publishes for one map and a set of requests. */
struct ModeRun {
  bool started = false;
  std::string error;
  std::size_t arena = 0;
  std::vector<std::vector<uint8_t>> traj, feas;     /**< encoded, wall-clock fields zeroed */
  std::vector<std::vector<uint8_t>> traj_no_energy; /**< traj with the energy and the minimum
                                                         clearance zeroed too */
  std::vector<double> energy;                       /**< m^2/s^3, of each trajectory answer */
  std::vector<double> min_clearance;                /**< m, of each trajectory answer */
  std::vector<int32_t> n_samples, sample_count;
};

ModeRun run_mode(int32_t stream_samples) {
  ModeRun out;
  tdo_lcm::Bus bus("memq://");  // first: outlives the node
  EXPECT_TRUE(bus.good());
  tdo_lcm::PlannerConfig cfg;
  cfg.vehicle_id = kVehicle;
  cfg.max_nx = 24;
  cfg.max_ny = 24;
  cfg.max_nz = 12;
  cfg.max_nodes = 400000;
  cfg.max_boxes = 8;
  cfg.max_clearance_ratio = 2.0;
  cfg.heartbeat_period_s = 0.0;
  cfg.stream_samples = stream_samples;
  tdo_lcm::PlannerNode node(&bus, cfg);
  out.started = node.start(&out.error);
  if (!out.started) return out;
  out.arena = node.arena_bytes();
  std::vector<tdo::trajectory_t> traj;
  std::vector<tdo::feasibility_t> feas;
  EXPECT_TRUE(bus.subscribe(cfg.trajectory_channel, collect(&traj)));
  EXPECT_TRUE(bus.subscribe(cfg.feasibility_channel, collect(&feas)));
  const auto pump = [&bus]() {
    for (int i = 0; i < 1000 && bus.handle_timeout(0) > 0; ++i) {
    }
  };
  EXPECT_TRUE(bus.publish(cfg.map_channel, wall_map(5)));
  pump();
  std::vector<tdo::plan_request_t> reqs;
  reqs.push_back(request(1));  // samples on
  reqs.push_back(request(2));
  reqs.back().samples = tdo::plan_request_t::SAMPLES_OFF;  // the compact form only
  reqs.push_back(request(3));
  reqs.back().samples = tdo::plan_request_t::SAMPLES_OFF;  // a moving start: travels as samples
  reqs.back().start_vel[1] = 1.0;
  reqs.back().start_acc[0] = 0.5;
  reqs.push_back(request(4));
  reqs.back().start[0] = 3.25;  // cannot stop before the wall: no samples
  reqs.back().start_vel[0] = 3.0;
  reqs.push_back(request(5));  // served again after the failure
  for (const tdo::plan_request_t& r : reqs) {
    EXPECT_TRUE(bus.publish(cfg.request_channel, r));
    pump();
  }
  for (tdo::trajectory_t t : traj) {
    out.n_samples.push_back(t.n_samples);
    out.sample_count.push_back(t.sample_count);
    t.utime = 0;
    t.plan_time_ms = 0.0;
    out.traj.push_back(bytes_of(t));
    out.energy.push_back(t.energy);
    out.min_clearance.push_back(t.min_clearance_m);
    t.energy = 0.0;
    t.min_clearance_m = 0.0;
    out.traj_no_energy.push_back(bytes_of(t));
  }
  for (tdo::feasibility_t f : feas) {
    f.utime = 0;
    out.feas.push_back(bytes_of(f));
  }
  return out;
}

TEST(PlannerNodeSamples, GivenSamplesStreamedWhenPlannedThenEveryAnswerIsTheStoredModesBytes) {
  // GIVEN two nodes, one keeping the samples in its arena, one regenerating them on demand
  const ModeRun stored = run_mode(0);
  const ModeRun streamed = run_mode(1);
  ASSERT_TRUE(stored.started) << stored.error;
  ASSERT_TRUE(streamed.started) << streamed.error;
  // (the mode took effect: the streamed arena holds no samples)
  EXPECT_LT(streamed.arena, stored.arena);
  // THEN the stored node's answers carry the samples asked for ...
  ASSERT_EQ(stored.traj.size(), 5u);
  ASSERT_EQ(stored.feas.size(), 5u);
  EXPECT_GT(stored.n_samples[0], 2);
  EXPECT_EQ(stored.n_samples[0], stored.sample_count[0]);
  EXPECT_EQ(stored.n_samples[1], 0);  // SAMPLES_OFF: the compact form counts them
  EXPECT_GT(stored.sample_count[1], 2);
  EXPECT_GT(stored.n_samples[2], 2);  // the moving start's samples
  EXPECT_EQ(stored.n_samples[3], 0);  // state_cannot_stop
  EXPECT_EQ(stored.n_samples[4], stored.n_samples[0]);
  // AND the streaming node publishes the same bytes, samples included
  EXPECT_EQ(streamed.n_samples, stored.n_samples);
  EXPECT_EQ(streamed.sample_count, stored.sample_count);
  ASSERT_EQ(streamed.traj.size(), stored.traj.size());
  ASSERT_EQ(streamed.feas.size(), stored.feas.size());
  for (std::size_t i = 0; i < stored.traj.size(); ++i) {
    EXPECT_TRUE(streamed.traj[i] == stored.traj[i]) << "trajectory answer " << i;
    EXPECT_TRUE(streamed.feas[i] == stored.feas[i]) << "feasibility answer " << i;
  }
}

TEST(PlannerNodeSamples, GivenSamplesPiecesThenTheSameAnswersUpToTheEnergyIntegral) {
  // Mode 2 (verified per profile piece, samples regenerated): the same trajectory answers, samples
  // included, except the energy, which that mode integrates instead of summing the samples by the
  // trapezoid rule (trajectory.h): within 1e-3 relative, the trapezoid's O(dt^2) error; and the
  // minimum clearance, which is the bound the planner's stages proved (the map's 0.25 m less
  // 1e-9 m) for a start at rest, at most the samples' measured minimum.
  const ModeRun pieces = run_mode(2);
  ASSERT_TRUE(pieces.started) << pieces.error;
  const ModeRun stored = run_mode(0);
  ASSERT_TRUE(stored.started) << stored.error;
  EXPECT_EQ(pieces.n_samples, stored.n_samples);
  EXPECT_EQ(pieces.sample_count, stored.sample_count);
  ASSERT_EQ(pieces.traj.size(), stored.traj.size());
  ASSERT_EQ(pieces.feas.size(), stored.feas.size());
  for (std::size_t i = 0; i < stored.traj.size(); ++i) {
    EXPECT_TRUE(pieces.traj_no_energy[i] == stored.traj_no_energy[i]) << "trajectory answer " << i;
    EXPECT_NEAR(pieces.energy[i], stored.energy[i], 1e-3 * std::fabs(stored.energy[i])) << i;
    EXPECT_LE(pieces.min_clearance[i], stored.min_clearance[i]) << i;
    if (stored.sample_count[i] > 0) {  // a flown plan (a refused one carries 0 in both modes)
      EXPECT_GE(pieces.min_clearance[i], 0.25 - 1e-9) << i;
    }
  }
  EXPECT_EQ(pieces.min_clearance[0], 0.25 - 1e-9);  // the first request starts at rest
}
}  // namespace

#if TDO_LCM_HAVE_OCTOMAP
namespace {

// An OctoMap-encoded map (the .bt bytes unchanged, 209 kB instead of 440 kB of run lengths at the
// tree's resolution): rasterised by the node exactly as mapio rasterises the file, and planned
// on with the optimal length the maps/octomap README gives for query G2 (res 0.2 m, clearance 0.4).
TEST(PlannerNodeOctoMap, OctoMapEncodedMapIsRasterisedAndPlanned) {
  const std::string bt = TDO_MAPS_DIR "/octomap/geb079.bt";
  tdo::map_t m{};
  std::string error;
  ASSERT_TRUE(tdo_lcm::octomap_msg_from_file(bt, 0.2, 0.4, &m, &error)) << error;
  EXPECT_EQ(m.encoding, tdo::map_t::ENCODING_OCTOMAP_BT);
  EXPECT_EQ(m.n_runs, 0);
  m.map_id = 79;

  // Same occupancy as mapio's reader of the file at the same resolution.
  tdo::map_t rle{};
  ASSERT_TRUE(tdo_lcm::octomap_to_rle(m, 1u << 22, &rle).ok());
  tdo_io::LoadOptions opt;
  opt.resolution = 0.2;
  tdo_io::Map file;
  ASSERT_TRUE(tdo_io::load_map(bt, opt, &file, &error)) << error;
  ASSERT_EQ(file.desc.nx, m.size[0]);
  std::vector<uint8_t> occ(static_cast<std::size_t>(m.size[0]) * m.size[1] * m.size[2], 0u);
  for (const tdo_voxel& v : file.voxels)
    occ[(static_cast<std::size_t>(v.k) * m.size[1] + v.j) * m.size[0] + v.i] = 1u;
  EXPECT_EQ(rle.runs, tdo_lcm::rle_encode(occ));
  EXPECT_EQ(tdo_lcm::octomap_to_rle(m, 1000, &rle).reason, tdo_lcm::Reason::map_capacity);

  tdo_lcm::Bus bus("memq://");
  tdo_lcm::PlannerConfig cfg;
  cfg.max_nx = m.size[0];
  cfg.max_ny = m.size[1];
  cfg.max_nz = m.size[2];
  cfg.max_nodes = 300000;
  cfg.max_clearance_ratio = 2.0;
  tdo_lcm::PlannerNode node(&bus, cfg);
  ASSERT_TRUE(node.start(&error)) << error;
  std::vector<tdo::trajectory_t> traj;
  bus.subscribe(cfg.trajectory_channel, collect(&traj));
  auto pump = [&]() {
    for (int i = 0; i < 100 && bus.handle_timeout(0) > 0; ++i) {
    }
  };
  tdo::map_t broken = m;  // bytes that are no OcTree: refused, counted
  broken.data.assign(100, uint8_t{7});
  broken.n_bytes = 100;
  ASSERT_TRUE(bus.publish(cfg.map_channel, broken));
  ASSERT_TRUE(bus.publish(cfg.map_channel, m));
  pump();
  EXPECT_EQ(node.counters().reasons.at("map.bad_encoding"), 1);
  ASSERT_EQ(node.map_id(), 79);

  tdo::plan_request_t r = request(1);
  r.vehicle_id = 0;
  r.start[0] = -5.0, r.start[1] = 0.0, r.start[2] = 1.2;
  r.goal[0] = 10.0, r.goal[1] = 0.0, r.goal[2] = 1.2;
  r.depth = tdo::plan_request_t::DEPTH_SEARCH;
  r.lambda_turn = 0.0;
  r.mu = 0.0;
  r.theta_max = 0.0;
  r.first_meet = false;
  ASSERT_TRUE(bus.publish(cfg.request_channel, r));
  pump();
  ASSERT_EQ(traj.size(), 1u);
  EXPECT_EQ(traj[0].status, "ok") << traj[0].detail;
  EXPECT_EQ(traj[0].map_id, 79);
  EXPECT_NEAR(traj[0].search_cost, 15.2, 1e-3);
}

// One message used to kill the node: an OcTree header and 300,000 bytes of 0xff (every node an
// inner node) made OctoMap's reader recurse ~87,000 deep. The stream is checked first: refused as
// bad_encoding (corrupt OcTree, too_deep), counted in the heartbeat, and a good map still loads.
TEST(PlannerNodeOctoMap, GivenOcTreeOfAllInnerNodesWhenSentThenRefusedCountedAndNodeServes) {
  tdo_lcm::Bus bus("memq://");
  tdo_lcm::PlannerConfig cfg;
  cfg.max_nx = 24;
  cfg.max_ny = 24;
  cfg.max_nz = 12;
  cfg.max_nodes = 100000;
  tdo_lcm::PlannerNode node(&bus, cfg);
  std::string error;
  ASSERT_TRUE(node.start(&error)) << error;
  const std::string header = "# Octomap OcTree binary file\nid OcTree\nsize 1000\nres 0.1\ndata\n";
  tdo::map_t m = wall_map(9);
  m.vehicle_id = -1;
  m.runs.clear();
  m.n_runs = 0;
  m.encoding = tdo::map_t::ENCODING_OCTOMAP_BT;
  m.data.assign(header.begin(), header.end());
  m.data.resize(header.size() + 300000u, uint8_t{0xff});
  m.n_bytes = static_cast<int32_t>(m.data.size());
  tdo::map_t color = m;  // a well-formed tree of another type
  const std::string color_header =
      "# Octomap OcTree binary file\nid ColorOcTree\nsize 9\nres 0.1\ndata\n";
  color.data.assign(color_header.begin(), color_header.end());
  for (uint8_t b : {uint8_t{0xaa}, uint8_t{0xaa}}) color.data.push_back(b);
  color.n_bytes = static_cast<int32_t>(color.data.size());
  ASSERT_TRUE(bus.publish(cfg.map_channel, m));
  ASSERT_TRUE(bus.publish(cfg.map_channel, color));
  ASSERT_TRUE(bus.publish(cfg.map_channel, wall_map(10)));
  for (int i = 0; i < 10 && bus.handle_timeout(0) > 0; ++i) {
  }
  EXPECT_EQ(node.counters().received, 3);
  EXPECT_EQ(node.counters().reasons.at("map.bad_encoding"), 2);
  EXPECT_EQ(node.map_id(), 10);
  tdo::map_t rle{};
  const tdo_lcm::Check c = tdo_lcm::octomap_to_rle(m, 1u << 20, &rle);
  EXPECT_EQ(c.reason, tdo_lcm::Reason::bad_encoding);
  EXPECT_NE(c.detail.find("corrupt OcTree (too_deep)"), std::string::npos) << c.detail;
  const tdo_lcm::Check t = tdo_lcm::octomap_to_rle(color, 1u << 20, &rle);
  EXPECT_NE(t.detail.find("corrupt OcTree (wrong_tree_type)"), std::string::npos) << t.detail;
}

}  // namespace
#endif
