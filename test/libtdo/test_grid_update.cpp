// Map updates (grid_update.h): a grid updated incrementally must equal a grid rebuilt from scratch
// with the same obstacles (blocked voxels, legal steps, collision answers), for cubes set, cubes
// cleared and boxes added, at clearance 0 and > 0; the work (voxel visits) must depend on the
// update, not on the map; bad updates are refused by name and change nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "../../libtdo/src/grid_internal.h"  // legal steps per voxel, compared with the rebuild
#include "rng.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;
using tdo_test::TestPlanner;

tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }

/** The obstacles of a test world, as the rebuild gets them. */
struct Obstacles {
  std::vector<tdo_box> boxes;
  std::set<std::tuple<int32_t, int32_t, int32_t>> cubes;
};

constexpr uint32_t kVoxels = 40000;

tdo_capacity cap_for(uint32_t voxels = kVoxels) {
  return tdo_test::make_cap(voxels, 16, 16, 256, 20000);
}

tdo_grid_desc desc_of(int32_t n, double res) {
  tdo_grid_desc d{};
  d.nx = n;
  d.ny = n;
  d.nz = n / 2;
  d.res = res;
  d.origin = v3(-1.0, 2.0, 0.5);
  return d;
}

void build(tdo_grid* g, const tdo_grid_desc& d, const Obstacles& o, double clearance) {
  ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
  for (const tdo_box& b : o.boxes) ASSERT_EQ(tdo_grid_add_box(g, &b), TDO_OK);
  for (const auto& c : o.cubes)
    ASSERT_EQ(tdo_grid_add_voxel(g, std::get<0>(c), std::get<1>(c), std::get<2>(c)), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(g, clearance), TDO_OK);
  // The legal steps now (computed on first use otherwise), so that an update keeps them current
  // and expect_same_grid compares them; the distance field stays for the update to build.
  tdo_internal::moves_ensure(g);
}

tdo_box random_box(Rng* rng, const tdo_grid_desc& d, double max_edge) {
  const double ex = d.nx * d.res, ey = d.ny * d.res, ez = d.nz * d.res;
  tdo_box b{};
  // Corners anywhere from a little outside the bounds, so some boxes reach out of the grid.
  b.min = v3(d.origin.x + rng->uniform(-0.1, 1.0) * ex, d.origin.y + rng->uniform(-0.1, 1.0) * ey,
             d.origin.z + rng->uniform(-0.1, 1.0) * ez);
  b.max = v3(b.min.x + rng->uniform(0.05, max_edge), b.min.y + rng->uniform(0.05, max_edge),
             b.min.z + rng->uniform(0.05, max_edge));
  return b;
}

tdo_voxel random_voxel(Rng* rng, const tdo_grid_desc& d) {
  return tdo_voxel{rng->range(0, d.nx - 1), rng->range(0, d.ny - 1), rng->range(0, d.nz - 1)};
}

// A cluster of cubes (so some are buried and surfaces change) around a random voxel.
void add_cluster(Rng* rng, const tdo_grid_desc& d, std::vector<tdo_voxel>* out) {
  const tdo_voxel c = random_voxel(rng, d);
  const int32_t r = rng->range(0, 2);
  for (int32_t k = c.k - r; k <= c.k + r; ++k)
    for (int32_t j = c.j - r; j <= c.j + r; ++j)
      for (int32_t i = c.i - r; i <= c.i + r; ++i)
        if (i >= 0 && j >= 0 && k >= 0 && i < d.nx && j < d.ny && k < d.nz)
          out->push_back(tdo_voxel{i, j, k});
}

