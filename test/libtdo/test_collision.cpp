// Exact continuous clearance queries (collision.h) against brute-force references written here:
// dense sampling plus a ternary search of the convex segment-to-box distance, and exact
// point-to-box distances. Seeded random maps of boxes (also reaching outside the grid) and cubes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "../../libtdo/src/collision_internal.h"  // segment_clear_hinted (correction stage)
#include "../../libtdo/src/grid_internal.h"       // the distance field, checked against brute force
#include "rng.h"
#include "tdo/collision.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;
using tdo_test::TestPlanner;
using tdo_test::VoxelMap;

tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }
tdo_vec3 lerp(const tdo_vec3& a, const tdo_vec3& b, double t) {
  return v3(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z));
}

/** Obstacle geometry of a test world as plain boxes (cubes included), for the references. */
struct World {
  VoxelMap m;
  std::vector<tdo_box> boxes;     // added with tdo_grid_add_box
  std::vector<tdo_voxel> cubes;   // added with tdo_grid_add_voxel
  std::vector<tdo_box> geometry;  // boxes + cube boxes

  double point_distance(const tdo_vec3& p) const {
    double best = tdo_test::kInf;
    for (const tdo_box& b : geometry) best = std::min(best, tdo_test::distance_to_box(p, b));
    return best;
  }
  bool inside(const tdo_vec3& p) const {
    return p.x >= m.origin.x && p.y >= m.origin.y && p.z >= m.origin.z &&
           p.x <= m.origin.x + m.nx * m.res && p.y <= m.origin.y + m.ny * m.res &&
           p.z <= m.origin.z + m.nz * m.res;
  }
};

/**
 * Reference minimum distance from [a, b] to one box: 4001 samples, then a ternary search of the
 * convex distance around the best sample (fine to ~1e-15 in the parameter).
 */
double brute_segment_box(const tdo_vec3& a, const tdo_vec3& b, const tdo_box& box) {
  const int n = 4000;
  int best_k = 0;
  double best = tdo_test::kInf;
  for (int k = 0; k <= n; ++k) {
    const double d = tdo_test::distance_to_box(lerp(a, b, static_cast<double>(k) / n), box);
    if (d < best) {
      best = d;
      best_k = k;
    }
  }
  double lo = std::max(0.0, (best_k - 1.0) / n), hi = std::min(1.0, (best_k + 1.0) / n);
  for (int it = 0; it < 200; ++it) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (tdo_test::distance_to_box(lerp(a, b, m1), box) <=
        tdo_test::distance_to_box(lerp(a, b, m2), box))
      hi = m2;
    else
      lo = m1;
  }
  return std::min(best, tdo_test::distance_to_box(lerp(a, b, 0.5 * (lo + hi)), box));
}

double brute_segment(const World& w, const tdo_vec3& a, const tdo_vec3& b) {
  double best = tdo_test::kInf;
  for (const tdo_box& box : w.geometry) {
    // Cheap skip of boxes that cannot beat the current best.
    const double lb =
        std::min(tdo_test::distance_to_box(a, box), tdo_test::distance_to_box(b, box)) -
        std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                  (b.z - a.z) * (b.z - a.z));
    if (lb >= best) continue;
    best = std::min(best, brute_segment_box(a, b, box));
  }
  return best;
}

/** Smallest exact point distance over `samples` + 1 evenly spaced points of [a, b]. */
double sampled_segment(const World& w, const tdo_vec3& a, const tdo_vec3& b, int samples) {
  double best = tdo_test::kInf;
  for (int k = 0; k <= samples; ++k)
    best = std::min(best, w.point_distance(lerp(a, b, static_cast<double>(k) / samples)));
  return best;
}

tdo_box random_box(Rng& rng, const VoxelMap& m, double max_edge) {
  const double ex = m.nx * m.res, ey = m.ny * m.res, ez = m.nz * m.res;
  // Corners up to 2 m outside the grid, so parts outside the bounds are covered too.
  const tdo_vec3 c =
      v3(m.origin.x + rng.uniform(-2.0, ex + 2.0), m.origin.y + rng.uniform(-2.0, ey + 2.0),
         m.origin.z + rng.uniform(-2.0, ez + 2.0));
  const tdo_vec3 h =
      v3(rng.uniform(0.02, max_edge), rng.uniform(0.02, max_edge), rng.uniform(0.02, max_edge));
  return tdo_box{v3(c.x - h.x, c.y - h.y, c.z - h.z), v3(c.x + h.x, c.y + h.y, c.z + h.z)};
}

tdo_vec3 random_point_in(Rng& rng, const VoxelMap& m) {
  return v3(m.origin.x + rng.uniform(0.0, m.nx * m.res),
            m.origin.y + rng.uniform(0.0, m.ny * m.res),
            m.origin.z + rng.uniform(0.0, m.nz * m.res));
}

/** A world with `n_boxes` random boxes and each voxel a cube with probability `cube_density`. */
World random_world(Rng& rng, int32_t nx, int32_t ny, int32_t nz, double res, int n_boxes,
                   double max_edge, double cube_density) {
  World w;
  w.m = VoxelMap(nx, ny, nz, res,
                 v3(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)));
  for (int b = 0; b < n_boxes; ++b) w.boxes.push_back(random_box(rng, w.m, max_edge));
  for (size_t n = 0; n < w.m.size(); ++n)
    if (rng.uniform() < cube_density) w.cubes.push_back(w.m.voxel(n));
  w.geometry = w.boxes;
  for (const tdo_voxel& v : w.cubes) w.geometry.push_back(tdo_test::cube_box(w.m, v));
  return w;
}

tdo_status load(tdo_grid* grid, const World& w, double clearance) {
  tdo_test::Obstacles obs;
  obs.boxes = w.boxes;
  obs.cubes = w.cubes;
  return tdo_test::load_obstacles(grid, w.m, obs, clearance);
}

