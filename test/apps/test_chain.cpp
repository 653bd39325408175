// The whole LCM system in one process over memq://, stepped deterministically: tdo-sim publishes
// Map6 and the vehicle, tdo-planner plans the requested flight, tdo-avoid follows it around the 12
// moving spheres, tdo-sim flies the setpoints, in lock-step (one state -> one setpoint -> one
// step), for a bounded number of messages. The vehicle must reach the goal, and checks made here,
// independently of the library, must find no collision with a column or a mover.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "avoid_node.h"
#include "chain_configs.h"
#include "node_test_util.h"
#include "planner_node.h"
#include "sim_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/wire.h"

namespace {

constexpr int64_t kT0 = tdo_test::kChainT0;

using tdo_test::box_distance;
using tdo_test::collect;

struct Flight {
  bool arrived = false;
  double time_s = 0.0;      // simulated time at arrival
  double min_static = 1e9;  // m, closest approach of the vehicle centre to a column
  double min_mover = 1e9;   // m, smallest surface gap to a mover (minus the vehicle radius)
  std::size_t states = 0;
  std::vector<double> final_p;
};

/** One whole run; every check of the run inside; the states it produced in `states_out`. */
void fly_map6(tdo_follower_kind kind, std::vector<tdo::vehicle_state_t>* states_out) {
  tdo_lcm::Bus bus("memq://");  // first: outlives the nodes
  ASSERT_TRUE(bus.good());
  std::vector<tdo::map_t> maps;
  std::vector<tdo::trajectory_t> trajs;
  std::vector<tdo::feasibility_t> feas;
  std::vector<tdo::setpoint_t> setpoints;
  std::vector<tdo::vehicle_state_t> states;
  std::vector<tdo::obstacles_t> obstacles;
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelMap, collect(&maps)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelTrajectory, collect(&trajs)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelFeasibility, collect(&feas)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelSetpoint, collect(&setpoints)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelObstacles, collect(&obstacles)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelVehicleState, collect(&states)));

  tdo_test::ChainConfigs cc = tdo_test::map6_chain(std::string(TDO_MAPS_DIR) + "/map6.tdomap");
  cc.avoid.kind = kind;
  const tdo_lcm::AvoidConfig& ac = cc.avoid;
  tdo_test::Map6Chain chain(&bus, cc, 600);  // the simulator publishes the map and the first state
  std::string error;
  ASSERT_TRUE(chain.start(&error)) << error;
  std::vector<std::vector<double>> boxes;
  bool requested = false;
  Flight run;
  std::size_t seen_states = 0;
  // Bounded: at most 60 s of flight at 50 Hz, three messages per step.
  const int max_messages = 3 * 50 * 60;
  for (int i = 0; i < max_messages && !run.arrived; ++i) {
    if (bus.handle_timeout(0) <= 0) break;  // nothing in flight: the chain stopped
    if (!requested && chain.planner.map_id() == 1) {
      ASSERT_TRUE(bus.publish(tdo_lcm::kChannelPlanRequest, chain.request));
      requested = true;
    }
    if (boxes.empty() && !maps.empty()) boxes = maps[0].boxes;
    // Independent checks on every new state, against the obstacles published with it.
    for (; seen_states < states.size(); ++seen_states) {
      const tdo::vehicle_state_t& s = states[seen_states];
      ASSERT_FALSE(boxes.empty());
      for (const auto& b : boxes)
        run.min_static = std::min(run.min_static, box_distance(s.position, b));
      ASSERT_FALSE(obstacles.empty());
      const tdo::obstacles_t& o = obstacles.back();
      ASSERT_EQ(o.utime, s.utime);  // published together, movers first
      for (int k = 0; k < o.n; ++k)
        run.min_mover = std::min(run.min_mover, tdo_test::dist3(s.position, o.position[k].data()) -
                                                    o.radius[k] - ac.vehicle_radius);
      if (tdo_test::dist3(s.position, chain.goal_p) < 0.25) {
        run.arrived = true;
        run.time_s = static_cast<double>(s.utime - kT0) * 1e-6;
      }
    }
  }
  run.states = states.size();
  ASSERT_FALSE(states.empty());
  run.final_p.assign(states.back().position, states.back().position + 3);

  // The plan: answered once, feasible, for this vehicle and request.
  ASSERT_TRUE(requested);
  ASSERT_EQ(trajs.size(), 1u);
  EXPECT_EQ(trajs[0].request_id, 600);
  EXPECT_EQ(trajs[0].status, "ok") << trajs[0].detail;
  EXPECT_EQ(trajs[0].map_id, 1);
  ASSERT_EQ(feas.size(), 1u);
  EXPECT_TRUE(feas[0].ok);
  // The follower followed it: every setpoint after the plan names it.
  std::size_t followed = 0;
  for (const auto& sp : setpoints) {
    if (sp.request_id == 600) ++followed;
    EXPECT_EQ(sp.status, "ok");
  }
  EXPECT_GT(followed, 100u);
  EXPECT_EQ(setpoints.back().request_id, 600);

  EXPECT_TRUE(run.arrived) << "after " << run.states << " states at (" << run.final_p[0] << ", "
                           << run.final_p[1] << ", " << run.final_p[2] << ")";
  // Independent collision checks: the vehicle centre stays at least its radius from every column
  // and no mover sphere touches the vehicle sphere.
  EXPECT_GE(run.min_static, ac.vehicle_radius) << "closest approach to a column";
  EXPECT_GT(run.min_mover, 0.0) << "smallest gap to a mover";
  // The simulator's own counters agree.
  EXPECT_EQ(chain.sim.counters().collision_steps, 0);
  EXPECT_EQ(chain.sim.counters().rejected, 0);
  EXPECT_EQ(chain.avoid.counters().rejected, 0);
  EXPECT_EQ(chain.planner.counters().rejected, 0);
  std::printf(
      "[chain] %s: arrived %d after %.2f s of simulated time, %zu states, closest column "
      "%.3f m, smallest mover gap %.3f m\n",
      kind == TDO_FOLLOWER_APF ? "apf" : "eapf", run.arrived ? 1 : 0, run.time_s, run.states,
      run.min_static, run.min_mover);
  *states_out = std::move(states);
}

class ChainTest : public ::testing::TestWithParam<tdo_follower_kind> {};

TEST_P(ChainTest, PlannerFollowerAndSimulatorFlyMap6ToTheGoal) {
  std::vector<tdo::vehicle_state_t> states;
  fly_map6(GetParam(), &states);
}

// Lock-step over memq:// is deterministic: the same run twice gives the same states, bit for bit.
TEST_P(ChainTest, TwoRunsAreIdenticalBitForBit) {
  std::vector<tdo::vehicle_state_t> a, b;
  fly_map6(GetParam(), &a);
  fly_map6(GetParam(), &b);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].utime, b[k].utime) << k;
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(a[k].position[i], b[k].position[i]) << k;
      ASSERT_EQ(a[k].velocity[i], b[k].velocity[i]) << k;
      ASSERT_EQ(a[k].acceleration[i], b[k].acceleration[i]) << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Followers, ChainTest, ::testing::Values(TDO_FOLLOWER_EAPF),
                         [](const ::testing::TestParamInfo<tdo_follower_kind>& i) {
                           return std::string(i.param == TDO_FOLLOWER_APF ? "apf" : "eapf");
                         });

}  // namespace
