// The voxel grid (grid.h, docs/design.md s.0): world/voxel conversion, box and cube occupancy, the
// clearance rule, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <limits>
#include <set>
#include <tuple>
#include <vector>

#include "../../libtdo/src/grid_internal.h"  // moves: the legal steps, checked against brute force
#include "../../libtdo/src/surface_index.h"  // the brick index's bytes (footprint)
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::Obstacles;
using tdo_test::Rng;
using tdo_test::TestPlanner;
using tdo_test::VoxelMap;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfty = std::numeric_limits<double>::infinity();

tdo_box box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return tdo_box{tdo_vec3{x0, y0, z0}, tdo_vec3{x1, y1, z1}};
}

class GridTest : public ::testing::Test {
 protected:
  GridTest() : pl_(tdo_test::make_cap(1024, 1024, 1025, 16, 20000)) {}
  void SetUp() override {
    ASSERT_EQ(pl_.status(), TDO_OK);
    grid_ = pl_.grid();
    ASSERT_NE(grid_, nullptr);
  }
  void reset(const VoxelMap& m) {
    const tdo_grid_desc d = m.desc();
    ASSERT_EQ(tdo_grid_reset(grid_, &d), TDO_OK);
  }
  /** Voxels (as a set) for which pred(v) holds, over the whole grid of m. */
  template <class Pred>
  std::set<std::tuple<int, int, int>> voxels_where(const VoxelMap& m, Pred pred) {
    std::set<std::tuple<int, int, int>> s;
    for (size_t n = 0; n < m.size(); ++n) {
      const tdo_voxel v = m.voxel(n);
      if (pred(v)) s.insert(std::make_tuple(v.i, v.j, v.k));
    }
    return s;
  }
  std::set<std::tuple<int, int, int>> occupied(const VoxelMap& m) {
    return voxels_where(m, [&](const tdo_voxel& v) { return tdo_grid_is_occupied(grid_, v) != 0; });
  }
  std::set<std::tuple<int, int, int>> blocked(const VoxelMap& m) {
    return voxels_where(m, [&](const tdo_voxel& v) { return tdo_grid_is_blocked(grid_, v) != 0; });
  }
  static std::set<std::tuple<int, int, int>> block_of(int i0, int i1, int j0, int j1, int k0,
                                                      int k1) {
    std::set<std::tuple<int, int, int>> s;
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        for (int k = k0; k <= k1; ++k) s.insert(std::make_tuple(i, j, k));
    return s;
  }

  TestPlanner pl_;
  tdo_grid* grid_ = nullptr;
};

// ---------------------------------------------------------------------------------------------
// World/voxel conversion

TEST_F(GridTest, GivenAGrid_WhenResetAndQueried_ThenDescIsReturnedUnchanged) {
  const VoxelMap m(4, 3, 2, 0.5, tdo_vec3{-2.5, 1.0, 0.25});
  reset(m);
  const tdo_grid_desc d = tdo_grid_get_desc(grid_);
  EXPECT_EQ(d.nx, 4);
  EXPECT_EQ(d.ny, 3);
  EXPECT_EQ(d.nz, 2);
  EXPECT_DOUBLE_EQ(d.res, 0.5);
  EXPECT_DOUBLE_EQ(d.origin.x, -2.5);
  EXPECT_DOUBLE_EQ(d.origin.y, 1.0);
  EXPECT_DOUBLE_EQ(d.origin.z, 0.25);
}

TEST_F(GridTest, GivenPointsOnVoxelFaces_WhenConverted_ThenVoxelsAreHalfOpen) {
  // Voxel i spans [origin + i*res, origin + (i+1)*res): a point on a face belongs to the voxel
  // above it; the maximum bound itself is outside. All values are exact in binary.
  const VoxelMap m(4, 3, 2, 0.5, tdo_vec3{-2.5, 1.0, 0.25});
  reset(m);
  const double yc = 1.0 + 0.25, zc = 0.25 + 0.25;  // centre of row j=0, layer k=0
  for (int i = 0; i < m.nx; ++i) {
    tdo_voxel v{-7, -7, -7};
    ASSERT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{-2.5 + i * 0.5, yc, zc}, &v), 1) << i;
    EXPECT_EQ(v.i, i);
    EXPECT_EQ(v.j, 0);
    EXPECT_EQ(v.k, 0);
    // Just below the face: the voxel before (or outside for i = 0).
    const double below = std::nextafter(-2.5 + i * 0.5, -kInfty);
    const int in = tdo_grid_world_to_voxel(grid_, tdo_vec3{below, yc, zc}, &v);
    if (i == 0) {
      EXPECT_EQ(in, 0) << "a point just below the origin is outside";
    } else {
      ASSERT_EQ(in, 1);
      EXPECT_EQ(v.i, i - 1);
    }
  }
  tdo_voxel v{};
  EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{-2.5 + 4 * 0.5, yc, zc}, &v), 0)
      << "the maximum x bound is outside (half-open)";
  EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{-0.5, 1.0 + 3 * 0.5, zc}, &v), 0)
      << "the maximum y bound is outside";
  EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{-0.5, yc, 0.25 + 2 * 0.5}, &v), 0)
      << "the maximum z bound is outside";
  ASSERT_EQ(
      tdo_grid_world_to_voxel(grid_,
                              tdo_vec3{std::nextafter(-0.5, -kInfty), std::nextafter(2.5, -kInfty),
                                       std::nextafter(1.25, -kInfty)},
                              &v),
      1);
  EXPECT_EQ(v.i, 3);
  EXPECT_EQ(v.j, 2);
  EXPECT_EQ(v.k, 1);
  ASSERT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{-2.5, 1.0, 0.25}, &v), 1) << "the origin";
  EXPECT_EQ(v.i, 0);
  EXPECT_EQ(v.j, 0);
  EXPECT_EQ(v.k, 0);
}

