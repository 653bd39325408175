// Stage 5 (trajectory.h, docs/design.md s.5): time parameterisation, feasibility verification by
// finite differences (paper eq. 15-19) and refinement. Every check of the samples is recomputed
// here from the sampled positions, independently of the library's own report.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "../../libtdo/src/bisect_highest.h"
#include "rng.h"
#include "tdo/path.h"
#include "tdo/trajectory.h"
#include "test_util.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfty = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Geometry built by the test itself.

double dist(const tdo_vec3& a, const tdo_vec3& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}
double len3(const tdo_vec3& a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
tdo_vec3 operator-(const tdo_vec3& a, const tdo_vec3& b) {
  return tdo_vec3{a.x - b.x, a.y - b.y, a.z - b.z};
}
tdo_vec3 operator+(const tdo_vec3& a, const tdo_vec3& b) {
  return tdo_vec3{a.x + b.x, a.y + b.y, a.z + b.z};
}
tdo_vec3 operator*(const tdo_vec3& a, double k) { return tdo_vec3{a.x * k, a.y * k, a.z * k}; }
double dot3(const tdo_vec3& a, const tdo_vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/** Bit-for-bit equality is intended here (exact end points, exact rest). */
bool exactly(double a, double b) { return !(a < b) && !(a > b); }

tdo_path_segment line(tdo_vec3 a, tdo_vec3 b, double v_limit = kInfty, int stop = 0) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_LINE;
  s.p[0] = a;
  s.p[1] = b;
  s.length = dist(a, b);
  s.v_limit = v_limit;
  s.stop_at_end = stop;
  return s;
}

/** Arc from a to b about centre c (|a - c| = |b - c|), length = radius * sweep. */
tdo_path_segment arc(tdo_vec3 a, tdo_vec3 b, tdo_vec3 c, double v_limit = kInfty) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_ARC;
  s.p[0] = a;
  s.p[1] = b;
  s.p[2] = c;
  const tdo_vec3 u = a - c, w = b - c;
  const double r = len3(u);
  const double cosang = dot3(u, w) / (r * len3(w));
  s.length = r * std::acos(std::fmax(-1.0, std::fmin(1.0, cosang)));
  s.v_limit = v_limit;
  return s;
}

/**
 * Cubic Bezier corner at w between the directions of a -> w and w -> b with control points
 * (a, w, w, b): zero curvature at both ends, tangent to both lines (a G2 junction with them).
 */
tdo_path_segment bezier_corner(tdo_vec3 a, tdo_vec3 w, tdo_vec3 b, double v_limit = kInfty) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_BEZIER;
  s.p[0] = a;
  s.p[1] = w;
  s.p[2] = w;
  s.p[3] = b;
  s.length = tdo_segment_length(&s);
  s.v_limit = v_limit;
  return s;
}

tdo_path make_path(const std::vector<tdo_path_segment>& segs) {
  tdo_path p{};
  p.seg = segs.data();
  p.n = static_cast<uint32_t>(segs.size());
  for (const auto& s : segs) p.length += s.length;
  return p;
}

/** L-shaped path: x axis to (10, 0), quarter arc of radius r, then up the y direction to y = 10. */
std::vector<tdo_path_segment> l_path_arc(double r) {
  return {line({0, 0, 0}, {10 - r, 0, 0}), arc({10 - r, 0, 0}, {10, r, 0}, {10 - r, r, 0}),
          line({10, r, 0}, {10, 10, 0})};
}

/** The same L with a G2 Bezier corner of size d instead of the arc. */
std::vector<tdo_path_segment> l_path_bezier(double d) {
  return {line({0, 0, 0}, {10 - d, 0, 0}), bezier_corner({10 - d, 0, 0}, {10, 0, 0}, {10, d, 0}),
          line({10, d, 0}, {10, 10, 0})};
}

// ---------------------------------------------------------------------------------------------
// The context on an exactly footprint-sized heap block.

tdo_traj_config default_config() {
  tdo_traj_config c{};
  c.max_samples = 20000;
  c.max_segments = 64;
  c.max_profile = 64 * TDO_TRAJ_PIECES_PER_SEGMENT + 1;
  c.max_violations = 32;
  c.max_refinements = 8;
  return c;
}

class Traj {
 public:
  explicit Traj(const tdo_traj_config& cfg = default_config()) {
    const size_t bytes = tdo_traj_footprint(&cfg);
    mem_.assign(bytes + 64, 0u);
    tdo_arena_init(&arena_, mem_.data(), mem_.size());
    status_ = tdo_traj_init(&ctx_, &arena_, &cfg);
  }
  tdo_status status() const { return status_; }
  tdo_traj* ctx() { return ctx_; }

