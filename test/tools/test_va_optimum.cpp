// Tests of the v/a time optimum along a sampled path (tools/tdo-plan/va_optimum.h), against closed
// forms derived here independently of the passes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "va_optimum.h"

using tdo_tools::va_optimum;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<tdo_vec3> line(double length, double step) {
  std::vector<tdo_vec3> p;
  const int n = static_cast<int>(std::lround(length / step));
  for (int i = 0; i <= n; ++i) p.push_back(tdo_vec3{length * i / n, 0.5, 2.0});
  return p;
}

/** Points on a circle of radius r about (1, 2, 3) in a tilted plane, sweep phi, every step m. */
std::vector<tdo_vec3> arc(double r, double phi, double step) {
  std::vector<tdo_vec3> p;
  const int n = static_cast<int>(std::lround(r * phi / step));
  const double c = std::sqrt(0.5);
  for (int i = 0; i <= n; ++i) {
    const double t = phi * i / n;
    const double x = r * std::cos(t), y = r * std::sin(t);
    p.push_back(tdo_vec3{1.0 + x, 2.0 + c * y, 3.0 + c * y});
  }
  return p;
}

}  // namespace

TEST(VaOptimum, GivenFewerThanTwoDistinctPointsThenTimeIsZero) {
  EXPECT_EQ(va_optimum({}, 3.0, 3.0).time_s, 0.0);
  EXPECT_EQ(va_optimum({tdo_vec3{1, 2, 3}, tdo_vec3{1, 2, 3}}, 3.0, 3.0).time_s, 0.0);
  EXPECT_EQ(va_optimum(line(5.0, 0.01), 0.0, 3.0).time_s, 0.0);
}

TEST(VaOptimum, GivenLongLineThenTimeIsTrapezoid) {
  // Rest to rest: accelerate to v_max over v^2 / (2a), cruise, brake: L / v + v / a.
  const double L = 20.0, v = 3.0, a = 3.0;
  const auto r = va_optimum(line(L, 0.01), v, a);
  EXPECT_NEAR(r.length_m, L, 1e-9);
  EXPECT_NEAR(r.time_s, L / v + v / a, 1e-3);
  EXPECT_LT(r.max_kappa, 1e-6);
}

TEST(VaOptimum, GivenShortLineThenTimeIsTriangle) {
  // L below v^2 / a: accelerate over L / 2 and brake, 2 sqrt(L / a).
  const double L = 2.0, a = 3.0;
  EXPECT_NEAR(va_optimum(line(L, 0.005), 3.0, a).time_s, 2.0 * std::sqrt(L / a), 1e-3);
}

TEST(VaOptimum, GivenArcThenTangentialAndCentripetalShareTheAcceleration) {
  // On a circle of radius r with sqrt(a r) < v_max: d(v^2)/ds = 2 sqrt(a^2 - v^4 / r^2), so
  // v^2 = a r sin(2 s / r) until s = pi r / 4 where v reaches sqrt(a r). That ramp takes
  // (r / 2) / sqrt(a r) * int_0^{pi/2} sin(x)^(-1/2) dx, the integral being
  // Gamma(1/4) sqrt(pi) / (2 Gamma(3/4)); rest to rest = two ramps and a cruise at sqrt(a r).
  const double r = 1.0, a = 3.0, phi = 1.5 * kPi;
  const double integral = std::tgamma(0.25) * std::sqrt(kPi) / (2.0 * std::tgamma(0.75));
  const double ramp = 0.5 * r / std::sqrt(a * r) * integral;
  const double cruise = (r * phi - 0.5 * kPi * r) / std::sqrt(a * r);
  const auto res = va_optimum(arc(r, phi, 0.001), 3.0, a);
  EXPECT_NEAR(res.max_kappa, 1.0 / r, 1e-6);
  EXPECT_NEAR(res.time_s, 2.0 * ramp + cruise, 0.005 * (2.0 * ramp + cruise));
  // Jerk-free but acceleration-bounded: slower than the same length straight.
  EXPECT_GT(res.time_s, va_optimum(line(r * phi, 0.001), 3.0, a).time_s);
}

TEST(VaOptimum, GivenRepeatedPointsThenTheyDoNotChangeTheResult) {
  std::vector<tdo_vec3> p = line(10.0, 0.01);
  std::vector<tdo_vec3> q;
  for (const tdo_vec3& x : p) {
    q.push_back(x);
    q.push_back(x);  // a vehicle at rest repeats its position
  }
  EXPECT_DOUBLE_EQ(va_optimum(p, 3.0, 3.0).time_s, va_optimum(q, 3.0, 3.0).time_s);
}