TEST_F(GridTest, GivenEveryVoxel_WhenCentreAsked_ThenOriginPlusHalfOffsetTimesRes) {
  const VoxelMap m(4, 3, 2, 0.5, tdo_vec3{-2.5, 1.0, 0.25});
  reset(m);
  for (int k = 0; k < m.nz; ++k)
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        const tdo_vec3 c = tdo_grid_voxel_center(grid_, tdo_voxel{i, j, k});
        EXPECT_DOUBLE_EQ(c.x, -2.5 + (i + 0.5) * 0.5);
        EXPECT_DOUBLE_EQ(c.y, 1.0 + (j + 0.5) * 0.5);
        EXPECT_DOUBLE_EQ(c.z, 0.25 + (k + 0.5) * 0.5);
        tdo_voxel back{};
        ASSERT_EQ(tdo_grid_world_to_voxel(grid_, c, &back), 1);
        EXPECT_TRUE(tdo_test::same_voxel(back, tdo_voxel{i, j, k}));
      }
}

TEST_F(GridTest, GivenRandomPointsInsideVoxels_WhenConverted_ThenTheirVoxelIsFound) {
  Rng rng(11);
  for (int round = 0; round < 50; ++round) {
    const double res = rng.uniform(0.05, 3.0);
    const VoxelMap m(rng.range(1, 9), rng.range(1, 9), rng.range(1, 9), res,
                     tdo_vec3{rng.uniform(-100.0, 100.0), rng.uniform(-100.0, 100.0),
                              rng.uniform(-100.0, 100.0)});
    reset(m);
    for (int q = 0; q < 50; ++q) {
      const tdo_voxel want{rng.range(0, m.nx - 1), rng.range(0, m.ny - 1), rng.range(0, m.nz - 1)};
      const tdo_vec3 p = m.point_in(want, rng.uniform(0.01, 0.99), rng.uniform(0.01, 0.99),
                                    rng.uniform(0.01, 0.99));
      tdo_voxel got{};
      ASSERT_EQ(tdo_grid_world_to_voxel(grid_, p, &got), 1);
      EXPECT_TRUE(tdo_test::same_voxel(got, want))
          << tdo_test::str(got) << " vs " << tdo_test::str(want) << " round " << round;
    }
  }
}

// The conversion agrees to the last bit with the voxel spans [origin + i*res, origin + (i+1)*res)
// that occupancy uses: points on a face and one ulp either side of it, random grids.
TEST_F(GridTest, GivenPointsWithinOneUlpOfAFace_WhenConverted_ThenTheHalfOpenSpanDecides) {
  Rng rng(12);
  int checked = 0;
  for (int round = 0; round < 200; ++round) {
    const double res = rng.uniform() < 0.5 ? rng.uniform(0.05, 2.0) : 0.1 * rng.range(1, 20);
    const VoxelMap m(rng.range(1, 12), 1, 1, res, tdo_vec3{rng.uniform(-50.0, 50.0), 0.0, 0.0});
    reset(m);
    for (int32_t i = 0; i <= m.nx; ++i) {
      const double face = m.origin.x + i * res;
      for (double x : {std::nextafter(face, -kInfty), face, std::nextafter(face, kInfty)}) {
        // The voxel whose span holds x, from the definition, and whether x is inside the bounds.
        int32_t want = -1;
        for (int32_t c = 0; c < m.nx; ++c)
          if (m.origin.x + c * res <= x && x < m.origin.x + (c + 1) * res) want = c;
        tdo_voxel v{-7, -7, -7};
        const int in = tdo_grid_world_to_voxel(grid_, tdo_vec3{x, 0.5 * res, 0.5 * res}, &v);
        ++checked;
        if (want < 0) {
          EXPECT_EQ(in, 0) << "x " << x << " res " << res << " origin " << m.origin.x
                           << " lies outside every voxel span but was mapped to " << v.i;
        } else {
          EXPECT_TRUE(in == 1 && v.i == want)
              << std::setprecision(17) << "x " << x << " (face " << i << " at " << face << ") res "
              << res << " origin " << m.origin.x << ": in " << in << " voxel " << v.i
              << ", the span [o + i*res, o + (i+1)*res) holding it is voxel " << want;
        }
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST_F(GridTest, GivenPointsOutsideOrNonFinite_WhenConverted_ThenZero) {
  const VoxelMap m(4, 3, 2, 0.5, tdo_vec3{-2.5, 1.0, 0.25});
  reset(m);
  const tdo_vec3 inside{-1.0, 1.5, 0.5};
  tdo_voxel v{};
  ASSERT_EQ(tdo_grid_world_to_voxel(grid_, inside, &v), 1);
  const double xs[] = {-3.0, -2.5000001, -0.5, 10.0, kNan, kInfty, -kInfty};
  for (double x : xs) {
    EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{x, inside.y, inside.z}, &v), 0) << "x " << x;
  }
  const double ys[] = {0.99, 2.5, 1e300, kNan};
  for (double y : ys) {
    EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{inside.x, y, inside.z}, &v), 0) << "y " << y;
  }
  const double zs[] = {0.2, 1.25, -1e300, kNan};
  for (double z : zs) {
    EXPECT_EQ(tdo_grid_world_to_voxel(grid_, tdo_vec3{inside.x, inside.y, z}, &v), 0) << "z " << z;
  }
}

TEST_F(GridTest, GivenVoxelsOutsideTheGrid_WhenQueried_ThenBlockedButNotOccupied) {
  const VoxelMap m(3, 3, 3, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  const tdo_voxel outside[] = {{-1, 0, 0}, {3, 0, 0}, {0, -1, 0}, {0, 3, 0}, {0, 0, -1}, {0, 0, 3}};
  for (const tdo_voxel& v : outside) {
    EXPECT_EQ(tdo_grid_is_blocked(grid_, v), 1) << tdo_test::str(v);
    EXPECT_EQ(tdo_grid_is_occupied(grid_, v), 0) << tdo_test::str(v);
  }
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 0u);
}

// ---------------------------------------------------------------------------------------------
// Box occupancy: a voxel is occupied iff it intersects the open interior of a box.