 private:
  std::vector<unsigned char> mem_;
  tdo_arena arena_{};
  tdo_traj* ctx_ = nullptr;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

tdo_traj_input make_input(const tdo_path& path, double v_max = 3.0, double a_max = 3.0,
                          double j_max = 10.0, double a_lat = 3.0, double dt = 0.01) {
  tdo_traj_input in{};
  in.path = path;
  in.grid = nullptr;
  in.clearance = 0.0;
  in.v_max = v_max;
  in.a_max = a_max;
  in.j_max = j_max;
  in.a_lat_max = a_lat;
  in.dt = dt;
  return in;
}

// ---------------------------------------------------------------------------------------------
// Independent finite differences (eq. 15-17) of the sampled positions.

struct Fd {
  double max_v = 0.0, max_a = 0.0, max_j = 0.0;
  double min_radius_ratio = kInfty;  // min over samples of r / (v^2 / a_max)
  bool uniform_time = true;          // t_i = i * dt
};

Fd finite_differences(const tdo_traj_output& out, double dt, double a_max) {
  Fd f;
  const uint32_t n = out.n_samples;
  std::vector<tdo_vec3> v(n > 0 ? n - 1 : 0), a(n > 1 ? n - 2 : 0);
  for (uint32_t i = 0; i < n; ++i)
    if (std::fabs(out.samples[i].t - i * dt) > 1e-9) f.uniform_time = false;
  for (uint32_t i = 0; i + 1 < n; ++i) {
    v[i] = (out.samples[i + 1].p - out.samples[i].p) * (1.0 / dt);
    f.max_v = std::fmax(f.max_v, len3(v[i]));
  }
  for (uint32_t i = 0; i + 2 < n; ++i) {
    a[i] = (v[i + 1] - v[i]) * (1.0 / dt);
    f.max_a = std::fmax(f.max_a, len3(a[i]));
    const tdo_vec3 vc = (v[i] + v[i + 1]) * 0.5;
    const double s = len3(vc);
    if (s > 1e-9) {
      const tdo_vec3 u = vc * (1.0 / s);
      const double ap = len3(a[i] - u * dot3(a[i], u));
      if (ap > 1e-12)
        f.min_radius_ratio = std::fmin(f.min_radius_ratio, (s * s / ap) / (s * s / a_max));
    }
  }
  for (uint32_t i = 0; i + 3 < n; ++i) f.max_j = std::fmax(f.max_j, len3(a[i + 1] - a[i]) / dt);
  return f;
}

/** Every paper check at 1 % tolerance, recomputed here. */
::testing::AssertionResult within_limits(const tdo_traj_output& out, const tdo_traj_input& in) {
  const Fd f = finite_differences(out, in.dt, in.a_max);
  if (!f.uniform_time) return ::testing::AssertionFailure() << "samples are not every dt";
  if (f.max_v > 1.01 * in.v_max) return ::testing::AssertionFailure() << "speed " << f.max_v;
  if (f.max_a > 1.01 * in.a_max) return ::testing::AssertionFailure() << "acceleration " << f.max_a;
  if (f.max_j > 1.01 * in.j_max) return ::testing::AssertionFailure() << "jerk " << f.max_j;
  if (f.min_radius_ratio < 1.0 / 1.01)
    return ::testing::AssertionFailure() << "turn radius ratio " << f.min_radius_ratio;
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult rest_to_rest(const tdo_traj_output& out, const tdo_path& path) {
  if (out.n_samples < 2) return ::testing::AssertionFailure() << "too few samples";
  const tdo_sample& first = out.samples[0];
  const tdo_sample& last = out.samples[out.n_samples - 1];
  const tdo_path_segment& s0 = path.seg[0];
  const tdo_path_segment& sn = path.seg[path.n - 1];
  const tdo_vec3 goal = sn.kind == TDO_SEGMENT_BEZIER ? sn.p[3] : sn.p[1];
  if (!exactly(first.t, 0.0) || !exactly(dist(first.p, s0.p[0]), 0.0))
    return ::testing::AssertionFailure() << "first sample not at the start at t = 0";
  if (!exactly(dist(last.p, goal), 0.0))
    return ::testing::AssertionFailure() << "last sample " << dist(last.p, goal) << " m from goal";
  if (!exactly(len3(first.v), 0.0) || !exactly(len3(last.v), 0.0) || !exactly(len3(last.a), 0.0))
    return ::testing::AssertionFailure() << "not at rest at the ends";
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------

TEST(Trajectory, GivenLongStraightLineWhenParameterisedThenRestToRestAtFullSpeedWithinLimits) {
  // GIVEN a 20 m line and the default limits
  Traj t;
  ASSERT_EQ(t.status(), TDO_OK);
  const std::vector<tdo_path_segment> segs{line({1, 2, 3}, {13, 18, 3})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  // WHEN it is time-parameterised
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  // THEN it starts and ends at rest exactly at the ends, every dt, within every limit
  EXPECT_TRUE(rest_to_rest(out, path));
  EXPECT_TRUE(within_limits(out, in));
  EXPECT_EQ(out.report.ok, 1);
  EXPECT_EQ(out.report.n_violations_total, 0u);
  EXPECT_EQ(out.refinements, 0u);
  // AND the length allows reaching v_max, so it does (finite-difference speed)
  const Fd f = finite_differences(out, in.dt, in.a_max);
  EXPECT_GT(f.max_v, 0.999 * in.v_max);
  // AND the duration is at least L / v_max and not much more (two S-curves of ~1.4 s)
  EXPECT_GE(out.duration, 20.0 / in.v_max);
  EXPECT_LE(out.duration, 20.0 / in.v_max + 2.0);
  EXPECT_DOUBLE_EQ(out.duration, (out.n_samples - 1) * in.dt);
  // AND every sample lies on the line and moves forward
  for (uint32_t i = 1; i < out.n_samples; ++i) {
    const tdo_vec3 d = out.samples[i].p - out.samples[i - 1].p;
    EXPECT_GE(dot3(d, segs[0].p[1] - segs[0].p[0]), 0.0);
  }
  // AND the report's maxima match the independent finite differences
  EXPECT_NEAR(out.report.max_speed, f.max_v, 1e-9);
  EXPECT_NEAR(out.report.max_acc, f.max_a, 1e-6);
  EXPECT_NEAR(out.report.max_jerk, f.max_j, 1e-3);
  EXPECT_EQ(out.report.min_clearance, HUGE_VAL);  // no grid: not checked
}

TEST(Trajectory, GivenShortLineWhenParameterisedThenTopSpeedStaysBelowWhatJerkAllows) {
  // GIVEN a 0.5 m line: rest to rest with |j| <= 10 no motion can exceed
  // v = (d sqrt(j) / 2)^(2/3) = 0.856 m/s, whatever the profile
  Traj t;
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {0, 0, 0.5})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  const Fd f = finite_differences(out, in.dt, in.a_max);
  // THEN v_max is not reached, the physical bound holds, and it is not needlessly slow
  EXPECT_LT(f.max_v, std::pow(0.5 * std::sqrt(10.0) / 2.0, 2.0 / 3.0));
  EXPECT_GT(f.max_v, 0.6);
  EXPECT_TRUE(rest_to_rest(out, path));
  EXPECT_TRUE(within_limits(out, in));
}

TEST(Trajectory, GivenSampledTrajectoryThenSampleVelocityAndAccelerationMatchThePositions) {
  // GIVEN an L path with a G2 Bezier corner
  Traj t;
  const auto segs = l_path_bezier(3.0);
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  // THEN v and a of every sample agree with central differences of the positions
  const double dt = in.dt;
  for (uint32_t i = 1; i + 1 < out.n_samples; ++i) {
    const tdo_sample& s = out.samples[i];
    const tdo_vec3 vc = (out.samples[i + 1].p - out.samples[i - 1].p) * (0.5 / dt);
    const tdo_vec3 ac =
        (out.samples[i + 1].p - s.p * 2.0 + out.samples[i - 1].p) * (1.0 / (dt * dt));
    ASSERT_LT(dist(vc, s.v), 1e-3) << "t=" << s.t;
    ASSERT_LT(dist(ac, s.a), 0.05) << "t=" << s.t;
  }
}

TEST(Trajectory, GivenLPathWithArcCornerThenCornerSpeedIsCurvatureLimitedAndAllLimitsHold) {
  // GIVEN an L path whose corner is an arc of radius 2 m (curvature jumps at both ends)
  const double r = 2.0, a_lat = 1.5;
  Traj t;
  const auto segs = l_path_arc(r);
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path, 3.0, 3.0, 10.0, a_lat);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(rest_to_rest(out, path));
  EXPECT_TRUE(within_limits(out, in));
  // THEN on the arc the speed respects sqrt(a_lat * r) and the lateral acceleration a_lat
  const tdo_vec3 centre{10 - r, r, 0};
  const Fd f = finite_differences(out, in.dt, in.a_max);
  uint32_t on_arc = 0;
  for (uint32_t i = 1; i + 1 < out.n_samples; ++i) {
    const tdo_vec3 p = out.samples[i].p;
    if (!(p.x > 10 - r && p.y < r)) continue;
    ++on_arc;
    EXPECT_NEAR(dist(p, centre), r, 1e-9);
    const double dt = in.dt;
    const tdo_vec3 vc = (out.samples[i + 1].p - out.samples[i - 1].p) * (0.5 / dt);
    EXPECT_LE(len3(vc), 1.01 * std::sqrt(a_lat * r));
    EXPECT_LE(dot3(vc, vc) / r, 1.01 * a_lat);
  }
  EXPECT_GT(on_arc, 10u);
  // AND the straight parts still reach v_max
  EXPECT_GT(f.max_v, 0.99 * in.v_max);
}

TEST(Trajectory, GivenLPathWithG2CornerThenItFliesTheCornerFasterThanWithTheArc) {
  // GIVEN the same L with a curvature-continuous corner and with an arc of similar size
  Traj t;
  const auto g2 = l_path_bezier(3.0);
  const auto pure = l_path_arc(2.0);
  const tdo_path pg = make_path(g2), pa = make_path(pure);
  const tdo_traj_input ig = make_input(pg), ia = make_input(pa);
  tdo_traj_output og{}, oa{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &ig, &og), TDO_OK);
  EXPECT_TRUE(rest_to_rest(og, pg));
  EXPECT_TRUE(within_limits(og, ig));
  const double tg = og.duration;
  ASSERT_EQ(tdo_traj_run(t.ctx(), &ia, &oa), TDO_OK);
  EXPECT_TRUE(within_limits(oa, ia));
  // THEN the arc's curvature jumps force a slower corner (lateral jerk v^2 dkappa / dt)
  EXPECT_LT(tg, oa.duration);
}

TEST(Trajectory, GivenStopPointThenASampleIsExactlyThereAtRest) {
  // GIVEN a straight path split in two with a stop at the junction
  Traj t;
  const tdo_vec3 stop{5, 0, 1};
  const std::vector<tdo_path_segment> segs{line({0, 0, 1}, stop, kInfty, 1),
                                           line(stop, {10, 0, 1})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(within_limits(out, in));
  // THEN one sample sits exactly on the stop point with zero velocity and acceleration, and the
  // finite-difference speeds around it are tiny
  uint32_t at = 0;
  for (uint32_t i = 0; i < out.n_samples; ++i)
    if (exactly(dist(out.samples[i].p, stop), 0.0) && exactly(len3(out.samples[i].v), 0.0)) at = i;
  ASSERT_GT(at, 0u);
  EXPECT_TRUE(exactly(len3(out.samples[at].a), 0.0));
  EXPECT_LT(dist(out.samples[at + 1].p, stop) / in.dt, 0.01);
  EXPECT_LT(dist(out.samples[at - 1].p, stop) / in.dt, 0.01);
}

TEST(Trajectory, GivenSharpPolylineCornerWithoutStopFlagThenItStillStopsThere) {
  // GIVEN a 90 degree polyline corner (tangent kink) not marked as a stop
  Traj t;
  const tdo_vec3 corner{4, 0, 0};
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, corner), line(corner, {4, 4, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  // THEN the trajectory is feasible because it comes to rest at the kink
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(within_limits(out, in));
  bool rest_at_corner = false;
  for (uint32_t i = 0; i < out.n_samples; ++i)
    rest_at_corner |=
        exactly(dist(out.samples[i].p, corner), 0.0) && exactly(len3(out.samples[i].v), 0.0);
  EXPECT_TRUE(rest_at_corner);
}

TEST(Trajectory, GivenSegmentSpeedCapThenItIsRespected) {
  // GIVEN a long line whose middle third is capped at 1 m/s
  Traj t;
  const std::vector<tdo_path_segment> segs{
      line({0, 0, 0}, {10, 0, 0}), line({10, 0, 0}, {20, 0, 0}, 1.0), line({20, 0, 0}, {30, 0, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(within_limits(out, in));
  // (finite-difference speeds whose both samples lie on the capped segment)
  for (uint32_t i = 0; i + 1 < out.n_samples; ++i) {
    const double x0 = out.samples[i].p.x, x1 = out.samples[i + 1].p.x;
    const double v = dist(out.samples[i + 1].p, out.samples[i].p) / in.dt;
    if (x0 >= 10.0 && x1 <= 20.0) {
      ASSERT_LE(v, 1.0 + 1e-9) << "x=" << x0;
    }
  }
  const Fd f = finite_differences(out, in.dt, in.a_max);
  EXPECT_GT(f.max_v, 2.9);  // fast outside
}

TEST(Trajectory, GivenSameInputTwiceThenSamplesAreBitIdentical) {
  Traj t1, t2;
  const auto segs = l_path_bezier(2.5);
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output a{}, b{}, c{};
  ASSERT_EQ(tdo_traj_run(t1.ctx(), &in, &a), TDO_OK);
  std::vector<tdo_sample> first(a.samples, a.samples + a.n_samples);
  ASSERT_EQ(tdo_traj_run(t1.ctx(), &in, &b), TDO_OK);  // same context again
  ASSERT_EQ(tdo_traj_run(t2.ctx(), &in, &c), TDO_OK);  // fresh context
  ASSERT_EQ(first.size(), b.n_samples);
  ASSERT_EQ(first.size(), c.n_samples);
  EXPECT_EQ(std::memcmp(first.data(), b.samples, first.size() * sizeof(tdo_sample)), 0);
  EXPECT_EQ(std::memcmp(first.data(), c.samples, first.size() * sizeof(tdo_sample)), 0);
}

// A cubic corner whose curvature peaks between the profile's curvature stations: the first profile
// underestimates the peak and only the finite differences of the samples see the violation.
std::vector<tdo_path_segment> peaked_path() {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_BEZIER;
  s.p[0] = tdo_vec3{0, 0, 0};
  s.p[1] = tdo_vec3{4, 0, 0};
  s.p[2] = tdo_vec3{4, 0.5, 0};
  s.p[3] = tdo_vec3{0, 2, 0};
  s.length = tdo_segment_length(&s);
  s.v_limit = kInfty;
  return {s};
}

TEST(Trajectory, GivenNoRefinementAllowedWhenFirstProfileViolatesThenInfeasibleWithTheViolations) {
  // GIVEN the peaked corner and max_refinements = 0
  const auto segs = peaked_path();
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_config cfg = default_config();
  cfg.max_refinements = 0;
  cfg.max_violations = 3;
  Traj t(cfg);
  tdo_traj_output out{};
  // WHEN it is parameterised
  // THEN it is INFEASIBLE, never OK, and the report lists what the independent check also sees
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INFEASIBLE);
  EXPECT_EQ(out.report.ok, 0);
  EXPECT_EQ(out.refinements, 0u);
  ASSERT_EQ(out.report.n_violations, 3u);        // capped list
  EXPECT_GT(out.report.n_violations_total, 3u);  // all of them counted
  EXPECT_FALSE(within_limits(out, in));
  const Fd f = finite_differences(out, in.dt, in.a_max);
  for (uint32_t i = 0; i < out.report.n_violations; ++i) {
    const tdo_violation& v = out.report.violations[i];
    EXPECT_EQ(v.what, TDO_QUANTITY_JERK);
    EXPECT_DOUBLE_EQ(v.limit, in.j_max);
    EXPECT_GT(v.value, 1.01 * in.j_max);
    EXPECT_LE(v.value, f.max_j + 1e-6);
    EXPECT_GE(v.t, 0.0);
    EXPECT_LE(v.t, out.duration);
  }
  EXPECT_NEAR(out.report.max_jerk, f.max_j, 1e-6);
}

TEST(Trajectory, GivenRefinementAllowedWhenFirstProfileViolatesThenItIsRefinedUntilFeasible) {
  const auto segs = peaked_path();
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  Traj t;  // 8 rounds allowed
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_GE(out.refinements, 1u);
  EXPECT_EQ(out.report.ok, 1);
  EXPECT_TRUE(within_limits(out, in));
  EXPECT_TRUE(rest_to_rest(out, path));
}

// ---------------------------------------------------------------------------------------------
// Seeded random G1 paths of lines, arcs and Bezier corners in 3D: every result either passes the
// independent finite-difference check or is not OK.

std::vector<tdo_path_segment> random_path(tdo_test::Rng& rng) {
  std::vector<tdo_path_segment> segs;
  tdo_vec3 p{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(0, 5)};
  tdo_vec3 dir{1, 0, 0};
  const int corners = static_cast<int>(rng.range(0, 5));
  for (int c = 0; c <= corners; ++c) {
    const double l = rng.uniform(0.5, 12.0);
    const tdo_vec3 q = p + dir * l;
    segs.push_back(line(p, q, rng.uniform() < 0.2 ? rng.uniform(0.5, 3.0) : kInfty,
                        rng.uniform() < 0.1 ? 1 : 0));
    p = q;
    if (c == corners) break;
    // New direction: random unit vector at 10..150 degrees from dir.
    tdo_vec3 nd;
    double ang;
    do {
      nd = tdo_vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.5, 0.5)};
      nd = nd * (1.0 / len3(nd));
      ang = std::acos(std::fmax(-1.0, std::fmin(1.0, dot3(nd, dir))));
    } while (ang < 10.0 * kPi / 180.0 || ang > 150.0 * kPi / 180.0);
    const double kind = rng.uniform();
    if (kind < 0.5) {
      // Bezier corner of size d around the virtual corner w = p + dir d.
      const double d = rng.uniform(0.3, 4.0);
      const tdo_vec3 w = p + dir * d;
      const tdo_vec3 b = w + nd * d;
      segs.push_back(bezier_corner(p, w, b));
      p = b;
    } else {
      // Arc of radius r tangent to dir at p, turning towards nd.
      const double r = rng.uniform(0.3, 5.0);
      tdo_vec3 nrm = nd - dir * dot3(nd, dir);
      nrm = nrm * (1.0 / len3(nrm));
      const tdo_vec3 centre = p + nrm * r;
      const tdo_vec3 b = centre + (dir * std::sin(ang) - nrm * std::cos(ang)) * r;
      segs.push_back(arc(p, b, centre));
      p = b;
    }
    dir = nd;
  }
  return segs;
}

// Random limits (v, a, j, lateral a) and dt for a random path: half of them at dt = 0.01 s.
tdo_traj_input random_input(tdo_test::Rng& rng, const tdo_path& path) {
  return make_input(path, rng.uniform(0.5, 5.0), rng.uniform(0.5, 6.0), rng.uniform(1.0, 30.0),
                    rng.uniform(0.3, 6.0), rng.uniform() < 0.5 ? 0.01 : rng.uniform(0.005, 0.05));
}

TEST(Trajectory, GivenRandomPathsAndLimitsThenEveryOkTrajectoryPassesTheIndependentCheck) {
  Traj t;
  uint32_t ok = 0, runs = 0;
  for (uint64_t seed = 1; seed <= 200; ++seed) {
    tdo_test::Rng rng(seed);
    const auto segs = random_path(rng);
    const tdo_path path = make_path(segs);
    const tdo_traj_input in = random_input(rng, path);
    tdo_traj_output out{};
    const tdo_status st = tdo_traj_run(t.ctx(), &in, &out);
    ++runs;
    ASSERT_TRUE(st == TDO_OK || st == TDO_ERR_INFEASIBLE || st == TDO_ERR_SAMPLE_CAPACITY)
        << "seed " << seed << " " << tdo_status_str(st);
    if (st != TDO_OK) continue;
    ++ok;
    ASSERT_TRUE(within_limits(out, in)) << "seed " << seed;
    ASSERT_TRUE(rest_to_rest(out, path)) << "seed " << seed;
    ASSERT_EQ(out.report.ok, 1);
    // stop points are at rest on a sample
    double s0 = 0.0;
    for (const auto& seg : segs) {
      s0 += seg.length;
      if (!seg.stop_at_end) continue;
      bool found = false;
      for (uint32_t i = 0; i < out.n_samples && !found; ++i)
        found =
            exactly(dist(out.samples[i].p, seg.p[1]), 0.0) && exactly(len3(out.samples[i].v), 0.0);
      ASSERT_TRUE(found) << "seed " << seed << " stop at s=" << s0;
    }
  }
  // The profile is built to pass: failures would be a regression, not bad luck.
  EXPECT_EQ(ok, runs);
}

// ---------------------------------------------------------------------------------------------
// Capacities and bad input.

TEST(Trajectory, GivenTooFewSamplesOrProfilePiecesThenSampleCapacity) {
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {30, 0, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_config small = default_config();
  small.max_samples = 500;  // 5 s at 0.01 s, the flight needs > 10 s
  Traj a(small);
  tdo_traj_output out{};
  EXPECT_EQ(tdo_traj_run(a.ctx(), &in, &out), TDO_ERR_SAMPLE_CAPACITY);
  tdo_traj_config few = default_config();
  few.max_profile = 3;  // a rest-to-rest line needs 7 pieces
  Traj b(few);
  EXPECT_EQ(tdo_traj_run(b.ctx(), &in, &out), TDO_ERR_SAMPLE_CAPACITY);
  tdo_traj_config exact = default_config();
  exact.max_profile = TDO_TRAJ_PIECES_PER_SEGMENT + 1;  // the documented bound suffices
  Traj c(exact);
  EXPECT_EQ(tdo_traj_run(c.ctx(), &in, &out), TDO_OK);
}

TEST(Trajectory, GivenStreamedSamplesThenMaxSamplesStillBoundsThemWithSampleCapacity) {
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {30, 0, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_config cfg = default_config();
  cfg.stream_samples = 1;
  // GIVEN streamed samples: none is stored, so the footprint drops by at least 84 bytes each
  tdo_traj_config stored = default_config();
  EXPECT_GE(tdo_traj_footprint(&stored), tdo_traj_footprint(&cfg) + 84u * cfg.max_samples);
  Traj ref(cfg);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(ref.ctx(), &in, &out), TDO_OK);
  EXPECT_EQ(out.samples, nullptr);
  const uint32_t need = out.n_samples;
  ASSERT_GT(need, 1000u);  // > 10 s at 0.01 s
  // WHEN max_samples is exactly the count, or one less
  cfg.max_samples = need;
  Traj exact(cfg);
  EXPECT_EQ(tdo_traj_run(exact.ctx(), &in, &out), TDO_OK);
  cfg.max_samples = need - 1u;
  Traj small(cfg);
  // THEN one less is the named status, and nothing is left to read
  EXPECT_EQ(tdo_traj_run(small.ctx(), &in, &out), TDO_ERR_SAMPLE_CAPACITY);
  EXPECT_EQ(tdo_traj_each_sample(
                small.ctx(), [](void*, uint32_t, const tdo_sample*) {}, nullptr),
            TDO_ERR_INVALID_ARGUMENT);
  tdo_traj_config bad = default_config();
  bad.stream_samples = 3;  // 0 stored, 1 streamed, 2 pieces: nothing else
  Traj b(bad);
  EXPECT_EQ(b.status(), TDO_ERR_INVALID_ARGUMENT);
}

TEST(Trajectory, GivenMoreSegmentsThanConfiguredThenPathCapacity) {
  tdo_traj_config cfg = default_config();
  cfg.max_segments = 2;
  Traj t(cfg);
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {1, 0, 0}), line({1, 0, 0}, {2, 0, 0}),
                                           line({2, 0, 0}, {3, 0, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_PATH_CAPACITY);
}

TEST(Trajectory, GivenBadConfigurationThenInitFails) {
  tdo_traj_config cfg = default_config();
  cfg.max_samples = 1;
  EXPECT_EQ(tdo_traj_footprint(&cfg), 0u);
  EXPECT_EQ(Traj(cfg).status(), TDO_ERR_INVALID_ARGUMENT);
  cfg = default_config();
  cfg.max_segments = 0;
  EXPECT_EQ(Traj(cfg).status(), TDO_ERR_INVALID_ARGUMENT);
  cfg = default_config();
  cfg.max_profile = 0;
  EXPECT_EQ(Traj(cfg).status(), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_traj_footprint(nullptr), 0u);
  // arena one carve short
  cfg = default_config();
  std::vector<unsigned char> mem(tdo_traj_footprint(&cfg) - 16);
  tdo_arena arena;
  tdo_arena_init(&arena, mem.data(), mem.size());
  tdo_traj* ctx = nullptr;
  EXPECT_EQ(tdo_traj_init(&ctx, &arena, &cfg), TDO_ERR_ARENA_TOO_SMALL);
  EXPECT_EQ(tdo_traj_init(nullptr, &arena, &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_traj_init(&ctx, nullptr, &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_traj_init(&ctx, &arena, nullptr), TDO_ERR_INVALID_ARGUMENT);
}

TEST(Trajectory, GivenInvalidLimitsOrPathThenInvalidArgument) {
  Traj t;
  std::vector<tdo_path_segment> segs{line({0, 0, 0}, {5, 0, 0}), line({5, 0, 0}, {5, 5, 0})};
  const tdo_path path = make_path(segs);
  tdo_traj_output out{};
  const tdo_traj_input good = make_input(path);
  ASSERT_EQ(tdo_traj_run(t.ctx(), &good, &out), TDO_OK);
  EXPECT_EQ(tdo_traj_run(nullptr, &good, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_traj_run(t.ctx(), nullptr, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_traj_run(t.ctx(), &good, nullptr), TDO_ERR_INVALID_ARGUMENT);
  for (double bad : {0.0, -1.0, kNan, kInfty, -kInfty}) {
    for (int field = 0; field < 5; ++field) {
      tdo_traj_input in = good;
      double* f[5] = {&in.v_max, &in.a_max, &in.j_max, &in.a_lat_max, &in.dt};
      *f[field] = bad;
      EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT)
          << "field " << field << " = " << bad;
      EXPECT_EQ(out.n_samples, 0u);
    }
  }
  // empty path, null segments, zero length
  tdo_traj_input in = good;
  in.path.n = 0;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  in = good;
  in.path.seg = nullptr;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  const auto with = [&](auto change) {
    std::vector<tdo_path_segment> s = segs;
    change(s);
    tdo_traj_input i = good;
    i.path = make_path(s);
    return tdo_traj_run(t.ctx(), &i, &out);
  };
  EXPECT_EQ(with([](auto& s) { s[0].length = 0.0, s[1].length = 0.0; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[0].length = -1.0; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[0].length = kNan; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[1].v_limit = 0.0; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[1].v_limit = kNan; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[1].p[1].y = kNan; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](auto& s) { s[1].kind = static_cast<tdo_segment_kind>(3); }),
            TDO_ERR_INVALID_ARGUMENT);
  // a gap between consecutive segments
  EXPECT_EQ(with([](auto& s) { s[1].p[0].x += 0.01; }), TDO_ERR_INVALID_ARGUMENT);
  // a negative or non-finite clearance with a grid; an unfinished grid
  tdo_test::TestPlanner pl(tdo_test::make_cap(4096, 4096, 256));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_test::VoxelMap m(16, 16, 4, 1.0, tdo_vec3{-2, -2, -2});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m, 0.5), TDO_OK);
  in = good;
  in.grid = pl.grid();
  in.clearance = -1.0;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  in.clearance = kNan;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  const tdo_grid_desc d = m.desc();
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);  // not finished
  in.clearance = 0.5;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_MAP_NOT_READY);
  // and the context still works afterwards
  EXPECT_EQ(tdo_traj_run(t.ctx(), &good, &out), TDO_OK);
}

TEST(Trajectory, GivenZeroLengthSegmentWithStopThenTheStopIsKept) {
  Traj t;
  tdo_path_segment stop = line({5, 0, 0}, {5, 0, 0}, kInfty, 1);
  const std::vector<tdo_path_segment> segs{line({0, 0, 0}, {5, 0, 0}), stop,
                                           line({5, 0, 0}, {9, 0, 0})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  bool rest = false;
  for (uint32_t i = 1; i + 1 < out.n_samples; ++i)
    rest |= exactly(out.samples[i].p.x, 5.0) && exactly(len3(out.samples[i].v), 0.0);
  EXPECT_TRUE(rest);
  EXPECT_TRUE(within_limits(out, in));
}

// ---------------------------------------------------------------------------------------------
// Clearance (needs the grid's exact distance queries).

class TrajectoryClearance : public ::testing::Test {
 protected:
  TrajectoryClearance() : pl_(tdo_test::make_cap(4096, 4096, 256)) {}
  void SetUp() override { ASSERT_EQ(pl_.status(), TDO_OK); }
  /** Map [0, 16] x [-4, 4] x [0, 4] with one box whose lower face is at y = y0 (above the x axis).
   */
  void load_box(double y0, double clearance) {
    map_ = tdo_test::VoxelMap(32, 16, 8, 0.5, tdo_vec3{0, -4, 0});
    obs_.boxes = {tdo_box{tdo_vec3{6, y0, 0}, tdo_vec3{9, y0 + 1.5, 4}}};
    ASSERT_EQ(tdo_test::load_obstacles(pl_.grid(), map_, obs_, clearance), TDO_OK);
  }
  /** make_input on this fixture's grid, checked at a clearance of 0.5 m. */
  tdo_traj_input input_on_grid(const tdo_path& path) {
    tdo_traj_input in = make_input(path);
    in.grid = pl_.grid();
    in.clearance = 0.5;
    return in;
  }
  tdo_test::TestPlanner pl_;
  tdo_test::VoxelMap map_;
  tdo_test::Obstacles obs_;
};

TEST_F(TrajectoryClearance, GivenPathClearOfObstaclesThenOkAndMinClearanceIsExact) {
  // GIVEN a straight path at z = 2 along y = 0, and a box 1.2 m away
  load_box(1.2, 0.5);
  Traj t;
  const std::vector<tdo_path_segment> segs{line({1, 0, 2}, {15, 0, 2})};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  // THEN the report's minimum clearance is the exact minimum over the samples
  double best = kInfty;
  for (uint32_t i = 0; i < out.n_samples; ++i)
    best = std::fmin(best, tdo_test::distance_to_box(out.samples[i].p, obs_.boxes[0]));
  EXPECT_NEAR(out.report.min_clearance, best, 1e-9);
  EXPECT_NEAR(out.report.min_clearance, 1.2, 1e-9);
}

TEST_F(TrajectoryClearance, GivenPathDippingTwiceTowardsABoxThenEveryCloseSampleIsReportedExactly) {
  // GIVEN a zigzag path that dips towards the box's lower face twice, to 0.3 m and then to 0.45 m
  // (the verification skips samples a Lipschitz bound clears: it must not miss any of the second
  // dip, which is closer than the clearance but farther than the minimum)
  load_box(0.3, 0.0);
  Traj t;
  const std::vector<tdo_path_segment> segs{
      line({6.5, -3, 2}, {7.0, 0.0, 2}), line({7.0, 0.0, 2}, {7.5, -3, 2}),
      line({7.5, -3, 2}, {8.0, -0.15, 2}), line({8.0, -0.15, 2}, {8.5, -3, 2})};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INFEASIBLE);
  // THEN the minimum is the exact minimum over all samples, and every sample closer than the
  // clearance is one violation, at its own distance
  double best = kInfty;
  uint32_t close = 0;
  for (uint32_t i = 0; i < out.n_samples; ++i) {
    const double d = tdo_test::distance_to_box(out.samples[i].p, obs_.boxes[0]);
    best = std::fmin(best, d);
    if (d < in.clearance - 1e-9) ++close;
  }
  ASSERT_GT(close, 0u);
  ASSERT_LT(close, out.n_samples / 2u);
  EXPECT_NEAR(out.report.min_clearance, best, 1e-9);
  EXPECT_EQ(out.report.n_violations_total, close);
  for (uint32_t i = 0; i < out.report.n_violations; ++i) {
    const tdo_violation& v = out.report.violations[i];
    EXPECT_EQ(v.what, TDO_QUANTITY_CLEARANCE);
    const uint32_t k = static_cast<uint32_t>(std::lround(v.t / in.dt));
    EXPECT_NEAR(tdo_test::distance_to_box(out.samples[k].p, obs_.boxes[0]), v.value, 1e-9);
  }
}

TEST_F(TrajectoryClearance,
       GivenLongPathWhoseClosestDipIsLateThenEveryCloseSampleIsReportedInOrder) {
  // GIVEN a path of over 1024 samples that dips towards the box twice: first to 0.45 m (closer
  // than the clearance, farther than the minimum), later to 0.3 m (the verification takes its
  // starting minimum from a sparse pre-pass over the samples, so the early dip is checked against
  // a minimum that may come from the late one: it must still report every sample of both)
  load_box(0.3, 0.0);
  Traj t;
  const std::vector<tdo_path_segment> segs{
      line({1, -3, 2}, {6.5, -0.15, 2}), line({6.5, -0.15, 2}, {7.25, -3, 2}),
      line({7.25, -3, 2}, {8.5, 0.0, 2}), line({8.5, 0.0, 2}, {15, -3, 2})};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INFEASIBLE);
  ASSERT_GT(out.n_samples, 1024u);
  // THEN the minimum is the exact minimum over all samples, and the violations are exactly the
  // samples closer than the clearance, each once, in sample order, at its own distance
  double best = kInfty;
  std::vector<uint32_t> close;
  for (uint32_t i = 0; i < out.n_samples; ++i) {
    const double d = tdo_test::distance_to_box(out.samples[i].p, obs_.boxes[0]);
    best = std::fmin(best, d);
    if (d < in.clearance - 1e-9) close.push_back(i);
  }
  EXPECT_NEAR(out.report.min_clearance, best, 1e-9);
  EXPECT_NEAR(best, 0.3, 1e-6);
  ASSERT_EQ(out.report.n_violations_total, close.size());
  ASSERT_EQ(out.report.n_violations, std::min<size_t>(close.size(), 32u));  // the list's capacity
  bool early = false;
  for (uint32_t i = 0; i < out.report.n_violations; ++i) {
    const tdo_violation& v = out.report.violations[i];
    EXPECT_EQ(v.what, TDO_QUANTITY_CLEARANCE);
    const uint32_t k = static_cast<uint32_t>(std::lround(v.t / in.dt));
    EXPECT_EQ(k, close[i]);
    EXPECT_NEAR(tdo_test::distance_to_box(out.samples[k].p, obs_.boxes[0]), v.value, 1e-9);
    early |= v.value > 0.4;  // a sample of the first dip
  }
  EXPECT_TRUE(early);
}

TEST_F(TrajectoryClearance, GivenPathTooCloseToAnObstacleThenInfeasibleWithoutRefinement) {
  // GIVEN the box 0.3 m from the path and a clearance of 0.5 m: no speed can fix that
  load_box(0.3, 0.0);
  Traj t;
  const std::vector<tdo_path_segment> segs{line({1, 0, 2}, {15, 0, 2})};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INFEASIBLE);
  // THEN the violations are all clearance ones, at the samples beside the box, and no round of
  // speed refinement was wasted on them
  EXPECT_EQ(out.refinements, 0u);
  ASSERT_GT(out.report.n_violations, 0u);
  for (uint32_t i = 0; i < out.report.n_violations; ++i) {
    const tdo_violation& v = out.report.violations[i];
    EXPECT_EQ(v.what, TDO_QUANTITY_CLEARANCE);
    EXPECT_DOUBLE_EQ(v.limit, 0.5);
    EXPECT_LT(v.value, 0.5);
    const uint32_t k = static_cast<uint32_t>(std::lround(v.t / in.dt));
    EXPECT_NEAR(tdo_test::distance_to_box(out.samples[k].p, obs_.boxes[0]), v.value, 1e-9);
  }
  EXPECT_NEAR(out.report.min_clearance, 0.3, 1e-9);
  // AND the dynamics of the returned attempt are fine: only the geometry fails
  EXPECT_TRUE(within_limits(out, in));
}

// Streamed samples (tdo_traj_config.stream_samples) against stored ones, on a run with jerk
// violations (the peaked corner without refinement) and clearance violations (a box beside its
// end): the same report, violation list order included, the same energy and the same sample bits.
void expect_same_run(const tdo_traj_output& a, const tdo_traj_output& b) {
  EXPECT_EQ(a.n_samples, b.n_samples);
  EXPECT_EQ(std::memcmp(&a.duration, &b.duration, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&a.energy, &b.energy, sizeof(double)), 0);
  EXPECT_EQ(a.refinements, b.refinements);
  EXPECT_EQ(a.report.ok, b.report.ok);
  for (const auto field :
       {&tdo_feasibility::max_speed, &tdo_feasibility::max_acc, &tdo_feasibility::max_jerk,
        &tdo_feasibility::min_turn_radius, &tdo_feasibility::min_clearance})
    EXPECT_EQ(std::memcmp(&(a.report.*field), &(b.report.*field), sizeof(double)), 0);
  EXPECT_EQ(a.report.n_violations_total, b.report.n_violations_total);
  ASSERT_EQ(a.report.n_violations, b.report.n_violations);
  for (uint32_t i = 0; i < a.report.n_violations; ++i) {  // field by field (padding differs)
    const tdo_violation& va = a.report.violations[i];
    const tdo_violation& vb = b.report.violations[i];
    EXPECT_EQ(va.what, vb.what) << "violation " << i;
    for (const auto field : {&tdo_violation::t, &tdo_violation::value, &tdo_violation::limit})
      EXPECT_EQ(std::memcmp(&(va.*field), &(vb.*field), sizeof(double)), 0) << "violation " << i;
  }
}

std::vector<tdo_sample> each_sample(const tdo_traj* ctx) {
  std::vector<tdo_sample> v;
  EXPECT_EQ(tdo_traj_each_sample(
                ctx,
                [](void* user, uint32_t, const tdo_sample* s) {
                  static_cast<std::vector<tdo_sample>*>(user)->push_back(*s);
                },
                &v),
            TDO_OK);
  return v;
}

TEST_F(TrajectoryClearance, GivenStreamedSamplesThenReportEnergyAndSamplesAreTheStoredOnes) {
  // GIVEN the peaked corner (jerk violations without refinement) ending 0.2 m below a box
  load_box(-0.3, 0.0);
  std::vector<tdo_path_segment> segs = peaked_path();
  for (int k = 0; k < 4; ++k) segs[0].p[k] = segs[0].p[k] + tdo_vec3{6.0, -2.5, 2.0};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  for (uint32_t refinements : {0u, 8u}) {
    for (uint32_t listed : {1000u, 4u}) {
      tdo_traj_config cfg = default_config();
      cfg.max_refinements = refinements;
      cfg.max_violations = listed;
      Traj stored(cfg);
      cfg.stream_samples = 1;
      Traj streamed(cfg);
      tdo_traj_output a{}, b{};
      // WHEN both run
      const tdo_status sa = tdo_traj_run(stored.ctx(), &in, &a);
      ASSERT_EQ(tdo_traj_run(streamed.ctx(), &in, &b), sa);
      ASSERT_EQ(sa, TDO_ERR_INFEASIBLE);
      // THEN the runs agree in every number
      expect_same_run(a, b);
      if (refinements == 0u && listed == 1000u) {  // both kinds are listed, dynamic ones first
        ASSERT_GT(a.report.n_violations, 1u);
        EXPECT_EQ(a.report.violations[0].what, TDO_QUANTITY_JERK);
        EXPECT_EQ(a.report.violations[a.report.n_violations - 1u].what, TDO_QUANTITY_CLEARANCE);
      }
      // AND the energy is the one the metrics compute from the stored samples
      tdo_metrics_input mi{};
      const tdo_vec3 ends[2] = {segs[0].p[0], segs[0].p[3]};
      mi.waypoints = ends;
      mi.n_waypoints = 2;
      mi.samples = a.samples;
      mi.n_samples = a.n_samples;
      mi.dt = in.dt;
      tdo_metrics m{};
      ASSERT_EQ(tdo_metrics_compute(&mi, &m), TDO_OK);
      EXPECT_EQ(std::memcmp(&m.energy, &b.energy, sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(&m.flight_time_s, &b.duration, sizeof(double)), 0);
      // AND the streamed samples, regenerated, are the stored ones bit for bit
      const std::vector<tdo_sample> sa_v = each_sample(stored.ctx());
      const std::vector<tdo_sample> sb_v = each_sample(streamed.ctx());
      ASSERT_EQ(sa_v.size(), a.n_samples);
      ASSERT_EQ(sb_v.size(), a.n_samples);
      EXPECT_EQ(std::memcmp(sa_v.data(), a.samples, a.n_samples * sizeof(tdo_sample)), 0);
      EXPECT_EQ(std::memcmp(sb_v.data(), a.samples, a.n_samples * sizeof(tdo_sample)), 0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Pieces mode (TDO_TRAJ_SAMPLES_PIECES): the closed-form verification against stored samples.

std::vector<tdo_traj_piece> pieces_of(const tdo_traj* ctx) {
  std::vector<tdo_traj_piece> v;
  tdo_traj_profile_info info{};
  EXPECT_EQ(tdo_traj_profile(ctx, &info), TDO_OK);
  for (uint32_t i = 0; i < info.n_pieces; ++i) {
    tdo_traj_piece p{};
    EXPECT_EQ(tdo_traj_piece_at(ctx, i, &p), TDO_OK);
    v.push_back(p);
  }
  return v;
}

/** The same profile (piece by piece, bit for bit), sample count, duration and samples. */
::testing::AssertionResult same_trajectory(const tdo_traj* stored, const tdo_traj_output& a,
                                           const tdo_traj* other, const tdo_traj_output& b) {
  if (a.n_samples != b.n_samples) return ::testing::AssertionFailure() << "n_samples";
  if (std::memcmp(&a.duration, &b.duration, sizeof(double)) != 0)
    return ::testing::AssertionFailure() << "duration";
  if (a.refinements != b.refinements) return ::testing::AssertionFailure() << "refinements";
  const std::vector<tdo_traj_piece> pa = pieces_of(stored), pb = pieces_of(other);
  if (pa.size() != pb.size()) return ::testing::AssertionFailure() << "piece count";
  for (size_t i = 0; i < pa.size(); ++i)
    for (const auto f : {&tdo_traj_piece::t0, &tdo_traj_piece::dur, &tdo_traj_piece::s0,
                         &tdo_traj_piece::v0, &tdo_traj_piece::a0, &tdo_traj_piece::j})
      if (std::memcmp(&(pa[i].*f), &(pb[i].*f), sizeof(double)) != 0)
        return ::testing::AssertionFailure() << "piece " << i;
  const std::vector<tdo_sample> sb = each_sample(other);
  if (sb.size() != a.n_samples ||
      std::memcmp(sb.data(), a.samples, a.n_samples * sizeof(tdo_sample)) != 0)
    return ::testing::AssertionFailure() << "regenerated samples differ";
  return ::testing::AssertionSuccess();
}

TEST(TrajectoryPieces, GivenModes_WhenInitialised_ThenPiecesIsValidAndThreeIsNot) {
  tdo_traj_config cfg = default_config();
  cfg.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
  Traj p(cfg);
  EXPECT_EQ(p.status(), TDO_OK);
  tdo_traj_config stored = default_config();
  EXPECT_LT(tdo_traj_footprint(&cfg), tdo_traj_footprint(&stored));
  cfg.stream_samples = 3;
  Traj bad(cfg);
  EXPECT_EQ(bad.status(), TDO_ERR_INVALID_ARGUMENT);
}

TEST(TrajectoryPieces,
     GivenRandomPathsAndLimits_WhenVerifiedByPieces_ThenTheSameTrajectoryAndBoundsAboveTheSamples) {
  // GIVEN the random paths and limits of the stored-samples property test, and more
  tdo_traj_config cfg = default_config();
  Traj stored(cfg);
  cfg.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
  Traj pieces(cfg);
  uint32_t closed = 0, fell_back = 0, runs = 0;
  for (uint64_t seed = 1; seed <= 400; ++seed) {
    tdo_test::Rng rng(seed);
    const auto segs = random_path(rng);
    const tdo_path path = make_path(segs);
    const tdo_traj_input in = random_input(rng, path);
    tdo_traj_output a{}, b{};
    // WHEN both run
    const tdo_status sa = tdo_traj_run(stored.ctx(), &in, &a);
    ASSERT_EQ(tdo_traj_run(pieces.ctx(), &in, &b), sa) << "seed " << seed;
    if (sa != TDO_OK && sa != TDO_ERR_INFEASIBLE) continue;
    ++runs;
    // THEN the profile, the sample count, the duration and the regenerated samples are the same
    ASSERT_TRUE(same_trajectory(stored.ctx(), a, pieces.ctx(), b)) << "seed " << seed;
    EXPECT_EQ(a.sample_passes, a.refinements + 1u);
    EXPECT_LE(b.sample_passes, b.refinements + 1u);
    if (b.sample_passes == b.refinements + 1u) {
      ++fell_back;  // every round on the samples: the stored run's numbers
      expect_same_run(a, b);
      continue;
    }
    // AND a round the closed form accepted is one the finite differences accept: the last one
    ASSERT_EQ(sa, TDO_OK) << "seed " << seed;
    ++closed;
    EXPECT_EQ(a.report.ok, 1);
    EXPECT_EQ(a.report.n_violations_total, 0u);
    ASSERT_TRUE(within_limits(a, in)) << "seed " << seed;
    // AND its bounds are at or above the samples' finite differences (this test's own)
    const Fd f = finite_differences(a, in.dt, in.a_max);
    EXPECT_GE(b.report.max_speed, f.max_v) << "seed " << seed;
    EXPECT_GE(b.report.max_acc, f.max_a) << "seed " << seed;
    EXPECT_GE(b.report.max_jerk, f.max_j) << "seed " << seed;
    EXPECT_GE(b.report.max_speed, a.report.max_speed) << "seed " << seed;
    EXPECT_GE(b.report.max_acc, a.report.max_acc) << "seed " << seed;
    EXPECT_GE(b.report.max_jerk, a.report.max_jerk) << "seed " << seed;
    EXPECT_LE(b.report.max_speed, 1.01 * in.v_max);
    EXPECT_LE(b.report.max_acc, 1.01 * in.a_max);
    EXPECT_LE(b.report.max_jerk, 1.01 * in.j_max);
    // AND the energy integral is near the trapezoid of the samples (relative 1e-2: the
    // trapezoid's error at dt up to 0.05 s over jerk switches and curvature kinks)
    EXPECT_NEAR(b.energy, a.energy, 1e-2 * a.energy + 1e-9) << "seed " << seed;
  }
  std::printf("pieces: %u runs, %u closed form, %u fell back\n", runs, closed, fell_back);
  // The closed form is meant to hold for most profiles: a majority, not every one
  EXPECT_GT(closed, runs / 2u);
}

TEST(TrajectoryPieces, GivenAProfileTheClosedFormRejects_WhenRun_ThenItFallsBackToTheSamples) {
  // GIVEN the peaked corner: its first profile violates the jerk limit at the samples
  const auto segs = peaked_path();
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  for (uint32_t refinements : {0u, 8u}) {
    tdo_traj_config cfg = default_config();
    cfg.max_refinements = refinements;
    cfg.stream_samples = TDO_TRAJ_SAMPLES_STREAMED;
    Traj streamed(cfg);
    cfg.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
    Traj pieces(cfg);
    tdo_traj_output a{}, b{};
    // WHEN it runs in pieces mode and streamed
    const tdo_status sa = tdo_traj_run(streamed.ctx(), &in, &a);
    ASSERT_EQ(tdo_traj_run(pieces.ctx(), &in, &b), sa);
    // THEN the first round fell back to the samples, with the streamed run's violations
    EXPECT_GE(b.sample_passes, 1u);
    EXPECT_EQ(a.refinements, b.refinements);
    if (refinements == 0u) {
      ASSERT_EQ(sa, TDO_ERR_INFEASIBLE);
      EXPECT_EQ(b.sample_passes, 1u);
      expect_same_run(a, b);
    } else {
      ASSERT_EQ(sa, TDO_OK);
    }
  }
}

/** m^2/s^3, the integral of |x''|^2 = s''^2 + s'^4 kappa^2 over the profile's pieces, by Simpson's
 *  rule on `steps` intervals per piece with kappa from tdo_segment_eval (this test's own). */
double profile_energy(const tdo_traj* ctx, const std::vector<tdo_path_segment>& segs, int steps) {
  double total = 0.0;
  for (const tdo_traj_piece& f : pieces_of(ctx)) {
    if (!(f.dur > 0.0)) continue;
    const double h = f.dur / steps;
    for (int i = 0; i <= steps; ++i) {
      const double t = h * i, v = f.v0 + t * (f.a0 + 0.5 * t * f.j), a = f.a0 + t * f.j;
      double s = f.s0 + t * (f.v0 + t * (0.5 * f.a0 + t * f.j / 6.0)), kappa = 0.0;
      for (const tdo_path_segment& seg : segs) {
        if (s <= seg.length || &seg == &segs.back()) {
          tdo_segment_state st;
          EXPECT_TRUE(tdo_segment_eval(&seg, std::fmin(std::fmax(s, 0.0), seg.length), &st));
          kappa = st.kappa;
          break;
        }
        s -= seg.length;
      }
      const double w = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      total += w * h / 3.0 * (a * a + v * v * v * v * kappa * kappa);
    }
  }
  return total;
}

TEST(TrajectoryPieces, GivenBezierCorners_WhenVerifiedByPieces_ThenTheEnergyIsTheProfilesIntegral) {
  // GIVEN L paths with G2 Bezier corners of three sizes (the curvature peaks in the corner's
  // middle, between the curve summary's stations)
  const std::vector<std::vector<tdo_path_segment>> paths{l_path_bezier(3.0), l_path_bezier(4.0),
                                                         l_path_bezier(6.0)};
  for (const auto& segs : paths) {
    const tdo_path path = make_path(segs);
    const tdo_traj_input in = make_input(path);
    tdo_traj_config cfg = default_config();
    cfg.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
    Traj pieces(cfg);
    tdo_traj_output out{};
    // WHEN the closed form accepts the last round's profile
    ASSERT_EQ(tdo_traj_run(pieces.ctx(), &in, &out), TDO_OK);
    ASSERT_LE(out.sample_passes, out.refinements);
    // THEN its energy is the integral of the profile's |x''|^2 along the path (relative 1e-4:
    // the curvature between the summary's stations is interpolated where that fits to 1e-3)
    const double e = profile_energy(pieces.ctx(), segs, 2000);
    EXPECT_NEAR(out.energy, e, 1e-4 * e);
  }
}

TEST_F(TrajectoryClearance, GivenPiecesMode_WhenThePathPassesABox_ThenThePathsExactDistance) {
  // GIVEN a straight path 1.2 m from a box, then one 0.3 m from it at a clearance of 0.5 m
  load_box(1.2, 0.5);
  tdo_traj_config cfg = default_config();
  Traj stored(cfg);
  cfg.stream_samples = TDO_TRAJ_SAMPLES_PIECES;
  Traj pieces(cfg);
  const std::vector<tdo_path_segment> segs{line({1, 0, 2}, {15, 0, 2})};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = input_on_grid(path);
  tdo_traj_output a{}, b{};
  ASSERT_EQ(tdo_traj_run(stored.ctx(), &in, &a), TDO_OK);
  ASSERT_EQ(tdo_traj_run(pieces.ctx(), &in, &b), TDO_OK);
  // THEN the closed form accepts it, its minimum is the line's exact distance, at most the samples'
  EXPECT_EQ(b.sample_passes, 0u);
  EXPECT_NEAR(b.report.min_clearance, 1.2, 1e-9);
  EXPECT_LE(b.report.min_clearance, a.report.min_clearance + 1e-12);
  // WHEN the box is 0.3 m from the path
  load_box(0.3, 0.0);
  // THEN not ok: the clearance violations, as the samples give them, and no refinement
  ASSERT_EQ(tdo_traj_run(pieces.ctx(), &in, &b), TDO_ERR_INFEASIBLE);
  EXPECT_EQ(b.report.ok, 0);
  EXPECT_EQ(b.refinements, 0u);
  EXPECT_EQ(b.sample_passes, 1u);
  ASSERT_GT(b.report.n_violations, 0u);
  for (uint32_t i = 0; i < b.report.n_violations; ++i)
    EXPECT_EQ(b.report.violations[i].what, TDO_QUANTITY_CLEARANCE);
  EXPECT_NEAR(b.report.min_clearance, 0.3, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Flight time (issue 23): pointwise curve ceilings and the budgets, against bounds derived here.

/** Largest curvature and |dkappa/ds| of a segment, from 4000 evaluations. */
void curve_extremes(const tdo_path_segment& s, double* kappa, double* dkappa) {
  *kappa = 0.0;
  *dkappa = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    tdo_segment_state st;
    ASSERT_TRUE(tdo_segment_eval(&s, s.length * i / 4000.0, &st));
    *kappa = std::fmax(*kappa, st.kappa);
    *dkappa = std::fmax(*dkappa, std::fabs(st.dkappa_ds));
  }
}

TEST(TrajectoryTime, GivenLongLineThenDurationIsWithinDtOfTheJerkLimitedOptimum) {
  // GIVEN a 20 m line: rest to rest under v, a and j no profile is faster than
  // L / v + v / a + a / j (each speed change needs v / a at full acceleration plus a / j of ramps)
  Traj t;
  const std::vector<tdo_path_segment> segs{line({0, 0, 1}, {12, 16, 1})};
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(within_limits(out, in));
  const double optimum = 20.0 / in.v_max + in.v_max / in.a_max + in.a_max / in.j_max;
  // THEN it takes at most 2 % of the speed changes and a sample period more
  EXPECT_GE(out.duration, optimum - in.dt);
  EXPECT_LE(out.duration, optimum + 0.02 * (in.v_max / in.a_max + in.a_max / in.j_max) + in.dt);
}

TEST(TrajectoryTime, GivenG2CornerThenItIsFlownFasterThanItsWorstPointAllowsWithinLimits) {
  // GIVEN an L with a Bezier corner whose curvature rises from 0 to its peak and falls again
  Traj t;
  const auto segs = l_path_bezier(3.0);
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  double kmax = 0.0, dkmax = 0.0;
  curve_extremes(segs[1], &kmax, &dkmax);
  // The former segment-wide ceiling: the worst curvature and curvature rate of the whole curve
  // together, (kappa^2 + |kappa'|) v^3 <= 0.45 j and kappa v^2 <= 0.78 a.
  const double worst = std::fmin(std::sqrt(0.78 * in.a_max / kmax),
                                 std::cbrt(0.45 * in.j_max / (kmax * kmax + dkmax)));
  // WHEN it is time-parameterised
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(within_limits(out, in));
  EXPECT_EQ(out.refinements, 0u);
  // THEN the time on the curve is below its length at that ceiling by a clear margin (the speed
  // follows the curvature along the curve instead of its worst point)
  double on_curve = 0.0, v_min = kInfty, v_max = 0.0;
  for (uint32_t i = 1; i < out.n_samples; ++i) {
    const tdo_vec3 p = out.samples[i].p;
    if (!(p.x > 7.0 && p.y < 3.0)) continue;
    on_curve += in.dt;
    const double v = len3(out.samples[i].v);
    v_min = std::fmin(v_min, v);
    v_max = std::fmax(v_max, v);
  }
  EXPECT_LT(on_curve, 0.85 * segs[1].length / worst);
  EXPECT_GT(v_max, 1.2 * worst);
  // AND nowhere on it slower than that ceiling
  EXPECT_GE(v_min, worst);
}

TEST(TrajectoryTime, GivenOnlyEightPiecesPerSegmentThenCurvesAreFlownWholeAndNoFaster) {
  // GIVEN the L with a Bezier corner, once with the documented capacity and once with 8 pieces per
  // segment (curves then cannot be split into parts, whose own limits the speed changes of a move
  // use where they cover them)
  const auto segs = l_path_bezier(3.0);
  const tdo_path path = make_path(segs);
  const tdo_traj_input in = make_input(path);
  tdo_traj_config small = default_config();
  small.max_segments = 3;
  small.max_profile = 8u * 3u + 1u;
  tdo_traj_config full = small;
  full.max_profile = TDO_TRAJ_PIECES_PER_SEGMENT * 3u + 1u;
  Traj ts(small), tf(full);
  ASSERT_EQ(ts.status(), TDO_OK);
  ASSERT_EQ(tf.status(), TDO_OK);
  tdo_traj_output os{}, of{};
  // WHEN both are time-parameterised
  ASSERT_EQ(tdo_traj_run(ts.ctx(), &in, &os), TDO_OK);
  EXPECT_TRUE(within_limits(os, in));
  EXPECT_TRUE(rest_to_rest(os, path));
  const double slow = os.duration;
  ASSERT_EQ(tdo_traj_run(tf.ctx(), &in, &of), TDO_OK);
  EXPECT_TRUE(within_limits(of, in));
  EXPECT_TRUE(rest_to_rest(of, path));
  // THEN both pass every check and the one with the parts is not slower (its moves see each
  // part's limits; a move's cruise stays under its lowest part's ceiling, so on this symmetric
  // corner, whose middle parts hold the speed, they fly the same)
  EXPECT_LE(of.duration, slow);
}

// ---------------------------------------------------------------------------------------------
// Moving start (tdo_traj_input.start, tdo_plan_request.state; docs/design.md s.5 "Moving start").
// Every limit is checked by the independent finite differences above (within_limits).

/** The plan's samples as a tdo_traj_output for the finite-difference checks. */
tdo_traj_output samples_of(const tdo_plan_result& r) {
  tdo_traj_output o{};
  o.samples = r.samples;
  o.n_samples = r.n_samples;
  return o;
}

/** The limits of `p` as a trajectory input (for within_limits). */
tdo_traj_input limits_of(const tdo_plan_params& p) {
  tdo_traj_input in{};
  in.v_max = p.v_max;
  in.a_max = p.a_max;
  in.j_max = p.j_max;
  in.a_lat_max = p.a_lat_max;
  in.dt = p.dt;
  return in;
}

/** Continuity at the first samples, from the sampled positions: sample 0 is the state exactly, the
 *  first forward difference is v0 + a0 dt/2 within j_max dt^2/6, and the first second difference
 *  (centred at t = dt) is within j_max dt (x1.01) of a0. */
::testing::AssertionResult continues(const tdo_traj_output& o, const tdo_vec3& p0,
                                     const tdo_start_state& st, double j_max, double dt) {
  if (o.n_samples < 3) return ::testing::AssertionFailure() << "too few samples";
  const tdo_sample& s0 = o.samples[0];
  if (!exactly(dist(s0.p, p0), 0.0) || !exactly(dist(s0.v, st.v), 0.0) ||
      !exactly(dist(s0.a, st.a), 0.0) || !exactly(s0.t, 0.0))
    return ::testing::AssertionFailure() << "sample 0 is not the start state";
  const tdo_vec3 v_fd = (o.samples[1].p - o.samples[0].p) * (1.0 / dt);
  const double dv = dist(v_fd, st.v + st.a * (0.5 * dt));
  if (dv > j_max * dt * dt / 6.0 * 1.01 + 1e-12)
    return ::testing::AssertionFailure() << "first velocity off by " << dv << " m/s";
  const tdo_vec3 a_fd =
      (o.samples[2].p - o.samples[1].p * 2.0 + o.samples[0].p) * (1.0 / (dt * dt));
  const double da = dist(a_fd, st.a);
  if (da > j_max * dt * 1.01 + 1e-6)
    return ::testing::AssertionFailure() << "first acceleration off by " << da << " m/s^2";
  return ::testing::AssertionSuccess();
}

/** Lowest finite-difference speed between the first and the last `margin` samples. */
double min_inner_speed(const tdo_traj_output& o, double dt, uint32_t margin) {
  double lo = kInfty;
  for (uint32_t i = margin; i + 1 + margin < o.n_samples; ++i)
    lo = std::fmin(lo, len3(o.samples[i + 1].p - o.samples[i].p) / dt);
  return lo;
}

constexpr int32_t kHallX = 30, kHallY = 12, kHallZ = 6;

/** A 30 x 12 x 6 m hall at 1 m voxels, a wall at x in [20, 21] for y < 8 (the goal lies behind it)
 *  and a planner with every stage (stored or streamed samples). */
class MovingStart : public ::testing::Test {
 protected:
  static tdo_capacity cap(uint32_t stream) {
    tdo_capacity c{};
    tdo_capacity_for_grid(&c, kHallX, kHallY, kHallZ, 0.5, 27u, 0u);
    c.max_boxes = 16;
    c.stream_samples = stream;
    return c;
  }
  MovingStart() : pl_(cap(0u)), streamed_(cap(1u)) {}
  void SetUp() override {
    ASSERT_EQ(pl_.status(), TDO_OK);
    ASSERT_EQ(streamed_.status(), TDO_OK);
    for (tdo_test::TestPlanner* p : {&pl_, &streamed_}) {
      const tdo_grid_desc d{kHallX, kHallY, kHallZ, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
      ASSERT_EQ(tdo_grid_reset(p->grid(), &d), TDO_OK);
      const tdo_box wall{tdo_vec3{20, 0, 0}, tdo_vec3{21, 8, 6}};
      ASSERT_EQ(tdo_grid_add_box(p->grid(), &wall), TDO_OK);
      ASSERT_EQ(tdo_grid_finish(p->grid(), 0.5), TDO_OK);
    }
  }
  static tdo_plan_request request(tdo_vec3 start, tdo_vec3 v, tdo_vec3 a) {
    tdo_plan_request r{};
    r.start = start;
    r.goal = tdo_vec3{25.5, 4.5, 3.0};
    tdo_plan_params_default(&r.params);
    r.state.v = v;
    r.state.a = a;
    return r;
  }
  tdo_status plan(const tdo_plan_request& r) { return tdo_planner_plan(pl_.planner(), &r, &res_); }
  /** The streamed planner regenerates the same samples bit for bit. */
  ::testing::AssertionResult streams_the_same(const tdo_plan_request& r) {
    tdo_plan_result s{};
    const tdo_status st = tdo_planner_plan(streamed_.planner(), &r, &s);
    if (st != TDO_OK) return ::testing::AssertionFailure() << tdo_status_str(st);
    std::vector<tdo_sample> got;
    tdo_planner_each_sample(
        streamed_.planner(),
        [](void* u, uint32_t, const tdo_sample* x) {
          static_cast<std::vector<tdo_sample>*>(u)->push_back(*x);
        },
        &got);
    if (got.size() != res_.n_samples) return ::testing::AssertionFailure() << "sample count";
    for (uint32_t i = 0; i < res_.n_samples; ++i)
      if (std::memcmp(&got[i], &res_.samples[i], sizeof(tdo_sample)) != 0)
        return ::testing::AssertionFailure() << "sample " << i << " differs";
    return ::testing::AssertionSuccess();
  }
  tdo_test::TestPlanner pl_, streamed_;
  tdo_plan_result res_{};
};

TEST_F(MovingStart,
       GivenAStartMovingTowardTheGoal_WhenPlanned_ThenItContinuesTheStateWithinLimits) {
  // GIVEN a vehicle at (3, 4.5, 3) flying +x at 2 m/s and accelerating (1, 0.5, 0) m/s^2, the goal
  // straight ahead behind the wall's gap
  const tdo_plan_request r =
      request(tdo_vec3{3.0, 4.5, 3.0}, tdo_vec3{2.0, 0.0, 0.0}, tdo_vec3{1.0, 0.5, 0.0});
  // WHEN planned
  ASSERT_EQ(plan(r), TDO_OK);
  const tdo_traj_output o = samples_of(res_);
  // THEN the samples begin with exactly that state and continue it (finite differences)
  EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt));
  // AND stay within v, a, j and the turn radius from the first sample (independent check)
  EXPECT_TRUE(within_limits(o, limits_of(r.params)));
  EXPECT_EQ(res_.feasibility.ok, 1);
  // AND end at the goal at rest
  const tdo_sample& last = o.samples[o.n_samples - 1];
  EXPECT_TRUE(exactly(dist(last.p, r.goal), 0.0));
  EXPECT_TRUE(exactly(len3(last.v), 0.0));
  // AND the vehicle keeps moving: no stop on the way (the corners curve it through the gap)
  EXPECT_GT(min_inner_speed(o, r.params.dt, 100u), 0.3);
  // AND it arrives sooner than from rest
  tdo_plan_request rest = r;
  rest.state = tdo_start_state{};
  tdo_plan_result from_rest{};
  ASSERT_EQ(tdo_planner_plan(pl_.planner(), &rest, &from_rest), TDO_OK);
  EXPECT_LT(o.n_samples, from_rest.n_samples);
  ASSERT_EQ(plan(r), TDO_OK);
  // AND the streamed planner hands out the same samples
  EXPECT_TRUE(streams_the_same(r));
}

TEST_F(MovingStart, GivenAStartMovingAwayFromTheGoal_WhenPlanned_ThenItBrakesToRestAndTurnsBack) {
  // GIVEN a vehicle at (10, 4.5, 3) flying -x at 2.5 m/s, away from the goal, braking slightly
  const tdo_plan_request r =
      request(tdo_vec3{10.0, 4.5, 3.0}, tdo_vec3{-2.5, 0.0, 0.0}, tdo_vec3{0.5, 0.0, 0.0});
  // WHEN planned
  ASSERT_EQ(plan(r), TDO_OK);
  const tdo_traj_output o = samples_of(res_);
  // THEN it begins with exactly the state, within every limit
  EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt));
  EXPECT_TRUE(within_limits(o, limits_of(r.params)));
  // AND it keeps flying -x until it stops (a sample at rest), then turns back to the goal
  uint32_t stop = 0;
  for (uint32_t i = 1; i + 1 < o.n_samples && stop == 0; ++i)
    if (exactly(len3(o.samples[i].v), 0.0)) stop = i;
  ASSERT_GT(stop, 0u) << "no stop";
  for (uint32_t i = 0; i < stop; ++i) EXPECT_LT(o.samples[i + 1].p.x, o.samples[i].p.x) << i;
  EXPECT_LT(o.samples[stop].p.x, r.start.x - 0.5);
  EXPECT_TRUE(exactly(dist(o.samples[o.n_samples - 1].p, r.goal), 0.0));
  EXPECT_TRUE(streams_the_same(r));
}

TEST_F(MovingStart, GivenAStartMovingAcrossThePath_WhenPlanned_ThenItCurvesInWithoutStopping) {
  // GIVEN a vehicle at (4, 3, 3) flying +y at 1.5 m/s, across the direction to the goal
  const tdo_plan_request r =
      request(tdo_vec3{4.0, 3.0, 3.0}, tdo_vec3{0.0, 1.5, 0.0}, tdo_vec3{0.0, 0.0, 0.0});
  // WHEN planned
  ASSERT_EQ(plan(r), TDO_OK);
  const tdo_traj_output o = samples_of(res_);
  // THEN it begins with exactly the state, within every limit
  EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt));
  EXPECT_TRUE(within_limits(o, limits_of(r.params)));
  // AND it turns towards the goal on a curve, without stopping
  EXPECT_GT(min_inner_speed(o, r.params.dt, 100u), 0.3);
  EXPECT_TRUE(exactly(dist(o.samples[o.n_samples - 1].p, r.goal), 0.0));
}

TEST_F(MovingStart, GivenAWallCloserThanTheStoppingDistance_WhenPlanned_ThenStateCannotStop) {
  // GIVEN a vehicle 2.5 m before the wall's face (x = 20, clearance 0.5 m) flying at it at 3 m/s:
  // it needs about 2.3 m to stop, more than the 2 m it has
  tdo_plan_request r =
      request(tdo_vec3{17.5, 4.0, 3.0}, tdo_vec3{3.0, 0.0, 0.0}, tdo_vec3{0.0, 0.0, 0.0});
  // WHEN planned
  // THEN no plan: the named status, and no samples
  EXPECT_EQ(plan(r), TDO_ERR_STATE_CANNOT_STOP);
  EXPECT_EQ(res_.n_samples, 0u);
  EXPECT_EQ(res_.samples, nullptr);
  // AND accelerating towards it from 2.5 m/s is as hopeless (the ramp first, then the braking)
  r.state.v = tdo_vec3{2.9, 0.0, 0.0};
  r.state.a = tdo_vec3{0.5, 0.0, 0.0};
  EXPECT_EQ(plan(r), TDO_ERR_STATE_CANNOT_STOP);
  // AND at 1 m/s it stops in time and flies to the goal
  r.state.v = tdo_vec3{1.0, 0.0, 0.0};
  r.state.a = tdo_vec3{0.0, 0.0, 0.0};
  ASSERT_EQ(plan(r), TDO_OK);
  const tdo_traj_output o = samples_of(res_);
  EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt));
  EXPECT_TRUE(within_limits(o, limits_of(r.params)));
  EXPECT_GE(res_.feasibility.min_clearance, 0.5 - 1e-9);
}

