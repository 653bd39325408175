// Stage 2, inflection correction (correct.h): every output segment is checked here independently
// (exact segment-to-box distance by ternary search of the convex distance, written in this file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "rng.h"
#include "tdo/collision.h"
#include "tdo/correct.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;
using tdo_test::TestCorrector;
using tdo_test::TestPlanner;
using tdo_test::VoxelMap;

tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }
tdo_vec3 lerp(const tdo_vec3& a, const tdo_vec3& b, double t) {
  return v3(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z));
}
bool same(const tdo_vec3& a, const tdo_vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/** Exact distance from [a, b] to a box: ternary search of the convex distance over [0, 1]. */
double ref_segment_box(const tdo_vec3& a, const tdo_vec3& b, const tdo_box& box) {
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 200; ++it) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (tdo_test::distance_to_box(lerp(a, b, m1), box) <=
        tdo_test::distance_to_box(lerp(a, b, m2), box))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({tdo_test::distance_to_box(a, box), tdo_test::distance_to_box(b, box),
                   tdo_test::distance_to_box(lerp(a, b, 0.5 * (lo + hi)), box)});
}

struct Map {
  VoxelMap m;
  std::vector<tdo_box> boxes;

  bool inside(const tdo_vec3& p) const {
    return p.x >= m.origin.x && p.y >= m.origin.y && p.z >= m.origin.z &&
           p.x <= m.origin.x + m.nx * m.res && p.y <= m.origin.y + m.ny * m.res &&
           p.z <= m.origin.z + m.nz * m.res;
  }
  /** Independent verdict: inside the bounds and at least c from every box. */
  bool segment_ok(const tdo_vec3& a, const tdo_vec3& b, double c) const {
    if (!inside(a) || !inside(b)) return false;
    for (const tdo_box& box : boxes)
      if (ref_segment_box(a, b, box) < c - 1e-9) return false;
    return true;
  }
};

/** Capacities of a correction context (tdo_test::TestCorrector: its own exactly sized arena). */
tdo_correct_config correct_cfg(uint32_t max_points, uint32_t max_checks) {
  tdo_correct_config cfg{};
  cfg.max_points = max_points;
  cfg.max_checks = max_checks;
  return cfg;
}

tdo_correct_input make_in(const tdo_grid* g, const std::vector<tdo_vec3>& pts,
                          tdo_correct_mode mode, double clearance,
                          double turn_threshold = 10.0 * std::acos(-1.0) / 180.0) {
  tdo_correct_input in{};
  in.grid = g;
  in.points = pts.data();
  in.n_points = static_cast<uint32_t>(pts.size());
  in.mode = mode;
  in.clearance = clearance;
  in.turn_threshold = turn_threshold;
  return in;
}

tdo_status load_boxes(tdo_grid* g, const Map& map, double clearance) {
  tdo_test::Obstacles obs;
  obs.boxes = map.boxes;
  return tdo_test::load_obstacles(g, map.m, obs, clearance);
}

/** Grid path of an A* search as world points: voxel centres with the exact start and goal. */
bool grid_path(TestPlanner& pl, const tdo_vec3& start, const tdo_vec3& goal,
               std::vector<tdo_vec3>* pts) {
  const tdo_search_input in = tdo_test::make_input(pl.grid(), start, goal, TDO_SEARCH_ASTAR);
  tdo_search_output out{};
  if (tdo_search_run(pl.search(), &in, &out) != TDO_OK) return false;
  pts->clear();
  for (uint32_t i = 0; i < out.n_path; ++i)
    pts->push_back(tdo_grid_voxel_center(pl.grid(), out.path[i]));
  if (pts->size() < 2) return false;
  pts->front() = start;
  pts->back() = goal;
  return true;
}

/** A random pillar map in pl's grid (24 x 24 x 10 voxels of 0.5 m; n boxes with footprints of 0.3
 *  to 2 m at x, y in [0, 12], from z = -0.5 up to 1 to 6 m) and the grid path between random
 *  voxels near opposite corners, z in [z_lo, z_hi]. False when an end is blocked or no path exists.
 */
