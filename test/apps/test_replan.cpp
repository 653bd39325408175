// Replanning over LCM, in one process over memq://, stepped deterministically (lock-step, as
// test_chain.cpp): tdo-sim flies Map6, tdo-planner plans, tdo-avoid follows. At t = 6 s a wall is
// published across the route as a map update (as tdo-publish-map would). With a way around it the
// follower brakes, replans from the predicted state and the vehicle reaches the goal without
// touching the wall or a column; with none it stops safely and says so by name, never "ok". The
// checks are made here, against the true world (the map's boxes and the wall), from the states
// tdo-sim published, independently of the programs' own counters; the setpoints across a replan
// are checked with finite differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
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
constexpr double kRadius = 0.25;  // m, the vehicle's
constexpr double kDt = 0.02;      // s, 50 Hz

using tdo_test::collect;

using tdo_test::box_distance;
using tdo_test::dist3;
using tdo_test::norm3;

enum class Wall { with_gap, closed };

/** What one flight produced, recorded from the bus. */
struct Flight {
  std::vector<tdo::vehicle_state_t> states;
  std::vector<tdo::setpoint_t> setpoints;
  std::vector<tdo::plan_request_t> requests;
  std::vector<tdo::trajectory_t> trajectories;
  std::vector<std::vector<double>> world;  // the true boxes: the map's and the wall
  std::size_t wall_state = 0;              // index of the state after which the wall came
  std::size_t wall_setpoint = 0;           // the first setpoint for a state after it
  bool arrived = false;
  double min_static = 1e9;  // m, closest approach of the centre to the true world
  tdo_lcm::AvoidCounters avoid;
  tdo_lcm::SimCounters sim;
};

/**
 * The wall, 4 m ahead of `s` along the main horizontal axis of its velocity, 0.6 m thick, the
 * whole height of the map; with_gap: 12 m wide (a way round its ends), closed: across the map.
 */
std::vector<double> wall_ahead(const tdo::vehicle_state_t& s, Wall kind) {
  const int a = std::fabs(s.velocity[0]) >= std::fabs(s.velocity[1]) ? 0 : 1, b = 1 - a;
  const double sign = s.velocity[a] >= 0.0 ? 1.0 : -1.0;
  const double c = s.position[a] + sign * 4.0;
  std::vector<double> w(6);
  w[a] = c - 0.3;
  w[a + 3] = c + 0.3;
  w[b] = kind == Wall::closed ? -1.0 : s.position[b] - 6.0;
  w[b + 3] = kind == Wall::closed ? 51.0 : s.position[b] + 6.0;
  w[2] = -1.0;
  w[5] = 21.0;
  return w;
}

/** Fly Map6 (no movers) with the wall published at t = 6 s; everything recorded in `f`. */
void fly(Wall kind, Flight* f) {
  tdo_lcm::Bus bus("memq://");  // first: outlives the nodes
  ASSERT_TRUE(bus.good());
  std::vector<tdo::map_t> maps;
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelMap, collect(&maps)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelTrajectory, collect(&f->trajectories)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelSetpoint, collect(&f->setpoints)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelVehicleState, collect(&f->states)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelPlanRequest, collect(&f->requests)));

  tdo_test::ChainConfigs cc = tdo_test::map6_chain(std::string(TDO_MAPS_DIR) + "/map6.tdomap");
  cc.sim.movers = false;
  tdo_test::Map6Chain chain(&bus, cc, 700);  // the simulator publishes the map and the first state
  std::string error;
  ASSERT_TRUE(chain.start(&error)) << error;

  bool requested = false, walled = false;
  std::size_t seen = 0;
  const int max_messages = 6 * 50 * 120;  // bounded: 120 s of flight, with requests and answers
  for (int i = 0; i < max_messages && !f->arrived; ++i) {
    if (bus.handle_timeout(0) <= 0) break;  // nothing in flight: the chain stopped
    if (!requested && chain.planner.map_id() == 1) {
      ASSERT_TRUE(bus.publish(tdo_lcm::kChannelPlanRequest, chain.request));
      requested = true;
    }
    if (f->world.empty() && !maps.empty()) f->world = maps[0].boxes;
    for (; seen < f->states.size(); ++seen) {
      const tdo::vehicle_state_t& s = f->states[seen];
      for (const auto& b : f->world)
        f->min_static = std::min(f->min_static, box_distance(s.position, b));
      if (dist3(s.position, chain.goal_p) < 0.25) f->arrived = true;
      if (!walled && s.utime - kT0 >= 6000000) {  // t = 6 s: the wall, as a map update
        tdo::map_update_t u{};
        u.utime = s.utime;
        u.map_id = 1;
        u.seq = 1;
        u.vehicle_id = -1;
        u.boxes = {wall_ahead(s, kind)};
        u.n_boxes = 1;
        f->world.push_back(u.boxes[0]);
        f->wall_state = seen;
        ASSERT_TRUE(bus.publish(tdo_lcm::kChannelMapUpdate, u));
        walled = true;
      }
    }
    // The closed wall: the run ends once the vehicle has stood still for 3 s after the update.
    if (walled && kind == Wall::closed && f->states.size() > f->wall_state + 50 * 8) break;
  }
  ASSERT_TRUE(walled) << "the flight ended before t = 6 s";
  // Setpoints are stamped with the state they answer: those after the wall's state know of it.
  const int64_t wall_utime = f->states[f->wall_state].utime;
  while (f->wall_setpoint < f->setpoints.size() &&
         f->setpoints[f->wall_setpoint].utime <= wall_utime)
    ++f->wall_setpoint;
  f->avoid = chain.avoid.counters();
  f->sim = chain.sim.counters();
}

