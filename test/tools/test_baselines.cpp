// Conformance suite of the bench planners (tools/baselines): every registered planner, on small
// maps built here, must
//  - begin exactly at the start and end exactly at the goal;
//  - keep the clearance, checked by an independent brute-force point-to-box distance on the path
//    sampled every 2 cm (and on the final curve), or report a failure;
//  - report a failure (never a path) when the goal is unreachable;
//  - return the identical result for a fixed seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "baselines.h"
#include "planners_internal.h"

namespace {

using tdo_baselines::Environment;
using tdo_baselines::PlanResult;

constexpr double kClearance = 0.5;

tdo_io::Map make_map(const tdo_grid_desc& d, const std::vector<tdo_box>& boxes) {
  tdo_io::Map m;
  m.desc = d;
  m.boxes = boxes;
  m.path = "conformance";
  return m;
}

// 12 x 12 x 6 m at 0.5 m: a wall across x = 5..6 with a gap at y > 9, and a column.
tdo_io::Map wall_map() {
  tdo_grid_desc d{24, 24, 12, 0.5, {0.0, 0.0, 0.0}};
  return make_map(
      d, {tdo_box{{5.0, 0.0, 0.0}, {6.0, 9.0, 6.0}}, tdo_box{{8.0, 3.0, 0.0}, {9.0, 4.0, 4.0}}});
}

// The goal sits in a closed shell (cavity 4 x 4 x 4 m), so no path exists.
tdo_io::Map shell_map() {
  tdo_grid_desc d{24, 24, 12, 0.5, {0.0, 0.0, 0.0}};
  const double a = 6.0, b = 11.0, t = 0.5;  // shell from a to b, walls t thick
  return make_map(
      d, {tdo_box{{a, a, 0.0}, {b, b, t}},        // floor (z 0..0.5)
          tdo_box{{a, a, 5.5}, {b, b, 6.0}},      // roof
          tdo_box{{a, a, 0.0}, {a + t, b, 6.0}},  // x walls
          tdo_box{{b - t, a, 0.0}, {b, b, 6.0}}, tdo_box{{a, a, 0.0}, {b, a + t, 6.0}},  // y walls
          tdo_box{{a, b - t, 0.0}, {b, b, 6.0}}});
}

double box_distance(const tdo_box& b, const tdo_vec3& p) {
  const double dx = std::max({b.min.x - p.x, 0.0, p.x - b.max.x});
  const double dy = std::max({b.min.y - p.y, 0.0, p.y - b.max.y});
  const double dz = std::max({b.min.z - p.z, 0.0, p.z - b.max.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Independent check: minimum brute-force distance of `pts` (sampled every `step` along the
// polyline) to the map's boxes; -1 when a sample leaves the bounds.
double min_clearance(const tdo_io::Map& m, const std::vector<tdo_vec3>& pts, double step) {
  const tdo_grid_desc& d = m.desc;
  double best = 1e9;
  auto visit = [&](const tdo_vec3& p) {
    if (p.x < d.origin.x || p.y < d.origin.y || p.z < d.origin.z ||
        p.x > d.origin.x + d.nx * d.res || p.y > d.origin.y + d.ny * d.res ||
        p.z > d.origin.z + d.nz * d.res)
      best = -1.0;
    for (const tdo_box& b : m.boxes) best = std::min(best, box_distance(b, p));
  };
  if (pts.size() == 1) visit(pts[0]);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const tdo_vec3 a = pts[i - 1], b = pts[i];
    const double len = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                                 (b.z - a.z) * (b.z - a.z));
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      visit(tdo_vec3{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)});
    }
  }
  return best;
}

bool same(const tdo_vec3& a, const tdo_vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Smaller budgets so that the suite stays fast (also under the sanitizers).
std::unique_ptr<tdo_baselines::Planner> make(const std::string& name, bool failing_query) {
  std::string err;
  auto p = tdo_baselines::make_planner(name, &err);
  EXPECT_TRUE(p) << err;
  if (!p) return p;
  const auto names = p->param_names();
  auto set = [&](const char* k, double v) {
    if (std::find(names.begin(), names.end(), k) != names.end()) {
      EXPECT_TRUE(p->set_param(k, v, &err)) << err;
    }
  };
  set("generations", 40);
  set("population", 16);
  set("waypoints", 4);
  set("max_iterations", failing_query ? 1500.0 : (name.rfind("rrtstar", 0) == 0 ? 600.0 : 20000.0));
  return p;
}

class Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Conformance, EndpointsClearanceDeterminism) {
  const tdo_io::Map map = wall_map();
  std::string err;
  auto env = Environment::create(map, kClearance, 0, &err);
  ASSERT_TRUE(env) << err;
  auto planner = make(GetParam(), false);
  ASSERT_TRUE(planner);
  EXPECT_EQ(planner->name(), GetParam());
  const tdo_vec3 start{1.3, 1.1, 2.2};
  const tdo_vec3 goal{10.7, 1.6, 2.9};
  int successes = 0;
  for (uint64_t seed : {1u, 2u, 3u}) {
    const PlanResult r = planner->plan(*env, start, goal, seed);
    EXPECT_FALSE(r.status.empty());
    EXPECT_GE(r.plan_time_ms, 0.0);
    if (!r.ok) {
      EXPECT_NE(r.status, "ok");
      // Only the swarm optimizers may fail on this easy query (their champion may still collide).
      EXPECT_TRUE(GetParam() == "pso" || GetParam() == "gwo") << GetParam() << ": " << r.status;
      continue;
    }
    ++successes;
    ASSERT_GE(r.path.size(), 2u);
    EXPECT_TRUE(same(r.path.front(), start));
    EXPECT_TRUE(same(r.path.back(), goal));
    ASSERT_GE(r.curve.size(), 2u);
    EXPECT_TRUE(same(r.curve.front(), start));
    EXPECT_TRUE(same(r.curve.back(), goal));
    EXPECT_GE(r.metrics.min_clearance_m, kClearance - 1e-9);
    // A raw path's curve is its polyline: every chord is flown, check it densely. A smoothed
    // path's curve is a 0.1 m sampling of lines and corner curves, whose chords cut inside a bend
    // by up to step^2 / (8 r) (about 0.7 mm at r = 1.8 m): there only the sampled points lie on
    // the path, and they must keep the clearance to the 1e-9 m of the library's own check. The
    // continuous certification of curves is test_pipeline_property.cpp's.
    if (r.curve.size() == r.path.size()) {
      EXPECT_GE(min_clearance(map, r.curve, 0.02), kClearance - 1e-6) << GetParam();
    } else {
      double worst = 1e9;
      for (const tdo_vec3& p : r.curve) worst = std::min(worst, min_clearance(map, {p}, 0.02));
      EXPECT_GE(worst, kClearance - 1e-9) << GetParam();
    }
    // The counted polyline of a raw-path planner is its flown path: check it as well.
    if (r.curve.size() == r.path.size()) {
      EXPECT_GE(min_clearance(map, r.path, 0.02), kClearance - 1e-6);
    }
    EXPECT_GT(r.metrics.length_m, 9.0);  // at least the straight distance
    // Same seed, same result.
    const PlanResult again = planner->plan(*env, start, goal, seed);
    ASSERT_EQ(again.ok, r.ok);
    ASSERT_EQ(again.path.size(), r.path.size());
    for (std::size_t i = 0; i < r.path.size(); ++i) EXPECT_TRUE(same(again.path[i], r.path[i]));
    EXPECT_EQ(again.metrics.turns, r.metrics.turns);
    EXPECT_EQ(std::memcmp(&again.metrics.length_m, &r.metrics.length_m, sizeof(double)), 0);
  }
  if (GetParam() != "pso" && GetParam() != "gwo") {
    EXPECT_EQ(successes, 3);
  }
}

TEST_P(Conformance, UnreachableGoalIsAFailure) {
  const tdo_io::Map map = shell_map();
  std::string err;
  auto env = Environment::create(map, kClearance, 0, &err);
  ASSERT_TRUE(env) << err;
  auto planner = make(GetParam(), true);
  ASSERT_TRUE(planner);
  const PlanResult r = planner->plan(*env, tdo_vec3{1.5, 1.5, 2.0}, tdo_vec3{8.5, 8.5, 3.0}, 7);
  EXPECT_FALSE(r.ok) << GetParam();
  EXPECT_NE(r.status, "ok");
}

INSTANTIATE_TEST_SUITE_P(Planners, Conformance, ::testing::ValuesIn(tdo_baselines::planner_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string s = i.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

TEST(Baselines, RegistryAndParameters) {
  std::string err;
  EXPECT_FALSE(tdo_baselines::make_planner("rrt", &err));
  EXPECT_NE(err.find("unknown planner 'rrt'"), std::string::npos);
  auto p = tdo_baselines::make_planner("tdo", &err);
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->param("lambda"), 50.0);
  EXPECT_DOUBLE_EQ(p->param("mu"), 20.0);
  EXPECT_TRUE(p->set_param("lambda", 10.0, &err));
  EXPECT_DOUBLE_EQ(p->param("lambda"), 10.0);
  EXPECT_FALSE(p->set_param("lambda", -1.0, &err));
  EXPECT_FALSE(p->set_param("nope", 1.0, &err));
  EXPECT_NE(err.find("unknown parameter 'nope'"), std::string::npos);
  EXPECT_TRUE(std::isnan(p->param("nope")));
  auto m = tdo_baselines::make_planner("msf-mtpo", &err);
  ASSERT_TRUE(m);
  EXPECT_DOUBLE_EQ(m->param("lambda"), 0.0);
  EXPECT_FALSE(m->stochastic());
  EXPECT_TRUE(tdo_baselines::make_planner("pso", &err)->stochastic());
}

// A swarm champion that still collides is reported as a failure, not as a path: one waypoint and
// a single generation cannot get around the wall.
TEST(Baselines, SwarmCollidingChampionFails) {
  const tdo_io::Map map = wall_map();
  std::string err;
  auto env = Environment::create(map, kClearance, 0, &err);
  ASSERT_TRUE(env) << err;
  for (const char* name : {"pso", "gwo"}) {
    auto p = tdo_baselines::make_planner(name, &err);
    ASSERT_TRUE(p);
    ASSERT_TRUE(p->set_param("waypoints", 1, &err));
    ASSERT_TRUE(p->set_param("generations", 1, &err));
    ASSERT_TRUE(p->set_param("population", 5, &err));
    // Start and goal on either side of the wall, far from the gap.
    const PlanResult r = p->plan(*env, tdo_vec3{1.0, 1.0, 1.0}, tdo_vec3{11.0, 1.0, 1.0}, 3);
    if (r.ok) {  // it may have found the gap; then the path must be genuinely clear
      EXPECT_GE(min_clearance(map, r.path, 0.02), kClearance - 1e-6);
    } else {
      EXPECT_EQ(r.status, "collides") << name;
    }
  }
}

// evaluate_polyline: the shared measuring code rejects a colliding polyline and measures a clear
// one like the library does (length, turns).
TEST(Baselines, EvaluatePolyline) {
  const tdo_io::Map map = wall_map();
  std::string err;
  auto env = Environment::create(map, kClearance, 0, &err);
  ASSERT_TRUE(env) << err;
  const tdo_vec3 s{1.0, 1.0, 1.0}, g{11.0, 1.0, 1.0};
  PlanResult r = tdo_baselines::evaluate_polyline(*env, {s, g}, s, g);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.status, "collides");
  const tdo_vec3 a{4.0, 10.5, 1.0}, b{7.0, 10.5, 1.0};
  r = tdo_baselines::evaluate_polyline(*env, {s, a, b, g}, s, g);
  ASSERT_TRUE(r.ok) << r.status;
  const double len = std::hypot(3.0, 9.5) + 3.0 + std::hypot(4.0, 9.5);
  EXPECT_NEAR(r.metrics.length_m, len, 1e-9);
  EXPECT_EQ(r.metrics.turns, 2u);
  EXPECT_TRUE(r.has_trajectory);
  EXPECT_GT(r.metrics.flight_time_s, len / 3.0);  // at rest at both corners, v_max 3 m/s
  r = tdo_baselines::evaluate_polyline(*env, {s, a, b, tdo_vec3{11.0, 1.0, 1.5}}, s, g);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.status, "endpoints");
}

