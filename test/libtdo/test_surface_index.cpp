// Brick index of the surface cubes (surface_index.h): the exact distance queries that use it give
// the brute-force minimum over every cube, also on the paths the index falls back to (more bricks
// than it sorts, grids too thin to index), and map updates keep it equal to a rebuild.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../../libtdo/src/grid_internal.h"  // the index itself, compared with a rebuild
#include "../../libtdo/src/surface_index.h"
#include "rng.h"
#include "tdo/collision.h"
#include "tdo/grid_update.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;
using tdo_test::TestPlanner;
using tdo_test::VoxelMap;

tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }

/** Cubes in clusters (filled blocks, hollow shells) plus scattered single cubes. */
std::vector<tdo_voxel> clustered_cubes(Rng& rng, const VoxelMap& m, int clusters, double scatter) {
  std::vector<uint8_t> on(m.size(), 0u);
  for (int c = 0; c < clusters; ++c) {
    const int32_t x0 = rng.range(0, m.nx - 1), y0 = rng.range(0, m.ny - 1),
                  z0 = rng.range(0, m.nz - 1);
    const int32_t ex = rng.range(1, 9), ey = rng.range(1, 9), ez = rng.range(1, 9);
    const bool hollow = rng.below(2) == 0u;
    for (int32_t k = z0; k < std::min(m.nz, z0 + ez); ++k)
      for (int32_t j = y0; j < std::min(m.ny, y0 + ey); ++j)
        for (int32_t i = x0; i < std::min(m.nx, x0 + ex); ++i) {
          const bool face = i == x0 || j == y0 || k == z0 || i == x0 + ex - 1 || j == y0 + ey - 1 ||
                            k == z0 + ez - 1;
          if (!hollow || face) on[static_cast<size_t>(i + m.nx * (j + m.ny * k))] = 1u;
        }
  }
  for (size_t n = 0; n < m.size(); ++n)
    if (rng.uniform() < scatter) on[n] = 1u;
  std::vector<tdo_voxel> cubes;
  for (size_t n = 0; n < m.size(); ++n)
    if (on[n] != 0u) cubes.push_back(m.voxel(n));
  return cubes;
}

tdo_status load_cubes(tdo_grid* g, const VoxelMap& m, const std::vector<tdo_voxel>& cubes,
                      double clearance) {
  tdo_test::Obstacles obs;
  obs.cubes = cubes;
  return tdo_test::load_obstacles(g, m, obs, clearance);
}

double brute_point(const VoxelMap& m, const std::vector<tdo_voxel>& cubes, const tdo_vec3& p) {
  double best = tdo_test::kInf;
  for (const tdo_voxel& v : cubes)
    best = std::min(best, tdo_test::distance_to_box(p, tdo_test::cube_box(m, v)));
  return best;
}

/** Segment reference: the smallest point distance over a dense sampling, then refined by a
 *  ternary search around the best sample (the distance to a union is not convex, so the search
 *  runs on the nearest cube of that sample, whose distance along the segment is convex). */
double brute_segment(const VoxelMap& m, const std::vector<tdo_voxel>& cubes, const tdo_vec3& a,
                     const tdo_vec3& b) {
  const auto at = [&](double t) {
    return v3(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z));
  };
  double best = tdo_test::kInf;
  for (const tdo_voxel& v : cubes) {
    const tdo_box box = tdo_test::cube_box(m, v);
    const int n = 64;
    int bk = 0;
    double bd = tdo_test::kInf;
    for (int k = 0; k <= n; ++k) {
      const double d = tdo_test::distance_to_box(at(static_cast<double>(k) / n), box);
      if (d < bd) {
        bd = d;
        bk = k;
      }
    }
    double lo = std::max(0.0, (bk - 1.0) / n), hi = std::min(1.0, (bk + 1.0) / n);
    for (int it = 0; it < 120; ++it) {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      if (tdo_test::distance_to_box(at(m1), box) <= tdo_test::distance_to_box(at(m2), box))
        hi = m2;
      else
        lo = m1;
    }
    best = std::min({best, bd, tdo_test::distance_to_box(at(0.5 * (lo + hi)), box)});
  }
  return best;
}