TEST_F(MovingStart, GivenBadStates_WhenPlanned_ThenNamedStatusesAndNoPlan) {
  const tdo_vec3 p0{5.0, 4.5, 3.0}, zero{0.0, 0.0, 0.0};
  struct Case {
    tdo_vec3 v, a;
    tdo_status want;
  };
  const Case cases[] = {
      {tdo_vec3{kNan, 0.0, 0.0}, zero, TDO_ERR_STATE_NOT_FINITE},
      {zero, tdo_vec3{0.0, kInfty, 0.0}, TDO_ERR_STATE_NOT_FINITE},
      {tdo_vec3{0.0, 0.0, -kInfty}, zero, TDO_ERR_STATE_NOT_FINITE},
      {tdo_vec3{2.5, 2.0, 0.0}, zero, TDO_ERR_STATE_TOO_FAST},  // 3.2 m/s > v_max
      {tdo_vec3{1.0, 0.0, 0.0}, tdo_vec3{0.0, 3.1, 0.0}, TDO_ERR_STATE_OVER_LIMITS},
      // at v_max and still accelerating along the velocity: the ramp would exceed v_max
      {tdo_vec3{3.0, 0.0, 0.0}, tdo_vec3{2.0, 0.0, 0.0}, TDO_ERR_STATE_OVER_LIMITS},
      // turning at v_max while still speeding up a little: a_t = 0.3 m/s^2 needs at least
      // a_t^2 / (2 j_max) = 4.5 mm/s of speed above v_max, whatever the jerk
      {tdo_vec3{3.0, 0.0, 0.0}, tdo_vec3{0.3, 2.9, 0.0}, TDO_ERR_STATE_OVER_LIMITS},
  };
  for (const Case& c : cases) {
    const tdo_plan_request r = request(p0, c.v, c.a);
    // WHEN planned, THEN the named status and no samples
    EXPECT_EQ(plan(r), c.want) << tdo_status_str(c.want);
    EXPECT_EQ(res_.status, c.want);
    EXPECT_EQ(res_.n_samples, 0u);
  }
  // AND a NaN is named at every depth; a moving start below depth TRAJECTORY is invalid
  tdo_plan_request r = request(p0, tdo_vec3{kNan, 0.0, 0.0}, zero);
  r.params.depth = TDO_PLAN_SEARCH;
  EXPECT_EQ(plan(r), TDO_ERR_STATE_NOT_FINITE);
  r.state.v = tdo_vec3{1.0, 0.0, 0.0};
  r.params.depth = TDO_PLAN_SMOOTH;
  EXPECT_EQ(plan(r), TDO_ERR_INVALID_ARGUMENT);
  // AND a start inside the wall's clearance stays start_blocked, moving or not
  r = request(tdo_vec3{19.8, 4.0, 3.0}, tdo_vec3{-1.0, 0.0, 0.0}, zero);
  EXPECT_EQ(plan(r), TDO_ERR_START_BLOCKED);
}

