// The G2 corner shape's rate bound (libtdo/src/g2_shape.h, internal): g2_rate_lower never exceeds
// the rate g2_shape gives, and the smoothing's shortcut built on it (smooth.cpp, g2_choose: a blend
// whose rate puts its jerk radius above r8 is not computed once the best speed is v_c) only skips
// blends that its comparison would reject.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../../libtdo/src/g2_shape.h"
#include "rng.h"

namespace {

using tdo_internal::g2_rate_lower;
using tdo_internal::g2_rate_lower_quick;
using tdo_internal::g2_shape;
using tdo_internal::g2_shape_lower;
using tdo_internal::kC2;
using tdo_internal::kC3;

constexpr double kGentle = 0.32;  // smooth.cpp's kGentleG and kGentleH

// The inner fractions of smooth.cpp's blend lam (0: Yang-Sukkarieh, 1: the gentle shape).
void blend(double lam, double* gf, double* hf) {
  const double ys_g = kC2 * kC3, ys_h = kC3;
  *gf = ys_g + lam * (kGentle - ys_g);
  *hf = ys_h + lam * (kGentle - ys_h);
}

// A random corner shape: a half-deflection from tiny (every 4th n) to near pi/2 (stop angles up to
// ~170 degrees), any blend, and g2_shape's tau and rate of it.
struct Shape {
  double beta, gf, hf, tau, rate;
};
Shape random_shape(tdo_test::Rng& rng, int n) {
  Shape s{};
  s.beta = n % 4 == 0 ? rng.uniform(1e-7, 1e-3) : rng.uniform(1e-3, 1.49);
  blend(rng.uniform(0.0, 1.0), &s.gf, &s.hf);
  g2_shape(s.beta, s.gf, s.hf, &s.tau, &s.rate);
  return s;
}

TEST(G2Shape, GivenRandomShapes_WhenRateBounded_ThenBoundNeverExceedsTheShapesRate) {
  tdo_test::Rng rng(20261207);
  int bounded = 0;
  for (int n = 0; n < 4000; ++n) {
    const Shape z = random_shape(rng, n);
    const double lower = g2_rate_lower(z.beta, z.gf, z.hf);
    ASSERT_GE(lower, 0.0);
    ASSERT_LE(lower, z.rate) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
    if (lower > 0.5 * z.rate) ++bounded;
  }
  // The bound is useful (within a factor 2) for most deflections, not only valid.
  EXPECT_GT(bounded, 2000);
}

// The quick bound is as sound (so the skip below holds with it too) and, though looser, useful:
// it serves where the rate lies far above the threshold, the common case in the smoothing.
TEST(G2Shape, GivenRandomShapes_WhenQuickBound_ThenNeverAboveTheShapesRateAndOftenWithin16x) {
  tdo_test::Rng rng(99);
  int useful = 0;
  for (int n = 0; n < 4000; ++n) {
    const Shape z = random_shape(rng, n);
    const double quick = g2_rate_lower_quick(z.beta, z.gf, z.hf);
    ASSERT_GE(quick, 0.0);
    ASSERT_LE(quick, z.rate) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
    if (quick > z.rate / 16.0) ++useful;
  }
  EXPECT_GT(useful, 2000);  // more than half of the shapes
}

// g2_shape_lower bounds what the smoothing's last-blend shortcut needs (g2_choose): tau and
// tau^2 rate (the rate at tangent length 1) from below, and mostly closely (its samples are the
// ones g2_shape refines).
TEST(G2Shape, GivenRandomShapes_WhenShapeLowerBounds_ThenBelowTauAndTau2RateAndMostlyClose) {
  tdo_test::Rng rng(1207);
  int close = 0;
  for (int n = 0; n < 4000; ++n) {
    const Shape z = random_shape(rng, n);
    double tau_lower = 0.0, f_lower = 0.0;
    g2_shape_lower(z.beta, z.gf, z.hf, &tau_lower, &f_lower);
    const double f = z.tau * z.tau * z.rate;
    ASSERT_LE(tau_lower, z.tau) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
    ASSERT_LE(f_lower, f * (1.0 + 1e-12)) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
    if (tau_lower > 0.98 * z.tau && f_lower > 0.9 * f) ++close;
  }
  EXPECT_GT(close, 3000);  // three quarters of the shapes
}

// The same bounds from every 4th sample only (the smoothing's first try): still below.
TEST(G2Shape, GivenRandomShapes_WhenCoarseShapeLowerBounds_ThenBelowTheFullBounds) {
  tdo_test::Rng rng(1208);
  for (int n = 0; n < 2000; ++n) {
    const Shape z = random_shape(rng, n);
    double tau_lower = 0.0, f_lower = 0.0, tau_full = 0.0, f_full = 0.0;
    g2_shape_lower(z.beta, z.gf, z.hf, &tau_lower, &f_lower, 4);
    g2_shape_lower(z.beta, z.gf, z.hf, &tau_full, &f_full);
    ASSERT_GT(tau_lower, 0.0);
    ASSERT_LE(tau_lower, tau_full) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
    ASSERT_LE(f_lower, f_full) << "beta " << z.beta << " gf " << z.gf << " hf " << z.hf;
  }
}

// smooth.cpp's speed of a blend with tau and rate (g2_choose).
double blend_speed(double tau, double rate, double r8, double v_c, double j_design, double a_lat,
                   double half_room) {
  const double r_des = std::max(r8, std::sqrt(v_c * v_c * v_c * rate / j_design));
  const double r = std::min(r_des, half_room / tau);
  return std::min(std::sqrt(a_lat * r), std::cbrt(j_design * r * r / rate));
}

TEST(G2Shape, GivenTheSkipCondition_WhenBlendComputed_ThenItCannotBeatTheBestSpeed) {
  tdo_test::Rng rng(7);
  int skipped = 0;
  for (int n = 0; n < 3000; ++n) {
    const double theta = rng.uniform(1e-4, 2.9);
    const double beta = 0.5 * theta;
    const double v_c = rng.uniform(0.5, 15.0), a_lat = rng.uniform(0.5, 10.0);
    const double j_design = 0.4 * rng.uniform(1.0, 40.0), k = rng.uniform(0.2, 3.0);
    const double r8 = k * theta / (2.0 * std::sin(0.5 * theta)) * (v_c * v_c / a_lat);
    const double half_room = rng.uniform(0.05, 50.0);
    const double rate_r8 = r8 * r8 * j_design / (v_c * v_c * v_c);
    for (int b = 1; b <= 4; ++b) {
      double gf = 0.0, hf = 0.0;
      blend(0.25 * b * rng.uniform(0.0, 1.0), &gf, &hf);
      if (!(g2_rate_lower(beta, gf, hf) > rate_r8 * (1.0 + 1e-9))) continue;
      ++skipped;
      double tau = 0.0, rate = 0.0;
      g2_shape(beta, gf, hf, &tau, &rate);
      // The best speed the condition allows is v_c (1 - 1e-10); the blend must not beat it.
      const double best_v = v_c * (1.0 - 1e-10);
      const double v = blend_speed(tau, rate, r8, v_c, j_design, a_lat, half_room);
      ASSERT_FALSE(v > best_v * (1.0 + 1e-9)) << "theta " << theta << " v " << v << " v_c " << v_c;
    }
  }
  EXPECT_GT(skipped, 500);  // the condition holds often enough to be exercised
}

}  // namespace
