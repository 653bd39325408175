// Stage 6 (metrics.h, docs/design.md s.6): metrics on shapes with known answers, computed here
// independently (closed forms, or dense quadrature with the test's own Bezier formulas).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "tdo/metrics.h"
#include "tdo/path.h"
#include "tdo/trajectory.h"
#include "test_util.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfty = std::numeric_limits<double>::infinity();

double dist(const tdo_vec3& a, const tdo_vec3& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

tdo_path_segment line(tdo_vec3 a, tdo_vec3 b) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_LINE;
  s.p[0] = a;
  s.p[1] = b;
  s.length = dist(a, b);
  s.v_limit = kInfty;
  return s;
}

/** Quarter circle (or any sweep < pi) from a to b about c in the plane they span. */
tdo_path_segment arc(tdo_vec3 a, tdo_vec3 b, tdo_vec3 c, double sweep) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_ARC;
  s.p[0] = a;
  s.p[1] = b;
  s.p[2] = c;
  s.length = dist(a, c) * sweep;
  s.v_limit = kInfty;
  return s;
}

tdo_path_segment bezier(tdo_vec3 p0, tdo_vec3 p1, tdo_vec3 p2, tdo_vec3 p3) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_BEZIER;
  s.p[0] = p0;
  s.p[1] = p1;
  s.p[2] = p2;
  s.p[3] = p3;
  s.length = tdo_segment_length(&s);
  s.v_limit = kInfty;
  return s;
}

tdo_path make_path(const std::vector<tdo_path_segment>& segs) {
  tdo_path p{};
  p.seg = segs.data();
  p.n = static_cast<uint32_t>(segs.size());
  for (const auto& s : segs) p.length += s.length;
  return p;
}

tdo_metrics_input input(const std::vector<tdo_vec3>& w, const tdo_path* path = nullptr) {
  tdo_metrics_input in{};
  in.waypoints = w.data();
  in.n_waypoints = static_cast<uint32_t>(w.size());
  in.path = path;
  in.dt = 0.01;
  in.clearance_cap = 10.0;
  return in;
}

/** The test's own cubic Bezier: integrals of kappa and kappa^2 over arclength, Simpson in u. */
void bezier_integrals(const tdo_path_segment& s, double* abs_k, double* sq_k, double* len) {
  const auto d1 = [&](double u, int axis) {
    const double p[4] = {axis == 0   ? s.p[0].x
                         : axis == 1 ? s.p[0].y
                                     : s.p[0].z,
                         axis == 0   ? s.p[1].x
                         : axis == 1 ? s.p[1].y
                                     : s.p[1].z,
                         axis == 0   ? s.p[2].x
                         : axis == 1 ? s.p[2].y
                                     : s.p[2].z,
                         axis == 0   ? s.p[3].x
                         : axis == 1 ? s.p[3].y
                                     : s.p[3].z};
    const double w = 1 - u;
    return 3 * (w * w * (p[1] - p[0]) + 2 * w * u * (p[2] - p[1]) + u * u * (p[3] - p[2]));
  };
  const auto d2 = [&](double u, int axis) {
    const double p[4] = {axis == 0   ? s.p[0].x
                         : axis == 1 ? s.p[0].y
                                     : s.p[0].z,
                         axis == 0   ? s.p[1].x
                         : axis == 1 ? s.p[1].y
                                     : s.p[1].z,
                         axis == 0   ? s.p[2].x
                         : axis == 1 ? s.p[2].y
                                     : s.p[2].z,
                         axis == 0   ? s.p[3].x
                         : axis == 1 ? s.p[3].y
                                     : s.p[3].z};
    return 6 * ((1 - u) * (p[2] - 2 * p[1] + p[0]) + u * (p[3] - 2 * p[2] + p[1]));
  };
  const int n = 20000;  // even
  *abs_k = *sq_k = *len = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    const double a[3] = {d1(u, 0), d1(u, 1), d1(u, 2)}, b[3] = {d2(u, 0), d2(u, 1), d2(u, 2)};
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    const double sp = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double k = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (sp * sp * sp);
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    *abs_k += w * k * sp;
    *sq_k += w * k * k * sp;
    *len += w * sp;
  }
  *abs_k /= 3.0 * n;
  *sq_k /= 3.0 * n;
  *len /= 3.0 * n;
}