/** Independent finite differences of consecutive setpoints (one step dt apart) at index k. */
struct StepDiff {
  double acc = 0.0;   // m/s^2, |v_k - v_{k-1}| / dt
  double jerk = 0.0;  // m/s^3, |a_k - a_{k-1}| / dt
  double pos = 0.0;   // m, |p_k - p_{k-1} - (v_{k-1} + v_k) dt / 2|: position consistent with v
};

StepDiff step_diff(const tdo::setpoint_t& a, const tdo::setpoint_t& b) {
  StepDiff d;
  double dv[3], da[3], dp[3];
  for (int i = 0; i < 3; ++i) {
    dv[i] = (b.velocity[i] - a.velocity[i]) / kDt;
    da[i] = (b.acceleration[i] - a.acceleration[i]) / kDt;
    dp[i] = b.position[i] - a.position[i] - 0.5 * (a.velocity[i] + b.velocity[i]) * kDt;
  }
  d.acc = norm3(dv);
  d.jerk = norm3(da);
  d.pos = norm3(dp);
  return d;
}

TEST(Replan, GivenAWallAcrossTheRouteMidFlight_WhenThereIsAWayRound_ThenReplansAndReachesTheGoal) {
  Flight f;
  fly(Wall::with_gap, &f);
  ASSERT_FALSE(f.states.empty());
  const double* last = f.states.back().position;
  EXPECT_TRUE(f.arrived) << "ended at (" << last[0] << ", " << last[1] << ", " << last[2]
                         << ") after " << f.states.size() << " states";
  EXPECT_GE(f.min_static, kRadius) << "the centre came closer than the radius to a box or the wall";
  // A replan: a request from tdo-avoid (its id range), answered ok and taken over.
  std::vector<const tdo::plan_request_t*> replans;
  for (const auto& r : f.requests)
    if (r.request_id >= 1000000000) replans.push_back(&r);
  ASSERT_GE(replans.size(), 1u);
  EXPECT_GE(f.avoid.replan_switches, 1);
  EXPECT_EQ(f.avoid.safe_stops, 0);
  // Never "ok" from the update until the new plan took over; "ok" again after it.
  std::size_t k = f.wall_setpoint;
  for (; k < f.setpoints.size() && f.setpoints[k].request_id == 700; ++k)
    ASSERT_EQ(f.setpoints[k].status, "path_blocked") << k;
  ASSERT_LT(k, f.setpoints.size());
  EXPECT_EQ(f.setpoints[k].request_id, replans[0]->request_id);
  EXPECT_EQ(f.setpoints.back().status, "ok");
  // The request's start is the state the vehicle really had at the takeover (prediction exact in
  // lock-step without noise): the state the switching setpoint was computed from.
  const tdo::setpoint_t& first = f.setpoints[k];
  const auto it =
      std::find_if(f.states.begin(), f.states.end(),
                   [&](const tdo::vehicle_state_t& s) { return s.utime == first.utime; });
  ASSERT_NE(it, f.states.end());
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(it->position[i], replans[0]->start[i], 1e-9) << i;
    EXPECT_NEAR(it->velocity[i], replans[0]->start_vel[i], 1e-9) << i;
    EXPECT_NEAR(it->acceleration[i], replans[0]->start_acc[i], 1e-9) << i;
  }
  std::printf(
      "[replan] wall with a way round: arrived %d, %zu states, %lld replans, closest %.3f m\n",
      f.arrived ? 1 : 0, f.states.size(), static_cast<long long>(f.avoid.replans), f.min_static);
}