/** Random segment: end points inside the grid, sometimes axis-parallel, short or degenerate. */
void random_segment(Rng& rng, const VoxelMap& m, tdo_vec3* a, tdo_vec3* b) {
  *a = random_point_in(rng, m);
  const uint32_t kind = rng.below(6);
  if (kind == 0) {
    *b = *a;               // a point
  } else if (kind == 1) {  // short
    *b = v3(a->x + rng.uniform(-0.6, 0.6), a->y + rng.uniform(-0.6, 0.6),
            a->z + rng.uniform(-0.6, 0.6));
  } else {
    *b = random_point_in(rng, m);
  }
  if (kind == 3) b->y = a->y;  // parallel to a coordinate plane
  if (kind == 4) {             // parallel to an axis
    b->y = a->y;
    b->z = a->z;
  }
  const double ex = m.origin.x + m.nx * m.res, ey = m.origin.y + m.ny * m.res,
               ez = m.origin.z + m.nz * m.res;
  b->x = std::min(std::max(b->x, m.origin.x), ex);
  b->y = std::min(std::max(b->y, m.origin.y), ey);
  b->z = std::min(std::max(b->z, m.origin.z), ez);
}

class CollisionTest : public ::testing::Test {
 protected:
  CollisionTest() : pl_(tdo_test::make_cap(20000, 1000, 1000, 256, 20000)) {}
  tdo_grid* grid() { return pl_.grid(); }
  TestPlanner pl_;
};

// ---------------------------------------------------------------------------------------------
// Exact distances.

TEST_F(CollisionTest,
       GivenOneRandomBox_WhenSegmentDistanceAsked_ThenItMatchesBruteForceAndNeverExceedsIt) {
  ASSERT_EQ(pl_.status(), TDO_OK);
  Rng rng(11);
  int compared = 0;
  for (int map = 0; map < 150; ++map) {
    World w;
    w.m = VoxelMap(16, 12, 10, 0.5, v3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)));
    w.boxes.push_back(random_box(rng, w.m, 2.5));
    w.geometry = w.boxes;
    ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
    for (int s = 0; s < 40; ++s) {
      tdo_vec3 a, b;
      random_segment(rng, w.m, &a, &b);
      if (s % 5 == 4) {  // also segments reaching outside the grid (exhaustive path)
        b = v3(b.x + rng.uniform(-4, 4), b.y + rng.uniform(-4, 4), b.z + rng.uniform(-4, 4));
      }
      const double ref = brute_segment_box(a, b, w.boxes[0]);
      const double got = tdo_collision_segment_distance(grid(), a, b, 1e3);
      ASSERT_NEAR(got, ref, 1e-9) << "map " << map << " segment " << s;
      ASSERT_LE(got, ref + 1e-12) << "map " << map << " segment " << s;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6000);
}

TEST_F(CollisionTest, GivenSegmentsTouchingOrCrossingABox_WhenDistanceAsked_ThenZero) {
  World w;
  w.m = VoxelMap(10, 10, 10, 1.0, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(3, 3, 3), v3(6, 5, 7)});
  ASSERT_EQ(load(grid(), w, 0.0), TDO_OK);
  // Through the box, along a face, ending on an edge, starting inside.
  EXPECT_EQ(tdo_collision_segment_distance(grid(), v3(1, 4, 4), v3(9, 4, 4), 10.0), 0.0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), v3(1, 3, 4), v3(9, 3, 4), 10.0), 0.0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), v3(1, 1, 1), v3(3, 3, 3), 10.0), 0.0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), v3(4, 4, 4), v3(4.5, 4.2, 4.1), 10.0), 0.0);
  EXPECT_EQ(tdo_collision_point_distance(grid(), v3(4, 4, 4), 10.0), 0.0);
  // Known answers: parallel to a face at 1 m, and diagonal past an edge.
  EXPECT_DOUBLE_EQ(tdo_collision_segment_distance(grid(), v3(1, 6, 4), v3(9, 6, 4), 10.0), 1.0);
  EXPECT_DOUBLE_EQ(tdo_collision_segment_distance(grid(), v3(7, 5, 0), v3(7, 5, 9), 10.0), 1.0);
  EXPECT_NEAR(tdo_collision_segment_distance(grid(), v3(7, 8, 1), v3(9, 6, 1), 10.0),
              std::sqrt(12.0), 1e-12);  // closest at (8, 7, 1): gaps 2, 2, 2
}

TEST_F(CollisionTest,
       GivenRandomBoxesAndCubes_WhenSegmentDistanceAsked_ThenItIsTheCappedBruteForceMinimum) {
  Rng rng(12);
  for (int map = 0; map < 25; ++map) {
    const World w =
        random_world(rng, 14, 12, 9, rng.uniform(0.3, 0.8), 12, 1.5, map % 3 == 0 ? 0.0 : 0.04);
    ASSERT_EQ(load(grid(), w, 0.5), TDO_OK) << "map " << map;
    for (int s = 0; s < 30; ++s) {
      tdo_vec3 a, b;
      random_segment(rng, w.m, &a, &b);
      const double ref = brute_segment(w, a, b);
      for (double cap : {0.3, 1.0, 3.0, 1e3}) {
        const double got = tdo_collision_segment_distance(grid(), a, b, cap);
        ASSERT_NEAR(got, std::min(ref, cap), 1e-9)
            << "map " << map << " segment " << s << " cap " << cap;
        ASSERT_LE(got, std::min(ref, cap) + 1e-12);
      }
    }
  }
}

TEST_F(CollisionTest, GivenRandomPoints_WhenPointDistanceAsked_ThenItIsTheCappedExactDistance) {
  Rng rng(13);
  for (int map = 0; map < 25; ++map) {
    const World w =
        random_world(rng, 12, 12, 8, rng.uniform(0.3, 1.0), 15, 2.0, map % 2 == 0 ? 0.05 : 0.0);
    ASSERT_EQ(load(grid(), w, rng.uniform(0.0, 1.0)), TDO_OK);
    for (int s = 0; s < 200; ++s) {
      tdo_vec3 p = random_point_in(rng, w.m);
      if (s % 4 == 0)
        p = v3(p.x + rng.uniform(-3, 3), p.y + rng.uniform(-3, 3), p.z);  // outside too
      const double ref = w.point_distance(p);
      for (double cap : {0.25, 2.0, 1e3}) {
        const double got = tdo_collision_point_distance(grid(), p, cap);
        ASSERT_NEAR(got, std::min(ref, cap), 1e-12) << "map " << map << " point " << s;
      }
    }
  }
}