/** Every observable of the two grids must agree. */
void expect_same_grid(const tdo_grid* inc, const tdo_grid* ref, double clearance, Rng* rng) {
  const tdo_grid_desc d = tdo_grid_get_desc(ref);
  ASSERT_EQ(tdo_grid_blocked_count(inc), tdo_grid_blocked_count(ref));
  int diff_blocked = 0, diff_occ = 0, diff_moves = 0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i) {
        const tdo_voxel v{i, j, k};
        diff_blocked += tdo_grid_is_blocked(inc, v) != tdo_grid_is_blocked(ref, v);
        diff_occ += tdo_grid_is_occupied(inc, v) != tdo_grid_is_occupied(ref, v);
        const int64_t idx =
            i + j * static_cast<int64_t>(d.nx) + k * static_cast<int64_t>(d.nx) * d.ny;
        diff_moves += inc->moves[idx] != ref->moves[idx];
      }
  EXPECT_EQ(diff_blocked, 0) << "voxels whose blocked bit differs from the rebuild";
  EXPECT_EQ(diff_occ, 0) << "voxels whose occupancy differs from the rebuild";
  EXPECT_EQ(diff_moves, 0) << "voxels whose legal steps differ from the rebuild";
  // Collision queries: points and segments anywhere in and around the bounds.
  const double ex = d.nx * d.res, ey = d.ny * d.res, ez = d.nz * d.res;
  auto point = [&]() {
    return v3(d.origin.x + rng->uniform(-0.05, 1.05) * ex,
              d.origin.y + rng->uniform(-0.05, 1.05) * ey,
              d.origin.z + rng->uniform(-0.05, 1.05) * ez);
  };
  int diff_clear = 0;
  for (int q = 0; q < 400; ++q) {
    const tdo_vec3 a = point();
    tdo_vec3 b = point();
    if (q % 2 == 0)
      b = v3(a.x + rng->uniform(-1, 1), a.y + rng->uniform(-1, 1), a.z + rng->uniform(-1, 1));
    const double cap = rng->uniform(0.1, 3.0);
    ASSERT_NEAR(tdo_collision_point_distance(inc, a, cap),
                tdo_collision_point_distance(ref, a, cap), 1e-12);
    ASSERT_NEAR(tdo_collision_segment_distance(inc, a, b, cap),
                tdo_collision_segment_distance(ref, a, b, cap), 1e-9);
    diff_clear += tdo_collision_segment_clear(inc, a, b, clearance) !=
                  tdo_collision_segment_clear(ref, a, b, clearance);
  }
  EXPECT_EQ(diff_clear, 0) << "segment_clear answers that differ from the rebuild";
}

struct Case {
  int32_t n;
  double res;
  double clearance;
};

class GridUpdateEquivalence : public ::testing::TestWithParam<Case> {
 protected:
  GridUpdateEquivalence() : inc_(cap_for()), ref_(cap_for()) {}
  TestPlanner inc_, ref_;
};

// A random base world: boxes plus cube clusters.
Obstacles base_world(Rng* rng, const tdo_grid_desc& d) {
  Obstacles o;
  for (int b = 0; b < 6; ++b) o.boxes.push_back(random_box(rng, d, 1.5));
  std::vector<tdo_voxel> cl;
  for (int c = 0; c < 5; ++c) add_cluster(rng, d, &cl);
  for (const tdo_voxel& v : cl) o.cubes.insert({v.i, v.j, v.k});
  return o;
}

TEST_P(GridUpdateEquivalence, GivenAFinishedGrid_WhenCubesAreSet_ThenItEqualsTheRebuild) {
  const Case c = GetParam();
  const tdo_grid_desc d = desc_of(c.n, c.res);
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed * 101 + static_cast<uint64_t>(c.n));
    Obstacles o = base_world(&rng, d);
    build(inc_.grid(), d, o, c.clearance);
    std::vector<tdo_voxel> set;
    for (int k = 0; k < 3; ++k) add_cluster(&rng, d, &set);
    for (int k = 0; k < 10; ++k) set.push_back(random_voxel(&rng, d));
    tdo_grid_update u{};
    u.set = set.data();
    u.n_set = static_cast<uint32_t>(set.size());
    tdo_grid_update_result r{};
    ASSERT_EQ(tdo_grid_apply_update(inc_.grid(), &u, &r), TDO_OK);
    EXPECT_GT(r.cubes_set, 0u);
    EXPECT_LE(r.cells_touched, tdo_grid_update_work(inc_.grid(), &u));
    for (const tdo_voxel& v : set) o.cubes.insert({v.i, v.j, v.k});
    build(ref_.grid(), d, o, c.clearance);
    expect_same_grid(inc_.grid(), ref_.grid(), c.clearance, &rng);
  }
}