class SurfaceIndexTest : public ::testing::Test {
 protected:
  SurfaceIndexTest() : pl_(tdo_test::make_cap(60000, 1000, 1000, 16, 60000)) {}
  tdo_grid* grid() { return pl_.grid(); }
  TestPlanner pl_;
};

TEST_F(SurfaceIndexTest,
       GivenClusteredCubes_WhenPointDistancesAreAsked_ThenTheyAreTheBruteForceMinimumOverAllCubes) {
  Rng rng(91);
  for (int map = 0; map < 12; ++map) {
    VoxelMap m(rng.range(12, 40), rng.range(12, 36), rng.range(12, 28), rng.uniform(0.08, 0.5),
               v3(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-1, 1)));
    const std::vector<tdo_voxel> cubes = clustered_cubes(rng, m, 6, map % 3 == 0 ? 0.0 : 0.004);
    if (cubes.empty()) continue;
    ASSERT_EQ(load_cubes(grid(), m, cubes, rng.uniform(0.0, 0.6)), TDO_OK);
    ASSERT_EQ(grid()->bricks_valid, 1) << "map " << map;
    for (int s = 0; s < 150; ++s) {
      tdo_vec3 p = v3(m.origin.x + rng.uniform(-0.5, m.nx * m.res + 0.5),
                      m.origin.y + rng.uniform(-0.5, m.ny * m.res + 0.5),
                      m.origin.z + rng.uniform(-0.5, m.nz * m.res + 0.5));
      const double ref = brute_point(m, cubes, p);
      for (double cap : {0.1, 1.0, 1e3}) {
        ASSERT_NEAR(tdo_collision_point_distance(grid(), p, cap), std::min(ref, cap), 1e-12)
            << "map " << map << " point " << s << " cap " << cap;
      }
    }
  }
}

TEST_F(SurfaceIndexTest,
       GivenClusteredCubes_WhenSegmentDistancesAndChecksAreAsked_ThenTheyMatchTheBruteForce) {
  Rng rng(92);
  for (int map = 0; map < 8; ++map) {
    VoxelMap m(rng.range(12, 32), rng.range(12, 28), rng.range(12, 20), rng.uniform(0.1, 0.4),
               v3(rng.uniform(-4, 4), rng.uniform(-4, 4), 0.0));
    const std::vector<tdo_voxel> cubes = clustered_cubes(rng, m, 5, 0.003);
    if (cubes.empty()) continue;
    ASSERT_EQ(load_cubes(grid(), m, cubes, 0.3), TDO_OK);
    for (int s = 0; s < 40; ++s) {
      const tdo_vec3 a = v3(m.origin.x + rng.uniform(0.0, m.nx * m.res),
                            m.origin.y + rng.uniform(0.0, m.ny * m.res),
                            m.origin.z + rng.uniform(0.0, m.nz * m.res));
      const double len = s % 2 == 0 ? 0.5 : 3.0;
      tdo_vec3 b = v3(a.x + rng.uniform(-len, len), a.y + rng.uniform(-len, len),
                      a.z + rng.uniform(-len, len));
      b.x = std::min(std::max(b.x, m.origin.x), m.origin.x + m.nx * m.res);
      b.y = std::min(std::max(b.y, m.origin.y), m.origin.y + m.ny * m.res);
      b.z = std::min(std::max(b.z, m.origin.z), m.origin.z + m.nz * m.res);
      const double ref = brute_segment(m, cubes, a, b);
      for (double cap : {0.2, 1e3}) {
        const double got = tdo_collision_segment_distance(grid(), a, b, cap);
        ASSERT_NEAR(got, std::min(ref, cap), 1e-9) << "map " << map << " segment " << s;
        ASSERT_LE(got, std::min(ref, cap) + 1e-12) << "map " << map << " segment " << s;
      }
      // The clearance check agrees with the reference away from the limit.
      for (double c : {0.0, 0.15, 0.6}) {
        if (std::fabs(ref - c) < 1e-9 || ref < 1e-9) continue;
        ASSERT_EQ(tdo_collision_segment_clear(grid(), a, b, c), ref > c ? 1 : 0)
            << "map " << map << " segment " << s << " clearance " << c;
      }
    }
  }
}