// The distance field is the exact centre-to-centre distance to the nearest occupied voxel (m),
// rounded down: checked against a brute-force minimum over all occupied voxels.
TEST_F(CollisionTest, GivenRandomMaps_WhenFinished_ThenTheDistanceFieldIsExactAndNeverTooLarge) {
  Rng rng(14);
  size_t compared = 0;
  for (int map = 0; map < 40; ++map) {
    const int32_t nx = rng.range(1, 17), ny = rng.range(1, 13), nz = rng.range(1, 9);
    World w = random_world(rng, nx, ny, nz, rng.uniform(0.2, 1.5), rng.range(0, 4), 1.0,
                           rng.uniform(0.0, 0.08));
    ASSERT_EQ(load(grid(), w, 0.3), TDO_OK);
    const tdo_grid* g = grid();
    std::vector<tdo_voxel> occ;
    for (size_t n = 0; n < w.m.size(); ++n)
      if (tdo_grid_is_occupied(g, w.m.voxel(n))) occ.push_back(w.m.voxel(n));
    ASSERT_EQ(g->df_valid, 1);
    tdo_internal::df_ensure(g);  // the field is built on first use
    for (size_t n = 0; n < w.m.size(); ++n) {
      const tdo_voxel v = w.m.voxel(n);
      if (!occ.empty()) ++compared;
      double best = tdo_test::kInf;
      for (const tdo_voxel& o : occ) {
        const double dx = v.i - o.i, dy = v.j - o.j, dz = v.k - o.k;
        best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz) * w.m.res);
      }
      const double df = static_cast<double>(g->df[n]);
      if (std::isinf(best)) {
        ASSERT_TRUE(std::isinf(df)) << "map " << map << " voxel " << n;
        continue;
      }
      ASSERT_LE(df, best) << "map " << map << " voxel " << n;
      ASSERT_GE(df, best * (1.0 - 1e-6)) << "map " << map << " voxel " << n;
    }
  }
  EXPECT_GT(compared, 5000u);
}

// The distance field is not part of the load: tdo_grid_finish leaves it unbuilt, the first query
// that needs it builds it (the exact field, checked above), and the next finish unbuilds it.
TEST_F(CollisionTest, GivenAFinishedGrid_WhenTheFirstCubeQueryRuns_ThenItBuildsTheDistanceField) {
  Rng rng(15);
  World w = random_world(rng, 12, 12, 8, 0.5, 2, 1.5, 0.05);
  ASSERT_EQ(load(grid(), w, 0.3), TDO_OK);
  const tdo_grid* g = grid();
  ASSERT_GT(g->n_cubes, 0u);
  EXPECT_EQ(g->df_built, 0);
  const tdo_voxel mid{6, 6, 4};
  EXPECT_GE(tdo_collision_point_distance(g, tdo_grid_voxel_center(g, mid), 10.0), 0.0);
  EXPECT_EQ(g->df_built, 1);
  ASSERT_EQ(tdo_grid_finish(grid(), 0.3), TDO_OK);
  EXPECT_EQ(g->df_built, 0);
}

// An explicit bucket capacity (tdo_capacity::max_box_refs) too small for the map is a named
// status of tdo_grid_finish, never a silent truncation; 0 derives a capacity that always fits.
TEST(CollisionBuckets, GivenAnExplicitBoxRefCapacity_WhenTheMapNeedsMore_ThenBoxCapacityStatus) {
  for (uint32_t refs : {0u, 4u, 1000u}) {
    tdo_internal::GridCapacity cap{4096, 8, 64};
    cap.max_box_refs = refs;
    std::vector<unsigned char> mem(tdo_internal::grid_footprint(cap) + TDO_ARENA_ALIGN);
    tdo_arena arena;
    tdo_arena_init(&arena, mem.data(), mem.size());
    tdo_grid* g = nullptr;
    ASSERT_EQ(tdo_internal::grid_init(&g, &arena, cap), TDO_OK);
    EXPECT_LE(arena.used, mem.size());
    const tdo_grid_desc d{16, 16, 16, 1.0, v3(0, 0, 0)};
    ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
    for (int b = 0; b < 8; ++b) {  // 8 small boxes, each listed in 1 to 27 cells
      const tdo_box box{v3(1.0 + 1.9 * b, 2.0, 3.0), v3(1.5 + 1.9 * b, 2.5, 3.5)};
      ASSERT_EQ(tdo_grid_add_box(g, &box), TDO_OK);
    }
    const tdo_status st = tdo_grid_finish(g, 0.5);
    if (refs == 4u) {
      EXPECT_EQ(st, TDO_ERR_BOX_CAPACITY);
      EXPECT_LT(tdo_grid_clearance(g), 0.0) << "not plannable after a failed finish";
      EXPECT_EQ(tdo_collision_segment_clear(g, v3(1, 1, 1), v3(2, 2, 2), 0.5), 0);
    } else {
      EXPECT_EQ(st, TDO_OK) << "refs " << refs;
      EXPECT_EQ(tdo_collision_segment_clear(g, v3(0.5, 8, 8), v3(15.5, 8, 8), 0.5), 1);
      EXPECT_EQ(tdo_collision_segment_clear(g, v3(0.5, 2.2, 3.2), v3(15.5, 2.2, 3.2), 0.5), 0);
    }
  }
}