TEST_F(MovingStart, GivenAZeroStateWithNegativeZeros_WhenPlanned_ThenExactlyThePlanFromRest) {
  // GIVEN the same request at rest, once all +0 and once with -0 components
  const tdo_plan_request a = request(tdo_vec3{3.0, 4.5, 3.0}, tdo_vec3{}, tdo_vec3{});
  const tdo_plan_request b =
      request(tdo_vec3{3.0, 4.5, 3.0}, tdo_vec3{-0.0, 0.0, -0.0}, tdo_vec3{0.0, -0.0, 0.0});
  // WHEN planned
  ASSERT_EQ(plan(a), TDO_OK);
  const std::vector<tdo_sample> want(res_.samples, res_.samples + res_.n_samples);
  ASSERT_EQ(plan(b), TDO_OK);
  // THEN the samples are the same bits, starting at rest
  ASSERT_EQ(res_.n_samples, want.size());
  EXPECT_EQ(std::memcmp(res_.samples, want.data(), want.size() * sizeof(tdo_sample)), 0);
  EXPECT_TRUE(exactly(len3(want[0].v), 0.0));
}

TEST_F(MovingStart, GivenAStateThatAlmostStopsOnTheRamp_WhenPlanned_ThenItPlansFromIt) {
  // GIVEN a vehicle braking near a stop: its acceleration's ramp would end at |v1| of 1e-10 to
  // 1e-6 m/s (v = -a T / 2 plus a tiny remainder), so the braking line is only nanometres long
  const tdo_vec3 a0{-0.75, -1.29, 2.48};
  const double ramp = len3(a0) / (0.95 * 10.0);
  for (const double rest : {1e-10, 1e-9, 3e-9, 1e-7, 1e-6}) {
    tdo_vec3 v = a0 * (-0.5 * ramp);
    v.x += rest;
    const tdo_plan_request r = request(tdo_vec3{5.0, 4.5, 3.0}, v, a0);
    // WHEN planned
    ASSERT_EQ(plan(r), TDO_OK) << "remainder " << rest;
    const tdo_traj_output o = samples_of(res_);
    // THEN it begins with exactly the state, stays within every limit and reaches the goal
    EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt)) << rest;
    EXPECT_TRUE(within_limits(o, limits_of(r.params))) << rest;
    EXPECT_TRUE(exactly(dist(o.samples[o.n_samples - 1].p, r.goal), 0.0)) << rest;
    EXPECT_TRUE(streams_the_same(r)) << rest;
  }
}