// The setpoints across each switch to a new plan: no jump in position, velocity or acceleration
// (finite differences within the limits, 1 % over at most, as anywhere else in the run).
TEST(Replan, GivenAReplan_ThenTheSetpointsAcrossTheSwitchHaveNoJump) {
  Flight f;
  fly(Wall::with_gap, &f);
  const double v_max = 3.0, a_max = 3.0, j_max = 10.0;
  int switches = 0;
  for (std::size_t k = 1; k < f.setpoints.size(); ++k) {
    const StepDiff d = step_diff(f.setpoints[k - 1], f.setpoints[k]);
    EXPECT_LE(norm3(f.setpoints[k].velocity), v_max * 1.01) << k;
    EXPECT_LE(d.acc, a_max * 1.01) << k;
    EXPECT_LE(d.jerk, j_max * 1.01) << k;
    EXPECT_LE(d.pos, 1e-6) << k;
    if (f.setpoints[k].request_id != f.setpoints[k - 1].request_id &&
        f.setpoints[k - 1].request_id >= 0) {
      ++switches;
      std::printf(
          "[replan] switch at setpoint %zu: |dv|/dt %.3f m/s^2, |da|/dt %.3f m/s^3, "
          "position residual %.2e m\n",
          k, d.acc, d.jerk, d.pos);
    }
  }
  EXPECT_GE(switches, 1);
}

TEST(Replan, GivenAWallWithNoWayThrough_ThenASafeStopNamedNoWayThroughNeverOk) {
  Flight f;
  fly(Wall::closed, &f);
  EXPECT_FALSE(f.arrived);
  EXPECT_GE(f.min_static, kRadius) << "the centre came closer than the radius to a box or the wall";
  ASSERT_GT(f.setpoints.size(), f.wall_setpoint + 100);
  for (std::size_t k = f.wall_setpoint; k < f.setpoints.size(); ++k)
    ASSERT_NE(f.setpoints[k].status, "ok") << k;
  EXPECT_EQ(f.setpoints.back().status, "no_way_through");
  EXPECT_EQ(f.setpoints.back().status_code, tdo_lcm::kStatusNoWayThrough);
  EXPECT_LT(norm3(f.states.back().velocity), 0.05) << "stopped";
  EXPECT_EQ(f.avoid.safe_stops, 1);
  EXPECT_GE(f.avoid.replans, 1);
  EXPECT_EQ(f.avoid.replan_switches, 0);
}

/** Fly Map6 with its movers and a share of the columns hidden until sensed; checks inside. */
struct SensedFlight {
  bool arrived = false;
  double min_static = 1e9;  // m, to the true world (every box of the map file)
  double min_mover = 1e9;   // m, surface gap to the movers
  int64_t updates = 0, revealed = 0, hidden = 0;
  tdo_lcm::AvoidCounters avoid;
  std::vector<tdo::vehicle_state_t> states;
};