// ---------------------------------------------------------------------------------------------

TEST(Metrics, GivenStraightLineThenZeroCurvatureSmoothnessOneNoTurns) {
  const std::vector<tdo_vec3> w{{0, 0, 0}, {3, 4, 12}};
  const std::vector<tdo_path_segment> segs{line(w[0], w[1])};
  const tdo_path path = make_path(segs);
  tdo_metrics m{};
  const tdo_metrics_input in = input(w, &path);
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_DOUBLE_EQ(m.length_m, 13.0);
  EXPECT_EQ(m.turns, 0u);
  EXPECT_EQ(m.total_turn_deg, 0.0);
  EXPECT_EQ(m.avg_curvature, 0.0);
  EXPECT_EQ(m.smoothness, 1.0);
  EXPECT_EQ(m.curvature_continuous, 1);
  EXPECT_EQ(m.energy, 0.0);                // no samples
  EXPECT_EQ(m.flight_time_s, 0.0);         // no samples
  EXPECT_EQ(m.min_clearance_m, HUGE_VAL);  // no grid
}

TEST(Metrics, GivenQuarterCircleThenCurvatureIntegralsAreKnown) {
  // GIVEN a quarter circle of radius R: integral kappa ds = pi/2, integral kappa^2 ds = pi/(2R)
  for (double r : {0.5, 2.0, 7.0}) {
    const std::vector<tdo_vec3> w{{r, 0, 1}, {r, r, 1}, {0, r, 1}};
    const std::vector<tdo_path_segment> segs{arc({r, 0, 1}, {0, r, 1}, {0, 0, 1}, kPi / 2)};
    const tdo_path path = make_path(segs);
    tdo_metrics m{};
    const tdo_metrics_input in = input(w, &path);
    ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
    EXPECT_NEAR(m.length_m, kPi * r / 2, 1e-12);
    EXPECT_NEAR(m.avg_curvature, 1.0 / r, 1e-12);
    EXPECT_NEAR(m.smoothness, 1.0 / (1.0 + kPi / (2.0 * r)), 1e-12);
    EXPECT_EQ(m.curvature_continuous, 1);
    EXPECT_EQ(m.turns, 1u);
    EXPECT_NEAR(m.total_turn_deg, 90.0, 1e-9);
  }
}

TEST(Metrics, GivenLineArcLineThenCurvatureJumpsAndIntegralsAddUp) {
  const double r = 2.0;
  const std::vector<tdo_vec3> w{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}};
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {10 - r, 0, 0}),
                                           arc({10 - r, 0, 0}, {10, r, 0}, {10 - r, r, 0}, kPi / 2),
                                           line({10, r, 0}, {10, 10, 0})};
  const tdo_path path = make_path(segs);
  tdo_metrics m{};
  const tdo_metrics_input in = input(w, &path);
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  const double len = 2 * (10 - r) + kPi * r / 2;
  EXPECT_NEAR(m.length_m, len, 1e-12);
  EXPECT_NEAR(m.avg_curvature, (kPi / 2) / len, 1e-12);
  EXPECT_NEAR(m.smoothness, 1.0 / (1.0 + kPi / (2 * r)), 1e-12);
  EXPECT_EQ(m.curvature_continuous, 0);  // 0 -> 1/r at both ends of the arc
}