TEST_F(MovingStart, GivenStatesOfItsOwnPlanAcceleratingToVMax_WhenReplanned_ThenTheyArePlanned) {
  // GIVEN the plan from rest at (3, 4.5, 3), and its samples still accelerating near v_max, where a
  // ramp at 0.95 j_max (removing the acceleration) would end above v_max
  const tdo_plan_request r0 = request(tdo_vec3{3.0, 4.5, 3.0}, tdo_vec3{}, tdo_vec3{});
  ASSERT_EQ(plan(r0), TDO_OK);
  const std::vector<tdo_sample> s(res_.samples, res_.samples + res_.n_samples);
  const double v_max = r0.params.v_max, j_max = r0.params.j_max;
  uint32_t tried = 0;
  for (const tdo_sample& x : s) {
    const double ramp = len3(x.a) / (0.95 * j_max);
    if (!(len3(x.v + x.a * (0.5 * ramp)) > v_max * (1.0 + 1e-6))) continue;
    if (!(len3(x.v) + len3(x.a) * len3(x.a) / (2.0 * 0.99 * j_max) <= v_max)) continue;
    ++tried;
    // WHEN replanned from that state
    const tdo_plan_request r = request(x.p, x.v, x.a);
    ASSERT_EQ(plan(r), TDO_OK) << "t " << x.t << " " << tdo_status_str(res_.status);
    // THEN the plan continues the state exactly and stays within every limit
    const tdo_traj_output o = samples_of(res_);
    EXPECT_TRUE(continues(o, r.start, r.state, j_max, r.params.dt)) << x.t;
    EXPECT_TRUE(within_limits(o, limits_of(r.params))) << x.t;
    EXPECT_TRUE(exactly(dist(o.samples[o.n_samples - 1].p, r.goal), 0.0)) << x.t;
  }
  EXPECT_GE(tried, 3u);
}