void fly_sensed(double unknown, double range, uint64_t seed, SensedFlight* f) {
  tdo_lcm::Bus bus("memq://");
  ASSERT_TRUE(bus.good());
  std::vector<tdo::obstacles_t> obstacles;
  std::vector<tdo::map_update_t> updates;
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelVehicleState, collect(&f->states)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelObstacles, collect(&obstacles)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelMapUpdate, collect(&updates)));
  tdo_test::ChainConfigs cc = tdo_test::map6_chain(std::string(TDO_MAPS_DIR) + "/map6.tdomap");
  cc.sim.unknown_fraction = unknown;
  cc.sim.sensor_range = range;
  cc.sim.seed = seed;
  cc.sim.request_goal = true;  // the flight's request, from the simulator as a ground station
  tdo_test::Map6Chain chain(&bus, cc, 0);  // the simulator publishes the map and the first state
  std::string error;
  ASSERT_TRUE(chain.start(&error)) << error;
  std::vector<std::vector<double>> world;  // the true world, from the map file, not the bus
  for (const tdo_box& b : chain.sim.true_boxes())
    world.push_back({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z});
  ASSERT_FALSE(world.empty());
  std::size_t seen = 0;
  const int max_messages = 8 * 50 * 120;
  for (int i = 0; i < max_messages && !f->arrived; ++i) {
    if (bus.handle_timeout(0) <= 0) break;
    for (; seen < f->states.size(); ++seen) {
      const tdo::vehicle_state_t& s = f->states[seen];
      for (const auto& b : world)
        f->min_static = std::min(f->min_static, box_distance(s.position, b));
      const tdo::obstacles_t& o = obstacles.back();
      for (int k = 0; k < o.n; ++k)
        f->min_mover =
            std::min(f->min_mover, dist3(s.position, o.position[k].data()) - o.radius[k] - kRadius);
      if (dist3(s.position, chain.goal_p) < 0.25) f->arrived = true;
    }
  }
  for (std::size_t k = 0; k < updates.size(); ++k) EXPECT_EQ(updates[k].seq, k + 1) << k;
  f->updates = static_cast<int64_t>(updates.size());
  f->revealed = chain.sim.counters().boxes_revealed;
  f->hidden = chain.sim.counters().boxes_hidden;
  f->avoid = chain.avoid.counters();
}