bool random_pillar_query(TestPlanner& pl, Rng& rng, int n, double clearance, int z_lo, int z_hi,
                         Map* mp, std::vector<tdo_vec3>* pts) {
  mp->m = VoxelMap(24, 24, 10, 0.5, v3(0.0, 0.0, 0.0));
  mp->boxes.clear();
  for (int b = 0; b < n; ++b) {
    const double x = rng.uniform(0, 12), y = rng.uniform(0, 12);
    const double wx = rng.uniform(0.3, 2.0), wy = rng.uniform(0.3, 2.0), h = rng.uniform(1.0, 6.0);
    mp->boxes.push_back(tdo_box{v3(x, y, -0.5), v3(x + wx, y + wy, h)});
  }
  if (load_boxes(pl.grid(), *mp, clearance) != TDO_OK) {
    ADD_FAILURE() << "the pillars do not load";
    return false;
  }
  const tdo_voxel s{rng.range(0, 5), rng.range(0, 5), rng.range(z_lo, z_hi)};
  const tdo_voxel g{rng.range(18, 23), rng.range(18, 23), rng.range(z_lo, z_hi)};
  if (tdo_grid_is_blocked(pl.grid(), s) || tdo_grid_is_blocked(pl.grid(), g)) return false;
  return grid_path(pl, tdo_grid_voxel_center(pl.grid(), s), tdo_grid_voxel_center(pl.grid(), g),
                   pts);
}

const tdo_correct_mode kModes[] = {TDO_CORRECT_MULTISCALE, TDO_CORRECT_GREEDY_LOS,
                                   TDO_CORRECT_NONE};
const char* mode_name(tdo_correct_mode m) {
  return m == TDO_CORRECT_MULTISCALE   ? "multiscale"
         : m == TDO_CORRECT_GREEDY_LOS ? "greedy"
                                       : "none";
}