TEST_F(GridTest, GivenABoxAlignedToVoxelFaces_WhenFinished_ThenOnlyVoxelsInsideAreOccupied) {
  const VoxelMap m(6, 6, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box b = box(1.0, 2.0, 0.0, 3.0, 4.0, 1.0);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  // Voxels 0 and 3 along x, 1 and 4 along y, and 1 along z only touch the box's faces.
  EXPECT_EQ(occupied(m), block_of(1, 2, 2, 3, 0, 0));
  EXPECT_EQ(blocked(m), block_of(1, 2, 2, 3, 0, 0)) << "clearance 0: blocked = occupied";
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 4u);
}

TEST_F(GridTest, GivenAnAlignedBoxOnAnOffsetFineGrid_WhenFinished_ThenFaceNeighboursAreFree) {
  const VoxelMap m(8, 4, 6, 0.25, tdo_vec3{-1.25, 0.5, 3.0});
  reset(m);
  // Faces at voxel indices x 2..5, y 1..2, z 3..4 (exact in binary).
  const tdo_box b = box(-1.25 + 2 * 0.25, 0.5 + 1 * 0.25, 3.0 + 3 * 0.25, -1.25 + 5 * 0.25,
                        0.5 + 2 * 0.25, 3.0 + 4 * 0.25);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_EQ(occupied(m), block_of(2, 4, 1, 1, 3, 3));
}

TEST_F(GridTest, GivenBoxesTouchingTheGridFromOutside_WhenFinished_ThenNothingIsOccupied) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box boxes[] = {box(-2, 0, 0, 0, 4, 4),     box(4, 0, 0, 6, 4, 4),
                           box(0, -3, 0, 4, 0, 4),     box(0, 4, 0, 4, 5, 4),
                           box(0, 0, -1, 4, 4, 0),     box(0, 0, 4, 4, 4, 9),
                           box(10, 10, 10, 11, 11, 11)};
  for (const tdo_box& b : boxes) ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_TRUE(occupied(m).empty());
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 0u);
}

TEST_F(GridTest, GivenUnalignedBoxes_WhenFinished_ThenEveryVoxelTheyCutIsOccupied) {
  const VoxelMap m(6, 6, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box a = box(1.2, 0.5, 4.99, 2.7, 0.6, 5.01);  // x 1..2, y 0, z 4..5
  const tdo_box b = box(3.4, 3.4, 3.4, 3.6, 3.6, 3.6);    // inside voxel (3,3,3) only
  const tdo_box c = box(-5.0, -5.0, 5.5, 0.5, 0.5, 100);  // reaches outside: voxel (0,0,5)
  for (const tdo_box* p : {&a, &b, &c}) ASSERT_EQ(tdo_grid_add_box(grid_, p), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  std::set<std::tuple<int, int, int>> want = block_of(1, 2, 0, 0, 4, 5);
  want.insert(std::make_tuple(3, 3, 3));
  want.insert(std::make_tuple(0, 0, 5));
  EXPECT_EQ(occupied(m), want);
  EXPECT_EQ(tdo_grid_blocked_count(grid_), static_cast<uint32_t>(want.size()));
}

TEST_F(GridTest, GivenABoxCoveringTheWholeGrid_WhenFinished_ThenEveryVoxelIsBlocked) {
  const VoxelMap m(5, 4, 3, 0.5, tdo_vec3{1.0, 1.0, 1.0});
  reset(m);
  const tdo_box b = box(-10, -10, -10, 10, 10, 10);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 60u);
  EXPECT_EQ(occupied(m).size(), 60u);
}

// ---------------------------------------------------------------------------------------------
// Voxel cubes

TEST_F(GridTest, GivenVoxelCubes_WhenFinishedWithoutClearance_ThenExactlyThoseVoxelsAreBlocked) {
  const VoxelMap m(5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 0, 0, 0), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 2, 3, 4), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 2, 3, 4), TDO_OK) << "adding a voxel twice is harmless";
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 4, 4, 4), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  const std::set<std::tuple<int, int, int>> want = {
      std::make_tuple(0, 0, 0), std::make_tuple(2, 3, 4), std::make_tuple(4, 4, 4)};
  EXPECT_EQ(occupied(m), want);
  EXPECT_EQ(blocked(m), want);
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 3u);
}

TEST_F(GridTest, GivenVoxelsOutsideTheGrid_WhenAddedAsCubes_ThenInvalidArgument) {
  const VoxelMap m(3, 4, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, -1, 0, 0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 3, 0, 0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 0, -1, 0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 0, 4, 0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 0, 0, -1), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 0, 0, 5), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(grid_, 2, 3, 4), TDO_OK);
}

// ---------------------------------------------------------------------------------------------
// Clearance: blocked iff occupied or the centre is strictly closer than clearance to an obstacle.

// One unit obstacle at (2,2,2) in a 5^3 grid of 1 m voxels. Distances from neighbour centres to it:
// face 0.5, edge sqrt(0.5) = 0.707, corner sqrt(0.75) = 0.866, next face 1.5.
void expect_shell_counts(tdo_grid* g) {
  struct Case {
    double clearance;
    uint32_t blocked;
  };
  const Case cases[] = {
      {0.0, 1u},
      {0.25, 1u},
      {0.5, 1u},  // face neighbours at exactly 0.5 are not strictly closer
      {std::nextafter(0.5, 1.0), 7u},
      {0.7, 7u},
      {0.75, 19u},
      {0.86, 19u},
      {0.9, 27u},
      {1.5, 27u},  // the next face layer at exactly 1.5 is not strictly closer
      {std::nextafter(1.5, 2.0), 33u},
  };
  for (const Case& c : cases) {
    ASSERT_EQ(tdo_grid_finish(g, c.clearance), TDO_OK);
    EXPECT_EQ(tdo_grid_blocked_count(g), c.blocked) << "clearance " << c.clearance;
    EXPECT_DOUBLE_EQ(tdo_grid_clearance(g), c.clearance);
    EXPECT_EQ(tdo_grid_is_occupied(g, tdo_voxel{2, 2, 2}), 1);
    EXPECT_EQ(tdo_grid_is_occupied(g, tdo_voxel{3, 2, 2}), 0)
        << "clearance blocks a voxel but does not make it occupied";
  }
}