TEST_P(GridUpdateEquivalence, GivenAFinishedGrid_WhenCubesAreCleared_ThenItEqualsTheRebuild) {
  const Case c = GetParam();
  const tdo_grid_desc d = desc_of(c.n, c.res);
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed * 211 + static_cast<uint64_t>(c.n));
    Obstacles o = base_world(&rng, d);
    // Some cubes inside boxes: clearing them leaves the box's occupancy.
    for (size_t k = 0; k < o.boxes.size(); ++k) {
      const tdo_box& b = o.boxes[k];
      const int32_t i =
          static_cast<int32_t>(std::floor((0.5 * (b.min.x + b.max.x) - d.origin.x) / d.res));
      const int32_t j =
          static_cast<int32_t>(std::floor((0.5 * (b.min.y + b.max.y) - d.origin.y) / d.res));
      const int32_t kk =
          static_cast<int32_t>(std::floor((0.5 * (b.min.z + b.max.z) - d.origin.z) / d.res));
      if (i >= 0 && j >= 0 && kk >= 0 && i < d.nx && j < d.ny && kk < d.nz)
        o.cubes.insert({i, j, kk});
    }
    build(inc_.grid(), d, o, c.clearance);
    std::vector<tdo_voxel> clear;
    for (const auto& cube : o.cubes)
      if (rng.below(2) == 0)
        clear.push_back(tdo_voxel{std::get<0>(cube), std::get<1>(cube), std::get<2>(cube)});
    clear.push_back(random_voxel(&rng, d));  // most likely no cube: nothing to do
    tdo_grid_update u{};
    u.clear = clear.data();
    u.n_clear = static_cast<uint32_t>(clear.size());
    tdo_grid_update_result r{};
    ASSERT_EQ(tdo_grid_apply_update(inc_.grid(), &u, &r), TDO_OK);
    EXPECT_GT(r.cubes_cleared, 0u);
    EXPECT_LE(r.cells_touched, tdo_grid_update_work(inc_.grid(), &u));
    for (const tdo_voxel& v : clear) o.cubes.erase({v.i, v.j, v.k});
    build(ref_.grid(), d, o, c.clearance);
    expect_same_grid(inc_.grid(), ref_.grid(), c.clearance, &rng);
  }
}

TEST_P(GridUpdateEquivalence, GivenAFinishedGrid_WhenBoxesAreAdded_ThenItEqualsTheRebuild) {
  const Case c = GetParam();
  const tdo_grid_desc d = desc_of(c.n, c.res);
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed * 307 + static_cast<uint64_t>(c.n));
    Obstacles o = base_world(&rng, d);
    build(inc_.grid(), d, o, c.clearance);
    std::vector<tdo_box> boxes;
    for (int k = 0; k < 4; ++k) boxes.push_back(random_box(&rng, d, 3.0));
    tdo_grid_update u{};
    u.boxes = boxes.data();
    u.n_boxes = static_cast<uint32_t>(boxes.size());
    tdo_grid_update_result r{};
    ASSERT_EQ(tdo_grid_apply_update(inc_.grid(), &u, &r), TDO_OK);
    EXPECT_EQ(r.boxes_added, 4u);
    EXPECT_LE(r.cells_touched, tdo_grid_update_work(inc_.grid(), &u));
    for (const tdo_box& b : boxes) o.boxes.push_back(b);
    build(ref_.grid(), d, o, c.clearance);
    expect_same_grid(inc_.grid(), ref_.grid(), c.clearance, &rng);
  }
}

TEST_P(GridUpdateEquivalence, GivenASequenceOfMixedUpdates_WhenApplied_ThenItEqualsTheRebuild) {
  const Case c = GetParam();
  const tdo_grid_desc d = desc_of(c.n, c.res);
  Rng rng(977 + static_cast<uint64_t>(c.n));
  Obstacles o = base_world(&rng, d);
  build(inc_.grid(), d, o, c.clearance);
  for (int step = 0; step < 8; ++step) {
    std::vector<tdo_voxel> set, clear;
    std::vector<tdo_box> boxes;
    add_cluster(&rng, d, &set);
    std::set<std::tuple<int32_t, int32_t, int32_t>> in_set;
    for (const tdo_voxel& v : set) in_set.insert({v.i, v.j, v.k});
    for (const auto& cube : o.cubes)
      if (rng.below(3) == 0 && in_set.count(cube) == 0)
        clear.push_back(tdo_voxel{std::get<0>(cube), std::get<1>(cube), std::get<2>(cube)});
    if (step % 3 == 0) boxes.push_back(random_box(&rng, d, 2.0));
    tdo_grid_update u{set.data(),
                      static_cast<uint32_t>(set.size()),
                      clear.data(),
                      static_cast<uint32_t>(clear.size()),
                      boxes.data(),
                      static_cast<uint32_t>(boxes.size()),
                      0};
    ASSERT_EQ(tdo_grid_apply_update(inc_.grid(), &u, nullptr), TDO_OK) << "step " << step;
    for (const tdo_voxel& v : clear) o.cubes.erase({v.i, v.j, v.k});
    for (const tdo_voxel& v : set) o.cubes.insert({v.i, v.j, v.k});
    for (const tdo_box& b : boxes) o.boxes.push_back(b);
    build(ref_.grid(), d, o, c.clearance);
    SCOPED_TRACE("step " + std::to_string(step));
    expect_same_grid(inc_.grid(), ref_.grid(), c.clearance, &rng);
  }
}