TEST(Metrics, GivenG2BezierCornerThenCurvatureContinuousAndTotalTurnIsTheDeflection) {
  // GIVEN lines joined by a cubic (a, w, w, b): zero curvature at both ends of the corner
  const std::vector<tdo_vec3> w{
      {0, 0, 0}, {10, 0, 0}, {10 + 4 * std::cos(1.0), 4 * std::sin(1.0), 0}};
  const tdo_vec3 a{7, 0, 0};
  const tdo_vec3 b{10 + 3 * std::cos(1.0), 3 * std::sin(1.0), 0};
  const std::vector<tdo_path_segment> segs{line(w[0], a), bezier(a, w[1], w[1], b), line(b, w[2])};
  const tdo_path path = make_path(segs);
  tdo_metrics m{};
  const tdo_metrics_input in = input(w, &path);
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  double abs_k, sq_k, blen;
  bezier_integrals(segs[1], &abs_k, &sq_k, &blen);
  const double len = 7.0 + blen + 1.0;
  // THEN integral |kappa| ds of a planar corner without inflection is its deflection (1 rad)
  EXPECT_NEAR(abs_k, 1.0, 1e-6);  // the test's own quadrature agrees with geometry
  EXPECT_NEAR(m.length_m, len, 1e-9);
  EXPECT_NEAR(m.avg_curvature * m.length_m, 1.0, 1e-6);
  EXPECT_NEAR(m.smoothness, 1.0 / (1.0 + sq_k), 1e-6);
  EXPECT_EQ(m.curvature_continuous, 1);
  EXPECT_EQ(m.turns, 1u);
  EXPECT_NEAR(m.total_turn_deg, 180.0 / kPi, 1e-9);
}

TEST(Metrics, GivenPolylineWithKnownTurnsThenTurnsAndDiscreteCurvature) {
  // GIVEN a polyline: 90 degrees, a repeated point, 45 degrees, a 0.5 degree kink
  const double small = std::tan(0.5 * kPi / 180.0);
  const std::vector<tdo_vec3> w{{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                {1, 1, 0}, {2, 2, 0}, {3, 3 + small, 0}};
  tdo_metrics m{};
  const tdo_metrics_input in = input(w);  // no geometric path
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  // THEN two turns (the repeated point and the 0.5 degree kink do not count)
  EXPECT_EQ(m.turns, 2u);
  EXPECT_NEAR(m.total_turn_deg, 135.0, 1e-9);
  const double l3 = std::sqrt(2.0), l4 = std::sqrt(1.0 + (1 + small) * (1 + small));
  const double len = 1.0 + 1.0 + l3 + l4;
  EXPECT_NEAR(m.length_m, len, 1e-12);
  // the kink's deflection (between (1,1) and (1,1+small), i.e. 45 deg minus atan) counts in the
  // integrals
  const double kink = std::atan2(1 + small, 1.0) - kPi / 4;
  EXPECT_NEAR(m.avg_curvature, (kPi / 2 + kPi / 4 + kink) / len, 1e-12);
  const double sq = (kPi / 2) * (kPi / 2) / 1.0 + (kPi / 4) * (kPi / 4) / ((1.0 + l3) / 2) +
                    kink * kink / ((l3 + l4) / 2);
  EXPECT_NEAR(m.smoothness, 1.0 / (1.0 + sq), 1e-12);
  EXPECT_EQ(m.curvature_continuous, 0);
}

TEST(Metrics, GivenCollinearPolylineThenNoTurnsAndSmooth) {
  const std::vector<tdo_vec3> w{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {2, 2, 2}, {5, 5, 5}};
  tdo_metrics m{};
  const tdo_metrics_input in = input(w);
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_EQ(m.turns, 0u);
  EXPECT_NEAR(m.length_m, 5 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(m.avg_curvature, 0.0, 1e-12);
  EXPECT_NEAR(m.smoothness, 1.0, 1e-12);
  EXPECT_EQ(m.curvature_continuous, 1);
}

TEST(Metrics, GivenSamplesThenEnergyIsTheTrapezoidOfSquaredAcceleration) {
  // GIVEN a(t) = (0, t, 0) on [0, 1] every 0.01 s: trapezoid = 1/3 + h^2/6
  std::vector<tdo_sample> s(101);
  for (size_t i = 0; i < s.size(); ++i) {
    s[i].t = 0.01 * static_cast<double>(i);
    s[i].a = tdo_vec3{0, s[i].t, 0};
  }
  const std::vector<tdo_vec3> w{{0, 0, 0}, {1, 0, 0}};
  tdo_metrics_input in = input(w);
  in.samples = s.data();
  in.n_samples = static_cast<uint32_t>(s.size());
  tdo_metrics m{};
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_NEAR(m.energy, 1.0 / 3.0 + 1e-4 / 6.0, 1e-12);
  EXPECT_NEAR(m.flight_time_s, 1.0, 1e-12);
  // constant |a| = 2 for 1 s: energy 4
  for (auto& x : s) x.a = tdo_vec3{1.2, 0, -1.6};
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_NEAR(m.energy, 4.0, 1e-12);
}

TEST(Metrics, GivenTrajectoryFromStageFiveThenEnergyMatchesIndependentSum) {
  const std::vector<tdo_vec3> w{{0, 0, 0}, {10, 0, 0}, {10, 8, 0}};
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {7, 0, 0}),
                                           bezier({7, 0, 0}, {10, 0, 0}, {10, 0, 0}, {10, 3, 0}),
                                           line({10, 3, 0}, {10, 8, 0})};
  const tdo_path path = make_path(segs);
  tdo_traj_config cfg{10000, 8, 8 * TDO_TRAJ_PIECES_PER_SEGMENT + 1, 8, 4, 0};
  std::vector<unsigned char> mem(tdo_traj_footprint(&cfg) + 64);
  tdo_arena arena;
  tdo_arena_init(&arena, mem.data(), mem.size());
  tdo_traj* ctx = nullptr;
  ASSERT_EQ(tdo_traj_init(&ctx, &arena, &cfg), TDO_OK);
  tdo_traj_input ti{};
  ti.path = path;
  ti.v_max = 3;
  ti.a_max = 3;
  ti.j_max = 10;
  ti.a_lat_max = 3;
  ti.dt = 0.01;
  tdo_traj_output to{};
  ASSERT_EQ(tdo_traj_run(ctx, &ti, &to), TDO_OK);
  tdo_metrics_input in = input(w, &path);
  in.samples = to.samples;
  in.n_samples = to.n_samples;
  tdo_metrics m{};
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  double e = 0.0;
  for (uint32_t i = 1; i < to.n_samples; ++i) {
    const tdo_vec3 a = to.samples[i - 1].a, b = to.samples[i].a;
    e += 0.5 * 0.01 * (a.x * a.x + a.y * a.y + a.z * a.z + b.x * b.x + b.y * b.y + b.z * b.z);
  }
  EXPECT_NEAR(m.energy, e, 1e-9 * e);
  EXPECT_GT(m.energy, 0.0);
  EXPECT_DOUBLE_EQ(m.flight_time_s, to.duration);
}