/** Largest finite-difference speed (m/s) over the samples: each is a mean of |v| over dt. */
double max_fd_speed(const tdo_traj_output& o, double dt) {
  double hi = 0.0;
  for (uint32_t i = 0; i + 1 < o.n_samples; ++i)
    hi = std::fmax(hi, len3(o.samples[i + 1].p - o.samples[i].p) / dt);
  return hi;
}

TEST_F(MovingStart, GivenAStateAtVMaxTurningAtAMax_WhenPlanned_ThenItContinuesWithinLimits) {
  // GIVEN a vehicle in the middle of the hall at v_max = 3 m/s in six horizontal directions,
  // each turning at a_max = 3 m/s^2 across its velocity: left, right, up, down, and up-left (a
  // one-piece ramp removing that acceleration would end at 3.037 m/s)
  const tdo_vec3 zhat{0.0, 0.0, 1.0};
  const double c = std::sqrt(0.5);
  const tdo_vec3 dirs[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {c, c, 0}, {c, -c, 0}};
  int planned = 0;
  for (const tdo_vec3& d : dirs) {
    const tdo_vec3 left{-d.y, d.x, 0.0};
    const tdo_vec3 across[] = {left, left * -1.0, zhat, zhat * -1.0, (left + zhat) * c};
    for (const tdo_vec3& n : across) {
      const tdo_plan_request r = request(tdo_vec3{10.0, 6.0, 3.0}, d * 3.0, n * 3.0);
      // WHEN planned
      ASSERT_EQ(plan(r), TDO_OK) << "v " << d.x << " " << d.y << ", a " << n.x << " " << n.y << " "
                                 << n.z << ": " << tdo_status_str(res_.status);
      ++planned;
      const tdo_traj_output o = samples_of(res_);
      // THEN the samples begin with exactly that state and continue it (finite differences)
      EXPECT_TRUE(continues(o, r.start, r.state, r.params.j_max, r.params.dt));
      // AND stay within v, a, j and the turn radius from the first sample (independent check)
      EXPECT_TRUE(within_limits(o, limits_of(r.params)));
      // AND the speed never rises above v_max at all (a mean of |v| <= v_max; rounding only)
      EXPECT_LE(max_fd_speed(o, r.params.dt), r.params.v_max + 1e-9);
      // AND the plan ends at the goal, and the streamed planner hands out the same samples
      EXPECT_TRUE(exactly(dist(o.samples[o.n_samples - 1].p, r.goal), 0.0));
      EXPECT_TRUE(streams_the_same(r));
    }
  }
  EXPECT_EQ(planned, 30);
}

