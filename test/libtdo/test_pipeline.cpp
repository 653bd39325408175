// tdo_planner_plan (pipeline.h): bad parameters, a clearance that leaves nothing free, an
// unreachable goal, and repeatability of the whole pipeline. The geometric properties of plans on
// many maps are in test/tools/test_pipeline_property.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "test_util.h"

namespace {

using tdo_test::TestPlanner;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int32_t kNx = 20, kNy = 12, kNz = 6;
constexpr double kClearance = 0.5;

/** Capacities for the whole pipeline on a kNx x kNy x kNz grid at 1 m, clearance up to `ratio`. */
tdo_capacity pipeline_cap(double ratio) {
  tdo_capacity cap{};
  tdo_capacity_for_grid(&cap, kNx, kNy, kNz, ratio, 27u, 0u);
  cap.max_boxes = 16;
  return cap;
}

/**
 * A 20 x 12 x 6 m room: a wall at x in [8, 9] with a 2 m door (y in [5, 7]) and a sealed chamber
 * of cubes (shell x 14..18, y 0..4, z 0..4) whose centre voxel (16, 2, 2) is free but unreachable.
 */
tdo_status load_room(tdo_grid* grid, double clearance) {
  const tdo_grid_desc d{kNx, kNy, kNz, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  tdo_status st = tdo_grid_reset(grid, &d);
  const tdo_box walls[2] = {{tdo_vec3{8, 0, 0}, tdo_vec3{9, 5, 6}},
                            {tdo_vec3{8, 7, 0}, tdo_vec3{9, 12, 6}}};
  for (const tdo_box& b : walls)
    if (st == TDO_OK) st = tdo_grid_add_box(grid, &b);
  for (int32_t k = 0; k <= 4; ++k)
    for (int32_t j = 0; j <= 4; ++j)
      for (int32_t i = 14; i <= 18; ++i) {
        const bool shell = i == 14 || i == 18 || j == 0 || j == 4 || k == 0 || k == 4;
        if (shell && st == TDO_OK) st = tdo_grid_add_voxel(grid, i, j, k);
      }
  return st == TDO_OK ? tdo_grid_finish(grid, clearance) : st;
}

tdo_plan_request room_request() {
  tdo_plan_request r{};
  r.start = tdo_vec3{2.3, 2.2, 2.5};
  r.goal = tdo_vec3{12.6, 9.4, 3.1};
  tdo_plan_params_default(&r.params);
  return r;
}

class Pipeline : public ::testing::Test {
 protected:
  Pipeline() : pl_(pipeline_cap(kClearance)) {}
  void SetUp() override {
    ASSERT_EQ(pl_.status(), TDO_OK);
    ASSERT_EQ(load_room(pl_.grid(), kClearance), TDO_OK);
  }
  tdo_status plan(const tdo_plan_request& r) { return tdo_planner_plan(pl_.planner(), &r, &res_); }
  TestPlanner pl_;
  tdo_plan_result res_{};
};

TEST_F(Pipeline, GivenDefaultsWhenPlannedThenOkFromStartToGoal) {
  const tdo_plan_request r = room_request();
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_EQ(res_.status, TDO_OK);
  EXPECT_EQ(res_.reached, TDO_PLAN_TRAJECTORY);
  ASSERT_GE(res_.n_samples, 2u);
  EXPECT_EQ(std::memcmp(&res_.samples[0].p, &r.start, sizeof(tdo_vec3)), 0);
  EXPECT_EQ(std::memcmp(&res_.samples[res_.n_samples - 1].p, &r.goal, sizeof(tdo_vec3)), 0);
  EXPECT_TRUE(res_.feasibility.ok);
}

TEST_F(Pipeline, GivenLambdaAndMuZeroWhenPlannedThenValidWithoutPenalty) {
  tdo_plan_request r = room_request();
  r.params.lambda = 0.0;
  r.params.mu = 0.0;
  ASSERT_EQ(plan(r), TDO_OK);
  // No turn term at all (equal up to the rounding of a differently ordered sum).
  EXPECT_NEAR(res_.search.penalized_cost, res_.search.cost, 1e-12 * res_.search.cost);
  r.params.lambda = 50.0;
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_GT(res_.search.penalized_cost, res_.search.cost);  // the door forces turns
}

TEST_F(Pipeline, GivenAClearStraightSegment_WhenPlannedWithDefaults_ThenTheDirectRouteAndNoSearch) {
  tdo_plan_request r = room_request();
  r.goal = tdo_vec3{6.4, 9.1, 4.2};  // west of the wall: the straight segment keeps 0.5 m
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_EQ(res_.search.direct, 1u);
  EXPECT_EQ(res_.search.expansions, 0u);
  EXPECT_EQ(res_.search.n_path, 0u);
  const double dx = r.goal.x - r.start.x, dy = r.goal.y - r.start.y, dz = r.goal.z - r.start.z;
  EXPECT_DOUBLE_EQ(res_.search.cost, std::sqrt(dx * dx + dy * dy + dz * dz));
  ASSERT_EQ(res_.n_waypoints, 2u);
  EXPECT_EQ(std::memcmp(&res_.waypoints[0], &r.start, sizeof(tdo_vec3)), 0);
  EXPECT_EQ(std::memcmp(&res_.waypoints[1], &r.goal, sizeof(tdo_vec3)), 0);
  EXPECT_TRUE(res_.feasibility.ok);
  // Every sample on the segment, at least the clearance from the wall and the chamber.
  ASSERT_GE(res_.n_samples, 2u);
  EXPECT_GE(res_.feasibility.min_clearance, kClearance - 1e-9);
  for (uint32_t i = 0; i < res_.n_samples; ++i) {
    const tdo_vec3 p = res_.samples[i].p;
    const double u = ((p.x - r.start.x) * dx + (p.y - r.start.y) * dy + (p.z - r.start.z) * dz) /
                     (dx * dx + dy * dy + dz * dz);
    const double ex = r.start.x + u * dx - p.x, ey = r.start.y + u * dy - p.y,
                 ez = r.start.z + u * dz - p.z;
    ASSERT_LT(std::sqrt(ex * ex + ey * ey + ez * ez), 1e-9) << "sample " << i;
  }
}

TEST_F(Pipeline, GivenASegmentThroughTheWall_WhenPlanned_ThenTheSearchRunsAndNoDirectRoute) {
  const tdo_plan_request r = room_request();  // start and goal on both sides of the wall
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_EQ(res_.search.direct, 0u);
  EXPECT_GT(res_.search.expansions, 0u);
  EXPECT_GT(res_.n_waypoints, 2u);
}

TEST_F(Pipeline, GivenAClearSegment_WhenOnlySearchingOrPlainAStar_ThenTheGridPathAsBefore) {
  tdo_plan_request r = room_request();
  r.goal = tdo_vec3{6.4, 9.1, 4.2};
  r.params.depth = TDO_PLAN_SEARCH;  // the raw search keeps its grid path (the oracle's)
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_EQ(res_.search.direct, 0u);
  EXPECT_GT(res_.search.n_path, 1u);
  r.params.depth = TDO_PLAN_TRAJECTORY;  // plain A*: no heading cost, no direct route
  r.params.lambda = 0.0;
  r.params.mu = 0.0;
  r.params.theta_max = 0.0;
  r.params.d_th = 0.0;
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_EQ(res_.search.direct, 0u);
  EXPECT_GT(res_.search.n_path, 1u);
}

TEST_F(Pipeline, GivenEndsTheSearchRefuses_WhenTheSegmentIsClear_ThenTheSearchsStatus) {
  tdo_plan_request r = room_request();
  r.goal = r.start;
  EXPECT_EQ(plan(r), TDO_ERR_START_EQUALS_GOAL);
  r.goal = tdo_vec3{6.4, 9.1, 21.0};  // above the room
  EXPECT_EQ(plan(r), TDO_ERR_GOAL_OUT_OF_BOUNDS);
}

/** One bad value of one parameter. */
struct BadParam {
  const char* name;
  double value;
  std::function<void(tdo_plan_params*, double)> set;
};

std::vector<BadParam> bad_params() {
  std::vector<BadParam> v;
  const auto add = [&v](const char* name, std::function<void(tdo_plan_params*, double)> set,
                        std::vector<double> values) {
    for (double x : values) v.push_back(BadParam{name, x, set});
  };
  const std::vector<double> not_non_negative = {-1.0, -1e-300, kNaN, kInfinity, -kInfinity};
  const std::vector<double> not_positive = {0.0, -0.0, -2.0, kNaN, kInfinity, -kInfinity};
  add(
      "lambda", [](tdo_plan_params* p, double x) { p->lambda = x; }, not_non_negative);
  add(
      "mu", [](tdo_plan_params* p, double x) { p->mu = x; }, not_non_negative);
  add(
      "k", [](tdo_plan_params* p, double x) { p->k = x; }, not_positive);
  add(
      "v_max", [](tdo_plan_params* p, double x) { p->v_max = x; }, not_positive);
  add(
      "a_max", [](tdo_plan_params* p, double x) { p->a_max = x; }, not_positive);
  add(
      "j_max", [](tdo_plan_params* p, double x) { p->j_max = x; }, not_positive);
  add(
      "dt", [](tdo_plan_params* p, double x) { p->dt = x; }, not_positive);
  add(
      "a_lat_max", [](tdo_plan_params* p, double x) { p->a_lat_max = x; }, not_positive);
  add(
      "v_cruise", [](tdo_plan_params* p, double x) { p->v_cruise = x; }, not_positive);
  add(
      "stop_angle", [](tdo_plan_params* p, double x) { p->stop_angle = x; }, not_positive);
  add(
      "theta_max", [](tdo_plan_params* p, double x) { p->theta_max = x; }, not_non_negative);
  add("h_weight", [](tdo_plan_params* p, double x) { p->h_weight = x; },
      {0.0, 0.5, kNaN, kInfinity});
  return v;
}

TEST_F(Pipeline, GivenZeroNegativeOrNonFiniteParameterWhenPlannedThenInvalidArgument) {
  for (const BadParam& b : bad_params()) {
    SCOPED_TRACE(std::string(b.name) + " = " + std::to_string(b.value));
    tdo_plan_request r = room_request();
    b.set(&r.params, b.value);
    res_.n_samples = 12345u;
    EXPECT_EQ(plan(r), TDO_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(res_.status, TDO_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(res_.n_samples, 0u);
    EXPECT_EQ(res_.samples, nullptr);
    EXPECT_EQ(res_.n_grid_path, 0u);
  }
  // The planner is unharmed: the next good request plans.
  EXPECT_EQ(plan(room_request()), TDO_OK);
}

// Only values inside each enum's range of values (C++ [dcl.enum]) are written, so the test stays
// defined behaviour (UBSan): 3 for the three-valued smoothing and correction modes.
TEST_F(Pipeline, GivenUnknownModesOrNullPointersWhenPlannedThenInvalidArgument) {
  const int bogus = 3;
  tdo_plan_request r = room_request();
  std::memcpy(&r.params.smoothing, &bogus, sizeof bogus);
  EXPECT_EQ(plan(r), TDO_ERR_INVALID_ARGUMENT);
  r = room_request();
  std::memcpy(&r.params.correction, &bogus, sizeof bogus);
  EXPECT_EQ(plan(r), TDO_ERR_INVALID_ARGUMENT);
  r = room_request();
  EXPECT_EQ(tdo_planner_plan(nullptr, &r, &res_), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_planner_plan(pl_.planner(), nullptr, &res_), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_planner_plan(pl_.planner(), &r, nullptr), TDO_ERR_INVALID_ARGUMENT);
}

TEST_F(Pipeline, GivenNonFiniteStartOrGoalWhenPlannedThenNamedStatus) {
  tdo_plan_request r = room_request();
  r.start.y = kNaN;
  const tdo_status st = plan(r);
  EXPECT_TRUE(st == TDO_ERR_INVALID_ARGUMENT || st == TDO_ERR_START_OUT_OF_BOUNDS)
      << tdo_status_str(st);
  r = room_request();
  r.goal.z = kInfinity;
  const tdo_status sg = plan(r);
  EXPECT_TRUE(sg == TDO_ERR_INVALID_ARGUMENT || sg == TDO_ERR_GOAL_OUT_OF_BOUNDS)
      << tdo_status_str(sg);
  EXPECT_EQ(res_.n_samples, 0u);
}

TEST_F(Pipeline, GivenGoalInSealedChamberWhenPlannedAtEveryDepthThenNoPath) {
  for (int depth = TDO_PLAN_SEARCH; depth <= TDO_PLAN_TRAJECTORY; ++depth) {
    for (tdo_search_kind kind : {TDO_SEARCH_ASTAR, TDO_SEARCH_BIDIR}) {
      SCOPED_TRACE("depth " + std::to_string(depth) + ", " + tdo_test::kind_name(kind));
      tdo_plan_request r = room_request();
      r.goal = tdo_vec3{16.5, 2.5, 2.5};  // free at 0.5 m, walled in
      r.params.depth = static_cast<tdo_plan_depth>(depth);
      r.params.search = kind;
      EXPECT_EQ(plan(r), TDO_ERR_NO_PATH);
      EXPECT_EQ(res_.status, TDO_ERR_NO_PATH);
      EXPECT_EQ(res_.n_samples, 0u);
      EXPECT_EQ(res_.n_grid_path, 0u);
    }
  }
}

// Voxel (7, 2, 2) is free at 0.5 m (its centre x = 7.5 is exactly 0.5 m from the wall at x = 8),
// but the point x = 7.7 in it is 0.3 m from the wall: no output can keep the clearance there.
TEST_F(Pipeline,
       GivenStartOrGoalPointWithinClearanceInAFreeVoxelWhenPlannedThenBlockedAtEveryDepth) {
  tdo_voxel v{};
  ASSERT_TRUE(tdo_grid_world_to_voxel(pl_.grid(), tdo_vec3{7.7, 2.5, 2.5}, &v));
  ASSERT_FALSE(tdo_grid_is_blocked(pl_.grid(), v));
  for (int depth = TDO_PLAN_SEARCH; depth <= TDO_PLAN_TRAJECTORY; ++depth) {
    SCOPED_TRACE("depth " + std::to_string(depth));
    tdo_plan_request r = room_request();
    r.params.depth = static_cast<tdo_plan_depth>(depth);
    r.start = tdo_vec3{7.7, 2.5, 2.5};
    EXPECT_EQ(plan(r), TDO_ERR_START_BLOCKED);
    EXPECT_EQ(res_.n_samples, 0u);
    r = room_request();
    r.params.depth = static_cast<tdo_plan_depth>(depth);
    r.goal = tdo_vec3{7.7, 2.5, 2.5};
    EXPECT_EQ(plan(r), TDO_ERR_GOAL_BLOCKED);
    r.goal = tdo_vec3{7.5, 2.5, 2.5};  // exactly at the clearance: allowed
    EXPECT_EQ(plan(r), TDO_OK);
  }
}

TEST(PipelineClearance, GivenClearanceSoLargeNothingIsFreeWhenPlannedThenStartBlocked) {
  const double clearance = 30.0;  // more than the room's diagonal from the walls
  TestPlanner pl(pipeline_cap(clearance));
  ASSERT_EQ(pl.status(), TDO_OK);
  ASSERT_EQ(load_room(pl.grid(), clearance), TDO_OK);
  EXPECT_EQ(tdo_grid_blocked_count(pl.grid()), static_cast<uint32_t>(kNx * kNy * kNz));
  tdo_plan_result res{};
  for (int depth = TDO_PLAN_SEARCH; depth <= TDO_PLAN_TRAJECTORY; ++depth) {
    tdo_plan_request r = room_request();
    r.params.depth = static_cast<tdo_plan_depth>(depth);
    EXPECT_EQ(tdo_planner_plan(pl.planner(), &r, &res), TDO_ERR_START_BLOCKED);
    EXPECT_EQ(res.n_samples, 0u);
  }
}

TEST(PipelineClearance, GivenClearanceBeyondTheStencilWhenFinishingThenClearanceCapacity) {
  TestPlanner pl(pipeline_cap(kClearance));
  ASSERT_EQ(pl.status(), TDO_OK);
  EXPECT_EQ(load_room(pl.grid(), 30.0), TDO_ERR_CLEARANCE_CAPACITY);
  tdo_plan_request r = room_request();
  tdo_plan_result res{};
  EXPECT_EQ(tdo_planner_plan(pl.planner(), &r, &res), TDO_ERR_MAP_NOT_READY);
}

TEST(PipelineNotConfigured, GivenSearchOnlyCapacitiesWhenAskedForATrajectoryThenNotConfigured) {
  tdo_capacity cap = pipeline_cap(kClearance);
  cap.max_checks = 0;  // no correction, smoothing or trajectory contexts
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  ASSERT_EQ(load_room(pl.grid(), kClearance), TDO_OK);
  tdo_plan_request r = room_request();
  tdo_plan_result res{};
  EXPECT_EQ(tdo_planner_plan(pl.planner(), &r, &res), TDO_ERR_NOT_CONFIGURED);
  r.params.depth = TDO_PLAN_SEARCH;
  EXPECT_EQ(tdo_planner_plan(pl.planner(), &r, &res), TDO_OK);
}

/** Everything a plan produced, as bytes, for bit-exact comparison. */
std::vector<unsigned char> bytes_of(const tdo_plan_result& r) {
  std::vector<unsigned char> b;
  const auto put = [&b](const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    b.insert(b.end(), c, c + n);
  };
  put(&r.status, sizeof r.status);
  put(&r.search.cost, sizeof r.search.cost);
  put(&r.search.expansions, sizeof r.search.expansions);
  put(r.grid_path, r.n_grid_path * sizeof(tdo_vec3));
  put(r.waypoints, r.n_waypoints * sizeof(tdo_vec3));
  for (uint32_t i = 0; i < r.path.n; ++i) {  // field by field: structs have padding
    const tdo_path_segment& s = r.path.seg[i];
    put(&s.kind, sizeof s.kind);
    put(s.p, sizeof s.p);
    put(&s.length, sizeof s.length);
    put(&s.v_limit, sizeof s.v_limit);
    put(&s.stop_at_end, sizeof s.stop_at_end);
  }
  put(r.samples, r.n_samples * sizeof(tdo_sample));  // doubles only
  const tdo_metrics& m = r.metrics;
  for (double x : {m.length_m, m.total_turn_deg, m.min_clearance_m, m.avg_curvature, m.smoothness,
                   m.energy, m.flight_time_s})
    put(&x, sizeof x);
  put(&m.turns, sizeof m.turns);
  return b;
}

// max_waypoints sizes smoothing and trajectory by the corrected waypoints instead of the grid path:
// with exactly the plan's count the result is the unlimited one bit for bit, in a smaller arena;
// one fewer stops the smoothing with TDO_ERR_PATH_CAPACITY. A path needs two ends: 1 is refused.
TEST(PipelineCapacity, GivenMaxWaypointsOneShortOfThePlan_WhenPlanned_ThenPathCapacityElseTheSame) {
  const tdo_capacity full = pipeline_cap(kClearance);
  TestPlanner ref(full);
  ASSERT_EQ(ref.status(), TDO_OK);
  ASSERT_EQ(load_room(ref.grid(), kClearance), TDO_OK);
  const tdo_plan_request r = room_request();
  tdo_plan_result want{};
  ASSERT_EQ(tdo_planner_plan(ref.planner(), &r, &want), TDO_OK);
  ASSERT_GE(want.n_waypoints, 3u) << "the room's plan should turn at the door";
  ASSERT_LT(want.n_waypoints + 2u, full.max_path + 2u) << "too long a plan to tell";
  const std::vector<unsigned char> want_bytes = bytes_of(want);
  tdo_planner_config cfg_full{}, cfg_exact{};
  cfg_full.cap = full;
  cfg_exact.cap = full;
  cfg_exact.cap.max_waypoints = want.n_waypoints;
  EXPECT_LT(tdo_planner_footprint(&cfg_exact), tdo_planner_footprint(&cfg_full));
  TestPlanner exact(cfg_exact.cap);
  ASSERT_EQ(exact.status(), TDO_OK);
  ASSERT_EQ(load_room(exact.grid(), kClearance), TDO_OK);
  tdo_plan_result got{};
  ASSERT_EQ(tdo_planner_plan(exact.planner(), &r, &got), TDO_OK);
  EXPECT_TRUE(bytes_of(got) == want_bytes);
  tdo_capacity short_cap = full;
  short_cap.max_waypoints = want.n_waypoints - 1u;
  TestPlanner shorter(short_cap);
  ASSERT_EQ(shorter.status(), TDO_OK);
  ASSERT_EQ(load_room(shorter.grid(), kClearance), TDO_OK);
  EXPECT_EQ(tdo_planner_plan(shorter.planner(), &r, &got), TDO_ERR_PATH_CAPACITY);
  tdo_planner_config one{};
  one.cap = full;
  one.cap.max_waypoints = 1u;
  EXPECT_EQ(tdo_planner_footprint(&one), 0u);
}

TEST_F(Pipeline, GivenTheSameRequestTwiceWithAnotherInBetweenThenBitIdenticalResults) {
  const tdo_plan_request r = room_request();
  ASSERT_EQ(plan(r), TDO_OK);
  const std::vector<unsigned char> first = bytes_of(res_);
  tdo_plan_request other = room_request();
  other.goal = tdo_vec3{18.5, 10.5, 1.5};
  other.params.smoothing = TDO_SMOOTHING_ARC;
  other.params.depth = TDO_PLAN_SMOOTH;
  ASSERT_EQ(plan(other), TDO_OK);
  ASSERT_EQ(plan(r), TDO_OK);
  EXPECT_TRUE(first == bytes_of(res_));
  EXPECT_GT(first.size(), 1000u);
}

// The coarse guide (tdo_capacity.guide_shift, docs/design.md s.1): on 32 x 16 x 4 maps crossed by
// walls with one hole each, and random voxels, a guided planner plans whenever the reference
// Dijkstra finds a path (TDO_ERR_NO_PATH otherwise), every path is legal, and both ends of the
// design run: plans found in the corridor, and plans found on the whole grid after a coarse route
// through a wall (clearance 0 keeps the cells on both sides of a one-voxel wall free) left the
// corridor without a path. A planner without the guide reports none.
TEST(PlannerGuide, GivenWallMaps_WhenPlanningWithTheGuide_ThenAPlanWheneverOneExists) {
  constexpr int32_t nx = 32, ny = 16, nz = 4;
  tdo_capacity cap{};
  tdo_capacity_for_grid(&cap, nx, ny, nz, 0.0, 27u, 0u);
  EXPECT_EQ(cap.guide_shift, 0u);  // below 2^19 voxels tdo_capacity_for_grid sets none
  cap.guide_shift = 2u;
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  tdo_test::Rng rng(777);
  int in_corridor = 0, whole_grid = 0, no_path = 0;
  for (int round = 0; round < 60; ++round) {
    tdo_test::VoxelMap m = tdo_test::random_voxel_map(rng, nx, ny, nz, 1.0, 0.05);
    const int walls = rng.range(0, 3);
    for (int w = 0; w < walls; ++w) {
      const int32_t x = rng.range(4, nx - 5);
      const int32_t hy = rng.range(0, ny - 1), hz = rng.range(0, nz - 1);
      const bool sealed = rng.uniform() < 0.1;
      for (int32_t k = 0; k < nz; ++k)
        for (int32_t j = 0; j < ny; ++j) m.set(x, j, k, sealed || j != hy || k != hz);
    }
    const tdo_voxel s{rng.range(0, 3), rng.range(0, ny - 1), rng.range(0, nz - 1)};
    const tdo_voxel g{rng.range(nx - 4, nx - 1), rng.range(0, ny - 1), rng.range(0, nz - 1)};
    m.set(s.i, s.j, s.k, false);
    m.set(g.i, g.j, g.k, false);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
    tdo_plan_request r{};
    r.start = m.center(s);
    r.goal = m.center(g);
    tdo_plan_params_default(&r.params);
    r.params.depth = TDO_PLAN_SEARCH;
    tdo_plan_result res{};
    const tdo_status st = tdo_planner_plan(pl.planner(), &r, &res);
    const double want = tdo_test::reference_cost(m, s, g);
    SCOPED_TRACE(::testing::Message() << "round " << round);
    if (!(want < kInfinity)) {
      EXPECT_EQ(st, TDO_ERR_NO_PATH) << tdo_status_str(st);
      ++no_path;
      continue;
    }
    ASSERT_EQ(st, TDO_OK) << tdo_status_str(st);
    EXPECT_TRUE(tdo_test::valid_path(m, res.search, s, g));
    ASSERT_TRUE(res.search.guide >= 1u && res.search.guide <= 3u) << res.search.guide;
    if (res.search.guide == 1u) ++in_corridor;
    if (res.search.guide == 2u) ++whole_grid;  // the corridor held no path
  }
  EXPECT_GT(in_corridor, 0);
  EXPECT_GT(whole_grid, 0);
  EXPECT_GT(no_path, 0);
  TestPlanner plain(pipeline_cap(kClearance));
  ASSERT_EQ(plain.status(), TDO_OK);
  ASSERT_EQ(load_room(plain.grid(), kClearance), TDO_OK);
  tdo_plan_request r = room_request();
  tdo_plan_result res{};
  ASSERT_EQ(tdo_planner_plan(plain.planner(), &r, &res), TDO_OK);
  EXPECT_EQ(res.search.guide, 0u);
}

// A thick wall with a slot that keeps the clearance but no voxel one edge deeper (so the route's
// coarse grid has no cell there) near the straight line, and a wide opening far from it: the
// second route (shallow coarse grid) finds the slot, whose plan is far shorter than the detour.
TEST(PlannerGuide, GivenASlotOnlyTheShallowGridSees_WhenPlanningWithTheGuide_ThenThroughTheSlot) {
  constexpr int32_t nx = 48, ny = 64, nz = 1;
  constexpr double clearance = 2.2;  // voxel edges of 1 m; the slot's centre row is 2.5 m clear
  tdo_capacity cap{};
  tdo_capacity_for_grid(&cap, nx, ny, nz, clearance, 27u, 0u);
  cap.guide_shift = 2u;
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  tdo_test::VoxelMap m(nx, ny, nz, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  for (int32_t i = 12; i < 28; ++i)
    for (int32_t j = 0; j < ny; ++j)
      m.set(i, j, 0, !(j >= 16 && j <= 20) && !(j >= 44));  // slot y 16..20, opening y >= 44
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m, clearance), TDO_OK);
  tdo_plan_request r{};
  r.start = m.center(tdo_voxel{4, 18, 0});
  r.goal = m.center(tdo_voxel{43, 18, 0});
  tdo_plan_params_default(&r.params);
  r.params.depth = TDO_PLAN_SEARCH;
  tdo_plan_result res{};
  ASSERT_EQ(tdo_planner_plan(pl.planner(), &r, &res), TDO_OK);
  EXPECT_EQ(res.search.guide, 1u);
  // Through the slot: 39 m straight; around through the opening: more than 2 * hypot(26, 19.5).
  EXPECT_LT(res.search.cost, 41.0);
  EXPECT_TRUE(tdo_test::valid_path(m, res.search, tdo_voxel{4, 18, 0}, tdo_voxel{43, 18, 0}));
}

TEST(PlanStageInputs, GivenParams_WhenStageInputsFilled_ThenTheirFieldsComeFromParamsAndNoOther) {
  tdo_plan_params p;
  tdo_plan_params_default(&p);
  p.correction = TDO_CORRECT_GREEDY_LOS;
  p.turn_threshold = 0.25;
  p.shorten = 0;
  p.smoothing = TDO_SMOOTHING_ARC;
  p.k = 1.75;
  p.v_cruise = 1.5;
  p.v_max = 2.5;
  p.a_lat_max = 3.5;
  p.a_max = 4.5;
  p.j_max = 5.5;
  p.stop_angle = 1.25;
  p.corner_time = 0.5;
  p.dt = 0.02;
  const tdo_vec3 pts[2] = {{0, 0, 0}, {1, 0, 0}};

  tdo_correct_input ci{};
  ci.points = pts;
  ci.clearance = 0.3;
  tdo_plan_correct_input(&p, &ci);
  EXPECT_EQ(ci.mode, TDO_CORRECT_GREEDY_LOS);
  EXPECT_DOUBLE_EQ(ci.turn_threshold, 0.25);
  EXPECT_EQ(ci.shorten, 0);
  EXPECT_EQ(ci.points, pts);
  EXPECT_DOUBLE_EQ(ci.clearance, 0.3);

  tdo_smooth_input si{};
  si.clearance = 0.3;
  tdo_plan_smooth_input(&p, &si);
  EXPECT_EQ(si.mode, TDO_SMOOTHING_ARC);
  EXPECT_DOUBLE_EQ(si.k, 1.75);
  EXPECT_DOUBLE_EQ(si.v_cruise, 1.5);
  EXPECT_DOUBLE_EQ(si.v_max, 2.5);
  EXPECT_DOUBLE_EQ(si.a_lat_max, 3.5);
  EXPECT_DOUBLE_EQ(si.j_max, 5.5);
  EXPECT_DOUBLE_EQ(si.stop_angle, 1.25);
  EXPECT_DOUBLE_EQ(si.corner_time, 0.5);
  EXPECT_DOUBLE_EQ(si.min_radius, 0.0);  // not a plan parameter
  EXPECT_DOUBLE_EQ(si.clearance, 0.3);

  tdo_traj_input ti{};
  ti.clearance = 0.3;
  tdo_plan_traj_input(&p, &ti);
  EXPECT_DOUBLE_EQ(ti.v_max, 2.5);
  EXPECT_DOUBLE_EQ(ti.a_max, 4.5);
  EXPECT_DOUBLE_EQ(ti.j_max, 5.5);
  EXPECT_DOUBLE_EQ(ti.a_lat_max, 3.5);
  EXPECT_DOUBLE_EQ(ti.dt, 0.02);
  EXPECT_DOUBLE_EQ(ti.clearance, 0.3);

  tdo_plan_correct_input(nullptr, &ci);  // nothing for NULL pointers
  tdo_plan_smooth_input(&p, nullptr);
  tdo_plan_traj_input(nullptr, nullptr);
  EXPECT_DOUBLE_EQ(ci.turn_threshold, 0.25);
}

TEST(PlanMetricNames, GivenMetrics_WhenReadByIndex_ThenEveryRealFieldUnderItsNameAndNaNBeyond) {
  tdo_metrics m{};
  m.length_m = 1.0;
  m.total_turn_deg = 2.0;
  m.min_clearance_m = 3.0;
  m.avg_curvature = 4.0;
  m.smoothness = 5.0;
  m.energy = 6.0;
  m.flight_time_s = 7.0;
  const char* names[] = {"length_m",   "total_turn_deg", "min_clearance_m", "avg_curvature",
                         "smoothness", "energy",         "flight_time_s"};
  ASSERT_EQ(tdo_metric_count(), 7u);
  for (uint32_t i = 0; i < 7u; ++i) {
    EXPECT_STREQ(tdo_metric_name(i), names[i]);
    EXPECT_DOUBLE_EQ(tdo_metric_value(&m, i), static_cast<double>(i + 1u));
  }
  EXPECT_EQ(tdo_metric_name(7u), nullptr);
  EXPECT_TRUE(std::isnan(tdo_metric_value(&m, 7u)));
  EXPECT_TRUE(std::isnan(tdo_metric_value(nullptr, 0u)));
}

}  // namespace