TEST(Metrics, GivenBadInputThenNamedStatus) {
  const std::vector<tdo_vec3> w{{0, 0, 0}, {1, 0, 0}};
  tdo_metrics m{};
  const tdo_metrics_input good = input(w);
  ASSERT_EQ(tdo_metrics_compute(&good, &m), TDO_OK);
  EXPECT_EQ(tdo_metrics_compute(nullptr, &m), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_metrics_compute(&good, nullptr), TDO_ERR_INVALID_ARGUMENT);
  tdo_metrics_input in = good;
  in.n_waypoints = 1;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  in = good;
  in.waypoints = nullptr;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  const std::vector<tdo_vec3> nan_w{{0, 0, 0}, {kNan, 0, 0}};
  in = input(nan_w);
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  // empty path, bad segment
  tdo_path empty{};
  in = input(w, &empty);
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_path_segment> segs{line({0, 0, 0}, {1, 0, 0})};
  segs[0].length = -1;
  tdo_path bad = make_path(segs);
  in = input(w, &bad);
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  // samples with times not increasing, or dt not > 0
  std::vector<tdo_sample> s(3);
  s[0].t = 0.0;
  s[1].t = 0.01;
  s[2].t = 0.01;
  in = good;
  in.samples = s.data();
  in.n_samples = 3;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  s[2].t = 0.02;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  in.dt = 0.0;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  // grid: cap not > 0, unfinished grid
  tdo_test::TestPlanner pl(tdo_test::make_cap(4096, 4096, 256));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_test::VoxelMap map(8, 8, 8, 1.0, tdo_vec3{-4, -4, -4});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), map, 0.0), TDO_OK);
  in = good;
  in.grid = pl.grid();
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  in.clearance_cap = 0.0;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  in.clearance_cap = kNan;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_INVALID_ARGUMENT);
  const tdo_grid_desc d = map.desc();
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  in.clearance_cap = 5.0;
  EXPECT_EQ(tdo_metrics_compute(&in, &m), TDO_ERR_MAP_NOT_READY);
}