// An axis longer than the exact transform handles (32768 voxels): the field is all zeros (still a
// lower bound) and the queries stay exact, only slower.
TEST(CollisionLongAxis, GivenAGridBeyondTheDistanceFieldLimit_WhenQueried_ThenStillExact) {
  TestPlanner pl(tdo_test::make_cap(40000, 16, 16, 8, 64));
  ASSERT_EQ(pl.status(), TDO_OK);
  World w;
  w.m = VoxelMap(40000, 1, 1, 0.1, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(3000.0, -1.0, -1.0), v3(3000.02, 2.0, 2.0)});
  w.cubes.push_back(tdo_voxel{35000, 0, 0});
  w.geometry = w.boxes;
  w.geometry.push_back(tdo_test::cube_box(w.m, w.cubes[0]));
  ASSERT_EQ(load(pl.grid(), w, 0.0), TDO_OK);
  EXPECT_EQ(pl.grid()->df_valid, 0);
  const tdo_vec3 a = v3(3400.0, 0.05, 0.05);
  // The cube spans x in [3500.0, 3500.1].
  EXPECT_EQ(tdo_collision_segment_clear(pl.grid(), a, v3(3500.05, 0.05, 0.05), 0.0), 0);
  EXPECT_EQ(tdo_collision_segment_clear(pl.grid(), a, v3(3499.95, 0.05, 0.05), 0.04), 1);
  EXPECT_EQ(tdo_collision_segment_clear(pl.grid(), a, v3(3499.95, 0.05, 0.05), 0.06), 0);
  EXPECT_NEAR(tdo_collision_segment_distance(pl.grid(), a, v3(3499.95, 0.05, 0.05), 2.0), 0.05,
              1e-9);
  EXPECT_EQ(tdo_collision_segment_clear(pl.grid(), v3(2990, 0.05, 0.05), v3(3010, 0.05, 0.05), 0.0),
            0);
  EXPECT_NEAR(tdo_collision_point_distance(pl.grid(), v3(2999.5, 0.05, 0.05), 2.0), 0.5, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Clearance verdicts.

TEST_F(
    CollisionTest,
    GivenRandomMaps_WhenSegmentClearAsked_ThenNeverClearWhenAPointIsTooCloseAndClearWithAMargin) {
  Rng rng(21);
  int said_clear = 0, said_blocked = 0;
  for (int map = 0; map < 30; ++map) {
    const World w = random_world(rng, 16, 14, 8, rng.uniform(0.3, 0.8), rng.range(0, 25), 1.2,
                                 map % 3 == 0 ? 0.0 : 0.03);
    const double finish_c = rng.uniform(0.0, 0.8);
    ASSERT_EQ(load(grid(), w, finish_c), TDO_OK);
    for (int s = 0; s < 40; ++s) {
      tdo_vec3 a, b;
      random_segment(rng, w.m, &a, &b);
      const double sampled = sampled_segment(w, a, b, 1000);
      const double exact = brute_segment(w, a, b);
      for (double c : {0.0, 0.25, finish_c, 0.6, 1.5}) {
        const int got = tdo_collision_segment_clear(grid(), a, b, c);
        if (sampled < c || !(sampled > 0.0)) {
          ASSERT_EQ(got, 0) << "map " << map << " segment " << s << " c " << c << " sampled "
                            << sampled;
        }
        if (exact > c + 1e-6) {
          ASSERT_EQ(got, 1) << "map " << map << " segment " << s << " c " << c << " exact "
                            << exact;
        }
        (got ? said_clear : said_blocked)++;
      }
    }
  }
  EXPECT_GT(said_clear, 500);
  EXPECT_GT(said_blocked, 500);
}

TEST_F(CollisionTest, GivenAThinWallBetweenTwoSamplePoints_WhenSegmentClearAsked_ThenItIsDetected) {
  World w;
  w.m = VoxelMap(20, 20, 10, 1.0, v3(0, 0, 0));
  // 5 cm thick, far thinner than a voxel; a segment sampled every 0.5 m steps over it.
  w.boxes.push_back(tdo_box{v3(9.20, 0.0, 0.0), v3(9.25, 20.0, 10.0)});
  w.geometry = w.boxes;
  ASSERT_EQ(load(grid(), w, 0.0), TDO_OK);
  const tdo_vec3 a = v3(3.0, 5.0, 5.0), b = v3(15.0, 6.0, 5.0);
  bool sample_hits = false;  // samples every 0.5 m along x: none lands in the wall
  for (int k = 0; k <= 24; ++k) sample_hits |= w.point_distance(lerp(a, b, k / 24.0)) <= 0.0;
  ASSERT_FALSE(sample_hits);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.0), 0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.5), 0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), a, b, 5.0), 0.0);
  // Stopping short: 0.3 m before the wall's face.
  const tdo_vec3 c = v3(8.9, 5.5, 5.0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, c, 0.25), 1);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, c, 0.35), 0);
  EXPECT_NEAR(tdo_collision_segment_distance(grid(), a, c, 5.0), 0.3, 1e-12);
  // The same thin wall under a Bezier arc that sweeps over it.
  const tdo_vec3 bz[4] = {v3(8.0, 2.0, 5.0), v3(9.6, 2.0, 5.0), v3(9.6, 2.0, 5.0),
                          v3(9.6, 3.0, 5.0)};
  EXPECT_EQ(tdo_collision_bezier_clear(grid(), bz, 0.0, 0.01), 0);
}

TEST_F(CollisionTest, GivenABoxOutsideTheGrid_WhenSegmentsRunAlongTheBoundary_ThenItCounts) {
  World w;
  w.m = VoxelMap(10, 10, 10, 1.0, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(-3.0, 2.0, 2.0), v3(-0.2, 8.0, 8.0)});  // 0.2 m outside x = 0
  w.geometry = w.boxes;
  ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
  const tdo_vec3 a = v3(0.0, 1.0, 5.0), b = v3(0.0, 9.0, 5.0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.5), 0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.15), 1);
  EXPECT_NEAR(tdo_collision_segment_distance(grid(), a, b, 5.0), 0.2, 1e-12);
  EXPECT_NEAR(tdo_collision_point_distance(grid(), v3(0.0, 5.0, 5.0), 5.0), 0.2, 1e-12);
}

TEST_F(CollisionTest, GivenABoxCoveringTheWholeGrid_WhenQueried_ThenEverySegmentIsBlocked) {
  World w;
  w.m = VoxelMap(30, 30, 12, 0.5, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(-1, -1, -1), v3(20, 20, 0.3)});  // a floor larger than the map
  w.boxes.push_back(tdo_box{v3(2, 2, 2), v3(3, 3, 3)});
  w.geometry = w.boxes;
  ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(1, 1, 0.7), v3(14, 14, 0.7), 0.5), 0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(1, 1, 0.8), v3(14, 14, 0.8), 0.5), 1);
  EXPECT_NEAR(tdo_collision_segment_distance(grid(), v3(1, 1, 0.7), v3(14, 14, 0.9), 5.0), 0.4,
              1e-12);
}