TEST_F(GridTest, GivenOneUnitBox_WhenClearanceGrows_ThenShellsAreBlockedAtTheirExactDistance) {
  const VoxelMap m(5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box b = box(2, 2, 2, 3, 3, 3);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  expect_shell_counts(grid_);
}

TEST_F(GridTest, GivenOneVoxelCube_WhenClearanceGrows_ThenShellsAreBlockedAtTheirExactDistance) {
  const VoxelMap m(5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 2, 2, 2), TDO_OK);
  expect_shell_counts(grid_);
}

TEST_F(GridTest, GivenAThinWallBetweenCentres_WhenClearanceBelowTheGap_ThenNeighboursStayFree) {
  // A 0.1 m thick wall at x in (2.45, 2.55): it cuts voxel 2 only; the centres of voxels 1 and 3
  // are 0.95 m away from it.
  const VoxelMap m(5, 3, 3, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box b = box(2.45, -1.0, -1.0, 2.55, 4.0, 4.0);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.94), TDO_OK);
  EXPECT_EQ(blocked(m), block_of(2, 2, 0, 2, 0, 2));
  ASSERT_EQ(tdo_grid_finish(grid_, 0.96), TDO_OK);
  EXPECT_EQ(blocked(m), block_of(1, 3, 0, 2, 0, 2));
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_EQ(blocked(m), block_of(2, 2, 0, 2, 0, 2)) << "finish again recomputes from scratch";
}

TEST_F(GridTest, GivenABoxOutsideTheGrid_WhenClearanceReachesIn_ThenNearVoxelsAreBlocked) {
  // Obstacle geometry outside the bounds still counts for clearance (exact distance to the box).
  const VoxelMap m(4, 4, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box b = box(-3.0, 0.0, 0.0, -0.2, 4.0, 1.0);  // 0.7 m from the centres of column 0
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.69), TDO_OK);
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 0u);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.71), TDO_OK);
  EXPECT_EQ(blocked(m), block_of(0, 0, 0, 3, 0, 0));
  EXPECT_TRUE(occupied(m).empty());
}

// Independent brute force over random boxes (some reaching outside the grid), random voxel cubes,
// random resolutions and random clearances on small grids.
TEST_F(GridTest, GivenRandomBoxesCubesAndClearances_WhenFinished_ThenBlockedMatchesBruteForce) {
  Rng rng(20240601);
  const double resolutions[] = {0.25, 0.3, 0.5, 0.7, 1.0};
  uint64_t total_blocked = 0, total_free = 0, total_near = 0;
  for (int round = 0; round < 1000; ++round) {
    const double res = resolutions[rng.below(5)];
    VoxelMap m(rng.range(1, 8), rng.range(1, 8), rng.range(1, 6), res,
               tdo_vec3{rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)});
    Obstacles obs;
    const int n_boxes = rng.range(0, 5);
    for (int b = 0; b < n_boxes; ++b) {
      tdo_box bx{};
      const double lo[3] = {m.origin.x, m.origin.y, m.origin.z};
      const int32_t n[3] = {m.nx, m.ny, m.nz};
      double* mins[3] = {&bx.min.x, &bx.min.y, &bx.min.z};
      double* maxs[3] = {&bx.max.x, &bx.max.y, &bx.max.z};
      for (int a = 0; a < 3; ++a) {
        *mins[a] = rng.uniform(lo[a] - 1.0, lo[a] + n[a] * res + 0.5);
        *maxs[a] = *mins[a] + rng.uniform(0.02, 2.5);
      }
      obs.boxes.push_back(bx);
    }
    const int n_cubes = rng.range(0, 6);
    for (int c = 0; c < n_cubes; ++c)
      obs.cubes.push_back(
          tdo_voxel{rng.range(0, m.nx - 1), rng.range(0, m.ny - 1), rng.range(0, m.nz - 1)});
    const double clearance = rng.uniform() < 0.25 ? 0.0 : rng.uniform(0.0, 2.5);

    ASSERT_EQ(tdo_test::load_obstacles(grid_, m, obs, clearance), TDO_OK) << "round " << round;
    const std::vector<uint8_t> occ = tdo_test::brute_occupied(m, obs);
    const std::vector<uint8_t> blk = tdo_test::brute_blocked(m, obs, clearance);
    uint32_t want_blocked = 0;
    int reported = 0;
    for (size_t n = 0; n < m.size(); ++n) {
      const tdo_voxel v = m.voxel(n);
      want_blocked += blk[n];
      const int got_occ = tdo_grid_is_occupied(grid_, v);
      const int got_blk = tdo_grid_is_blocked(grid_, v);
      if ((got_occ != occ[n] || got_blk != blk[n]) && reported++ < 5) {
        ADD_FAILURE() << "round " << round << " voxel " << tdo_test::str(v) << " res " << res
                      << " clearance " << clearance << ": occupied " << got_occ << " (want "
                      << int(occ[n]) << "), blocked " << got_blk << " (want " << int(blk[n]) << ")";
      }
      total_near += (blk[n] && !occ[n]) ? 1u : 0u;
    }
    EXPECT_EQ(tdo_grid_blocked_count(grid_), want_blocked) << "round " << round;
    EXPECT_DOUBLE_EQ(tdo_grid_clearance(grid_), clearance);
    total_blocked += want_blocked;
    total_free += m.size() - want_blocked;
  }
  // The generator exercised every kind of voxel.
  EXPECT_GT(total_blocked, 3000u);
  EXPECT_GT(total_free, 3000u);
  EXPECT_GT(total_near, 1500u) << "too few voxels blocked by clearance alone";
}

