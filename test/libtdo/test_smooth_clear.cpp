// The smoothing's certificates (libtdo/src/smooth_clear.h, internal) against the exact check they
// stand in for: whenever bezier_surely_clear claims a curve, tdo_collision_bezier_clear passes it,
// and whenever bezier_surely_blocked claims one, it fails it. Seeded random voxel maps (some with
// boxes too) and random cubic Beziers near the obstacles; each certificate must decide a good
// share of them, so the property is not vacuous.
#include <gtest/gtest.h>

#include <vector>

#include "../../libtdo/src/collision_internal.h"
#include "../../libtdo/src/smooth_clear.h"
#include "rng.h"
#include "tdo/collision.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_internal::bezier_clear_hinted;
using tdo_internal::bezier_surely_blocked;
using tdo_internal::bezier_surely_clear;
using tdo_test::Rng;

constexpr double kTolerance = 0.005;  // smooth.cpp's kClearTolerance

tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }

/** A 24 x 24 x 6 voxel grid with random cubes (and `boxes` random boxes), finished. */
class Map {
 public:
  Map(Rng& rng, double res, int boxes) : tp_(tdo_test::make_cap(24u * 24u * 6u, 1000u, 100u, 64u)) {
    tdo_grid_desc d{};
    d.nx = 24;
    d.ny = 24;
    d.nz = 6;
    d.res = res;
    d.origin = v3(-3.0, 1.5, 0.25);
    status_ = tp_.status();
    if (status_ == TDO_OK) status_ = tdo_grid_reset(tp_.grid(), &d);
    for (int i = 0; i < 24 * 24 * 6 / 8 && status_ == TDO_OK; ++i)
      status_ = tdo_grid_add_voxel(tp_.grid(), static_cast<int32_t>(rng.below(24)),
                                   static_cast<int32_t>(rng.below(24)),
                                   static_cast<int32_t>(rng.below(6)));
    for (int i = 0; i < boxes && status_ == TDO_OK; ++i) {
      tdo_box b{};
      b.min =
          v3(d.origin.x + rng.uniform(0.0, 24.0 * res), d.origin.y + rng.uniform(0.0, 24.0 * res),
             d.origin.z + rng.uniform(0.0, 6.0 * res));
      b.max = v3(b.min.x + rng.uniform(0.1, 2.0) * res, b.min.y + rng.uniform(0.1, 2.0) * res,
                 b.min.z + rng.uniform(0.1, 2.0) * res);
      status_ = tdo_grid_add_box(tp_.grid(), &b);
    }
    if (status_ == TDO_OK) status_ = tdo_grid_finish(tp_.grid(), 0.0);
    origin_ = d.origin;
    res_ = res;
  }
  tdo_status status() const { return status_; }
  const tdo_grid* grid() { return tp_.grid(); }
  /** A random point of the grid, 1 voxel away from its sides. */
  tdo_vec3 point(Rng& rng) const {
    return v3(origin_.x + rng.uniform(1.0, 23.0) * res_, origin_.y + rng.uniform(1.0, 23.0) * res_,
              origin_.z + rng.uniform(1.0, 5.0) * res_);
  }

 private:
  tdo_test::TestPlanner tp_;
  tdo_vec3 origin_{};
  double res_ = 1.0;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

TEST(SmoothClear, GivenRandomCurvesNearCubes_WhenCertified_ThenTheExactCheckAgrees) {
  Rng rng(20261207);
  int clear_claims = 0, blocked_claims = 0, curves = 0;
  for (int m = 0; m < 6; ++m) {
    const double res = m % 2 == 0 ? 1.0 : 0.25;
    Map map(rng, res, m < 4 ? 0 : 5);
    ASSERT_EQ(map.status(), TDO_OK);
    for (int q = 0; q < 1500; ++q) {
      const tdo_vec3 centre = map.point(rng);
      const double reach = rng.uniform(0.05, 2.5) * res;
      tdo_vec3 c[4];
      for (tdo_vec3& p : c)
        p = v3(centre.x + rng.uniform(-reach, reach), centre.y + rng.uniform(-reach, reach),
               centre.z + rng.uniform(-reach, reach) * 0.5);
      const double clearance = q % 3 == 0 ? 0.0 : rng.uniform(0.0, 0.6) * res;
      const int exact = tdo_collision_bezier_clear(map.grid(), c, clearance, kTolerance);
      ++curves;
      if (bezier_surely_clear(map.grid(), c, clearance, kTolerance)) {
        ++clear_claims;
        EXPECT_EQ(exact, 1) << "map " << m << " curve " << q;
      }
      for (int end = 0; end < 2; ++end) {
        if (bezier_surely_blocked(map.grid(), c, clearance, end)) {
          ++blocked_claims;
          EXPECT_EQ(exact, 0) << "map " << m << " curve " << q << " end " << end;
        }
      }
    }
  }
  EXPECT_GT(clear_claims, curves / 20);
  EXPECT_GT(blocked_claims, curves / 20);
}

// As the smoothing's shrink steps: runs of curves scaled about one point, checked with the hints
// carried from check to check: bezier_clear_hinted answers as the exact check does.
TEST(SmoothClear, GivenRunsOfScaledCurves_WhenHintsCarried_ThenTheExactCheckAgrees) {
  Rng rng(19);
  int fails = 0, passes = 0;
  for (int m = 0; m < 6; ++m) {
    const double res = m % 2 == 0 ? 1.0 : 0.25;
    Map map(rng, res, m < 4 ? 0 : 5);
    ASSERT_EQ(map.status(), TDO_OK);
    for (int q = 0; q < 300; ++q) {
      const tdo_vec3 w = map.point(rng);
      const double reach = rng.uniform(0.2, 3.0) * res;
      tdo_vec3 u[4];
      for (tdo_vec3& p : u)
        p = v3(rng.uniform(-reach, reach), rng.uniform(-reach, reach),
               rng.uniform(-reach, reach) * 0.5);
      const double clearance = q % 4 == 0 ? 0.0 : rng.uniform(0.0, 0.8) * res;
      uint32_t box = 0, cube = 0;
      for (int k = 0; k < 8; ++k) {
        const double f = rng.uniform(0.3, 1.0);
        tdo_vec3 c[4];
        for (int i = 0; i < 4; ++i) c[i] = v3(w.x + f * u[i].x, w.y + f * u[i].y, w.z + f * u[i].z);
        const int exact = tdo_collision_bezier_clear(map.grid(), c, clearance, kTolerance);
        ++(exact == 0 ? fails : passes);
        EXPECT_EQ(bezier_clear_hinted(map.grid(), c, clearance, kTolerance, &box, &cube), exact)
            << "map " << m << " run " << q << " step " << k;
      }
    }
  }
  EXPECT_GT(fails, 1000);  // both answers are common
  EXPECT_GT(passes, 1000);
}

TEST(SmoothClear, GivenBadInput_WhenCertified_ThenNoClaim) {
  const tdo_vec3 c[4] = {v3(0, 0, 0), v3(1, 0, 0), v3(2, 0, 0), v3(3, 0, 0)};
  EXPECT_EQ(bezier_surely_clear(nullptr, c, 0.0, kTolerance), 0);
  EXPECT_EQ(bezier_surely_blocked(nullptr, c, 0.0, 1), 0);
}

}  // namespace
