// The trajectory stage's clearance verification (trajectory.cpp, clearance_pass; docs/design.md
// s.5) against brute force on real maps: every sample's exact distance by
// tdo_collision_point_distance, their minimum (capped at clearance + 1 m, as the report says) and
// the samples below the clearance, in order. Paths planned on Map1-6, verified at the plan's
// clearance, at a clearance that the closest sample just grazes (equal: no violation; above by
// 2e-9: the closest samples violate), at a clearance that most samples miss, and moved into the
// obstacles; with stored and with streamed samples.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "arena_contexts.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace {

const std::string kMaps = std::string(TDO_SOURCE_DIR) + "/maps";
constexpr double kCapExtra = 1.0;  // m, the report's distances are capped at clearance + this
constexpr double kSlack = 1e-9;    // m, the report's clearance slack (a sample at exactly the
                                   // clearance keeps it)
constexpr uint32_t kMaxViolations = 64;

using tdo_test::TestPlanner;
using tdo_test::TestTraj;

/** `map` at `clearance` in a planner of tdo_io::capacity_for's sizes, its samples stored (big
 *  grids default to pieces, whose report gives the path's clearance, not the samples'). */
TestPlanner map_planner(const tdo_io::Map& map, double clearance) {
  tdo_capacity cap = tdo_io::capacity_for(map, clearance, 27u, 400000u);
  cap.stream_samples = TDO_TRAJ_SAMPLES_STORED;
  return TestPlanner(cap, [&](tdo_grid* g) { return tdo_io::load_into(map, g, clearance); });
}

tdo_traj_config traj_cfg(uint32_t max_samples, uint32_t max_segments, uint32_t stream) {
  tdo_traj_config cfg{};
  cfg.max_samples = max_samples;
  cfg.max_segments = max_segments;
  cfg.max_profile = max_segments * TDO_TRAJ_PIECES_PER_SEGMENT + 1u;
  cfg.max_violations = kMaxViolations;
  cfg.max_refinements = 8;
  cfg.stream_samples = stream;
  return cfg;
}

/** What the report's clearance part must be: every sample queried. */
struct Brute {
  double min = HUGE_VAL;
  std::vector<double> t, value;  // the violations in sample order
};

Brute brute_force(const tdo_grid* grid, const std::vector<tdo_sample>& samples, double clearance) {
  Brute b;
  for (const tdo_sample& s : samples) {
    const double d = tdo_collision_point_distance(grid, s.p, clearance + kCapExtra);
    b.min = std::fmin(b.min, d);
    if (d < clearance - kSlack) {
      b.t.push_back(s.t);
      b.value.push_back(d);
    }
  }
  return b;
}

struct Run {
  tdo_status status = TDO_ERR_INVALID_ARGUMENT;
  tdo_traj_output out{};
  std::vector<tdo_sample> samples;
  std::vector<tdo_violation> violations;
};

void collect(void* user, uint32_t /*index*/, const tdo_sample* s) {
  static_cast<std::vector<tdo_sample>*>(user)->push_back(*s);
}

Run run_traj(TestTraj* traj, const tdo_grid* grid, const tdo_path& path, double clearance,
             int clearance_proven = 0) {
  tdo_plan_params params;
  tdo_plan_params_default(&params);
  tdo_traj_input in{};
  tdo_plan_traj_input(&params, &in);
  in.path = path;
  in.grid = grid;
  in.clearance = clearance;
  in.clearance_proven = clearance_proven;
  Run r;
  r.status = tdo_traj_run(traj->ctx(), &in, &r.out);
  if (r.status != TDO_OK && r.status != TDO_ERR_INFEASIBLE) return r;
  EXPECT_EQ(tdo_traj_each_sample(traj->ctx(), collect, &r.samples), TDO_OK);
  EXPECT_EQ(r.samples.size(), r.out.n_samples);
  r.violations.assign(r.out.report.violations, r.out.report.violations + r.out.report.n_violations);
  return r;
}