// Random voxel maps in the shapes real maps have (runs along every axis, walls, solid blocks,
// scattered voxels) on grids long enough for the word-at-a-time paths of tdo_grid_finish (runs of
// cubes, 8 voxels per read), at real-map resolutions and random clearances: the blocked set and
// every voxel's legal steps equal the brute force (distance to every cube; MovingAI rule).
TEST(GridInflation,
     GivenRandomVoxelMaps_WhenFinishedWithRandomClearance_ThenBlockedAndStepsMatchBruteForce) {
  TestPlanner pl(tdo_test::make_cap(40 * 12 * 8, 16, 16, 1, 20000));
  ASSERT_EQ(pl.status(), TDO_OK);
  tdo_grid* grid = pl.grid();
  const tdo_grid* gi = grid;  // its moves (grid_internal.h): the legal steps the search reads
  Rng rng(19190719);
  const double resolutions[] = {0.08, 0.1, 0.25, 0.3, 0.5, 1.0};
  uint64_t near = 0, steps_checked = 0, partial = 0;
  for (int round = 0; round < 300; ++round) {
    const double res = resolutions[rng.below(6)];
    VoxelMap m(rng.range(1, 40), rng.range(1, 12), rng.range(1, 8), res,
               tdo_vec3{rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)});
    std::set<std::tuple<int, int, int>> cubes;
    const int n_shapes = rng.range(0, 6);
    for (int s = 0; s < n_shapes; ++s) {
      int32_t lo[3] = {rng.range(0, m.nx - 1), rng.range(0, m.ny - 1), rng.range(0, m.nz - 1)};
      int32_t len[3] = {1, 1, 1};
      const uint32_t kind = rng.below(4);  // 0 voxel, 1 run, 2 wall, 3 block
      if (kind == 1) len[rng.below(3)] = rng.range(2, 30);
      if (kind == 2) {
        const uint32_t thin = rng.below(3);
        for (int a = 0; a < 3; ++a) len[a] = a == static_cast<int>(thin) ? 1 : rng.range(2, 20);
      }
      if (kind == 3)
        for (int a = 0; a < 3; ++a) len[a] = rng.range(2, 8);
      for (int32_t k = lo[2]; k < lo[2] + len[2] && k < m.nz; ++k)
        for (int32_t j = lo[1]; j < lo[1] + len[1] && j < m.ny; ++j)
          for (int32_t i = lo[0]; i < lo[0] + len[0] && i < m.nx; ++i)
            cubes.insert(std::make_tuple(i, j, k));
    }
    Obstacles obs;
    for (const auto& c : cubes)
      obs.cubes.push_back(tdo_voxel{std::get<0>(c), std::get<1>(c), std::get<2>(c)});
    const double clearance = rng.uniform() < 0.2 ? 0.0 : rng.uniform(0.0, 5.0 * res);

    ASSERT_EQ(tdo_test::load_obstacles(grid, m, obs, clearance), TDO_OK) << "round " << round;
    ASSERT_EQ(tdo_grid_prepare(grid), TDO_OK);  // the steps are computed on first use
    const std::vector<uint8_t> blk = tdo_test::brute_blocked(m, obs, clearance);
    m.blocked = blk;
    uint32_t want = 0;
    int reported = 0;
    for (size_t n = 0; n < m.size(); ++n) {
      const tdo_voxel v = m.voxel(n);
      want += blk[n];
      near += blk[n] != 0 && cubes.count(std::make_tuple(v.i, v.j, v.k)) == 0 ? 1u : 0u;
      if (tdo_grid_is_blocked(grid, v) != blk[n] && reported++ < 5)
        ADD_FAILURE() << "round " << round << " voxel " << tdo_test::str(v) << " res " << res
                      << " clearance " << clearance << ": blocked " << tdo_grid_is_blocked(grid, v)
                      << ", brute force " << int(blk[n]);
      const uint32_t moves = gi->moves[n];
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int cell = (dz + 1) * 9 + (dy + 1) * 3 + (dx + 1);
            if (cell == 13) continue;
            const int d = cell < 13 ? cell : cell - 1;
            const bool want_step =
                m.is_free(v.i, v.j, v.k) &&
                tdo_test::legal_step(m, v, tdo_voxel{v.i + dx, v.j + dy, v.k + dz});
            const bool got_step = ((moves >> d) & 1u) != 0;
            ++steps_checked;
            if (want_step != got_step && reported++ < 5)
              ADD_FAILURE() << "round " << round << " voxel " << tdo_test::str(v) << " step (" << dx
                            << "," << dy << "," << dz << "): legal " << got_step << ", brute force "
                            << want_step;
          }
      partial += m.is_free(v.i, v.j, v.k) && moves != (1u << 26) - 1u && moves != 0u ? 1u : 0u;
    }
    EXPECT_EQ(tdo_grid_blocked_count(grid), want) << "round " << round;
  }
  // The generator exercised clearance shells and voxels with some but not all steps legal.
  EXPECT_GT(near, 20000u);
  EXPECT_GT(partial, 5000u);
  EXPECT_GT(steps_checked, 1000000u);
}