TEST(
    Correct,
    GivenRandomMapsAndGridPaths_WhenCorrected_ThenEndsMatchEverySegmentKeepsClearanceAndNoPointIsAdded) {
  TestPlanner pl(tdo_test::make_cap(24 * 24 * 10, 24 * 24 * 10, 2000, 64, 20000));
  ASSERT_EQ(pl.status(), TDO_OK);
  TestCorrector corr(correct_cfg(2000, 200000));
  ASSERT_EQ(corr.status(), TDO_OK);
  Rng rng(7);
  const double clearance = 0.5;
  int planned = 0;
  uint64_t in_points = 0, ms_points = 0, greedy_points = 0, none_points = 0;
  for (int map = 0; map < 40; ++map) {
    Map mp;
    mp.m = VoxelMap(24, 24, 10, 0.5, v3(rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0));
    const int n_boxes = rng.range(10, 40);
    for (int b = 0; b < n_boxes; ++b) {
      const double x = mp.m.origin.x + rng.uniform(0, 12), y = mp.m.origin.y + rng.uniform(0, 12);
      const double wx = rng.uniform(0.3, 2.0), wy = rng.uniform(0.3, 2.0),
                   h = rng.uniform(1.0, 6.0);
      mp.boxes.push_back(tdo_box{v3(x, y, -0.5), v3(x + wx, y + wy, h)});
    }
    ASSERT_EQ(load_boxes(pl.grid(), mp, clearance), TDO_OK);
    // Start and goal: centres of free voxels near opposite corners.
    tdo_voxel s{-1, -1, -1}, g{-1, -1, -1};
    for (int tries = 0; tries < 200 && (s.i < 0 || g.i < 0); ++tries) {
      const tdo_voxel a{rng.range(0, 5), rng.range(0, 5), rng.range(0, 9)};
      const tdo_voxel b{rng.range(18, 23), rng.range(18, 23), rng.range(0, 9)};
      if (s.i < 0 && !tdo_grid_is_blocked(pl.grid(), a)) s = a;
      if (g.i < 0 && !tdo_grid_is_blocked(pl.grid(), b)) g = b;
    }
    if (s.i < 0 || g.i < 0) continue;
    std::vector<tdo_vec3> pts;
    if (!grid_path(pl, tdo_grid_voxel_center(pl.grid(), s), tdo_grid_voxel_center(pl.grid(), g),
                   &pts))
      continue;
    bool input_ok = true;
    for (size_t i = 1; i < pts.size(); ++i)
      input_ok = input_ok && mp.segment_ok(pts[i - 1], pts[i], clearance);
    for (tdo_correct_mode mode : kModes) {
      const tdo_correct_input in = make_in(pl.grid(), pts, mode, clearance);
      tdo_correct_output out{};
      const tdo_status st = tdo_correct_run(corr.ctx(), &in, &out);
      if (!input_ok) {  // a grid path can graze a box between two free centres: that is refused
        EXPECT_EQ(st, TDO_ERR_NO_PATH) << "map " << map << " " << mode_name(mode);
        EXPECT_EQ(out.n_waypoints, 0u);
        continue;
      }
      ASSERT_EQ(st, TDO_OK) << "map " << map << " " << mode_name(mode);
      ASSERT_GE(out.n_waypoints, 2u);
      EXPECT_TRUE(same(out.waypoints[0], pts.front())) << "map " << map;
      EXPECT_TRUE(same(out.waypoints[out.n_waypoints - 1], pts.back())) << "map " << map;
      EXPECT_LE(out.n_waypoints, pts.size());
      EXPECT_GE(out.checks, pts.size() - 1u) << "every input segment is verified";
      for (uint32_t i = 1; i < out.n_waypoints; ++i)
        ASSERT_TRUE(mp.segment_ok(out.waypoints[i - 1], out.waypoints[i], clearance))
            << "map " << map << " " << mode_name(mode) << " segment " << i;
      // Every output point comes from the input, in input order.
      size_t at = 0;
      for (uint32_t i = 0; i < out.n_waypoints; ++i) {
        while (at < pts.size() && !same(pts[at], out.waypoints[i])) ++at;
        ASSERT_LT(at, pts.size()) << "map " << map << " output point " << i
                                  << " not from the input";
      }
      if (mode == TDO_CORRECT_NONE) {
        EXPECT_EQ(out.n_safety_critical, 0u);
      } else {
        EXPECT_EQ(out.n_safety_critical, out.n_waypoints - 2u);
      }
      (mode == TDO_CORRECT_MULTISCALE   ? ms_points
       : mode == TDO_CORRECT_GREEDY_LOS ? greedy_points
                                        : none_points) += out.n_waypoints;
    }
    if (input_ok) {
      ++planned;
      in_points += pts.size();
    }
  }
  EXPECT_GE(planned, 25);
  // Both corrections remove most grid turns; neither keeps more than collinear dropping does.
  EXPECT_LT(none_points, in_points);
  EXPECT_LT(ms_points, none_points);
  EXPECT_LT(greedy_points, none_points);
}

TEST(Correct, GivenAStraightInputWithRepeatedPoints_WhenCorrected_ThenTwoPointsRemainInEveryMode) {
  TestPlanner pl(tdo_test::make_cap(4000, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 10, 1.0, v3(0, 0, 0));
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  std::vector<tdo_vec3> pts;
  const tdo_vec3 a = v3(1.2, 2.3, 3.4), b = v3(18.7, 15.1, 6.6);
  for (int k = 0; k <= 30; ++k) {
    pts.push_back(lerp(a, b, k / 30.0));
    if (k % 7 == 3) pts.push_back(pts.back());  // a repeated point
  }
  pts.front() = a;
  pts.back() = b;
  TestCorrector corr(correct_cfg(100, 1000));
  for (tdo_correct_mode mode : kModes) {
    const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
    tdo_correct_output out{};
    ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_OK) << mode_name(mode);
    ASSERT_EQ(out.n_waypoints, 2u) << mode_name(mode);
    EXPECT_TRUE(same(out.waypoints[0], a));
    EXPECT_TRUE(same(out.waypoints[1], b));
    EXPECT_EQ(out.n_safety_critical, 0u);
  }
}