TEST_F(CollisionTest, GivenSolidCubes_WhenASegmentLiesDeepInside_ThenItIsBlocked) {
  World w;
  w.m = VoxelMap(12, 12, 12, 0.5, v3(0, 0, 0));
  for (int32_t k = 2; k < 10; ++k)
    for (int32_t j = 2; j < 10; ++j)
      for (int32_t i = 2; i < 10; ++i) w.cubes.push_back(tdo_voxel{i, j, k});
  for (const tdo_voxel& v : w.cubes) w.geometry.push_back(tdo_test::cube_box(w.m, v));
  ASSERT_EQ(load(grid(), w, 0.2), TDO_OK);
  const tdo_vec3 a = v3(2.6, 2.6, 2.6), b = v3(3.4, 3.3, 2.9);  // inside buried cubes only
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.0), 0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), a, b, 5.0), 0.0);
  EXPECT_EQ(tdo_collision_point_distance(grid(), a, 5.0), 0.0);
  EXPECT_NEAR(tdo_collision_point_distance(grid(), v3(0.5, 3.0, 3.0), 5.0), 0.5, 1e-12);
}

TEST_F(CollisionTest, GivenSegmentsLeavingTheGrid_WhenSegmentClearAsked_ThenNotClear) {
  World w;
  w.m = VoxelMap(10, 10, 10, 1.0, v3(0, 0, 0));
  ASSERT_EQ(load(grid(), w, 0.0), TDO_OK);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(1, 1, 1), v3(9, 9, 9), 0.5), 1);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(0, 0, 0), v3(10, 10, 10), 0.5), 1)
      << "closed bounds";
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(1, 1, 1), v3(10.01, 9, 9), 0.5), 0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), v3(-0.01, 1, 1), v3(5, 5, 5), 0.5), 0);
  const tdo_vec3 bulge[4] = {v3(1, 5, 5), v3(1, 5, 13), v3(9, 5, 13), v3(9, 5, 5)};
  EXPECT_EQ(tdo_collision_bezier_clear(grid(), bulge, 0.0, 0.01), 0);
}

TEST_F(
    CollisionTest,
    GivenRandomBeziers_WhenBezierClearAsked_ThenNeverClearWhenASampleIsTooCloseAndClearWithAMargin) {
  Rng rng(31);
  int said_clear = 0, said_blocked = 0;
  const double tol = 0.01;
  for (int map = 0; map < 20; ++map) {
    const World w = random_world(rng, 16, 16, 8, 0.5, rng.range(3, 20), 1.0, map % 2 ? 0.02 : 0.0);
    ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
    for (int s = 0; s < 30; ++s) {
      tdo_vec3 c[4];
      c[0] = random_point_in(rng, w.m);
      for (int k = 1; k < 4; ++k) {
        c[k] = v3(c[0].x + rng.uniform(-3, 3), c[0].y + rng.uniform(-3, 3),
                  c[0].z + rng.uniform(-1, 1));
        c[k].x =
            std::min(std::max(c[k].x, w.m.origin.x + 0.01), w.m.origin.x + w.m.nx * w.m.res - 0.01);
        c[k].y =
            std::min(std::max(c[k].y, w.m.origin.y + 0.01), w.m.origin.y + w.m.ny * w.m.res - 0.01);
        c[k].z =
            std::min(std::max(c[k].z, w.m.origin.z + 0.01), w.m.origin.z + w.m.nz * w.m.res - 0.01);
      }
      // Dense samples of the curve; a point between samples is within half a step of one.
      const int n = 3000;
      double sampled = tdo_test::kInf, step = 0.0;
      tdo_vec3 prev = c[0];
      for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n, u = 1.0 - t;
        const double b0 = u * u * u, b1 = 3 * u * u * t, b2 = 3 * u * t * t, b3 = t * t * t;
        const tdo_vec3 p = v3(b0 * c[0].x + b1 * c[1].x + b2 * c[2].x + b3 * c[3].x,
                              b0 * c[0].y + b1 * c[1].y + b2 * c[2].y + b3 * c[3].y,
                              b0 * c[0].z + b1 * c[1].z + b2 * c[2].z + b3 * c[3].z);
        step = std::max(
            step, std::sqrt((p.x - prev.x) * (p.x - prev.x) + (p.y - prev.y) * (p.y - prev.y) +
                            (p.z - prev.z) * (p.z - prev.z)));
        prev = p;
        sampled = std::min(sampled, w.point_distance(p));
      }
      for (double clr : {0.0, 0.3, 0.5}) {
        const int got = tdo_collision_bezier_clear(grid(), c, clr, tol);
        if (sampled < clr || !(sampled > 0.0)) {
          ASSERT_EQ(got, 0) << "map " << map << " curve " << s << " c " << clr;
        }
        if (sampled - 0.5 * step > clr + tol + 1e-9) {
          ASSERT_EQ(got, 1) << "map " << map << " curve " << s << " c " << clr << " sampled "
                            << sampled;
        }
        (got ? said_clear : said_blocked)++;
      }
    }
  }
  EXPECT_GT(said_clear, 200);
  EXPECT_GT(said_blocked, 200);
}

TEST_F(CollisionTest, GivenBadArguments_WhenQueried_ThenNamedFailureValues) {
  const tdo_vec3 a = v3(1, 1, 1), b = v3(2, 2, 2);
  const tdo_vec3 c4[4] = {a, a, b, b};
  EXPECT_EQ(tdo_collision_point_distance(nullptr, a, 1.0), -1.0);
  EXPECT_EQ(tdo_collision_segment_distance(nullptr, a, b, 1.0), -1.0);
  EXPECT_EQ(tdo_collision_segment_clear(nullptr, a, b, 0.5), 0);
  EXPECT_EQ(tdo_collision_bezier_clear(nullptr, c4, 0.5, 0.01), 0);
  const tdo_grid_desc d{10, 10, 10, 1.0, v3(0, 0, 0)};
  ASSERT_EQ(tdo_grid_reset(grid(), &d), TDO_OK);  // not finished
  EXPECT_EQ(tdo_collision_point_distance(grid(), a, 1.0), -1.0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.5), 0);
  ASSERT_EQ(tdo_grid_finish(grid(), 0.5), TDO_OK);
  const double nan = std::nan("");
  EXPECT_EQ(tdo_collision_point_distance(grid(), v3(nan, 1, 1), 1.0), -1.0);
  EXPECT_EQ(tdo_collision_point_distance(grid(), a, -1.0), -1.0);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), a, v3(1, tdo_test::kInf, 1), 1.0), -1.0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, -0.1), 0);
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, nan), 0);
  EXPECT_EQ(tdo_collision_bezier_clear(grid(), nullptr, 0.5, 0.01), 0);
  EXPECT_EQ(tdo_collision_bezier_clear(grid(), c4, 0.5, nan), 0);
  // An empty map: everything inside is clear, distances are the cap.
  EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, 0.5), 1);
  EXPECT_EQ(tdo_collision_bezier_clear(grid(), c4, 0.5, 0.01), 1);
  EXPECT_EQ(tdo_collision_segment_distance(grid(), a, b, 3.0), 3.0);
}