INSTANTIATE_TEST_SUITE_P(Clearances, GridUpdateEquivalence,
                         ::testing::Values(Case{24, 0.25, 0.0}, Case{24, 0.25, 0.3},
                                           Case{24, 0.25, 0.6}, Case{20, 0.5, 0.5},
                                           Case{20, 1.0, 0.0}, Case{20, 1.0, 0.3}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           return "n" + std::to_string(i.param.n) + "_res" +
                                  std::to_string(static_cast<int>(i.param.res * 100)) + "cm_c" +
                                  std::to_string(static_cast<int>(i.param.clearance * 100)) + "cm";
                         });

// ---- work proportional to the update

// The same obstacles and update near the origin corner of a small and a large grid.
uint64_t cells_for(int32_t n, const tdo_grid_update& u) {
  TestPlanner pl(cap_for(200000));
  tdo_grid_desc d = desc_of(n, 0.25);
  d.nz = 20;
  Obstacles o;
  o.boxes.push_back(tdo_box{v3(0.0, 3.0, 1.0), v3(0.5, 3.5, 2.0)});
  o.cubes.insert({3, 3, 3});
  build(pl.grid(), d, o, 0.5);
  tdo_grid_update_result r{};
  EXPECT_EQ(tdo_grid_apply_update(pl.grid(), &u, &r), TDO_OK);
  EXPECT_LE(r.cells_touched, tdo_grid_update_work(pl.grid(), &u));
  return r.cells_touched;
}

TEST(GridUpdateWork, GivenTheSameUpdate_WhenTheMapIsLarger_ThenTheWorkIsTheSame) {
  const tdo_voxel set[2] = {{5, 5, 5}, {6, 5, 5}};
  const tdo_voxel clear[1] = {{3, 3, 3}};
  const tdo_box box{v3(1.0, 4.0, 1.0), v3(1.3, 5.0, 2.5)};
  const tdo_grid_update u{set, 2, clear, 1, &box, 1, 0};
  const uint64_t small = cells_for(24, u);  // 24 x 24 x 20 voxels
  const uint64_t large = cells_for(96, u);  // 96 x 96 x 20: 16 times the voxels
  EXPECT_GT(small, 0u);
  EXPECT_EQ(small, large) << "the work of an update must not depend on the map's size";
}

TEST(GridUpdateWork, GivenMoreVoxels_WhenSet_ThenTheWorkGrowsWithTheUpdate) {
  // Isolated voxels far apart: each costs the same, so ten cost ten times one.
  std::vector<tdo_voxel> one{{10, 10, 10}}, ten;
  for (int32_t k = 0; k < 10; ++k) ten.push_back(tdo_voxel{10 + 7 * (k % 5), 10 + 7 * (k / 5), 10});
  const uint64_t w1 = cells_for(96, tdo_grid_update{one.data(), 1, nullptr, 0, nullptr, 0, 0});
  const uint64_t w10 = cells_for(96, tdo_grid_update{ten.data(), 10, nullptr, 0, nullptr, 0, 0});
  EXPECT_EQ(w10, 10 * w1);
  // A rebuild (tdo_grid_finish and the legal steps its first search computes) visits every voxel
  // of the map at least 28 times (the steps alone); one set voxel visits fewer than the map has.
  EXPECT_LT(w1, 96u * 96u * 20u);
}

// ---- bad updates: a named status, the grid unchanged