// A voxel cube and the box with the same extent are the same obstacle.
TEST_F(GridTest, GivenCubesAndEqualBoxes_WhenFinishedWithRandomClearance_ThenSameBlockedVoxels) {
  Rng rng(77);
  const double resolutions[] = {0.25, 0.5, 1.0};
  for (int round = 0; round < 100; ++round) {
    const double res = resolutions[rng.below(3)];
    const VoxelMap m(rng.range(2, 9), rng.range(2, 9), rng.range(1, 6), res,
                     tdo_vec3{0.125 * rng.range(-40, 40), 0.125 * rng.range(-40, 40),
                              0.125 * rng.range(-40, 40)});
    Obstacles cubes, boxes;
    const int n = rng.range(1, 8);
    for (int c = 0; c < n; ++c) {
      const tdo_voxel v{rng.range(0, m.nx - 1), rng.range(0, m.ny - 1), rng.range(0, m.nz - 1)};
      cubes.cubes.push_back(v);
      boxes.boxes.push_back(tdo_test::cube_box(m, v));
    }
    const double clearance = rng.uniform() < 0.2 ? 0.0 : rng.uniform(0.0, 2.0);
    ASSERT_EQ(tdo_test::load_obstacles(grid_, m, cubes, clearance), TDO_OK);
    const auto blocked_by_cubes = blocked(m);
    const auto occupied_by_cubes = occupied(m);
    ASSERT_EQ(tdo_test::load_obstacles(grid_, m, boxes, clearance), TDO_OK);
    EXPECT_EQ(blocked(m), blocked_by_cubes) << "round " << round << " clearance " << clearance;
    EXPECT_EQ(occupied(m), occupied_by_cubes) << "round " << round;
    std::set<std::tuple<int, int, int>> cube_set;
    for (const tdo_voxel& v : cubes.cubes) cube_set.insert(std::make_tuple(v.i, v.j, v.k));
    EXPECT_EQ(occupied_by_cubes, cube_set) << "round " << round;
  }
}

// ---------------------------------------------------------------------------------------------
// Map lifecycle

TEST_F(GridTest, GivenAFinishedMap_WhenReset_ThenObstaclesAreClearedAndClearanceIsUnset) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  EXPECT_DOUBLE_EQ(tdo_grid_clearance(grid_), -1.0) << "not finished yet";
  const tdo_box b = box(0, 0, 0, 2, 2, 2);
  ASSERT_EQ(tdo_grid_add_box(grid_, &b), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 3, 3, 3), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.3), TDO_OK);
  EXPECT_DOUBLE_EQ(tdo_grid_clearance(grid_), 0.3);
  EXPECT_EQ(occupied(m).size(), 9u);
  reset(m);
  EXPECT_DOUBLE_EQ(tdo_grid_clearance(grid_), -1.0);
  ASSERT_EQ(tdo_grid_finish(grid_, 0.3), TDO_OK);
  EXPECT_TRUE(occupied(m).empty());
  EXPECT_EQ(tdo_grid_blocked_count(grid_), 0u);
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST_F(GridTest, GivenInvertedOrDegenerateBoxes_WhenAdded_ThenInvalidBoxAndNothingIsAdded) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  const tdo_box good = box(1, 1, 1, 3, 3, 3);
  for (int axis = 0; axis < 3; ++axis) {
    for (double delta : {-1.0, 0.0}) {  // max < min, max == min
      tdo_box b = good;
      double* mn[3] = {&b.min.x, &b.min.y, &b.min.z};
      double* mx[3] = {&b.max.x, &b.max.y, &b.max.z};
      *mx[axis] = *mn[axis] + delta;
      EXPECT_EQ(tdo_grid_add_box(grid_, &b), TDO_ERR_INVALID_BOX)
          << "axis " << axis << " max - min = " << delta;
    }
  }
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_TRUE(occupied(m).empty()) << "a rejected box must not mark voxels";
}

TEST_F(GridTest, GivenNonFiniteBoxCorners_WhenAdded_ThenInvalidBox) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  for (int c = 0; c < 6; ++c) {
    for (double bad : {kNan, kInfty, -kInfty}) {
      tdo_box b = box(1, 1, 1, 3, 3, 3);
      double* coords[6] = {&b.min.x, &b.min.y, &b.min.z, &b.max.x, &b.max.y, &b.max.z};
      *coords[c] = bad;
      EXPECT_EQ(tdo_grid_add_box(grid_, &b), TDO_ERR_INVALID_BOX)
          << "coordinate " << c << " = " << bad;
    }
  }
  ASSERT_EQ(tdo_grid_finish(grid_, 0.0), TDO_OK);
  EXPECT_TRUE(occupied(m).empty());
}

TEST_F(GridTest, GivenInvalidSizesOrPlacement_WhenReset_ThenInvalidArgument) {
  const tdo_grid_desc good{4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(grid_, &good), TDO_OK);
  std::vector<tdo_grid_desc> bad;
  for (int32_t n : {0, -1, std::numeric_limits<int32_t>::min()}) {
    tdo_grid_desc d = good;
    d.nx = n;
    bad.push_back(d);
    d = good;
    d.ny = n;
    bad.push_back(d);
    d = good;
    d.nz = n;
    bad.push_back(d);
  }
  for (double r : {0.0, -1.0, -0.0, kNan, kInfty, -kInfty}) {
    tdo_grid_desc d = good;
    d.res = r;
    bad.push_back(d);
  }
  for (double o : {kNan, kInfty, -kInfty}) {
    tdo_grid_desc d = good;
    d.origin.x = o;
    bad.push_back(d);
    d = good;
    d.origin.y = o;
    bad.push_back(d);
    d = good;
    d.origin.z = o;
    bad.push_back(d);
  }
  for (size_t n = 0; n < bad.size(); ++n)
    EXPECT_EQ(tdo_grid_reset(grid_, &bad[n]), TDO_ERR_INVALID_ARGUMENT) << "case " << n;
}

TEST(GridCapacity, GivenAMapLargerThanMaxVoxels_WhenReset_ThenMapCapacity) {
  TestPlanner pl(tdo_test::make_cap(1000, 1000, 100));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_grid_desc fits{10, 10, 10, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &fits), TDO_OK) << "exactly max_voxels fits";
  const tdo_grid_desc one_more{10, 10, 11, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &one_more), TDO_ERR_MAP_CAPACITY);
  const tdo_grid_desc long_thin{1001, 1, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &long_thin), TDO_ERR_MAP_CAPACITY);
  // Products that wrap around in 32 bits (2^32 and 2^32 + 1000-ish) must not sneak through.
  const tdo_grid_desc wrap{65536, 65536, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &wrap), TDO_ERR_MAP_CAPACITY);
  const tdo_grid_desc wrap2{65536, 65536, 2, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &wrap2), TDO_ERR_MAP_CAPACITY);
  const int32_t big = std::numeric_limits<int32_t>::max();
  const tdo_grid_desc huge{big, big, big, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  EXPECT_EQ(tdo_grid_reset(pl.grid(), &huge), TDO_ERR_MAP_CAPACITY);
}