// A wall between start and goal: the detour corner must stay (its removal would cross the wall),
// every other point of the dense, zig-zagging input goes.
TEST(Correct, GivenAWallBetweenStartAndGoal_WhenCorrected_ThenTheDetourCornerIsSafetyCritical) {
  TestPlanner pl(tdo_test::make_cap(20 * 20 * 4, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 4, 1.0, v3(0, 0, 0));
  mp.boxes.push_back(tdo_box{v3(9, -1, -1), v3(11, 13, 5)});
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  const tdo_vec3 a = v3(2.5, 5.5, 2.0), corner = v3(10.0, 16.0, 2.0), c = v3(17.5, 5.5, 2.0);
  ASSERT_FALSE(mp.segment_ok(a, c, 0.5));
  ASSERT_TRUE(mp.segment_ok(a, corner, 0.5));
  ASSERT_TRUE(mp.segment_ok(corner, c, 0.5));
  std::vector<tdo_vec3> pts;
  for (int k = 0; k < 8; ++k) {  // along a -> corner with a small zig-zag
    tdo_vec3 p = lerp(a, corner, k / 8.0);
    if (k % 2 == 1) p.x += 0.1;
    pts.push_back(p);
  }
  for (int k = 0; k <= 8; ++k) pts.push_back(lerp(corner, c, k / 8.0));
  for (size_t i = 1; i < pts.size(); ++i) ASSERT_TRUE(mp.segment_ok(pts[i - 1], pts[i], 0.5));
  TestCorrector corr(correct_cfg(100, 10000));
  for (tdo_correct_mode mode : {TDO_CORRECT_MULTISCALE, TDO_CORRECT_GREEDY_LOS}) {
    const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
    tdo_correct_output out{};
    ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_OK) << mode_name(mode);
    ASSERT_EQ(out.n_waypoints, 3u) << mode_name(mode);
    EXPECT_TRUE(same(out.waypoints[1], corner)) << mode_name(mode);
    EXPECT_EQ(out.n_safety_critical, 1u) << mode_name(mode);
  }
  // Without correction only the collinear points go: the zig-zag stays.
  const tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_NONE, 0.5);
  tdo_correct_output out{};
  ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_OK);
  EXPECT_GT(out.n_waypoints, 3u);
  EXPECT_EQ(out.n_safety_critical, 0u);
}

TEST(Correct, GivenAnInputSegmentThroughAnObstacle_WhenCorrected_ThenNoPathAndNoOutput) {
  TestPlanner pl(tdo_test::make_cap(20 * 20 * 4, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 4, 1.0, v3(0, 0, 0));
  mp.boxes.push_back(tdo_box{v3(9, 9, -1), v3(9.05, 11, 5)});  // thin
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  const std::vector<tdo_vec3> pts = {v3(2, 10, 2), v3(5, 10, 2), v3(15, 10, 2), v3(15, 15, 2)};
  TestCorrector corr(correct_cfg(100, 1000));
  for (tdo_correct_mode mode : kModes) {
    const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
    tdo_correct_output out{};
    out.n_waypoints = 77;
    EXPECT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_ERR_NO_PATH) << mode_name(mode);
    EXPECT_EQ(out.n_waypoints, 0u);
    EXPECT_EQ(out.waypoints, nullptr);
  }
}