TEST(TrajectoryStart,
     GivenAStateAtVMaxTurning_WhenTheEntryIsPlanned_ThenTwoPiecesKeepEveryLimitAndEndAtRestAcc) {
  // GIVEN v = (3, 0, 0) m/s at v_max and a = (-0.1, 2.998, 0) m/s^2 (|a| = a_max), limits 3/3/10
  const tdo_vec3 p0{1.0, 2.0, 3.0};
  tdo_start_state st{};
  st.v = tdo_vec3{3.0, 0.0, 0.0};
  st.a = tdo_vec3{-0.1, std::sqrt(9.0 - 0.01), 0.0};
  tdo_traj_entry e{};
  // WHEN its entry is planned
  ASSERT_EQ(tdo_traj_entry_plan(p0, &st, 3.0, 3.0, 10.0, &e), TDO_OK);
  // THEN the ramp has two pieces, each within 0.995 j_max, that bring the acceleration to zero
  ASSERT_GT(e.knot, 0.0);
  ASSERT_LT(e.knot, e.ramp);
  EXPECT_LE(len3(e.jerk), 0.995 * 10.0 + 1e-12);
  EXPECT_LE(len3(e.jerk2), 0.995 * 10.0 + 1e-12);
  const double t1 = e.knot, t2 = e.ramp - e.knot;
  EXPECT_LT(dist(e.knot_a, st.a + e.jerk * t1), 1e-12);
  EXPECT_LT(len3(e.knot_a + e.jerk2 * t2), 1e-12);
  EXPECT_LE(len3(e.knot_a), 3.0);
  // AND the pieces join: the knot and the end are where the cubics put them
  const auto at = [](tdo_vec3 p, tdo_vec3 v, tdo_vec3 a, tdo_vec3 j, double t) {
    return p + v * t + a * (t * t / 2.0) + j * (t * t * t / 6.0);
  };
  EXPECT_LT(dist(e.knot_p, at(p0, st.v, st.a, e.jerk, t1)), 1e-12);
  EXPECT_LT(dist(e.knot_v, st.v + st.a * t1 + e.jerk * (t1 * t1 / 2.0)), 1e-12);
  EXPECT_LT(dist(e.p, at(e.knot_p, e.knot_v, e.knot_a, e.jerk2, t2)), 1e-12);
  EXPECT_LT(dist(e.v, e.knot_v + e.knot_a * t2 + e.jerk2 * (t2 * t2 / 2.0)), 1e-12);
  // AND the speed stays within v_max all along (2000 points per piece)
  double hi = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double u = t1 * k / 2000.0, w = t2 * k / 2000.0;
    hi = std::fmax(hi, len3(st.v + st.a * u + e.jerk * (u * u / 2.0)));
    hi = std::fmax(hi, len3(e.knot_v + e.knot_a * w + e.jerk2 * (w * w / 2.0)));
  }
  EXPECT_LE(hi, 3.0 * (1.0 + 1e-9));
  EXPECT_NEAR(e.speed, len3(e.v), 1e-15);
  // AND a 12 m line from the ramp's end along its velocity is flown from exactly the state,
  // within every limit (finite differences), never above v_max
  const tdo_vec3 d = e.v * (1.0 / e.speed);
  Traj t;
  ASSERT_EQ(t.status(), TDO_OK);
  const std::vector<tdo_path_segment> segs{line(e.p, e.p + d * 12.0)};
  const tdo_path path = make_path(segs);
  tdo_traj_input in = make_input(path);
  in.start_p = p0;
  in.start = st;
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  EXPECT_TRUE(continues(out, p0, st, in.j_max, in.dt));
  EXPECT_TRUE(within_limits(out, in));
  EXPECT_LE(max_fd_speed(out, in.dt), in.v_max + 1e-9);
  EXPECT_TRUE(exactly(dist(out.samples[out.n_samples - 1].p, segs[0].p[1]), 0.0));
}