// In a hollow room whose distance field is no longer an upper bound (a map update cleared a
// cube), a point query searches up to its cap: more bricks lie within it than one query sorts
// (kMaxBrickCands), and the unsorted pass answers, exactly.
TEST_F(SurfaceIndexTest,
       GivenAHollowRoomAfterACubeIsCleared_WhenManyBricksAreNear_ThenStillTheExactDistance) {
  VoxelMap m(40, 40, 36, 0.1, v3(0.0, 0.0, 0.0));
  std::vector<tdo_voxel> cubes;
  for (size_t n = 0; n < m.size(); ++n) {
    const tdo_voxel v = m.voxel(n);
    if (v.i == 0 || v.j == 0 || v.k == 0 || v.i == m.nx - 1 || v.j == m.ny - 1 || v.k == m.nz - 1)
      cubes.push_back(v);
  }
  ASSERT_EQ(load_cubes(grid(), m, cubes, 0.0), TDO_OK);
  const tdo_voxel gone = cubes.back();  // a corner cube
  cubes.pop_back();
  tdo_grid_update u{};
  u.clear = &gone;
  u.n_clear = 1u;
  ASSERT_EQ(tdo_grid_apply_update(grid(), &u, nullptr), TDO_OK);
  ASSERT_EQ(grid()->df_valid, 0);
  const double p[3] = {2.0, 2.0, 1.8};
  tdo_internal::BrickCand cand[tdo_internal::kMaxBrickCands];
  ASSERT_GT(tdo_internal::surface_bricks_sorted(grid(), p, p, 1e3, 1e3, cand),
            tdo_internal::kMaxBrickCands);
  Rng rng(93);
  for (int s = 0; s < 50; ++s) {
    const tdo_vec3 q = v3(p[0] + rng.uniform(-1.5, 1.5), p[1] + rng.uniform(-1.5, 1.5),
                          p[2] + rng.uniform(-1.5, 1.5));
    ASSERT_NEAR(tdo_collision_point_distance(grid(), q, 1e3), brute_point(m, cubes, q), 1e-12);
  }
}

// A grid with an axis of a few voxels needs more bricks than the capacity holds for its voxels:
// it goes without the index, and the queries stay exact (the voxel scan answers).
TEST(SurfaceIndexThin, GivenAGridTooThinToIndex_WhenQueried_ThenNoIndexAndStillExact) {
  TestPlanner pl(tdo_test::make_cap(2000, 100, 100, 4, 2000));
  VoxelMap m(1, 2, 1000, 0.2, v3(0.0, 0.0, 0.0));
  Rng rng(94);
  std::vector<tdo_voxel> cubes;
  for (size_t n = 0; n < m.size(); ++n)
    if (rng.uniform() < 0.05) cubes.push_back(m.voxel(n));
  ASSERT_EQ(load_cubes(pl.grid(), m, cubes, 0.0), TDO_OK);
  EXPECT_EQ(pl.grid()->bricks_valid, 0);
  for (int s = 0; s < 100; ++s) {
    const tdo_vec3 p = v3(rng.uniform(0.0, 0.2), rng.uniform(0.0, 0.4), rng.uniform(0.0, 200.0));
    ASSERT_NEAR(tdo_collision_point_distance(pl.grid(), p, 1e3), brute_point(m, cubes, p), 1e-12);
  }
}