// A collinear run is verified as its merged segment when that keeps the clearance with a margin;
// otherwise segment by segment. Either way the status, the check count and the output are those
// of checking every input segment in order.
TEST(Correct,
     GivenACollinearRunThroughAnObstacle_WhenCorrected_ThenNoPathAtItsFirstBlockedSegment) {
  TestPlanner pl(tdo_test::make_cap(20 * 20 * 4, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 4, 1.0, v3(0, 0, 0));
  mp.boxes.push_back(tdo_box{v3(9, 9, -1), v3(9.05, 11, 5)});  // a thin wall across y = 10
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  std::vector<tdo_vec3> pts;
  for (int x = 2; x <= 15; ++x) pts.push_back(v3(x, 10, 2));  // one collinear run
  pts.push_back(v3(15, 15, 2));
  // Segments 1-6 end at x <= 8, a metre from the wall; segment 7, [8, 9], touches it.
  for (uint32_t budget : {6u, 7u, 1000u}) {
    TestCorrector corr(correct_cfg(100, budget));
    for (tdo_correct_mode mode : kModes) {
      const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
      tdo_correct_output out{};
      const tdo_status st = tdo_correct_run(corr.ctx(), &in, &out);
      EXPECT_EQ(st, budget < 7u ? TDO_ERR_BUDGET : TDO_ERR_NO_PATH) << mode_name(mode);
      EXPECT_EQ(out.checks, budget < 7u ? budget : 7u) << mode_name(mode);
      EXPECT_EQ(out.n_waypoints, 0u);
    }
  }
}

TEST(Correct,
     GivenACollinearRunExactlyAtTheClearance_WhenCorrected_ThenItIsMergedAsCheckedOneByOne) {
  TestPlanner pl(tdo_test::make_cap(20 * 20 * 4, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 4, 1.0, v3(0, 0, 0));
  mp.boxes.push_back(tdo_box{v3(0, 0, -1), v3(20, 9.5, 5)});  // face at y = 9.5
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  std::vector<tdo_vec3> pts;
  for (int x = 2; x <= 15; ++x) pts.push_back(v3(x, 10, 2));  // 0.5 m from the face
  const uint32_t n = static_cast<uint32_t>(pts.size());
  ASSERT_TRUE(mp.segment_ok(pts.front(), pts.back(), 0.5));
  TestCorrector corr(correct_cfg(100, 0));
  const tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_NONE, 0.5);
  tdo_correct_output out{};
  ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_OK);
  ASSERT_EQ(out.n_waypoints, 2u);
  EXPECT_TRUE(same(out.waypoints[0], pts.front()));
  EXPECT_TRUE(same(out.waypoints[1], pts.back()));
  EXPECT_EQ(out.checks, n) << "n - 1 input segments and the merged one";
}

TEST(Correct, GivenASmallCheckBudget_WhenCorrected_ThenBudgetStatusAndNoOutput) {
  TestPlanner pl(tdo_test::make_cap(20 * 20 * 4, 100, 100));
  Map mp;
  mp.m = VoxelMap(20, 20, 4, 1.0, v3(0, 0, 0));
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  std::vector<tdo_vec3> pts;
  for (int k = 0; k < 12; ++k) pts.push_back(v3(1.5 + k, 1.5 + (k % 2), 2.0));  // a zig-zag
  for (uint32_t budget : {1u, 5u, 11u, 12u}) {
    TestCorrector corr(correct_cfg(100, budget));
    for (tdo_correct_mode mode : kModes) {
      const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
      tdo_correct_output out{};
      const tdo_status st = tdo_correct_run(corr.ctx(), &in, &out);
      // 11 input checks; then NONE needs none, greedy one (the whole chord is clear on this
      // empty map), multi-scale several.
      const uint32_t needs = mode == TDO_CORRECT_NONE         ? 11u
                             : mode == TDO_CORRECT_GREEDY_LOS ? 12u
                                                              : 13u;
      if (budget < needs) {
        EXPECT_EQ(st, TDO_ERR_BUDGET) << mode_name(mode) << " budget " << budget;
        EXPECT_EQ(out.n_waypoints, 0u);
        EXPECT_EQ(out.checks, budget);
      } else {
        EXPECT_EQ(st, TDO_OK) << mode_name(mode) << " budget " << budget;
        EXPECT_EQ(out.checks, needs) << mode_name(mode);
      }
    }
  }
}

