// pagmo2 particle swarm (pagmo::pso) and grey wolf optimizer (pagmo::gwo) over K intermediate
// waypoints (stand-ins for the paper's "Improved PSO" and the swarm method ICSSA).
//
// Decision vector: K waypoints (3K numbers) inside the map bounds; the path is start, the K points,
// goal. Fitness = length + penalty * sum over colliding segments of (1 + deficit), where a segment
// collides when libtdo's exact check (tdo_collision_segment_clear) rejects it and its deficit is
// the integral of (clearance - distance) along it, sampled every res/2 (a graded signal for the
// swarm; the verdict itself is exact). The population is drawn uniformly in the bounds by pagmo
// from the seed; individual 0 is replaced by the straight start-goal line (K evenly spaced points).
// The champion is checked exactly: if any of its segments still breaks the clearance the run is a
// FAILURE ("collides"), never a path.
#include <chrono>
#include <cmath>
#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/gwo.hpp>
#include <pagmo/algorithms/pso.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include "planners_internal.h"

namespace tdo_baselines {
namespace {

struct WaypointProblem {
  const Environment* env = nullptr;
  tdo_vec3 start{};
  tdo_vec3 goal{};
  unsigned k = 1;
  double penalty = 1000.0;

  double segment_cost(const tdo_vec3& a, const tdo_vec3& b) const {
    const double dx = b.x - a.x;
    const double dy = b.y - a.y;
    const double dz = b.z - a.z;
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (env->segment_valid(a, b)) return len;
    const double c = env->clearance();
    const double h = 0.5 * env->map().desc.res;
    const int n = static_cast<int>(std::min(400.0, std::ceil(len / h)));
    double deficit = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double t = n > 0 ? static_cast<double>(i) / n : 0.0;
      const tdo_vec3 p{a.x + t * dx, a.y + t * dy, a.z + t * dz};
      const double d = tdo_collision_point_distance(env->grid(), p, c);
      if (d < c) deficit += (c - (d < 0.0 ? 0.0 : d)) * (n > 0 ? len / n : 0.0);
    }
    return len + penalty * (1.0 + deficit);
  }

  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    double f = 0.0;
    tdo_vec3 prev = start;
    for (unsigned i = 0; i < k; ++i) {
      const tdo_vec3 p{x[3 * i], x[3 * i + 1], x[3 * i + 2]};
      f += segment_cost(prev, p);
      prev = p;
    }
    f += segment_cost(prev, goal);
    return {f};
  }

  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    pagmo::vector_double lb(3 * k);
    pagmo::vector_double ub(3 * k);
    const tdo_vec3 lo = env->lo();
    const tdo_vec3 hi = env->hi();
    for (unsigned i = 0; i < k; ++i) {
      lb[3 * i] = lo.x;
      lb[3 * i + 1] = lo.y;
      lb[3 * i + 2] = lo.z;
      ub[3 * i] = hi.x;
      ub[3 * i + 1] = hi.y;
      ub[3 * i + 2] = hi.z;
    }
    return {lb, ub};
  }

  std::string get_name() const { return "tdo waypoint path"; }
};

class SwarmPlanner : public Planner {
 public:
  explicit SwarmPlanner(bool gwo) : gwo_(gwo) {
    add_param("waypoints", 8.0, 1.0, 200.0);
    add_param("population", 40.0, 5.0, 100000.0);
    add_param("generations", 300.0, 1.0, 1e6);
    add_param("penalty", 1000.0, 0.0, 1e12);
  }
  std::string name() const override { return gwo_ ? "gwo" : "pso"; }
  std::string description() const override {
    return std::string("pagmo2 ") + (gwo_ ? "grey wolf optimizer" : "particle swarm (pso)") +
           " over K waypoints, collision penalty; a colliding champion is a failure";
  }
  bool stochastic() const override { return true; }

  PlanResult plan(Environment& env, const tdo_vec3& start, const tdo_vec3& goal,
                  uint64_t seed) override {
    const auto t0 = std::chrono::steady_clock::now();
    WaypointProblem wp;
    wp.env = &env;
    wp.start = start;
    wp.goal = goal;
    wp.k = static_cast<unsigned>(std::llround(p("waypoints")));
    wp.penalty = p("penalty");
    pagmo::problem prob{wp};
    const auto pop_size = static_cast<pagmo::population::size_type>(std::llround(p("population")));
    const auto gens = static_cast<unsigned>(std::llround(p("generations")));
    const auto s32 = static_cast<unsigned>(seed & 0xFFFFFFFFu);
    pagmo::population pop{prob, pop_size, s32};
    pagmo::vector_double line(3 * wp.k);
    for (unsigned i = 0; i < wp.k; ++i) {
      const double t = static_cast<double>(i + 1) / static_cast<double>(wp.k + 1);
      line[3 * i] = start.x + t * (goal.x - start.x);
      line[3 * i + 1] = start.y + t * (goal.y - start.y);
      line[3 * i + 2] = start.z + t * (goal.z - start.z);
    }
    pop.set_x(0, line);
    pagmo::algorithm algo =
        gwo_ ? pagmo::algorithm{pagmo::gwo(gens, s32)}
             : pagmo::algorithm{pagmo::pso(gens, 0.7298, 2.05, 2.05, 0.5, 5u, 2u, 4u, false, s32)};
    pop = algo.evolve(pop);
    const pagmo::vector_double best = pop.champion_x();
    std::vector<tdo_vec3> pts;
    pts.push_back(start);
    for (unsigned i = 0; i < wp.k; ++i)
      pts.push_back({best[3 * i], best[3 * i + 1], best[3 * i + 2]});
    pts.push_back(goal);
    const auto t1 = std::chrono::steady_clock::now();
    PlanResult r = evaluate_polyline(env, pts, start, goal);
    r.plan_time_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    r.expansions = pop.get_problem().get_fevals();
    return r;
  }

 private:
  bool gwo_;
};

}  // namespace

std::unique_ptr<Planner> make_swarm_planner(const std::string& name) {
  if (name == "pso") return std::make_unique<SwarmPlanner>(false);
  if (name == "gwo") return std::make_unique<SwarmPlanner>(true);
  return nullptr;
}

}  // namespace tdo_baselines