// Map updates set and clear cubes; the masks and tight boxes then equal those of a grid rebuilt
// from the same cubes.
TEST(SurfaceIndexUpdate, GivenCubesSetAndCleared_WhenUpdated_ThenTheIndexEqualsARebuild) {
  const tdo_capacity cap = tdo_test::make_cap(30000, 100, 100, 4, 30000);
  TestPlanner inc(cap), fresh(cap);
  VoxelMap m(30, 26, 20, 0.25, v3(-1.0, 2.0, 0.0));
  Rng rng(95);
  std::vector<tdo_voxel> cubes = clustered_cubes(rng, m, 5, 0.01);
  ASSERT_EQ(load_cubes(inc.grid(), m, cubes, 0.4), TDO_OK);
  std::vector<uint8_t> on(m.size(), 0u);
  for (const tdo_voxel& v : cubes) on[static_cast<size_t>(v.i + m.nx * (v.j + m.ny * v.k))] = 1u;
  for (int round = 0; round < 6; ++round) {
    std::vector<tdo_voxel> set, clear;
    for (int n = 0; n < 40; ++n) {
      const size_t idx = rng.below(static_cast<uint32_t>(m.size()));
      if (on[idx] == 2u || on[idx] == 3u) continue;  // one change per voxel and round
      if (on[idx] == 1u) {
        clear.push_back(m.voxel(idx));
        on[idx] = 2u;
      } else {
        set.push_back(m.voxel(idx));
        on[idx] = 3u;
      }
    }
    for (uint8_t& x : on) x = (x == 1u || x == 3u) ? 1u : 0u;
    tdo_grid_update u{};
    u.set = set.data();
    u.n_set = static_cast<uint32_t>(set.size());
    u.clear = clear.data();
    u.n_clear = static_cast<uint32_t>(clear.size());
    ASSERT_EQ(tdo_grid_apply_update(inc.grid(), &u, nullptr), TDO_OK);
    std::vector<tdo_voxel> now;
    for (size_t n = 0; n < m.size(); ++n)
      if (on[n] != 0u) now.push_back(m.voxel(n));
    ASSERT_EQ(load_cubes(fresh.grid(), m, now, 0.4), TDO_OK);
    const tdo_grid* a = inc.grid();
    const tdo_grid* b = fresh.grid();
    ASSERT_EQ(a->bricks_valid, 1);
    ASSERT_EQ(b->bricks_valid, 1);
    const uint32_t nb = static_cast<uint32_t>(b->nbx * b->nby * b->nbz);
    for (uint32_t k = 0; k < nb; ++k) {
      ASSERT_EQ(a->brick_mask[k], b->brick_mask[k]) << "round " << round << " brick " << k;
      ASSERT_EQ(a->brick_box[k], b->brick_box[k]) << "round " << round << " brick " << k;
    }
    for (int s = 0; s < 30; ++s) {
      const tdo_vec3 p = v3(m.origin.x + rng.uniform(0.0, m.nx * m.res),
                            m.origin.y + rng.uniform(0.0, m.ny * m.res),
                            m.origin.z + rng.uniform(0.0, m.nz * m.res));
      ASSERT_EQ(tdo_collision_point_distance(a, p, 1e3), tdo_collision_point_distance(b, p, 1e3));
    }
  }
}

TEST(SurfaceIndexMask, GivenLocalVoxelRanges_WhenMasked_ThenExactlyTheBitsInside) {
  // Ranges reaching past the brick on either side, empty ones, single voxels.
  for (int64_t lx = -2; lx <= 4; ++lx)
    for (int64_t hx = lx - 1; hx <= 5; ++hx)
      for (int64_t ly = -1; ly <= 3; ly += 2)
        for (int64_t hy = ly; hy <= 4; hy += 2)
          for (int64_t lz = -1; lz <= 4; lz += 3)
            for (int64_t hz = lz - 1; hz <= 4; hz += 2) {
              const int64_t lo[3] = {lx, ly, lz}, hi[3] = {hx, hy, hz};
              uint64_t want = 0u;
              for (uint32_t b = 0; b < 64u; ++b) {
                const int64_t v[3] = {b & 3u, (b >> 2) & 3u, b >> 4};
                bool in = true;
                for (int a = 0; a < 3; ++a) in = in && v[a] >= lo[a] && v[a] <= hi[a];
                if (in) want |= uint64_t{1} << b;
              }
              ASSERT_EQ(tdo_internal::brick_local_mask(lo, hi), want)
                  << lx << " " << hx << " " << ly << " " << hy << " " << lz << " " << hz;
            }
}

}  // namespace