TEST(Correct, GivenBadArguments_WhenInitOrRun_ThenNamedStatuses) {
  tdo_correct_config cfg{0, 10};
  EXPECT_EQ(tdo_correct_footprint(&cfg), 0u);
  EXPECT_EQ(tdo_correct_footprint(nullptr), 0u);
  std::vector<unsigned char> mem(1 << 16);
  tdo_arena arena;
  tdo_arena_init(&arena, mem.data(), mem.size());
  tdo_correct* ctx = nullptr;
  EXPECT_EQ(tdo_correct_init(&ctx, &arena, &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_correct_init(&ctx, &arena, nullptr), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_correct_init(nullptr, &arena, &cfg), TDO_ERR_INVALID_ARGUMENT);
  cfg = tdo_correct_config{10, 0};  // 0 checks: no budget of its own
  EXPECT_EQ(tdo_correct_init(&ctx, &arena, &cfg), TDO_OK);
  cfg = tdo_correct_config{100000, 10};
  EXPECT_EQ(tdo_correct_init(&ctx, &arena, &cfg), TDO_ERR_ARENA_TOO_SMALL);

  TestPlanner pl(tdo_test::make_cap(1000, 100, 100));
  TestCorrector corr(correct_cfg(8, 100));
  const tdo_grid_desc d{10, 10, 10, 1.0, v3(0, 0, 0)};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  std::vector<tdo_vec3> pts = {v3(1, 1, 1), v3(5, 5, 5)};
  tdo_correct_output out{};
  tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_MULTISCALE, 0.5);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_ERR_MAP_NOT_READY);
  ASSERT_EQ(tdo_grid_finish(pl.grid(), 0.5), TDO_OK);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_OK);
  EXPECT_EQ(tdo_correct_run(nullptr, &in, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), nullptr, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &in, nullptr), TDO_ERR_INVALID_ARGUMENT);
  tdo_correct_input bad = in;
  bad.n_points = 1;
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_INVALID_ARGUMENT);
  bad = in;
  bad.clearance = -1.0;
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_INVALID_ARGUMENT);
  bad = in;
  bad.turn_threshold = std::nan("");
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_INVALID_ARGUMENT);
  bad = in;
  const int bogus_mode = 3;
  std::memcpy(&bad.mode, &bogus_mode, sizeof bogus_mode);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_vec3> nan_pts = {v3(1, 1, 1), v3(std::nan(""), 5, 5)};
  bad = make_in(pl.grid(), nan_pts, TDO_CORRECT_MULTISCALE, 0.5);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_vec3> many(9, v3(1, 1, 1));
  bad = make_in(pl.grid(), many, TDO_CORRECT_MULTISCALE, 0.5);
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &bad, &out), TDO_ERR_PATH_CAPACITY);
}

TEST(Correct, GivenTheSameInput_WhenRunTwice_ThenOutputsAreBitIdentical) {
  TestPlanner pl(tdo_test::make_cap(24 * 24 * 10, 24 * 24 * 10, 2000, 64, 20000));
  Rng rng(99);
  Map mp;
  mp.m = VoxelMap(24, 24, 10, 0.5, v3(0, 0, 0));
  for (int b = 0; b < 30; ++b) {
    const double x = rng.uniform(1, 11), y = rng.uniform(1, 11);
    // Drawn in sequence (the order of a call's arguments is unspecified: gcc and clang differ);
    // y's width first, as gcc drew them when the map was chosen.
    const double wy = rng.uniform(0.3, 1.5), wx = rng.uniform(0.3, 1.5);
    mp.boxes.push_back(tdo_box{v3(x, y, -1), v3(x + wx, y + wy, 6)});
  }
  ASSERT_EQ(load_boxes(pl.grid(), mp, 0.5), TDO_OK);
  std::vector<tdo_vec3> pts;
  ASSERT_TRUE(grid_path(pl, v3(0.25, 0.25, 2.25), v3(11.75, 11.75, 2.25), &pts));
  TestCorrector corr(correct_cfg(2000, 100000));
  for (tdo_correct_mode mode : kModes) {
    const tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.5);
    tdo_correct_output a{}, b{};
    ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &a), TDO_OK);
    const std::vector<tdo_vec3> first(a.waypoints, a.waypoints + a.n_waypoints);
    ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &b), TDO_OK);
    ASSERT_EQ(a.n_waypoints, b.n_waypoints);
    EXPECT_EQ(std::memcmp(first.data(), b.waypoints, first.size() * sizeof(tdo_vec3)), 0);
    EXPECT_EQ(a.checks, b.checks);
  }
}

double polyline_length(const tdo_vec3* p, uint32_t n) {
  double s = 0.0;
  for (uint32_t i = 1; i < n; ++i)
    s += std::sqrt((p[i].x - p[i - 1].x) * (p[i].x - p[i - 1].x) +
                   (p[i].y - p[i - 1].y) * (p[i].y - p[i - 1].y) +
                   (p[i].z - p[i - 1].z) * (p[i].z - p[i - 1].z));
  return s;
}