// Two grids of the same (reset) size get the same 6 random boxes and clearance 0.4 m; their blocked
// voxels and 500 random point and segment distances must agree bit for bit.
void expect_same_box_answers(tdo_grid* a, tdo_grid* b, uint64_t seed) {
  tdo_test::Rng rng(seed);
  for (int n = 0; n < 6; ++n) {
    const tdo_vec3 lo{rng.uniform(-1.0, 5.0), rng.uniform(2.0, 7.0), rng.uniform(0.5, 4.5)};
    const tdo_box box{lo, tdo_vec3{lo.x + rng.uniform(0.1, 1.5), lo.y + rng.uniform(0.1, 1.5),
                                   lo.z + rng.uniform(0.1, 1.5)}};
    for (tdo_grid* g : {a, b}) ASSERT_EQ(tdo_grid_add_box(g, &box), TDO_OK);
  }
  for (tdo_grid* g : {a, b}) ASSERT_EQ(tdo_grid_finish(g, 0.4), TDO_OK);
  EXPECT_EQ(tdo_grid_blocked_count(a), tdo_grid_blocked_count(b));
  for (int n = 0; n < 500; ++n) {
    const tdo_vec3 p{rng.uniform(-1.0, 5.0), rng.uniform(2.0, 7.0), rng.uniform(0.5, 4.5)};
    const tdo_vec3 q{rng.uniform(-1.0, 5.0), rng.uniform(2.0, 7.0), rng.uniform(0.5, 4.5)};
    const double pa = tdo_collision_point_distance(a, p, 3.0);
    const double pb = tdo_collision_point_distance(b, p, 3.0);
    EXPECT_EQ(std::memcmp(&pa, &pb, sizeof pa), 0) << n;
    const double sa = tdo_collision_segment_distance(a, p, q, 3.0);
    const double sb = tdo_collision_segment_distance(b, p, q, 3.0);
    EXPECT_EQ(std::memcmp(&sa, &sb, sizeof sa), 0) << n;
  }
}

// max_axis sizes the distance field's line scratch: a longer axis is refused by name, and a grid
// within it answers every query exactly as an unlimited one.
TEST(GridCapacity, GivenAnAxisLongerThanMaxAxis_WhenReset_ThenMapCapacityElseTheSameDistances) {
  tdo_capacity cap = tdo_test::make_cap(1000, 1000, 100);
  tdo_planner_config loose{}, tight{};
  loose.cap = cap;
  cap.max_axis = 12;
  tight.cap = cap;
  // 1000 voxels of line scratch (8 bytes each) became 12
  EXPECT_EQ(tdo_planner_footprint(&loose) - tdo_planner_footprint(&tight), 8u * (1000u - 12u));
  TestPlanner a(loose.cap), b(tight.cap);
  ASSERT_EQ(a.status(), TDO_OK);
  ASSERT_EQ(b.status(), TDO_OK);
  for (const tdo_grid_desc& d : {tdo_grid_desc{13, 1, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0}},
                                 tdo_grid_desc{1, 13, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0}},
                                 tdo_grid_desc{2, 2, 13, 1.0, tdo_vec3{0.0, 0.0, 0.0}}}) {
    EXPECT_EQ(tdo_grid_reset(b.grid(), &d), TDO_ERR_MAP_CAPACITY);
    EXPECT_EQ(tdo_grid_reset(a.grid(), &d), TDO_OK);
  }
  const tdo_grid_desc d{12, 10, 8, 0.5, tdo_vec3{-1.0, 2.0, 0.5}};
  for (tdo_grid* g : {a.grid(), b.grid()}) ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
  expect_same_box_answers(a.grid(), b.grid(), 77u);
}

// boxes_only drops the distance field (4 bytes per voxel), its line scratch (8 bytes per voxel
// of max_axis, here max_voxels) and the brick index of the surface cubes (1/32 brick per voxel,
// 10 bytes each): a voxel obstacle is refused by name, and box maps answer every query exactly
// as with the field.
TEST(GridCapacity, GivenBoxesOnly_WhenAVoxelIsAdded_ThenMapCapacityElseTheSameDistances) {
  tdo_planner_config full{}, boxes{};
  full.cap = tdo_test::make_cap(1000, 1000, 100);
  boxes.cap = full.cap;
  boxes.cap.boxes_only = 1u;
  tdo_internal::GridCapacity grid_cap{};
  grid_cap.max_voxels = 1000u;
  EXPECT_EQ(tdo_internal::surface_index_footprint(grid_cap),
            tdo_arena_round((1000u / 32u + 64u) * 8u + 1u) +
                tdo_arena_round((1000u / 32u + 64u) * 2u + 1u));
  EXPECT_EQ(tdo_planner_footprint(&full) - tdo_planner_footprint(&boxes),
            (4u + 8u) * 1000u + tdo_internal::surface_index_footprint(grid_cap));
  TestPlanner a(full.cap), b(boxes.cap);
  ASSERT_EQ(a.status(), TDO_OK);
  ASSERT_EQ(b.status(), TDO_OK);
  const tdo_grid_desc d{12, 10, 8, 0.5, tdo_vec3{-1.0, 2.0, 0.5}};
  for (tdo_grid* g : {a.grid(), b.grid()}) ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
  EXPECT_EQ(tdo_grid_add_voxel(a.grid(), 3, 4, 5), TDO_OK);
  EXPECT_EQ(tdo_grid_add_voxel(b.grid(), 3, 4, 5), TDO_ERR_MAP_CAPACITY);
  ASSERT_EQ(tdo_grid_reset(a.grid(), &d), TDO_OK);  // drop the voxel again
  expect_same_box_answers(a.grid(), b.grid(), 78u);
}

