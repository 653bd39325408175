// Map updates over a real LCM (memq://): tdo-planner's node and tdo-publish-map's node on one bus.
// The wall scenario of issue 20: a map, a plan, an update with a wall across the route, the next
// plan goes around it; a wall that closes every way gives a named status; a gap in the updates
// makes the node report a stale map, refuse to plan, ask for the whole map and plan again once
// the publisher answers. Bad updates are counted by reason and leave the node serving.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "map_publisher.h"
#include "node_test_util.h"
#include "planner_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"

namespace {

using tdo_test::collect;

constexpr int32_t kVehicle = 2;
constexpr double kClearance = 0.5;  // m, the map's hint

/** 20 x 12 x 6 m at 0.5 m, free: the straight route at y = 6 m, z = 3 m. */
tdo::map_t open_map(int64_t map_id) {
  const tdo_grid_desc d{40, 24, 12, 0.5, {0.0, 0.0, 0.0}};
  tdo::map_t m{};
  EXPECT_TRUE(tdo_lcm::map_from_occupancy(d, {}, {}, kClearance, &m).ok());
  m.map_id = map_id;
  m.vehicle_id = -1;
  return m;
}

// A wall across the route at x = 9.5..10.5 m, open for y > 8.5 m (3.5 m of the 12 m width).
const tdo_box kWall{{9.5, -1.0, -1.0}, {10.5, 8.5, 7.0}};
// The rest of the wall: with both, every way from x < 9.5 to x > 10.5 is closed.
const tdo_box kClosing{{9.5, 8.0, -1.0}, {10.5, 13.0, 7.0}};

tdo::plan_request_t request(int64_t id) {
  tdo_plan_request r{};
  tdo_plan_params_default(&r.params);
  r.start = tdo_vec3{2.25, 6.25, 3.25};
  r.goal = tdo_vec3{17.75, 6.25, 3.25};
  tdo::plan_request_t m{};
  tdo_lcm::plan_request_to_msg(r, -1.0, &m);
  m.request_id = id;
  m.seq = id;
  m.vehicle_id = kVehicle;
  m.map_id = -1;
  m.samples = tdo::plan_request_t::SAMPLES_ON;
  return m;
}

double distance_to_box(double x, double y, double z, const tdo_box& b) {
  const double dx = std::max({b.min.x - x, 0.0, x - b.max.x});
  const double dy = std::max({b.min.y - y, 0.0, y - b.max.y});
  const double dz = std::max({b.min.z - z, 0.0, z - b.max.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/** Smallest distance (m) of the answer's samples to box b. */
double min_distance(const tdo::trajectory_t& t, const tdo_box& b) {
  double best = 1e300;
  for (const auto& s : t.samples) best = std::min(best, distance_to_box(s[1], s[2], s[3], b));
  return best;
}

class MapUpdateMemq
    : public tdo_test::NodeTest<tdo_lcm::PlannerNode, tdo_lcm::PlannerConfig, 1000> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(bus_.good());
    cfg_.vehicle_id = kVehicle;
    cfg_.max_nx = 40;
    cfg_.max_ny = 24;
    cfg_.max_nz = 12;
    cfg_.max_nodes = 400000;
    cfg_.max_boxes = 16;
    cfg_.max_clearance_ratio = 2.0;
    cfg_.heartbeat_period_s = 0.0;
    node_ = std::make_unique<tdo_lcm::PlannerNode>(&bus_, cfg_);
    std::string error;
    ASSERT_TRUE(node_->start(&error)) << error;
    ASSERT_TRUE(bus_.subscribe(cfg_.trajectory_channel, collect(&traj_)));
    ASSERT_TRUE(bus_.subscribe(cfg_.map_request_channel, collect(&map_requests_)));
    pub_ =
        std::make_unique<tdo_lcm::MapPublisher>(&bus_, tdo_lcm::MapPublisherConfig{}, open_map(40));
  }
  /** The publisher answers map requests from now on. */
  void serve() {
    std::string error;
    ASSERT_TRUE(pub_->start(&error)) << error;
  }
  const tdo::trajectory_t& plan(int64_t id) {
    send(cfg_.request_channel, request(id));
    EXPECT_FALSE(traj_.empty());
    if (traj_.empty()) traj_.emplace_back();
    EXPECT_EQ(traj_.back().request_id, id);
    return traj_.back();
  }
  void publish_boxes(const std::vector<tdo_box>& b) {
    ASSERT_TRUE(pub_->publish_boxes(b));
    pump();
  }
  /** An update from the test itself (a lost, repeated or bad one). */
  tdo::map_update_t update(int64_t map_id, int64_t seq) {
    tdo::map_update_t u{};
    u.map_id = map_id;
    u.seq = seq;
    u.vehicle_id = -1;
    return u;
  }
  int64_t heartbeat_reason(const std::string& key) const {
    const tdo::status_t s = node_->status_message();
    for (int32_t k = 0; k < s.n_reasons; ++k)
      if (s.reason[static_cast<std::size_t>(k)] == key)
        return s.reason_count[static_cast<std::size_t>(k)];
    return 0;
  }

  std::vector<tdo::trajectory_t> traj_;
  std::vector<tdo::map_request_t> map_requests_;
  std::unique_ptr<tdo_lcm::MapPublisher> pub_;
};

TEST_F(MapUpdateMemq, GivenAPlan_WhenAWallIsPublishedAcrossTheRoute_ThenTheNextPlanGoesAround) {
  ASSERT_TRUE(pub_->publish_map());
  pump();
  ASSERT_EQ(node_->map_id(), 40);
  const tdo::trajectory_t before = plan(1);
  ASSERT_EQ(before.status, "ok");
  EXPECT_EQ(min_distance(before, kWall), 0.0) << "the first plan must cross where the wall comes";

  publish_boxes({kWall});
  EXPECT_EQ(node_->counters().updates_applied, 1);
  EXPECT_FALSE(node_->map_stale());
  const tdo::trajectory_t after = plan(2);
  ASSERT_EQ(after.status, "ok") << after.detail;
  EXPECT_EQ(after.map_id, 40);
  EXPECT_GE(min_distance(after, kWall), kClearance - 1e-9) << "the plan must keep the clearance";
  bool through_gap = false;  // it goes through the opening at y > 8.5 m
  for (const auto& s : after.samples)
    through_gap = through_gap || (s[1] > 9.5 && s[1] < 10.5 && s[2] > 8.5);
  EXPECT_TRUE(through_gap);
  EXPECT_NEAR(after.samples.back()[1], 17.75, 1e-9);
}

TEST_F(MapUpdateMemq, GivenAWallThatClosesEveryWay_WhenPlanned_ThenNoPathNotOk) {
  ASSERT_TRUE(pub_->publish_map());
  pump();
  publish_boxes({kWall});
  publish_boxes({kClosing});
  EXPECT_EQ(node_->counters().updates_applied, 2);
  const tdo::trajectory_t t = plan(3);
  EXPECT_EQ(t.status, "no_path");
  EXPECT_EQ(t.status_code, static_cast<int32_t>(TDO_ERR_NO_PATH));
  EXPECT_EQ(t.n_samples, 0);
  EXPECT_EQ(node_->counters().failed, 1);
  EXPECT_EQ(node_->counters().succeeded, 0);
}

TEST_F(MapUpdateMemq, GivenASeqGap_WhenARequestComes_ThenMapStaleAndAWholeMapIsAskedFor) {
  ASSERT_TRUE(pub_->publish_map());
  pump();
  publish_boxes({kWall});  // seq 1, applied
  // seq 2 (the closing wall) is lost: the publisher sends it, the test drops it by sending it
  // to nobody; the next one the node sees is seq 3.
  tdo::map_update_t u3 = update(40, 3);
  send(cfg_.map_update_channel, u3);
  EXPECT_TRUE(node_->map_stale());
  EXPECT_EQ(node_->counters().updates_applied, 1);
  EXPECT_EQ(heartbeat_reason("update.gap"), 1);
  EXPECT_EQ(heartbeat_reason("state.map_stale"), 1);
  ASSERT_EQ(map_requests_.size(), 1u);
  EXPECT_EQ(map_requests_[0].map_id, 40);
  EXPECT_EQ(map_requests_[0].last_seq, 1);
  EXPECT_EQ(map_requests_[0].reason, "gap");
  EXPECT_EQ(map_requests_[0].program, "tdo-planner");

  // No plan on the stale map: a named refusal, never ok.
  const tdo::trajectory_t refused = plan(4);
  EXPECT_EQ(refused.status, "map_stale");
  EXPECT_EQ(refused.status_code, tdo::trajectory_t::STATUS_REJECTED);
  EXPECT_EQ(refused.n_samples, 0);
  EXPECT_EQ(heartbeat_reason("request.map_stale"), 1);
  // Later updates of the stale map are not applied either.
  send(cfg_.map_update_channel, update(40, 4));
  EXPECT_EQ(heartbeat_reason("update.map_stale"), 1);

  // The publisher answers the request the node repeats (one heartbeat period later) with the
  // whole map under a new id: the node plans again, around the wall.
  serve();
  node_->poll(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  pump();
  ASSERT_EQ(map_requests_.size(), 2u);
  EXPECT_EQ(pub_->requests_answered(), 1);
  EXPECT_FALSE(node_->map_stale());
  EXPECT_EQ(node_->map_id(), 41);
  EXPECT_EQ(heartbeat_reason("state.map_stale"), 0);
  const tdo::trajectory_t again = plan(5);
  ASSERT_EQ(again.status, "ok") << again.detail;
  EXPECT_EQ(again.map_id, 41);
  EXPECT_GE(min_distance(again, kWall), kClearance - 1e-9);
  // And the updates of the new map apply from seq 1.
  publish_boxes({kClosing});
  EXPECT_EQ(pub_->seq(), 1);
  EXPECT_EQ(node_->counters().updates_applied, 2);
  EXPECT_EQ(plan(6).status, "no_path");
}

TEST_F(MapUpdateMemq, GivenBadUpdates_WhenReceived_ThenEachIsCountedByNameAndServingGoesOn) {
  send(cfg_.map_update_channel, update(40, 1));  // before any map
  EXPECT_EQ(heartbeat_reason("update.no_map"), 1);
  ASSERT_TRUE(pub_->publish_map());
  pump();
  publish_boxes({kWall});                        // seq 1 applied
  send(cfg_.map_update_channel, update(40, 1));  // repeated
  send(cfg_.map_update_channel, update(40, 0));  // seq < 1
  send(cfg_.map_update_channel, update(39, 2));  // another map
  tdo::map_update_t other_vehicle = update(40, 2);
  other_vehicle.vehicle_id = kVehicle + 1;
  send(cfg_.map_update_channel, other_vehicle);
  tdo::map_update_t nan_box = update(40, 2);
  nan_box.boxes.push_back({1.0, 1.0, 1.0, std::nan(""), 2.0, 2.0});
  nan_box.n_boxes = 1;
  send(cfg_.map_update_channel, nan_box);
  EXPECT_EQ(heartbeat_reason("update.stale_update"), 1);
  EXPECT_EQ(heartbeat_reason("update.out_of_range"), 1);
  EXPECT_EQ(heartbeat_reason("update.other_map"), 1);
  EXPECT_EQ(heartbeat_reason("update.other_vehicle"), 1);
  EXPECT_EQ(heartbeat_reason("update.non_finite"), 1);
  EXPECT_FALSE(node_->map_stale()) << "refused by its content checks, before its place in order";
  EXPECT_EQ(plan(7).status, "ok");

  // A contradictory update is the next one but cannot be applied: the map is stale.
  tdo::map_update_t bad = update(40, 2);
  bad.set = {{3, 3, 3}};
  bad.n_set = 1;
  bad.clear = {{3, 3, 3}};
  bad.n_clear = 1;
  send(cfg_.map_update_channel, bad);
  EXPECT_EQ(heartbeat_reason("update.contradictory"), 1);
  EXPECT_TRUE(node_->map_stale());
  ASSERT_EQ(map_requests_.size(), 1u);
  EXPECT_EQ(map_requests_[0].reason, "update_contradictory");
  EXPECT_EQ(plan(8).status, "map_stale");
  // A voxel outside the grid, after the whole map came back, likewise.
  serve();
  node_->poll(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  pump();
  ASSERT_FALSE(node_->map_stale());
  tdo::map_update_t outside = update(node_->map_id(), 1);
  outside.set = {{40, 0, 0}};
  outside.n_set = 1;
  send(cfg_.map_update_channel, outside);
  EXPECT_EQ(heartbeat_reason("update.out_of_range"), 2);
  // Stale at once, asked for the whole map, which the serving publisher sends right away (the
  // same id: no update of it was published since).
  ASSERT_EQ(map_requests_.size(), 3u);
  EXPECT_EQ(map_requests_[2].reason, "update_out_of_range");
  EXPECT_FALSE(node_->map_stale());
  EXPECT_EQ(node_->counters().maps_loaded, 3);
  EXPECT_EQ(plan(9).status, "ok");
  // no_map, stale_update, out_of_range (seq 0), other_map, non_finite, contradictory,
  // request.map_stale, out_of_range (voxel): rejected; other_vehicle: ignored.
  const auto& c = node_->counters();
  EXPECT_EQ(c.rejected, 8);
  EXPECT_EQ(c.ignored, 1);
}

}  // namespace
