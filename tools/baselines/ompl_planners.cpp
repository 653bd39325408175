// OMPL RRTConnect and RRT* in the map's bounds, raw and with OMPL's PathSimplifier (stands in for
// the paper's "Improved RRT"). States are checked with libtdo's exact point clearance, motions with
// libtdo's exact segment clearance (tdo_collision_segment_clear), so OMPL never samples a motion.
//
// Determinism: ompl::RNG::setSeed(seed + 1) before any OMPL object of a plan is built, so every
// RNG instance of that plan gets its seed from the same sequence; the planners stop after a fixed
// number of iterations (ompl::base::IterationTerminationCondition), and the simplifier runs
// simplifyMax (no time limit). A wall-clock cap (time_cap_s) exists only as a safety net; when it
// fires the result is still reported, and the status says "time_cap".
#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/terminationconditions/IterationTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cmath>

#include "planners_internal.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace tdo_baselines {
namespace {

tdo_vec3 to_vec(const ob::State* s) {
  const auto* r = s->as<ob::RealVectorStateSpace::StateType>();
  return tdo_vec3{r->values[0], r->values[1], r->values[2]};
}

class Validity : public ob::StateValidityChecker {
 public:
  Validity(const ob::SpaceInformationPtr& si, const Environment* env)
      : ob::StateValidityChecker(si), env_(env) {}
  bool isValid(const ob::State* s) const override { return env_->point_valid(to_vec(s)); }

 private:
  const Environment* env_;
};

class Motion : public ob::MotionValidator {
 public:
  Motion(const ob::SpaceInformationPtr& si, const Environment* env)
      : ob::MotionValidator(si), env_(env) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    return env_->segment_valid(to_vec(a), to_vec(b));
  }
  // Only the verdict is exact; the last valid point is approximated by bisection on the segment
  // (RRT* / the simplifier do not use it with the default settings).
  bool checkMotion(const ob::State* a, const ob::State* b,
                   std::pair<ob::State*, double>& last_valid) const override {
    if (checkMotion(a, b)) return true;
    double lo = 0.0;
    double hi = 1.0;
    const tdo_vec3 pa = to_vec(a);
    const tdo_vec3 pb = to_vec(b);
    for (int i = 0; i < 30; ++i) {
      const double m = 0.5 * (lo + hi);
      const tdo_vec3 pm{pa.x + m * (pb.x - pa.x), pa.y + m * (pb.y - pa.y),
                        pa.z + m * (pb.z - pa.z)};
      if (env_->segment_valid(pa, pm))
        lo = m;
      else
        hi = m;
    }
    if (last_valid.first != nullptr) si_->getStateSpace()->interpolate(a, b, lo, last_valid.first);
    last_valid.second = lo;
    return false;
  }

 private:
  const Environment* env_;
};

class OmplPlanner : public Planner {
 public:
  OmplPlanner(bool star, bool simplify) : star_(star), simplify_(simplify) {
    add_param("max_iterations", star ? 10000.0 : 100000.0, 1.0, 1e8);
    add_param("range", 0.0, 0.0, 1e6);  // m, 0 = OMPL's default (20 % of the bounds' extent)
    add_param("goal_bias", 0.05, 0.0, 1.0);
    add_param("time_cap_s", 60.0, 0.01, 3600.0);
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  }
  std::string name() const override {
    return std::string(star_ ? "rrtstar" : "rrtconnect") + (simplify_ ? "-simplify" : "");
  }
  std::string description() const override {
    return std::string("OMPL ") + (star_ ? "RRT*" : "RRTConnect") +
           (simplify_ ? " + PathSimplifier::simplifyMax" : " (raw path)") +
           ", libtdo exact clearance checks";
  }
  bool stochastic() const override { return true; }

  PlanResult plan(Environment& env, const tdo_vec3& start, const tdo_vec3& goal,
                  uint64_t seed) override {
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed % 2147483646u) + 1u);
    const auto t0 = std::chrono::steady_clock::now();
    auto space = std::make_shared<ob::RealVectorStateSpace>(3);
    ob::RealVectorBounds bounds(3);
    const tdo_vec3 lo = env.lo();
    const tdo_vec3 hi = env.hi();
    bounds.setLow(0, lo.x);
    bounds.setLow(1, lo.y);
    bounds.setLow(2, lo.z);
    bounds.setHigh(0, hi.x);
    bounds.setHigh(1, hi.y);
    bounds.setHigh(2, hi.z);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    si->setStateValidityChecker(std::make_shared<Validity>(si, &env));
    auto motion = std::make_shared<Motion>(si, &env);
    si->setMotionValidator(motion);
    si->setup();
    ob::ScopedState<> s(space);
    ob::ScopedState<> g(space);
    s[0] = start.x;
    s[1] = start.y;
    s[2] = start.z;
    g[0] = goal.x;
    g[1] = goal.y;
    g[2] = goal.z;
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    pdef->setStartAndGoalStates(s, g, 1e-9);

    ob::PlannerPtr planner;
    if (star_) {
      auto rs = std::make_shared<og::RRTstar>(si);
      if (p("range") > 0.0) rs->setRange(p("range"));
      rs->setGoalBias(p("goal_bias"));
      planner = rs;
    } else {
      auto rc = std::make_shared<og::RRTConnect>(si);
      if (p("range") > 0.0) rc->setRange(p("range"));
      planner = rc;
    }
    planner->setProblemDefinition(pdef);
    planner->setup();
    ob::IterationTerminationCondition iters(
        static_cast<unsigned int>(std::llround(p("max_iterations"))));
    const ob::PlannerTerminationCondition ptc = ob::plannerOrTerminationCondition(
        iters, ob::timedPlannerTerminationCondition(p("time_cap_s")));
    const ob::PlannerStatus st = planner->solve(ptc);
    const double solve_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool time_cap = solve_s >= p("time_cap_s");
    PlanResult r;
    std::vector<tdo_vec3> pts;
    bool exact = st == ob::PlannerStatus::EXACT_SOLUTION && pdef->hasExactSolution();
    if (exact) {
      og::PathGeometric path(*pdef->getSolutionPath()->as<og::PathGeometric>());
      if (simplify_) {
        og::PathSimplifier simplifier(si);
        simplifier.simplifyMax(path);
      }
      for (unsigned int i = 0; i < static_cast<unsigned int>(path.getStateCount()); ++i)
        pts.push_back(to_vec(path.getState(i)));
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    if (!exact) {
      r.status = time_cap ? "time_cap" : "no_solution";
    } else {
      // OMPL keeps the start and goal states it was given; make them bit-exact (a no-op unless
      // the goal was reached within the 1e-9 m threshold), then check and measure.
      if (!pts.empty()) {
        pts.front() = start;
        pts.back() = goal;
      }
      r = evaluate_polyline(env, pts, start, goal);
      if (r.ok && time_cap) r.status = "ok_time_cap";  // stopped by the clock: not reproducible
    }
    r.plan_time_ms = ms;
    r.expansions = iters.getTimesCalled();
    return r;
  }

 private:
  bool star_;
  bool simplify_;
};

}  // namespace

std::unique_ptr<Planner> make_ompl_planner(const std::string& name) {
  if (name == "rrtconnect") return std::make_unique<OmplPlanner>(false, false);
  if (name == "rrtconnect-simplify") return std::make_unique<OmplPlanner>(false, true);
  if (name == "rrtstar") return std::make_unique<OmplPlanner>(true, false);
  if (name == "rrtstar-simplify") return std::make_unique<OmplPlanner>(true, true);
  return nullptr;
}

}  // namespace tdo_baselines