TEST(GridCapacity, GivenMoreBoxesThanMaxBoxes_WhenAdded_ThenBoxCapacity) {
  TestPlanner pl(tdo_test::make_cap(64, 64, 64, 2));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_grid_desc d{4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  const tdo_box b1 = box(0, 0, 0, 1, 1, 1), b2 = box(2, 2, 2, 3, 3, 3), b3 = box(3, 0, 0, 4, 1, 1);
  EXPECT_EQ(tdo_grid_add_box(pl.grid(), &b1), TDO_OK);
  EXPECT_EQ(tdo_grid_add_box(pl.grid(), &b2), TDO_OK);
  EXPECT_EQ(tdo_grid_add_box(pl.grid(), &b3), TDO_ERR_BOX_CAPACITY);
  // A reset empties the box list again.
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  EXPECT_EQ(tdo_grid_add_box(pl.grid(), &b3), TDO_OK);
}

TEST_F(GridTest, GivenNegativeOrNonFiniteClearance_WhenFinished_ThenInvalidArgument) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  reset(m);
  ASSERT_EQ(tdo_grid_add_voxel(grid_, 1, 1, 1), TDO_OK);
  for (double c : {-0.5, -1e-12, kNan, kInfty, -kInfty})
    EXPECT_EQ(tdo_grid_finish(grid_, c), TDO_ERR_INVALID_ARGUMENT) << "clearance " << c;
  EXPECT_DOUBLE_EQ(tdo_grid_clearance(grid_), -1.0) << "a rejected finish leaves it unfinished";
}

namespace {
/** Cells of the stencil at clearance c and resolution r, counted the way grid.cpp defines it. */
uint64_t stencil_count(double c, double r) {
  const int reach = static_cast<int>(std::ceil(c / r + 0.5));
  uint64_t n = 0;
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double gx = std::fmax(0.0, std::fabs(i) * r - 0.5 * r);
        const double gy = std::fmax(0.0, std::fabs(j) * r - 0.5 * r);
        const double gz = std::fmax(0.0, std::fabs(k) * r - 0.5 * r);
        if (gx * gx + gy * gy + gz * gz < c * c) ++n;
      }
  return n;
}
}  // namespace

// Issue 24: the stencil is refused in constant time when the clearance reaches far past the
// capacity (the bounding box of (2 c / r)^2 cells was scanned first: hours at c / r = 1e5, and past
// c / r = 2.1e9 an out-of-range conversion to int left an empty stencil and TDO_OK). The constant
// time check only refuses what the count refuses: finish succeeds exactly when the cells fit.
TEST(GridCapacity, GivenClearancesUpToBillionsOfVoxels_WhenFinished_ThenOkExactlyWhenTheCellsFit) {
  TestPlanner pl(tdo_test::make_cap(512, 512, 512, 4, 2000));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_grid_desc d{8, 8, 8, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(pl.grid(), 4, 4, 4), TDO_OK);
  int fitted = 0;
  for (double c = 0.0; c < 12.0; c += 0.05) {
    const bool fits = stencil_count(c, 1.0) <= 2000u;
    fitted += fits ? 1 : 0;
    EXPECT_EQ(tdo_grid_finish(pl.grid(), c), fits ? TDO_OK : TDO_ERR_CLEARANCE_CAPACITY) << c;
  }
  EXPECT_GT(fitted, 100);  // both sides of the capacity were tried
  EXPECT_LT(fitted, 240);
  for (double c : {1e4, 1e5, 5e5, 2.2e9, 1e12, 1e300}) {
    EXPECT_EQ(tdo_grid_finish(pl.grid(), c), TDO_ERR_CLEARANCE_CAPACITY) << c;
    EXPECT_DOUBLE_EQ(tdo_grid_clearance(pl.grid()), -1.0);
  }
  const tdo_grid_desc fine{8, 8, 8, 1e-9, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &fine), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(pl.grid(), 4, 4, 4), TDO_OK);
  EXPECT_EQ(tdo_grid_finish(pl.grid(), 3.0), TDO_ERR_CLEARANCE_CAPACITY) << "3e9 voxels of reach";
}

TEST(GridCapacity, GivenAClearanceBeyondTheStencil_WhenFinished_ThenClearanceCapacityAndNotReady) {
  TestPlanner pl(tdo_test::make_cap(512, 512, 512, 4, 27));  // room for K = 1 only
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_grid_desc d{8, 8, 8, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(pl.grid(), 4, 4, 4), TDO_OK);
  EXPECT_EQ(tdo_grid_finish(pl.grid(), 0.4), TDO_OK) << "K = ceil(0.4 + 0.5) = 1 fits 27 cells";
  EXPECT_EQ(tdo_grid_finish(pl.grid(), 3.0), TDO_ERR_CLEARANCE_CAPACITY);
  EXPECT_DOUBLE_EQ(tdo_grid_clearance(pl.grid()), -1.0);
  tdo_search_output out{};
  const tdo_search_input in = tdo_test::make_input(pl.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                   tdo_vec3{7.5, 7.5, 7.5}, TDO_SEARCH_ASTAR);
  EXPECT_EQ(tdo_search_run(pl.search(), &in, &out), TDO_ERR_MAP_NOT_READY)
      << "a grid whose finish failed must not be planned on";
}

TEST_F(GridTest, GivenNullPointers_WhenCallingGridFunctions_ThenInvalidArgument) {
  const tdo_grid_desc d{4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  const tdo_box b = box(0, 0, 0, 1, 1, 1);
  EXPECT_EQ(tdo_grid_reset(nullptr, &d), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_reset(grid_, nullptr), TDO_ERR_INVALID_ARGUMENT);
  ASSERT_EQ(tdo_grid_reset(grid_, &d), TDO_OK);
  EXPECT_EQ(tdo_grid_add_box(nullptr, &b), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_box(grid_, nullptr), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_add_voxel(nullptr, 0, 0, 0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_finish(nullptr, 0.0), TDO_ERR_INVALID_ARGUMENT);
}

}  // namespace