/** A random unit vector (rejection from the cube). */
tdo_vec3 random_unit(tdo_test::Rng& rng) {
  for (;;) {
    const tdo_vec3 d{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
    const double n = len3(d);
    if (n > 0.1 && n <= 1.0) return d * (1.0 / n);
  }
}

TEST(
    TrajectoryStart,
    GivenRandomStatesWithinTheLimits_WhenTheEntryIsPlanned_ThenOnlyStatesThatMustSpeedUpAreRefused) {
  // GIVEN 6000 random states per limit set (a third at v_max, half at a_max), for limit sets
  // with a_max^2 <= 0.9 j_max v_max (the default 3/3/10 among them)
  struct Limits {
    double v, a, j;
  };
  const Limits sets[] = {
      {3.0, 3.0, 10.0}, {3.0, 3.0, 5.0}, {1.0, 3.0, 10.0}, {5.0, 3.0, 25.0}, {2.0, 1.0, 1.0}};
  tdo_test::Rng rng(2020u);
  for (const Limits& L : sets) {
    int refused = 0, accepted = 0;
    for (int i = 0; i < 6000; ++i) {
      const double sp = i % 3 == 0 ? L.v : L.v * std::sqrt(rng.uniform());
      const double am = i % 2 == 0 ? L.a : L.a * std::sqrt(rng.uniform());
      tdo_start_state st{};
      st.v = random_unit(rng) * sp;
      st.a = random_unit(rng) * am;
      const double a_t = dot3(st.v, st.a) / sp;
      // the speed rises at least by a_t^2 / (2 j_max) whatever the jerk (d a_t / dt >= -j_max)
      const double bound = sp + (a_t > 0.0 ? a_t * a_t / (2.0 * L.j) : 0.0);
      // docs/design.md s.5: a refused state lies less than 1.25 w^2 / (2 v_max) below that bound,
      // w = a_max^2 / (1.9 j_max) (lat) the velocity a one-piece ramp adds to a lateral a_max
      const double lat = L.a * L.a / (1.9 * L.j), band = 1.25 * lat * lat / (2.0 * L.v);
      tdo_traj_entry e{};
      // WHEN the entry is planned
      const tdo_status got = tdo_traj_entry_plan(tdo_vec3{0, 0, 0}, &st, L.v, L.a, L.j, &e);
      // THEN a state that must exceed v_max is refused, every state not speeding up (a_t <= 0)
      // is accepted, and a refused state lies within `band` below the bound
      if (bound > L.v * (1.0 + 1e-9) + 1e-12) {
        EXPECT_EQ(got, TDO_ERR_STATE_OVER_LIMITS) << sp << " " << a_t;
      } else if (!(a_t > 0.0)) {
        EXPECT_EQ(got, TDO_OK) << sp << " " << a_t << " " << am;
      } else if (got != TDO_OK) {
        EXPECT_EQ(got, TDO_ERR_STATE_OVER_LIMITS);
        EXPECT_GT(bound, L.v - band) << sp << " " << a_t << " " << am;
      }
      if (got != TDO_OK) {
        ++refused;
        continue;
      }
      ++accepted;
      // AND an accepted ramp keeps |v| <= v_max, |a| <= a_max and |j| <= 0.995 j_max, and ends
      // with zero acceleration (its pieces evaluated here at 200 points each)
      const double t1 = e.knot, t2 = e.ramp - e.knot;
      ASSERT_LE(len3(e.jerk), 0.995 * L.j * (1.0 + 1e-12));
      ASSERT_LE(len3(e.jerk2), 0.995 * L.j * (1.0 + 1e-12));
      ASSERT_LE(len3(e.knot_a), L.a * (1.0 + 1e-9));
      ASSERT_LT(len3(e.knot_a + e.jerk2 * t2), 1e-9 * L.a);
      double hi = 0.0;
      for (int k = 0; k <= 200; ++k) {
        const double u = t1 * k / 200.0, w = t2 * k / 200.0;
        hi = std::fmax(hi, len3(st.v + st.a * u + e.jerk * (u * u / 2.0)));
        hi = std::fmax(hi, len3(e.knot_v + e.knot_a * w + e.jerk2 * (w * w / 2.0)));
      }
      ASSERT_LE(hi, L.v * (1.0 + 1e-9)) << sp << " " << a_t << " " << am;
      ASSERT_LE(e.speed, L.v);
    }
    EXPECT_GT(accepted, 3000);
    EXPECT_GT(refused, 600);  // the states at v_max speeding up are many
  }
}

TEST(TrajectoryStart,
     GivenAMovingStartAndItsBrakingLine_WhenParameterised_ThenItContinuesTheState) {
  // GIVEN a state at (1, 2, 3) with v = (1.5, 1, 0) m/s and a = (0, -1, 0.5) m/s^2, its entry
  const tdo_vec3 p0{1.0, 2.0, 3.0};
  tdo_start_state st{};
  st.v = tdo_vec3{1.5, 1.0, 0.0};
  st.a = tdo_vec3{0.0, -1.0, 0.5};
  tdo_traj_entry e{};
  ASSERT_EQ(tdo_traj_entry_plan(p0, &st, 3.0, 3.0, 10.0, &e), TDO_OK);
  EXPECT_NEAR(e.ramp, len3(st.a) / (0.95 * 10.0), 1e-15);
  EXPECT_GT(e.brake, 0.0);
  // AND a 12 m line from the ramp's end along its velocity
  const tdo_vec3 d = e.v * (1.0 / e.speed);
  Traj t;
  ASSERT_EQ(t.status(), TDO_OK);
  std::vector<tdo_path_segment> segs{line(e.p, e.p + d * 12.0)};
  tdo_path path = make_path(segs);
  tdo_traj_input in = make_input(path);
  in.start_p = p0;
  in.start = st;
  // WHEN parameterised
  tdo_traj_output out{};
  ASSERT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_OK);
  // THEN it starts in the state, within every limit, and ends at rest at the line's end
  EXPECT_TRUE(continues(out, p0, st, in.j_max, in.dt));
  EXPECT_TRUE(within_limits(out, in));
  EXPECT_TRUE(exactly(dist(out.samples[out.n_samples - 1].p, segs[0].p[1]), 0.0));
  // AND a path that does not begin with the braking line is refused
  segs[0] = line(e.p, e.p + d * (0.5 * e.brake));
  path = make_path(segs);
  in.path = path;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  segs[0] = line(e.p, e.p + tdo_vec3{0.0, 0.0, 12.0});  // the wrong direction
  path = make_path(segs);
  in.path = path;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
  segs[0] = line(p0, p0 + d * 12.0);  // not at the ramp's end
  path = make_path(segs);
  in.path = path;
  EXPECT_EQ(tdo_traj_run(t.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
}

}  // namespace

// bisect_highest (the speed bisections of the moves) decides a step from its bracket where it can
// instead of evaluating: on growing functions with smooth parts, jumps and a steep rise at the top
// (what the S-curves' lengths look like near a ceiling) it returns what the plain kBisections
// steps return, bit for bit.
TEST(TrajectoryBisection, GivenGrowingFunctions_WhenBisected_ThenThePlainBisectionsResult) {
  tdo_test::Rng rng(7122026u);
  for (int trial = 0; trial < 2000; ++trial) {
    const double lo = rng.uniform(0.0, 3.0), hi = lo + rng.uniform(1e-6, 3.0);
    const double quad = rng.uniform(0.0, 5.0), lin = rng.uniform(0.0, 2.0);
    const double steep = rng.below(2) ? rng.uniform(1e-6, 1e-2) : 0.0;
    const double eps = rng.uniform(1e-9, 1e-3);
    const double jump_at = rng.uniform(lo, hi), jump = rng.below(3) ? 0.0 : rng.uniform(0.0, 1e4);
    const auto lhs = [&](double v) {
      const double d = v - lo;
      return lin * d + quad * (d * d) + steep / (hi + eps - v) + (v >= jump_at ? jump : 0.0);
    };
    const double len = rng.uniform(lhs(lo), lhs(hi));
    const double lhs_hi = lhs(hi);
    if (!(lhs(lo) <= len) || !(lhs_hi > len)) continue;
    double plo = lo, phi = hi;  // the plain bisection
    for (int i = 0; i < tdo_internal::kBisections; ++i) {
      const double mid = 0.5 * (plo + phi);
      if (!(mid > plo && mid < phi)) break;
      if (lhs(mid) <= len)
        plo = mid;
      else
        phi = mid;
    }
    const double got = tdo_internal::bisect_highest(lo, hi, len, lhs_hi, lhs);
    EXPECT_EQ(std::memcmp(&got, &plo, sizeof got), 0)
        << "trial " << trial << ": " << got << " vs " << plo;
  }
}