class GridUpdateRefused : public ::testing::Test {
 protected:
  GridUpdateRefused() : pl_(tdo_test::make_cap(4000, 16, 16, 3, 2000)) {
    d_ = desc_of(16, 0.25);
    Obstacles o;
    o.boxes.push_back(tdo_box{v3(0.0, 3.0, 1.0), v3(0.5, 3.5, 2.0)});
    o.cubes.insert({3, 3, 3});
    build(pl_.grid(), d_, o, 0.3);
    blocked_ = tdo_grid_blocked_count(pl_.grid());
  }
  void expect_refused(const tdo_grid_update& u, tdo_status want) {
    tdo_grid_update_result r{};
    EXPECT_EQ(tdo_grid_apply_update(pl_.grid(), &u, &r), want) << tdo_status_str(want);
    EXPECT_EQ(tdo_grid_blocked_count(pl_.grid()), blocked_);
    EXPECT_EQ(r.cells_touched, 0u);
    EXPECT_EQ(tdo_grid_is_occupied(pl_.grid(), tdo_voxel{10, 10, 6}), 0);
  }
  TestPlanner pl_;
  tdo_grid_desc d_{};
  uint32_t blocked_ = 0;
};

TEST_F(GridUpdateRefused, GivenOneVoxelSetAndCleared_WhenApplied_ThenContradictory) {
  const tdo_voxel set[2] = {{10, 10, 6}, {6, 6, 6}};
  const tdo_voxel clear[2] = {{3, 3, 3}, {6, 6, 6}};
  expect_refused(tdo_grid_update{set, 2, clear, 2, nullptr, 0, 0}, TDO_ERR_UPDATE_CONTRADICTORY);
  EXPECT_EQ(tdo_grid_is_occupied(pl_.grid(), tdo_voxel{3, 3, 3}), 1);
  // The scratch mark is gone: the same voxels apart are fine.
  const tdo_grid_update only_set{set, 2, nullptr, 0, nullptr, 0, 0};
  EXPECT_EQ(tdo_grid_apply_update(pl_.grid(), &only_set, nullptr), TDO_OK);
  EXPECT_EQ(pl_.grid()->flags[6 + 6 * 16 + 6 * 256] & tdo_internal::kFlagMark, 0);
}

TEST_F(GridUpdateRefused, GivenBadVoxelsOrBoxes_WhenApplied_ThenNamedStatuses) {
  const tdo_voxel in[1] = {{10, 10, 6}};
  const tdo_voxel out[2] = {{10, 10, 6}, {16, 0, 0}};
  expect_refused(tdo_grid_update{out, 2, nullptr, 0, nullptr, 0, 0}, TDO_ERR_INVALID_ARGUMENT);
  expect_refused(tdo_grid_update{in, 1, out + 1, 1, nullptr, 0, 0}, TDO_ERR_INVALID_ARGUMENT);
  expect_refused(tdo_grid_update{nullptr, 3, nullptr, 0, nullptr, 0, 0}, TDO_ERR_INVALID_ARGUMENT);
  const tdo_box flat{v3(0, 3, 1), v3(1, 3, 2)};
  expect_refused(tdo_grid_update{in, 1, nullptr, 0, &flat, 1, 0}, TDO_ERR_INVALID_BOX);
  const tdo_box nan_box{v3(0, 3, 1), v3(1, std::nan(""), 2)};
  expect_refused(tdo_grid_update{in, 1, nullptr, 0, &nan_box, 1, 0}, TDO_ERR_INVALID_BOX);
  const tdo_box three[3] = {{v3(0, 3, 1), v3(1, 4, 2)},
                            {v3(0, 3, 1), v3(1, 4, 2)},
                            {v3(0, 3, 1), v3(1, 4, 2)}};  // 1 + 3 > max_boxes 3
  expect_refused(tdo_grid_update{in, 1, nullptr, 0, three, 3, 0}, TDO_ERR_BOX_CAPACITY);
  const tdo_grid_update small_budget{in, 1, nullptr, 0, nullptr, 0, 10};
  expect_refused(small_budget, TDO_ERR_BUDGET);
}

TEST_F(GridUpdateRefused, GivenAnUnfinishedGrid_WhenApplied_ThenMapNotReady) {
  ASSERT_EQ(tdo_grid_reset(pl_.grid(), &d_), TDO_OK);
  const tdo_voxel in[1] = {{10, 10, 6}};
  const tdo_grid_update u{in, 1, nullptr, 0, nullptr, 0, 0};
  EXPECT_EQ(tdo_grid_apply_update(pl_.grid(), &u, nullptr), TDO_ERR_MAP_NOT_READY);
  EXPECT_EQ(tdo_grid_apply_update(nullptr, &u, nullptr), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_grid_update_work(pl_.grid(), &u), 0u);
}

}  // namespace