// tdo-sim alone: the first map holds the known boxes only, each update the boxes just seen (none
// known before, all from the map file), and a map request for the map in use gets every known box
// under a new map_id.
TEST(Replan, GivenHiddenColumns_ThenTheSimulatorPublishesWhatItSeesAsNumberedUpdates) {
  tdo_lcm::Bus bus("memq://");
  std::vector<tdo::map_t> maps;
  std::vector<tdo::map_update_t> updates;
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelMap, collect(&maps)));
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelMapUpdate, collect(&updates)));
  tdo_lcm::SimConfig sc = tdo_test::map6_chain(std::string(TDO_MAPS_DIR) + "/map6.tdomap").sim;
  sc.unknown_fraction = 0.3;
  sc.sensor_range = 5.0;
  sc.seed = 7;
  tdo_lcm::SimNode sim(&bus, sc);
  std::string error;
  ASSERT_TRUE(sim.start(&error)) << error;
  for (int i = 0; i < 100 && bus.handle_timeout(0) > 0; ++i) {
  }
  const std::size_t n = sim.true_boxes().size();
  ASSERT_EQ(n, 500u);
  EXPECT_EQ(sim.counters().boxes_hidden, 150);
  ASSERT_EQ(maps.size(), 1u);
  const int64_t seen_at_start = sim.counters().boxes_revealed;
  EXPECT_EQ(maps[0].n_boxes, static_cast<int32_t>(350 + seen_at_start));
  // The hidden boxes are libtdo's seeded choice (tdo_sense_hide, as tdo-sim-run's): every box it
  // keeps known is known, and of those it hides only the ones seen at the start are known.
  std::vector<uint8_t> chosen(n, 7u);
  ASSERT_EQ(tdo_sense_hide(static_cast<uint32_t>(n), 0.3, 7u, chosen.data()), TDO_OK);
  int64_t hidden_but_known = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (chosen[i] == 1u) {
      EXPECT_EQ(sim.known()[i], 1u) << "box " << i;
    }
    hidden_but_known += chosen[i] == 0u && sim.known()[i] == 1u;
  }
  EXPECT_EQ(hidden_but_known, seen_at_start);
  // Fly the vehicle along the diagonal at 2 m/s for 10 s (setpoint accelerations towards that
  // velocity, from the states it publishes): it sees more columns.
  std::vector<tdo::vehicle_state_t> states;
  ASSERT_TRUE(bus.subscribe(tdo_lcm::kChannelVehicleState, collect(&states)));
  std::vector<std::vector<double>> known = maps[0].boxes;
  auto is_in = [](const std::vector<std::vector<double>>& list, const std::vector<double>& b) {
    return std::find(list.begin(), list.end(), b) != list.end();
  };
  std::vector<std::vector<double>> truth;
  for (const tdo_box& b : sim.true_boxes())
    truth.push_back({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z});
  sim.publish_state();
  for (int i = 0; i < 100 && bus.handle_timeout(0) > 0; ++i) {
  }
  const double v_des[3] = {std::sqrt(2.0), std::sqrt(2.0), 0.0};
  for (int k = 1; k <= 500 && !states.empty(); ++k) {
    const tdo::vehicle_state_t& st = states.back();
    tdo::setpoint_t sp{};
    sp.utime = st.utime;
    for (int i = 0; i < 3; ++i) {
      sp.position[i] = st.position[i];
      sp.velocity[i] = st.velocity[i];
      sp.acceleration[i] = 2.0 * (v_des[i] - st.velocity[i]);
    }
    sp.status = "ok";
    ASSERT_TRUE(bus.publish(tdo_lcm::kChannelSetpoint, sp));
    for (int i = 0; i < 100 && bus.handle_timeout(0) > 0; ++i) {
    }
  }
  ASSERT_GT(states.back().position[0], 10.0) << "the vehicle flew";
  ASSERT_FALSE(updates.empty());
  int64_t boxes = 0;
  for (std::size_t k = 0; k < updates.size(); ++k) {
    EXPECT_EQ(updates[k].map_id, 1);
    EXPECT_EQ(updates[k].seq, static_cast<int64_t>(k) + 1);
    for (const auto& b : updates[k].boxes) {
      EXPECT_TRUE(is_in(truth, b)) << "a box of the map file";
      EXPECT_FALSE(is_in(known, b)) << "not known before";
      known.push_back(b);
      ++boxes;
    }
  }
  EXPECT_EQ(boxes + seen_at_start, sim.counters().boxes_revealed);
  // A map request for map 1: every known box under map 2.
  tdo::map_request_t r{};
  r.program = "test";
  r.reason = "gap";
  r.map_id = 1;
  ASSERT_TRUE(bus.publish(tdo_lcm::kChannelMapRequest, r));
  for (int i = 0; i < 100 && bus.handle_timeout(0) > 0; ++i) {
  }
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[1].map_id, 2);
  EXPECT_EQ(sim.map_id(), 2);
  EXPECT_EQ(static_cast<std::size_t>(maps[1].n_boxes), known.size());
  for (const auto& b : known) EXPECT_TRUE(is_in(maps[1].boxes, b));
}

TEST(Replan, GivenMap6With30PercentOfTheColumnsUnknown_ThenTheLoopReachesTheGoalWithoutContact) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    SensedFlight f;
    fly_sensed(0.3, 5.0, seed, &f);
    EXPECT_TRUE(f.arrived) << "seed " << seed;
    EXPECT_GE(f.min_static, kRadius) << "seed " << seed;
    EXPECT_GT(f.min_mover, 0.0) << "seed " << seed;
    EXPECT_GT(f.hidden, 0) << "seed " << seed;
    EXPECT_EQ(f.avoid.safe_stops, 0) << "seed " << seed;
    for (const auto& kv : f.avoid.reasons)
      std::printf("[replan]   tdo-avoid %s %lld\n", kv.first.c_str(),
                  static_cast<long long>(kv.second));
    std::printf(
        "[replan] Map6, 30 %% unknown, seed %llu: arrived %d after %zu states, %lld of "
        "%lld hidden columns revealed in %lld updates, %lld replans (%lld taken over), "
        "closest column %.3f m, mover gap %.3f m\n",
        static_cast<unsigned long long>(seed), f.arrived ? 1 : 0, f.states.size(),
        static_cast<long long>(f.revealed), static_cast<long long>(f.hidden),
        static_cast<long long>(f.updates), static_cast<long long>(f.avoid.replans),
        static_cast<long long>(f.avoid.replan_switches), f.min_static, f.min_mover);
  }
}

}  // namespace
