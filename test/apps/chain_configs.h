// The configurations of the closed loop's three nodes (tdo-planner, tdo-avoid, tdo-sim) on Map6
// for the in-process tests (test_chain.cpp, test_replan.cpp): capacities of a 50 x 50 x 20 voxel
// map with up to 600 boxes, lock-step, no heartbeats, the simulator's clock from kChainT0; and the
// tests' own distance checks.
#ifndef TDO_TEST_APPS_CHAIN_CONFIGS_H
#define TDO_TEST_APPS_CHAIN_CONFIGS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "avoid_node.h"
#include "planner_node.h"
#include "sim_node.h"
#include "tdo_lcm/adapters.h"

namespace tdo_test {

constexpr int64_t kChainT0 = 1767225600000000;  // us, 2026-01-01

struct ChainConfigs {
  tdo_lcm::PlannerConfig planner;
  tdo_lcm::AvoidConfig avoid;
  tdo_lcm::SimConfig sim;
};

/** @param map_file the map tdo-sim flies in and publishes */
inline ChainConfigs map6_chain(const std::string& map_file) {
  ChainConfigs c;
  c.planner.max_nx = c.avoid.max_nx = 50;
  c.planner.max_ny = c.avoid.max_ny = 50;
  c.planner.max_nz = c.avoid.max_nz = 20;
  c.planner.max_nodes = 600000;
  c.planner.max_boxes = c.avoid.max_boxes = 600;
  c.planner.heartbeat_period_s = c.avoid.heartbeat_period_s = c.sim.heartbeat_period_s = 0.0;
  c.avoid.lockstep = c.sim.lockstep = true;
  c.sim.map_file = map_file;
  c.sim.start_utime = kChainT0;
  return c;
}

/** The three nodes on one bus (declare the bus first); start() in the order planner, follower,
 *  simulator (which publishes the map and the first state). */
struct ChainNodes {
  ChainNodes(tdo_lcm::Bus* bus, const ChainConfigs& c)
      : planner(bus, c.planner), avoid(bus, c.avoid), sim(bus, c.sim) {}
  bool start(std::string* error) {
    return planner.start(error) && avoid.start(error) && sim.start(error);
  }
  tdo_lcm::PlannerNode planner;
  tdo_lcm::AvoidNode avoid;
  tdo_lcm::SimNode sim;
};

/** The flight's request, as a ground station sends it: Map6's start to `goal`, libtdo's
 *  defaults, vehicle 0, on the planner's latest map. */
inline tdo::plan_request_t map6_request(tdo_vec3 goal, int64_t request_id) {
  tdo_plan_request req{};
  tdo_plan_params_default(&req.params);
  req.start = tdo_vec3{2, 2, 3};
  req.goal = goal;
  tdo::plan_request_t rm{};
  tdo_lcm::plan_request_to_msg(req, -1.0, &rm);
  rm.request_id = request_id;
  rm.vehicle_id = 0;
  rm.map_id = -1;
  return rm;
}

/** The closed loop started on Map6 (the set-up test_chain.cpp and test_replan.cpp share): the
 *  three nodes on `bus`, the map's goal and the request to it. Declare the bus first; call
 *  start() (asserted by the caller) before using the nodes. */
struct Map6Chain {
  Map6Chain(tdo_lcm::Bus* bus, const ChainConfigs& c, int64_t request_id)
      : nodes(bus, c), id(request_id) {}
  /** Start the nodes, read the goal the simulator's map gives, build the request. */
  bool start(std::string* error) {
    if (!nodes.start(error)) return false;
    if (!nodes.sim.goal(&goal)) {
      *error = "the simulator's map has no goal";
      return false;
    }
    goal_p[0] = goal.x;
    goal_p[1] = goal.y;
    goal_p[2] = goal.z;
    request = map6_request(goal, id);
    return true;
  }
  ChainNodes nodes;
  tdo_lcm::PlannerNode& planner = nodes.planner;
  tdo_lcm::AvoidNode& avoid = nodes.avoid;
  tdo_lcm::SimNode& sim = nodes.sim;
  int64_t id;
  tdo_vec3 goal{};
  double goal_p[3] = {0.0, 0.0, 0.0}; /**< m, the goal as an array */
  tdo::plan_request_t request{};      /**< Map6's start to the goal, request `id` */
};

/** m, Euclidean distance from p to an axis-aligned box xmin ymin zmin xmax ymax zmax (0 inside). */
inline double box_distance(const double* p, const std::vector<double>& b) {
  double s = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double d = std::max({b[a] - p[a], 0.0, p[a] - b[a + 3]});
    s += d * d;
  }
  return std::sqrt(s);
}

inline double norm3(const double* a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

inline double dist3(const double* a, const double* b) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

}  // namespace tdo_test

#endif  // TDO_TEST_APPS_CHAIN_CONFIGS_H