// ---------------------------------------------------------------------------------------------
// Minimum clearance (needs the grid's exact distance queries).

class MetricsClearance : public ::testing::Test {
 protected:
  MetricsClearance() : pl_(tdo_test::make_cap(8192, 8192, 256)) {}
  void SetUp() override {
    ASSERT_EQ(pl_.status(), TDO_OK);
    map_ = tdo_test::VoxelMap(32, 32, 8, 0.5, tdo_vec3{-4, -4, -2});
    box_ = tdo_box{tdo_vec3{2.0, 2.0, -2.0}, tdo_vec3{4.0, 4.0, 2.0}};
    obs_.boxes = {box_};
    ASSERT_EQ(tdo_test::load_obstacles(pl_.grid(), map_, obs_, 0.0), TDO_OK);
  }
  /** True minimum distance of a segment's points to the box, by dense sampling. */
  double sampled_min(const tdo_path_segment& s) const {
    double best = kInfty;
    for (int i = 0; i <= 200000; ++i)
      best = std::fmin(
          best, tdo_test::distance_to_box(tdo_segment_point(&s, s.length * i / 200000), box_));
    return best;
  }
  tdo_test::TestPlanner pl_;
  tdo_test::VoxelMap map_;
  tdo_test::Obstacles obs_;
  tdo_box box_{};
};

TEST_F(MetricsClearance, GivenLinePathThenMinClearanceIsExact) {
  const std::vector<tdo_vec3> w{{-3, 1, 0}, {8, 1, 0}};
  const std::vector<tdo_path_segment> segs{line(w[0], w[1])};
  const tdo_path path = make_path(segs);
  tdo_metrics_input in = input(w, &path);
  in.grid = pl_.grid();
  tdo_metrics m{};
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_NEAR(m.min_clearance_m, 1.0, 1e-12);
  in.path = nullptr;  // the polyline gives the same
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_NEAR(m.min_clearance_m, 1.0, 1e-12);
  in.clearance_cap = 0.25;  // above the cap: the cap
  ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
  EXPECT_EQ(m.min_clearance_m, 0.25);
}

TEST_F(MetricsClearance, GivenCurvesNearTheBoxThenMinClearanceIsATightLowerBound) {
  // GIVEN an arc bulging towards the box corner (2, 2) and a Bezier corner pointing at it
  const double r = 2.0;
  const std::vector<tdo_vec3> w{{-1, 0, 0}, {1, 1, 0}, {0, 2, 0}};
  const tdo_vec3 c{-1.0, 0.0, 0.0};
  const std::vector<tdo_path_segment> arcs{arc({c.x + r * std::cos(-0.7), r * std::sin(-0.7), 0},
                                               {c.x + r * std::cos(1.4), r * std::sin(1.4), 0}, c,
                                               2.1)};
  const std::vector<tdo_path_segment> bez{
      bezier({-1, 0.5, 0}, {1.5, 1.5, 0}, {1.5, 1.5, 0}, {0.5, -1, 0})};
  for (const auto* segs : {&arcs, &bez}) {
    const tdo_path path = make_path(*segs);
    tdo_metrics_input in = input(w, &path);
    in.grid = pl_.grid();
    tdo_metrics m{};
    ASSERT_EQ(tdo_metrics_compute(&in, &m), TDO_OK);
    const double truth = sampled_min((*segs)[0]);
    // THEN never above the true distance (a lower bound), and within 1e-3 m of it
    EXPECT_LE(m.min_clearance_m, truth + 1e-9) << (*segs)[0].kind;
    EXPECT_GE(m.min_clearance_m, truth - 1e-3) << (*segs)[0].kind;
  }
}

}  // namespace