TEST_F(CollisionTest, GivenTheSameQueries_WhenRepeated_ThenResultsAreBitIdentical) {
  Rng rng(41);
  const World w = random_world(rng, 16, 16, 8, 0.5, 20, 1.5, 0.02);
  ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
  std::vector<double> first;
  for (int pass = 0; pass < 2; ++pass) {
    Rng q(42);
    for (int s = 0; s < 200; ++s) {
      tdo_vec3 a, b;
      random_segment(q, w.m, &a, &b);
      const double d = tdo_collision_segment_distance(grid(), a, b, 2.0);
      if (pass == 0)
        first.push_back(d);
      else
        ASSERT_EQ(std::memcmp(&d, &first[s], sizeof d), 0) << "segment " << s;
    }
  }
}

// The correction stage's hinted query must answer exactly as the plain one: runs of queries that
// share an end point (as the shortcut sweeps make them), random segments, and segments placed at
// the clearance distance of a box give or take a few times the hint's rounding margin, for
// clearances inside and beyond the bucket reach, on box and box + cube maps.
TEST_F(CollisionTest, GivenRunsOfQueries_WhenAskedWithAHint_ThenSameAnswerAsWithout) {
  Rng rng(57);
  int compared = 0, failed = 0, hinted = 0, near = 0;
  for (int map = 0; map < 24; ++map) {
    const double cube_density = map % 3 == 2 ? 0.02 : 0.0;
    const World w = random_world(rng, 20, 16, 8, 0.5, 25, 1.5, cube_density);
    const double finish_clearance = 0.5;
    ASSERT_EQ(load(grid(), w, finish_clearance), TDO_OK);
    uint32_t hint = 0;
    for (int run = 0; run < 30; ++run) {
      // Clearance of this run: usually the finish clearance, sometimes beyond the bucket reach.
      const double c = run % 5 == 4 ? 2.5 : (run % 7 == 6 ? 0.0 : finish_clearance);
      const tdo_vec3 from = random_point_in(rng, w.m);
      tdo_vec3 s0, s1;
      random_segment(rng, w.m, &s0, &s1);
      for (int k = 0; k < 12; ++k) {
        tdo_vec3 to = lerp(s0, s1, 1.0 - k / 12.0);
        tdo_vec3 a = from;
        if (k % 4 == 3) random_segment(rng, w.m, &a, &to);
        if (k % 3 == 2 && !w.boxes.empty()) {
          // A segment through the middle of a box (it fails on that box, which becomes the
          // hint when the box lies in the grid), then one parallel to its +y face at distance
          // c +/- up to 3e-7 (so on both sides of the hint's margin).
          const tdo_box& bx = w.boxes[rng.below(static_cast<uint32_t>(w.boxes.size()))];
          const double y = bx.max.y + c + rng.uniform(-3e-7, 3e-7);
          const double z = 0.5 * (bx.min.z + bx.max.z), my = 0.5 * (bx.min.y + bx.max.y);
          const tdo_vec3 t0 = v3(bx.min.x - 0.3, my, z), t1 = v3(bx.max.x + 0.3, my, z);
          a = v3(bx.min.x - 0.3, y, z);
          to = v3(bx.max.x + 0.3, y, z);
          if (!w.inside(a) || !w.inside(to) || !w.inside(t0) || !w.inside(t1)) continue;
          const int through = tdo_collision_segment_clear(grid(), t0, t1, c);
          ASSERT_EQ(tdo_internal::segment_clear_hinted(grid(), t0, t1, c, &hint), through);
          ++near;
        }
        const uint32_t before = hint;
        const int plain = tdo_collision_segment_clear(grid(), a, to, c);
        const int got = tdo_internal::segment_clear_hinted(grid(), a, to, c, &hint);
        ASSERT_EQ(got, plain) << "map " << map << " run " << run << " query " << k;
        ++compared;
        if (!plain) ++failed;
        if (!plain && before != 0u && hint == before) ++hinted;
      }
    }
  }
  EXPECT_GT(compared, 6000);
  EXPECT_GT(failed, 1000);  // the hint path is exercised
  EXPECT_GT(hinted, 300);
  EXPECT_GT(near, 200);
}

TEST_F(CollisionTest,
       GivenAHintBox_WhenASegmentRunsAtTheClearanceDistance_ThenSameAnswerAsWithout) {
  World w;
  w.m = VoxelMap(12, 12, 12, 0.5, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(2.0, 2.0, 2.0), v3(3.5, 2.75, 4.0)});
  const double c = 0.5;
  ASSERT_EQ(load(grid(), w, c), TDO_OK);
  int clear = 0, blocked = 0;
  for (int k = -40; k <= 40; ++k) {
    uint32_t hint = 0;
    // Through the box: fails on box 0, which becomes the hint.
    ASSERT_EQ(
        tdo_internal::segment_clear_hinted(grid(), v3(1.0, 2.5, 3.0), v3(4.5, 2.5, 3.0), c, &hint),
        0);
    ASSERT_EQ(hint, 1u);
    // Along the +y face at distance c + k * 1e-8 (the hint's margin is 1e-7).
    const double y = 2.75 + c + k * 1e-8;
    const tdo_vec3 a = v3(1.0, y, 3.0), b = v3(4.5, y, 3.1);
    const int plain = tdo_collision_segment_clear(grid(), a, b, c);
    ASSERT_EQ(tdo_internal::segment_clear_hinted(grid(), a, b, c, &hint), plain) << "k " << k;
    plain ? ++clear : ++blocked;
  }
  EXPECT_EQ(clear, 41);  // k >= 0: not closer than c
  EXPECT_EQ(blocked, 40);
}