// The measuring stage reads a trajectory's samples stored or regenerated (tdo_traj_config
// stream_samples): the same metrics from both, and the samples count (a dropped sample array
// would give the polyline's metrics without flight time or energy).
TEST(Baselines, MetricsWithTrajectoryAreTheSameWithSamplesStreamed) {
  const tdo_io::Map map = wall_map();
  std::string err;
  auto env = Environment::create(map, kClearance, 0, &err);
  ASSERT_TRUE(env) << err;
  const std::vector<tdo_vec3> pts = {
      {1.0, 1.0, 1.0}, {4.0, 10.5, 1.0}, {7.0, 10.5, 1.0}, {11.0, 1.0, 1.0}};
  const tdo_plan_params dp = tdo_baselines::default_params();
  tdo_smooth_input si{};
  si.grid = env->grid();
  si.waypoints = pts.data();
  si.n_waypoints = static_cast<uint32_t>(pts.size());
  si.clearance = env->clearance();
  tdo_plan_smooth_input(&dp, &si);
  si.mode = TDO_SMOOTHING_NONE;
  tdo_smooth_output so{};
  ASSERT_EQ(tdo_smooth_run(env->smoother(), &si, &so), TDO_OK);
  tdo_traj_input ti{};
  ti.path = so.path;
  ti.grid = env->grid();
  ti.clearance = env->clearance();
  tdo_plan_traj_input(&dp, &ti);
  tdo_metrics_input mi{};
  mi.waypoints = pts.data();
  mi.n_waypoints = static_cast<uint32_t>(pts.size());
  mi.grid = env->grid();
  mi.clearance_cap = 10.0;

  PlanResult by_mode[2];
  uint32_t n[2] = {0u, 0u};
  for (uint32_t stream = 0; stream < 2u; ++stream) {
    const uint32_t segs = 64u;
    const tdo_traj_config tc{1u << 14, segs, TDO_TRAJ_PIECES_PER_SEGMENT * segs + 1u,
                             16u,      0u,   stream};
    std::vector<unsigned char> mem(tdo_traj_footprint(&tc));
    ASSERT_FALSE(mem.empty());
    tdo_arena arena;
    tdo_arena_init(&arena, mem.data(), mem.size());
    tdo_traj* traj = nullptr;
    ASSERT_EQ(tdo_traj_init(&traj, &arena, &tc), TDO_OK);
    tdo_traj_output to{};
    const tdo_status ts = tdo_traj_run(traj, &ti, &to);
    ASSERT_EQ(ts, TDO_OK);
    EXPECT_EQ(to.samples == nullptr, stream == 1u);  // the mode took effect
    n[stream] = to.n_samples;
    ASSERT_TRUE(tdo_baselines::metrics_with_trajectory(mi, ts, traj, to, dp.dt, &by_mode[stream]))
        << by_mode[stream].status;
  }
  EXPECT_GT(n[0], 2u);
  EXPECT_EQ(n[1], n[0]);
  EXPECT_TRUE(by_mode[0].has_trajectory);
  EXPECT_TRUE(by_mode[1].has_trajectory);
  EXPECT_NEAR(by_mode[0].metrics.flight_time_s, (n[0] - 1u) * dp.dt, 1e-9);
  EXPECT_GT(by_mode[0].metrics.energy, 0.0);
  for (uint32_t i = 0; i < tdo_metric_count(); ++i) {  // bit for bit
    const double a = tdo_metric_value(&by_mode[0].metrics, i);
    const double b = tdo_metric_value(&by_mode[1].metrics, i);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << tdo_metric_name(i) << ": " << a << " vs " << b;
  }
}

}  // namespace
