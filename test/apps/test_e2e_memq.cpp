// In-process end to end over memq:// on Map6: the map file published as a map_t, a plan request,
// the trajectory and the feasibility report, checked independently of the planner (distance of
// every sample to every box, speeds from the samples). Stages a later follower (tdo-avoid:
// setpoints) and simulator (tdo-sim: vehicle states) join by subscribing on the same bus in SetUp
// and adding their checks after plan(); see the comment at the end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "planner_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/wire.h"

namespace {

/** m, distance from p to an axis-aligned box (0 inside). */
double box_distance(const double p[3], const std::vector<double>& b) {
  double s = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double lo = b[static_cast<std::size_t>(a)];
    const double hi = b[static_cast<std::size_t>(a + 3)];
    const double d = std::max({lo - p[a], 0.0, p[a] - hi});
    s += d * d;
  }
  return std::sqrt(s);
}

class EndToEndMemq : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(bus_.good());
    std::string error;
    ASSERT_TRUE(tdo_lcm::map_msg_from_file(TDO_MAPS_DIR "/map6.tdomap", 0.5, &map_, &info_, &error))
        << error;
    ASSERT_TRUE(info_.has_query);
    EXPECT_EQ(info_.movers, 12u);  // Map6's moving spheres: the simulator's, not in the map
    map_.map_id = 6;
    tdo_lcm::PlannerConfig cfg;
    cfg.max_nx = 50;
    cfg.max_ny = 50;
    cfg.max_nz = 20;
    cfg.max_nodes = 500000;
    cfg.max_boxes = 512;
    planner_ = std::make_unique<tdo_lcm::PlannerNode>(&bus_, cfg);
    ASSERT_TRUE(planner_->start(&error)) << error;
    bus_.subscribe(tdo_lcm::kChannelTrajectory,
                   [this](const void* d, std::size_t n, const std::string&) {
                     tdo::trajectory_t m{};
                     ASSERT_TRUE(tdo_lcm::decode(d, n, &m).ok());
                     traj_.push_back(m);
                   });
    bus_.subscribe(tdo_lcm::kChannelFeasibility,
                   [this](const void* d, std::size_t n, const std::string&) {
                     tdo::feasibility_t m{};
                     ASSERT_TRUE(tdo_lcm::decode(d, n, &m).ok());
                     feas_.push_back(m);
                   });
    // Later: the follower node (TDO_TRAJECTORY + TDO_UAV_STATE -> TDO_SETPOINT) and the simulator
    // node (TDO_SETPOINT -> TDO_UAV_STATE, TDO_OBSTACLES) are created here on the same bus.
  }

  void pump() {
    for (int i = 0; i < 10000 && bus_.handle_timeout(0) > 0; ++i) {
    }
  }

  /** Publish the map and one request, as separate publishers would; wait for the answers. */
  void plan(int64_t request_id) {
    ASSERT_TRUE(bus_.publish(tdo_lcm::kChannelMap, map_));
    tdo_plan_request r{};
    tdo_plan_params_default(&r.params);
    r.start = info_.start;
    r.goal = info_.goal;
    tdo::plan_request_t m{};
    tdo_lcm::plan_request_to_msg(r, -1.0, &m);
    m.request_id = request_id;
    m.vehicle_id = 0;
    m.map_id = 6;
    m.samples = tdo::plan_request_t::SAMPLES_ON;  // the checks below read the samples
    ASSERT_TRUE(bus_.publish(tdo_lcm::kChannelPlanRequest, m));
    pump();
  }

  tdo_lcm::Bus bus_{"memq://"};
  tdo::map_t map_{};
  tdo_lcm::MapFileInfo info_;
  std::unique_ptr<tdo_lcm::PlannerNode> planner_;
  std::vector<tdo::trajectory_t> traj_;
  std::vector<tdo::feasibility_t> feas_;
};

TEST_F(EndToEndMemq, Map6MapRequestTrajectoryReport) {
  plan(42);
  ASSERT_EQ(traj_.size(), 1u);
  ASSERT_EQ(feas_.size(), 1u);
  const tdo::trajectory_t& t = traj_[0];
  const tdo::feasibility_t& f = feas_[0];
  ASSERT_EQ(t.status, "ok") << t.detail;
  EXPECT_EQ(t.request_id, 42);
  EXPECT_EQ(t.map_id, 6);
  EXPECT_EQ(f.request_id, 42);
  EXPECT_TRUE(f.checked);
  EXPECT_TRUE(f.ok);
  EXPECT_EQ(f.clearance, 0.5);
  ASSERT_GT(t.n_samples, 100);

  // Starts at the start and ends at the goal, at rest.
  const auto& s0 = t.samples.front();
  const auto& s1 = t.samples.back();
  const double start[3] = {info_.start.x, info_.start.y, info_.start.z};
  const double goal[3] = {info_.goal.x, info_.goal.y, info_.goal.z};
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_NEAR(s0[1 + a], start[a], 1e-9);
    EXPECT_NEAR(s1[1 + a], goal[a], 1e-6);
    EXPECT_NEAR(s1[4 + a], 0.0, 1e-6);
  }

  // Independent checks: every sample keeps the clearance from every column of the map message,
  // stays in the map, and the speed from the samples' positions stays under v_max.
  double min_dist = HUGE_VAL;
  double max_fd_speed = 0.0;
  for (std::size_t i = 0; i < t.samples.size(); ++i) {
    const double p[3] = {t.samples[i][1], t.samples[i][2], t.samples[i][3]};
    for (const auto& b : map_.boxes) min_dist = std::min(min_dist, box_distance(p, b));
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], map_.origin[a]);
      EXPECT_LE(p[a], map_.origin[a] + map_.resolution * map_.size[a]);
    }
    if (i > 0) {
      const double dt = t.samples[i][0] - t.samples[i - 1][0];
      ASSERT_GT(dt, 0.0);
      double d2 = 0.0;
      for (std::size_t a = 1; a <= 3; ++a) {
        const double d = t.samples[i][a] - t.samples[i - 1][a];
        d2 += d * d;
      }
      max_fd_speed = std::max(max_fd_speed, std::sqrt(d2) / dt);
    }
  }
  EXPECT_GE(min_dist, 0.5 - 1e-9);
  EXPECT_LE(max_fd_speed, 3.0 + 1e-6);
  EXPECT_GE(f.min_clearance, 0.5 - 1e-9);
  EXPECT_LE(f.max_speed, f.v_max + 1e-9);
  // The route is longer than the straight line and no longer than it need be (README: 77.5 m
  // optimal grid path at 0.5 m clearance; smoothing shortens corners).
  const double straight = std::sqrt((goal[0] - start[0]) * (goal[0] - start[0]) +
                                    (goal[1] - start[1]) * (goal[1] - start[1]) +
                                    (goal[2] - start[2]) * (goal[2] - start[2]));
  EXPECT_GT(t.length_m, straight);
  EXPECT_LT(t.length_m, 1.1 * 77.5);
  EXPECT_EQ(planner_->counters().succeeded, 1);

  // Follower and simulator (later, other issue): pump until the simulated vehicle state is within
  // tolerance of the goal, checking setpoints against the trajectory and the moving spheres.
}

}  // namespace