// The optional shortening after the scales (input `shorten`): on random maps every segment keeps
// clearance (checked here), the ends stay, and it never adds a waypoint nor lengthens the polyline.
TEST(
    Correct,
    GivenRandomMaps_WhenMultiscaleShortens_ThenSegmentsKeepClearanceAndPathIsNoLongerWithNoMorePoints) {
  TestPlanner pl(tdo_test::make_cap(24 * 24 * 10, 24 * 24 * 10, 2000, 64, 20000));
  ASSERT_EQ(pl.status(), TDO_OK);
  TestCorrector plain(correct_cfg(2000, 200000)), shortened(correct_cfg(2000, 200000));
  ASSERT_EQ(plain.status(), TDO_OK);
  ASSERT_EQ(shortened.status(), TDO_OK);
  Rng rng(11);
  const double clearance = 0.5;
  int compared = 0, shorter = 0;
  for (int map = 0; map < 80; ++map) {
    Map mp;
    std::vector<tdo_vec3> pts;
    const int n_boxes = rng.range(10, 40);
    if (!random_pillar_query(pl, rng, n_boxes, clearance, 0, 9, &mp, &pts)) continue;
    tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_MULTISCALE, clearance);
    tdo_correct_output a{}, b{};
    if (tdo_correct_run(plain.ctx(), &in, &a) != TDO_OK) continue;  // grazing grid path
    in.shorten = 1;
    ASSERT_EQ(tdo_correct_run(shortened.ctx(), &in, &b), TDO_OK) << "map " << map;
    ++compared;
    ASSERT_GE(b.n_waypoints, 2u);
    EXPECT_TRUE(same(b.waypoints[0], pts.front())) << "map " << map;
    EXPECT_TRUE(same(b.waypoints[b.n_waypoints - 1], pts.back())) << "map " << map;
    for (uint32_t i = 1; i < b.n_waypoints; ++i)
      ASSERT_TRUE(mp.segment_ok(b.waypoints[i - 1], b.waypoints[i], clearance))
          << "map " << map << " segment " << i;
    EXPECT_LE(b.n_waypoints, a.n_waypoints) << "map " << map;
    const double la = polyline_length(a.waypoints, a.n_waypoints);
    const double lb = polyline_length(b.waypoints, b.n_waypoints);
    EXPECT_LE(lb, la + 1e-9) << "map " << map;
    if (lb < la - 1e-6) ++shorter;
    // Ample budget: every interior point's removal was checked and fails.
    EXPECT_EQ(b.n_safety_critical, b.n_waypoints - 2u) << "map " << map;
    for (uint32_t i = 1; i + 1 < b.n_waypoints; ++i)
      EXPECT_FALSE(mp.segment_ok(b.waypoints[i - 1], b.waypoints[i + 1], clearance + 1e-6))
          << "map " << map << " point " << i << " could be dropped";
    // Deterministic.
    tdo_correct_output c{};
    ASSERT_EQ(tdo_correct_run(shortened.ctx(), &in, &c), TDO_OK);
    ASSERT_EQ(c.n_waypoints, b.n_waypoints);
    EXPECT_EQ(std::memcmp(c.waypoints, b.waypoints, b.n_waypoints * sizeof(tdo_vec3)), 0);
  }
  EXPECT_GE(compared, 30);
  EXPECT_GE(shorter, 1) << "the pass never shortened anything";
}