// The trajectory check's hinted point distance must give the plain query's value bit for bit:
// walks of small steps (as samples move) with jumps, along box faces and near corners between
// boxes, points on the bounds, several caps; box-only and box + cube maps (the latter always run
// the full query).
TEST_F(CollisionTest,
       GivenWalksOfPoints_WhenPointDistanceIsHinted_ThenBitIdenticalToThePlainQuery) {
  Rng rng(91);
  int compared = 0, reused = 0;
  for (int map = 0; map < 30; ++map) {
    const double cube_density = map % 5 == 4 ? 0.02 : 0.0;
    const World w = random_world(rng, 20, 16, 8, 0.5, 12 + map % 20, 1.2, cube_density);
    ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
    tdo_internal::PointHint hint;
    hint.valid = 0;
    tdo_vec3 p = random_point_in(rng, w.m);
    const double cap = map % 3 == 0 ? 1.5 : (map % 3 == 1 ? 0.4 : 10.0);
    for (int s = 0; s < 600; ++s) {
      if (s % 97 == 0) {
        p = random_point_in(rng, w.m);
      } else if (s % 131 == 0 && !w.boxes.empty()) {  // just off a box face
        const tdo_box& b = w.boxes[rng.below(static_cast<uint32_t>(w.boxes.size()))];
        p = v3(0.5 * (b.min.x + b.max.x), b.max.y + rng.uniform(0.0, 0.6),
               0.5 * (b.min.z + b.max.z));
      } else {
        const double step = s % 7 == 0 ? 0.2 : 0.03;
        p = v3(p.x + rng.uniform(-step, step), p.y + rng.uniform(-step, step),
               p.z + rng.uniform(-step, step));
      }
      if (s % 53 == 0) p.x = w.m.origin.x + w.m.nx * w.m.res;  // on the max face
      const double before_q = hint.valid ? hint.q[0] : 0.0;
      const int before_valid = hint.valid;
      const double plain = tdo_collision_point_distance(grid(), p, cap);
      const double got = tdo_internal::point_distance_hinted(grid(), p, cap, &hint);
      ASSERT_EQ(std::memcmp(&got, &plain, sizeof got), 0)
          << "map " << map << " step " << s << ": " << got << " vs " << plain;
      ++compared;
      // Answered from the hint: the fully evaluated point stayed, and it was not this one.
      const bool same_q = std::memcmp(&hint.q[0], &before_q, sizeof before_q) == 0;
      const bool here = std::memcmp(&p.x, &before_q, sizeof before_q) == 0;
      if (before_valid && hint.valid && same_q && !here) ++reused;
    }
  }
  EXPECT_EQ(compared, 30 * 600);
  EXPECT_GT(reused, 1000);  // the hint answers a good share of the queries
}

}  // namespace

// The box tests decide some boxes before the exact segment-to-box distance (the distance of the
// segment's bounding box, a point of the segment); those quick decisions must never change an
// answer. Segments tangent to the circle of radius r around a box edge keep exactly r from the
// box (touching it at one point, not at an end); r = c (1 +/- 1e-6 .. 1e-9): clear exactly when
// r >= c, and the distance query returns r.
TEST_F(CollisionTest, GivenSegmentsTangentNearABoxEdge_WhenQueried_ThenExactAtTheClearance) {
  World w;
  w.m = VoxelMap(16, 16, 16, 0.5, v3(0, 0, 0));
  w.boxes.push_back(tdo_box{v3(2.0, 2.5, 1.0), v3(3.5, 3.25, 6.0)});
  ASSERT_EQ(load(grid(), w, 0.5), TDO_OK);
  Rng rng(91);
  int clear = 0, blocked = 0;
  for (int q = 0; q < 400; ++q) {
    const double c = q % 4 == 3 ? 2.5 : rng.uniform(0.2, 0.9);  // inside and beyond the reach
    const double rel = std::pow(10.0, -static_cast<double>(6 + q % 4));
    const double r = c * (1.0 + (q % 2 == 0 ? rel : -rel));
    const double phi = rng.uniform(0.15, 1.4);  // around the +x +y edge, between its faces
    const double z = rng.uniform(1.5, 5.5);
    const double cx = 3.5 + r * std::cos(phi), cy = 3.25 + r * std::sin(phi);
    const tdo_vec3 u = v3(-std::sin(phi), std::cos(phi), 0.0);
    const double l0 = rng.uniform(0.2, 1.5), l1 = rng.uniform(0.2, 1.5), dz = rng.uniform(-1, 1);
    const tdo_vec3 a = v3(cx - l0 * u.x, cy - l0 * u.y, z - dz * 0.1);
    const tdo_vec3 b = v3(cx + l1 * u.x, cy + l1 * u.y, z + dz * 0.1);
    if (!w.inside(a) || !w.inside(b)) continue;
    const double ref = brute_segment_box(a, b, w.boxes[0]);
    ASSERT_NEAR(ref, r, 1e-12 * r) << "query " << q;  // the construction itself
    const int want = r >= c ? 1 : 0;
    ASSERT_EQ(tdo_collision_segment_clear(grid(), a, b, c), want) << "query " << q;
    uint32_t hint = 1;  // box 0 as the hint
    ASSERT_EQ(tdo_internal::segment_clear_hinted(grid(), a, b, c, &hint), want) << "query " << q;
    EXPECT_NEAR(tdo_collision_segment_distance(grid(), a, b, 2.0 * c + 1.0), r, 1e-12 * r);
    want ? ++clear : ++blocked;
  }
  EXPECT_GT(clear, 150);
  EXPECT_GT(blocked, 150);
}

// ---------------------------------------------------------------------------------------------
// The voxel-box bound of the cube walk (collision_internal.h, voxel_gap2_lower).