/** The clearance part of `r`'s report equals brute force over its samples, bit for bit. */
void expect_brute(const tdo_grid* grid, const Run& r, double clearance, const std::string& label) {
  SCOPED_TRACE(label);
  ASSERT_TRUE(r.status == TDO_OK || r.status == TDO_ERR_INFEASIBLE) << tdo_status_str(r.status);
  ASSERT_GT(r.samples.size(), 1u);
  const Brute b = brute_force(grid, r.samples, clearance);
  EXPECT_EQ(r.out.report.min_clearance, b.min);
  std::vector<double> t, value;
  uint32_t others = 0;
  for (const tdo_violation& v : r.violations) {
    if (v.what != TDO_QUANTITY_CLEARANCE) {
      ++others;
      continue;
    }
    t.push_back(v.t);
    value.push_back(v.value);
    EXPECT_EQ(v.limit, clearance);
  }
  if (r.out.report.n_violations_total == r.out.report.n_violations) {
    EXPECT_EQ(t, b.t);
    EXPECT_EQ(value, b.value);
    EXPECT_EQ(r.out.report.ok, b.t.empty() && others == 0u ? 1 : 0);
  } else {  // the list is full: its clearance entries are brute force's first ones
    ASSERT_LE(t.size(), b.t.size());
    EXPECT_EQ(t, std::vector<double>(b.t.begin(), b.t.begin() + static_cast<long>(t.size())));
    EXPECT_EQ(r.out.report.ok, 0);
  }
}

tdo_path moved(const tdo_path& path, std::vector<tdo_path_segment>* store, tdo_vec3 by) {
  store->assign(path.seg, path.seg + path.n);
  for (tdo_path_segment& s : *store) {
    const int points = s.kind == TDO_SEGMENT_BEZIER ? 4 : 3;
    for (int k = 0; k < points; ++k) {
      s.p[k].x += by.x;
      s.p[k].y += by.y;
      s.p[k].z += by.z;
    }
  }
  tdo_path p = path;
  p.seg = store->data();
  return p;
}

tdo_io::Map load(const std::string& file) {
  tdo_io::Map map;
  std::string err;
  EXPECT_TRUE(tdo_io::load_map(kMaps + "/" + file, &map, &err)) << err;
  return map;
}

/** Plans start -> goal at `clearance` and checks the report of the plan and of its path verified
 *  again at other clearances and moved (stored and streamed samples) against brute force. */
void check_plan(TestPlanner* pl, double clearance, tdo_vec3 start, tdo_vec3 goal) {
  tdo_plan_request req{};
  req.start = start;
  req.goal = goal;
  tdo_plan_params_default(&req.params);
  tdo_plan_result res{};
  ASSERT_EQ(tdo_planner_plan(pl->planner(), &req, &res), TDO_OK);
  const tdo_grid* grid = tdo_planner_grid(pl->planner());
  // The planner's own run: its report is brute force's too.
  std::vector<tdo_sample> planned(res.samples, res.samples + res.n_samples);
  const Brute bp = brute_force(grid, planned, clearance);
  EXPECT_EQ(res.feasibility.min_clearance, bp.min);
  EXPECT_TRUE(bp.t.empty());

  // The path is copied: the planner's arena is not touched again, but keep it independent.
  std::vector<tdo_path_segment> segs(res.path.seg, res.path.seg + res.path.n);
  tdo_path path = res.path;
  path.seg = segs.data();
  const uint32_t max_samples = 4u * res.n_samples + 1000u;
  const uint32_t max_segments = res.path.n + 8u;
  TestTraj stored(traj_cfg(max_samples, max_segments, 0u), 64u),
      streamed(traj_cfg(max_samples, max_segments, 1u), 64u);
  ASSERT_EQ(stored.status(), TDO_OK);
  ASSERT_EQ(streamed.status(), TDO_OK);

  const double m = res.feasibility.min_clearance;
  std::vector<tdo_path_segment> into;
  struct Case {
    std::string label;
    tdo_path path;
    double clearance;
    int violations;  // -1: none expected, 1: some expected, 0: either
  };
  const std::vector<Case> cases{
      {"plan clearance", path, clearance, -1},
      {"grazing: clearance = min", path, m, -1},
      {"grazing: clearance = min + 1e-9 (within the slack)", path, m + 1e-9, -1},
      {"grazing: clearance = min + 2e-9", path, m + 2e-9, 1},
      {"clearance = min + 0.3", path, m + 0.3, 1},
      {"clearance 0", path, 0.0, -1},
      {"moved 0.6 m down", moved(path, &into, tdo_vec3{0.0, 0.0, -0.6}), clearance, 0},
  };
  for (const Case& c : cases) {
    const Run a = run_traj(&stored, grid, c.path, c.clearance);
    expect_brute(grid, a, c.clearance, c.label + ", stored");
    const Run b = run_traj(&streamed, grid, c.path, c.clearance);
    expect_brute(grid, b, c.clearance, c.label + ", streamed");
    EXPECT_EQ(a.out.report.min_clearance, b.out.report.min_clearance) << c.label;
    EXPECT_EQ(a.out.report.n_violations_total, b.out.report.n_violations_total) << c.label;
    if (c.violations < 0) {
      EXPECT_EQ(a.status, TDO_OK) << c.label;
      EXPECT_EQ(a.out.report.ok, 1) << c.label;
    }
    if (c.violations > 0) {
      EXPECT_EQ(a.status, TDO_ERR_INFEASIBLE) << c.label;
      EXPECT_GT(a.out.report.n_violations_total, 0u) << c.label;
    }
  }
}