// The shortening counts every check it would make, also those it skips as known to fail (the
// shortcut sweep's blocked chords): with a budget at least the unbounded run's count the output
// is the same; with less, the run uses exactly the budget (the shortening stops where it runs out)
// and every segment still keeps clearance (checked here).
TEST(Correct, GivenEveryBudget_WhenShortened_ThenChecksUseItExactlyAndSegmentsKeepClearance) {
  TestPlanner pl(tdo_test::make_cap(24 * 24 * 10, 24 * 24 * 10, 2000, 64, 20000));
  ASSERT_EQ(pl.status(), TDO_OK);
  Rng rng(23);
  const double clearance = 0.5;
  int runs = 0, cut = 0;
  for (int map = 0; map < 40 && runs < 6; ++map) {
    Map mp;
    std::vector<tdo_vec3> pts;
    if (!random_pillar_query(pl, rng, 30, clearance, 4, 4, &mp, &pts)) continue;
    tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_MULTISCALE, clearance);
    in.shorten = 1;
    TestCorrector full(correct_cfg(2000, 0));
    tdo_correct_output ref{};
    if (tdo_correct_run(full.ctx(), &in, &ref) != TDO_OK) continue;  // grazing grid path
    ++runs;
    const uint32_t n = ref.checks;
    for (uint32_t budget = n + 2u; budget > 0u; budget = budget > 7u ? budget - 7u : budget - 1u) {
      TestCorrector corr(correct_cfg(2000, budget));
      tdo_correct_output out{};
      const tdo_status st = tdo_correct_run(corr.ctx(), &in, &out);
      if (st == TDO_ERR_BUDGET) {  // before the shortening
        EXPECT_EQ(out.checks, budget);
        continue;
      }
      ASSERT_EQ(st, TDO_OK) << "map " << map << " budget " << budget;
      if (budget >= n) {
        EXPECT_EQ(out.checks, n) << "map " << map << " budget " << budget;
        ASSERT_EQ(out.n_waypoints, ref.n_waypoints);
        EXPECT_EQ(std::memcmp(out.waypoints, ref.waypoints, ref.n_waypoints * sizeof(tdo_vec3)), 0);
        continue;
      }
      ++cut;
      EXPECT_EQ(out.checks, budget) << "map " << map << " budget " << budget;
      for (uint32_t i = 1; i < out.n_waypoints; ++i)
        ASSERT_TRUE(mp.segment_ok(out.waypoints[i - 1], out.waypoints[i], clearance))
            << "map " << map << " budget " << budget << " segment " << i;
    }
  }
  EXPECT_GE(runs, 3);
  EXPECT_GE(cut, 20);
}

}  // namespace

// steps_proven (the planner's grid paths at clearance 0): the interior grid steps are not checked
// again, and the run is the one that checks them: the same status, waypoints and check count, in
// every mode. The steps do keep half a voxel edge (an independent distance to every box), which
// is what lets the planner claim them. Other values of the flag are refused.
TEST(Correct, GivenGridStepsProvenAtClearanceZero_WhenCorrected_ThenTheSameRunAsCheckingThem) {
  TestPlanner pl(tdo_test::make_cap(24 * 24 * 10, 24 * 24 * 10, 2000, 64, 20000));
  TestCorrector corr(correct_cfg(2000, 100000));
  Rng rng(5150);
  int compared = 0;
  for (int q = 0; q < 40; ++q) {
    Map mp;
    std::vector<tdo_vec3> pts;
    if (!random_pillar_query(pl, rng, 25, 0.0, 0, 9, &mp, &pts)) continue;
    for (size_t i = 2; i + 1 < pts.size(); ++i)
      for (const tdo_box& box : mp.boxes)
        ASSERT_GE(ref_segment_box(pts[i - 1], pts[i], box), 0.5 * mp.m.res - 1e-9) << q << " " << i;
    for (tdo_correct_mode mode : kModes) {
      tdo_correct_input in = make_in(pl.grid(), pts, mode, 0.0);
      in.shorten = 1;
      tdo_correct_output a{}, b{};
      const tdo_status sa = tdo_correct_run(corr.ctx(), &in, &a);
      const std::vector<tdo_vec3> checked(a.waypoints, a.waypoints + a.n_waypoints);
      in.steps_proven = 1;
      ASSERT_EQ(tdo_correct_run(corr.ctx(), &in, &b), sa) << q << " " << mode_name(mode);
      ASSERT_EQ(b.n_waypoints, checked.size()) << q << " " << mode_name(mode);
      EXPECT_EQ(std::memcmp(checked.data(), b.waypoints, checked.size() * sizeof(tdo_vec3)), 0)
          << q << " " << mode_name(mode);
      EXPECT_EQ(a.checks, b.checks) << q << " " << mode_name(mode);
      ++compared;
    }
  }
  EXPECT_GE(compared, 60);
  std::vector<tdo_vec3> pts = {v3(1.25, 1.25, 1.25), v3(1.75, 1.25, 1.25), v3(2.25, 1.25, 1.25)};
  tdo_correct_input in = make_in(pl.grid(), pts, TDO_CORRECT_MULTISCALE, 0.0);
  in.steps_proven = 2;
  tdo_correct_output out{};
  EXPECT_EQ(tdo_correct_run(corr.ctx(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
}