TEST(CollisionGapTable, GivenEverySquaredOffset_WhenTabulated_ThenItIsTheBruteForceSmallestGap) {
  // Brute force over signed offsets: a component of 25 or more alone gives a gap^2 of 576,
  // above the gap^2 225 of offset (16, 0, 0), which qualifies for every tabulated n.
  for (uint32_t n = 0; n <= tdo_internal::kGapTableMax; ++n) {
    uint32_t best = 0xFFFFFFFFu;
    for (int a = -25; a <= 25; ++a)
      for (int b = -25; b <= 25; ++b)
        for (int c = -25; c <= 25; ++c) {
          if (static_cast<uint32_t>(a * a + b * b + c * c) < n) continue;
          const auto gap = [](int x) { return std::max(std::abs(x) - 1, 0); };
          const uint32_t e =
              static_cast<uint32_t>(gap(a) * gap(a) + gap(b) * gap(b) + gap(c) * gap(c));
          best = std::min(best, e);
        }
    ASSERT_EQ(tdo_internal::voxel_gap2_lower(n), best) << "n " << n;
  }
  EXPECT_EQ(tdo_internal::voxel_gap2_lower(3), 0u);  // a 26-neighbour touches
  EXPECT_EQ(tdo_internal::voxel_gap2_lower(4), 1u);  // (2, 0, 0): one voxel between
  EXPECT_EQ(tdo_internal::voxel_gap2_lower(tdo_internal::kGapTableMax + 1), 0xFFFFFFFFu);
}

TEST_F(CollisionTest,
       GivenSparseCubes_WhenSegmentsPassNearThem_ThenClearAndDistanceMatchTheBruteForce) {
  // Few cubes, so most voxels lie far from every cube and the voxel-box bound decides there;
  // segments end at random points, at cube faces, edges and corners, or graze a face at an
  // offset around the clearance (also 0: touching is never clear).
  Rng rng(77);
  int said_clear = 0, said_blocked = 0;
  for (int map = 0; map < 20; ++map) {
    const double res = rng.uniform(0.2, 1.0);
    const World w = random_world(rng, 18, 16, 12, res, 0, 1.0, 0.004);
    if (w.cubes.empty()) continue;
    ASSERT_EQ(load(grid(), w, 0.0), TDO_OK);
    for (int s = 0; s < 60; ++s) {
      const double c = s % 3 == 0 ? 0.0 : rng.uniform(0.0, 3.0 * res);
      tdo_vec3 a, b;
      random_segment(rng, w.m, &a, &b);
      if (s % 2 == 1) {
        // Graze a cube: both ends on a plane parallel to one of its faces, at offset c + eps.
        const tdo_box cube =
            tdo_test::cube_box(w.m, w.cubes[rng.below(static_cast<uint32_t>(w.cubes.size()))]);
        const double eps = (rng.below(3) == 0 ? 0.0 : 1.0) * rng.uniform(-1e-6, 1e-6);
        const double z = cube.max.z + c + eps;
        a.z = z;
        b.z = z;
        a.x = cube.min.x + rng.uniform(-3.0, 3.0) * res;
        b.x = cube.min.x + rng.uniform(-3.0, 3.0) * res;
        a.y = cube.min.y + (rng.below(2) == 0 ? 0.0 : rng.uniform(-3.0, 3.0) * res);
        b.y = rng.below(2) == 0 ? a.y : cube.max.y + rng.uniform(-3.0, 3.0) * res;
        if (!w.inside(a) || !w.inside(b)) continue;
      }
      const double exact = brute_segment(w, a, b);
      const int got = tdo_collision_segment_clear(grid(), a, b, c);
      if (exact < c - 1e-9 || !(exact > 1e-12)) {
        ASSERT_EQ(got, 0) << "map " << map << " segment " << s << " c " << c << " exact " << exact;
      }
      if (exact > c + 1e-9) {
        ASSERT_EQ(got, 1) << "map " << map << " segment " << s << " c " << c << " exact " << exact;
      }
      (got ? said_clear : said_blocked)++;
      for (double cap : {0.5 * res, 10.0 * res, 1e3}) {
        const double d = tdo_collision_segment_distance(grid(), a, b, cap);
        ASSERT_NEAR(d, std::min(exact, cap), 1e-9) << "map " << map << " segment " << s;
        ASSERT_LE(d, std::min(exact, cap) + 1e-12);
      }
    }
  }
  EXPECT_GT(said_clear, 100);
  EXPECT_GT(said_blocked, 100);
}

TEST_F(CollisionTest,
       GivenALongSegmentAlongAWallOfCubes_WhenDistanceAsked_ThenItIsTheWallDistanceAtEveryCap) {
  // Every piece of a segment parallel to a wall is about equally near it, so the best-first
  // walk of the cube minimum keeps many pieces waiting (more than its heap holds: the
  // depth-first fallback runs too); the answer must still be the exact minimum.
  Rng rng(5);
  for (int trial = 0; trial < 12; ++trial) {
    World w;
    const double res = rng.uniform(0.1, 0.6);
    w.m = VoxelMap(120, 9, 6, res, v3(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), 0.0));
    for (int32_t i = 0; i < w.m.nx; ++i)
      for (int32_t k = 0; k < w.m.nz; ++k)
        if (trial % 3 != 0 || rng.uniform() < 0.9) w.cubes.push_back(tdo_voxel{i, 0, k});
    w.geometry.clear();
    for (const tdo_voxel& v : w.cubes) w.geometry.push_back(tdo_test::cube_box(w.m, v));
    ASSERT_EQ(load(grid(), w, 0.0), TDO_OK);
    const double y = w.m.origin.y + res * rng.uniform(1.2, 8.0);
    const double z = w.m.origin.z + res * rng.uniform(0.5, 5.5);
    const tdo_vec3 a = v3(w.m.origin.x + res * rng.uniform(0.0, 3.0), y, z);
    const tdo_vec3 b = v3(w.m.origin.x + res * rng.uniform(117.0, 120.0),
                          y + res * rng.uniform(-0.1, 0.1), z + res * rng.uniform(-0.3, 0.3));
    const double exact = brute_segment(w, a, b);
    for (double cap : {0.5 * exact, exact, 2.0 * exact, 1e3}) {
      const double d = tdo_collision_segment_distance(grid(), a, b, cap);
      ASSERT_NEAR(d, std::min(exact, cap), 1e-9) << "trial " << trial << " cap " << cap;
      ASSERT_LE(d, std::min(exact, cap) + 1e-12);
    }
    EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, exact - 1e-6), 1) << "trial " << trial;
    EXPECT_EQ(tdo_collision_segment_clear(grid(), a, b, exact + 1e-6), 0) << "trial " << trial;
  }
}