void check_map(const std::string& name) {
  SCOPED_TRACE(name);
  const tdo_io::Map map = load(name + ".tdomap");
  ASSERT_TRUE(map.has_start && map.has_goal);
  TestPlanner pl =
      map_planner(map, 0.5);  // tdo-plan's default clearance on .tdomap maps (obstacle boxes)
  ASSERT_EQ(pl.status(), TDO_OK);
  check_plan(&pl, 0.5, map.start, map.goal);
}

TEST(TrajectoryClearance, GivenMap1WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map1"); }
TEST(TrajectoryClearance, GivenMap2WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map2"); }
TEST(TrajectoryClearance, GivenMap3WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map3"); }
TEST(TrajectoryClearance, GivenMap4WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map4"); }
TEST(TrajectoryClearance, GivenMap5WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map5"); }
TEST(TrajectoryClearance, GivenMap6WhenVerifiedThenClearanceEqualsBruteForce) { check_map("map6"); }

/** The first n queries of MovingAI Simple's scenario file (fewer when it does not load). */
std::vector<tdo_io::ScenQuery> simple_queries(size_t n) {
  std::vector<tdo_io::ScenQuery> queries;
  std::string err;
  EXPECT_TRUE(tdo_io::load_scen(kMaps + "/movingai/Simple.3dmap.3dscen", &queries, &err)) << err;
  if (queries.size() > n) queries.resize(n);
  return queries;
}

// MovingAI Simple (voxel cubes, clearance 0: the paths graze the cubes), its first queries.
TEST(TrajectoryClearance, GivenMovingAISimpleWhenVerifiedThenClearanceEqualsBruteForce) {
  const tdo_io::Map map = load("movingai/Simple.3dmap");
  const std::vector<tdo_io::ScenQuery> queries = simple_queries(40u);
  ASSERT_EQ(queries.size(), 40u);
  TestPlanner pl = map_planner(map, 0.0);
  ASSERT_EQ(pl.status(), TDO_OK);
  for (const tdo_io::ScenQuery& q : queries) {
    SCOPED_TRACE("Simple query " + std::to_string(q.line));
    check_plan(&pl, 0.0, q.start, q.goal);
  }
}

// Fine OcTrees, where clearance_min's query margin is half a voxel edge (0.04 m at geb079's 0.08 m,
// 0.05 m at the forests' 0.1 m) instead of 0.2 m: the report is still brute force's.
TEST(TrajectoryClearance, GivenGeb079CorridorQueriesWhenVerifiedThenClearanceEqualsBruteForce) {
  const tdo_io::Map map = load("octomap/geb079.bt");
  TestPlanner pl = map_planner(map, 0.3);
  ASSERT_EQ(pl.status(), TDO_OK);
  // maps/octomap/README.md: G2 and G3, straight along the corridor's walls.
  check_plan(&pl, 0.3, tdo_vec3{-5.0, 0.0, 1.2}, tdo_vec3{10.0, 0.0, 1.2});
  check_plan(&pl, 0.3, tdo_vec3{13.0, 0.0, 1.2}, tdo_vec3{27.0, 0.0, 1.2});
}

TEST(TrajectoryClearance, GivenForestPairsWhenVerifiedThenClearanceEqualsBruteForce) {
  const tdo_io::Map map = load("forest_gen/forest2.bt");
  TestPlanner pl = map_planner(map, 0.5);
  ASSERT_EQ(pl.status(), TDO_OK);
  // maps/forest_gen/start_and_end.csv, pairs 205 and 200.
  check_plan(&pl, 0.5, tdo_vec3{2.083444, -3.562597, 1.0}, tdo_vec3{-1.367670, 3.574024, 1.0});
  check_plan(&pl, 0.5, tdo_vec3{-0.910768, 2.729434, 1.0}, tdo_vec3{4.385792, 2.004155, 1.0});
}

/** `map` at `clearance` in a planner of tdo_io::capacity_for's sizes, the pieces mode forced. */
TestPlanner pieces_planner(const tdo_io::Map& map, double clearance) {
  tdo_capacity cap = tdo_io::capacity_for(map, clearance, 27u, 400000u);
  cap.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
  return TestPlanner(cap, [&](tdo_grid* g) { return tdo_io::load_into(map, g, clearance); });
}

/** Plans start -> goal in the pieces mode, where the trajectory takes the clearance the correction
 *  and the smoothing proved instead of measuring it: the report gives that bound, and the proof
 *  holds, by brute force over every sample and by tdo_metrics_compute's own path measurement. The
 *  same path run with clearance_proven 0 is measured (the metric) and with 2 refused. */
void check_proven(TestPlanner* pl, double clearance, tdo_vec3 start, tdo_vec3 goal) {
  tdo_plan_request req{};
  req.start = start;
  req.goal = goal;
  tdo_plan_params_default(&req.params);
  tdo_plan_result res{};
  ASSERT_EQ(tdo_planner_plan(pl->planner(), &req, &res), TDO_OK);
  ASSERT_EQ(res.sample_passes, 0u);  // the closed-form check accepted the plan
  const double bound = std::fmax(0.0, clearance - kSlack);
  EXPECT_EQ(res.feasibility.min_clearance, bound);
  EXPECT_EQ(res.metrics.min_clearance_m, bound);
  const tdo_grid* grid = tdo_planner_grid(pl->planner());
  std::vector<tdo_sample> samples;
  ASSERT_EQ(tdo_planner_each_sample(pl->planner(), collect, &samples), TDO_OK);
  ASSERT_GT(samples.size(), 1u);
  const Brute b = brute_force(grid, samples, clearance);
  EXPECT_TRUE(b.t.empty()) << b.t.size() << " samples closer than the clearance";
  EXPECT_GE(b.min, bound);
  tdo_metrics_input mi{};
  mi.path = &res.path;
  mi.waypoints = res.waypoints;
  mi.n_waypoints = res.n_waypoints;
  mi.grid = grid;
  mi.clearance_cap = clearance + kCapExtra;
  tdo_metrics measured{};
  ASSERT_EQ(tdo_metrics_compute(&mi, &measured), TDO_OK);
  EXPECT_GE(measured.min_clearance_m, bound);

  std::vector<tdo_path_segment> segs(res.path.seg, res.path.seg + res.path.n);
  tdo_path path = res.path;
  path.seg = segs.data();
  TestTraj traj(traj_cfg(4u * res.n_samples + 1000u, res.path.n + 8u, TDO_TRAJ_SAMPLES_PIECES),
                64u);
  ASSERT_EQ(traj.status(), TDO_OK);
  const Run r = run_traj(&traj, grid, path, clearance);
  ASSERT_EQ(r.status, TDO_OK);
  ASSERT_EQ(r.out.sample_passes, 0u);
  EXPECT_EQ(r.out.report.min_clearance, measured.min_clearance_m);
  EXPECT_EQ(run_traj(&traj, grid, path, clearance, 2).status, TDO_ERR_INVALID_ARGUMENT);
}

// The planner's pieces-mode plans on the forests (clearance 0.5), geb079 (0.3) and MovingAI Simple
// (0: the paths graze the cubes).
TEST(TrajectoryClearance, GivenPiecesPlansWhenTheStagesProveTheClearanceThenBruteForceAgrees) {
  const tdo_io::Map forest = load("forest_gen/forest2.bt");
  TestPlanner pf = pieces_planner(forest, 0.5);
  ASSERT_EQ(pf.status(), TDO_OK);
  // maps/forest_gen/start_and_end.csv, pairs 205 and 200.
  check_proven(&pf, 0.5, tdo_vec3{2.083444, -3.562597, 1.0}, tdo_vec3{-1.367670, 3.574024, 1.0});
  check_proven(&pf, 0.5, tdo_vec3{-0.910768, 2.729434, 1.0}, tdo_vec3{4.385792, 2.004155, 1.0});
  const tdo_io::Map geb = load("octomap/geb079.bt");
  TestPlanner pg = pieces_planner(geb, 0.3);
  ASSERT_EQ(pg.status(), TDO_OK);
  check_proven(&pg, 0.3, tdo_vec3{6.0, 5.0, 1.2}, tdo_vec3{11.0, -5.0, 1.2});  // G5, with turns
  const tdo_io::Map simple = load("movingai/Simple.3dmap");
  const std::vector<tdo_io::ScenQuery> queries = simple_queries(20u);
  ASSERT_EQ(queries.size(), 20u);
  TestPlanner ps = pieces_planner(simple, 0.0);
  ASSERT_EQ(ps.status(), TDO_OK);
  for (const tdo_io::ScenQuery& q : queries) {
    SCOPED_TRACE("Simple query " + std::to_string(q.line));
    check_proven(&ps, 0.0, q.start, q.goal);
  }
}

}  // namespace
