// tdo-request's core (apps/tdo-request/request_cli.h) against tdo-planner's node in-process over
// memq://: a request with only start and goal (use_defaults) is planned with the library's
// defaults; --param sets one field and clears its bit; bad parameters are refused by name; the
// answer prints as tdo-plan's summary table.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "planner_node.h"
#include "request_cli.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/wire.h"

namespace {

using R = tdo::plan_request_t;

TEST(RequestCli, GivenParamsThenEachSetsItsFieldAndClearsItsDefaultBit) {
  const double a[3] = {1, 2, 3}, b[3] = {4, 5, 6};
  R m{};
  std::string error;
  ASSERT_TRUE(tdo_lcm::build_request(a, b, {}, &m, &error)) << error;
  EXPECT_EQ(m.use_defaults, R::USE_DEFAULT_ALL);
  EXPECT_EQ(m.goal[2], 6.0);
  ASSERT_TRUE(tdo_lcm::build_request(a, b, {"v_max=2.5", "smoothing=1", "shorten=0"}, &m, &error))
      << error;
  EXPECT_EQ(m.v_max, 2.5);
  EXPECT_EQ(m.smoothing, R::SMOOTHING_ARC);
  EXPECT_FALSE(m.shorten);
  EXPECT_EQ(m.use_defaults, R::USE_DEFAULT_ALL & ~(R::USE_DEFAULT_V_MAX | R::USE_DEFAULT_SMOOTHING |
                                                   R::USE_DEFAULT_SHORTEN));
  EXPECT_FALSE(tdo_lcm::build_request(a, b, {"frob=1"}, &m, &error));
  EXPECT_NE(error.find("unknown parameter 'frob'"), std::string::npos) << error;
  EXPECT_FALSE(tdo_lcm::build_request(a, b, {"smoothing=7"}, &m, &error));
  EXPECT_NE(error.find("whole number in [0, 2]"), std::string::npos) << error;
  EXPECT_FALSE(tdo_lcm::build_request(a, b, {"v_max=fast"}, &m, &error));
  EXPECT_FALSE(tdo_lcm::build_request(a, b, {"v_max"}, &m, &error));
  EXPECT_FALSE(tdo_lcm::build_request(a, b, {"dt=nan"}, &m, &error));
}

TEST(RequestCli, GivenOnlyStartAndGoalWhenPlannedThenTheSummaryIsTdoPlansTable) {
  tdo_lcm::Bus bus("memq://");
  tdo_lcm::PlannerConfig cfg;
  cfg.max_nx = 20;
  cfg.max_ny = 20;
  cfg.max_nz = 20;
  cfg.max_nodes = 200000;
  cfg.max_boxes = 64;
  tdo_lcm::PlannerNode node(&bus, cfg);
  std::string error;
  ASSERT_TRUE(node.start(&error)) << error;
  tdo::map_t map{};
  tdo_lcm::MapFileInfo info;
  ASSERT_TRUE(tdo_lcm::map_msg_from_file(TDO_MAPS_DIR "/map1.tdomap", 0.5, &map, &info, &error));
  map.map_id = 1;
  std::vector<std::pair<tdo::trajectory_t, std::size_t>> traj;
  std::vector<tdo::feasibility_t> feas;
  bus.subscribe(tdo_lcm::kChannelTrajectory, [&](const void* d, std::size_t n, const std::string&) {
    tdo::trajectory_t m{};
    ASSERT_TRUE(tdo_lcm::decode(d, n, &m).ok());
    traj.emplace_back(m, n);
  });
  bus.subscribe(tdo_lcm::kChannelFeasibility,
                [&](const void* d, std::size_t n, const std::string&) {
                  tdo::feasibility_t m{};
                  ASSERT_TRUE(tdo_lcm::decode(d, n, &m).ok());
                  feas.push_back(m);
                });
  ASSERT_TRUE(bus.publish(tdo_lcm::kChannelMap, map));
  const auto pump = [&] {
    for (int i = 0; i < 1000 && bus.handle_timeout(0) > 0; ++i) {
    }
  };
  pump();
  const double s[3] = {info.start.x, info.start.y, info.start.z};
  const double g[3] = {info.goal.x, info.goal.y, info.goal.z};
  R req{};
  ASSERT_TRUE(tdo_lcm::build_request(s, g, {}, &req, &error)) << error;
  req.request_id = 5;
  req.seq = 1;
  ASSERT_TRUE(bus.publish(tdo_lcm::kChannelPlanRequest, req));
  pump();
  ASSERT_EQ(traj.size(), 1u);
  ASSERT_EQ(feas.size(), 1u);
  const std::string out = tdo_lcm::answer_summary(req, traj[0].first, feas[0], traj[0].second);
  // tdo-plan's rows in tdo-plan's order, around them the request's own.
  std::size_t at = 0;
  for (const char* key :
       {"request ", "start -> goal ", "status           ok", "grid path ", "waypoints ",
        "length_m ", "turns ", "min_clearance_m ", "avg_curvature ", "smoothness ", "energy ",
        "flight_time_s ", "feasible         yes", "expansions ", "plan_time_ms ", "trajectory "}) {
    const std::size_t p = out.find(key, at);
    ASSERT_NE(p, std::string::npos) << key << " after " << at << " in\n" << out;
    at = p;
  }
  EXPECT_NE(out.find("(seq 1)"), std::string::npos) << out;
  // Refused: the field and the reason are printed.
  ASSERT_TRUE(tdo_lcm::build_request(s, g, {"v_max=0"}, &req, &error)) << error;
  req.request_id = 6;
  ASSERT_TRUE(bus.publish(tdo_lcm::kChannelPlanRequest, req));
  pump();
  ASSERT_EQ(traj.size(), 2u);
  const std::string refused = tdo_lcm::answer_summary(req, traj[1].first, feas[1], traj[1].second);
  EXPECT_NE(refused.find("status           out_of_range"), std::string::npos) << refused;
  EXPECT_NE(refused.find("refused field    v_max"), std::string::npos) << refused;
}

}  // namespace
