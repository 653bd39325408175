// Capacities, footprint and planner init (config.h, planner.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::make_cap;

tdo_planner_config config(const tdo_capacity& cap) {
  tdo_planner_config cfg{};
  cfg.cap = cap;
  return cfg;
}

tdo_planner_config small_config() { return config(make_cap(1000, 1000, 200, 8, 343, 5000)); }

TEST(Config, GivenAValidConfig_WhenFootprintAsked_ThenPositive) {
  const tdo_planner_config cfg = small_config();
  EXPECT_GT(tdo_planner_footprint(&cfg), 0u);
}

TEST(Config, GivenNullOrZeroCapacities_WhenFootprintAsked_ThenZero) {
  EXPECT_EQ(tdo_planner_footprint(nullptr), 0u);
  const tdo_planner_config zero = config(tdo_capacity{});
  EXPECT_EQ(tdo_planner_footprint(&zero), 0u);
  for (int field = 0; field < 3; ++field) {
    tdo_planner_config cfg = small_config();
    if (field == 0) cfg.cap.max_voxels = 0;
    if (field == 1) cfg.cap.max_nodes = 0;
    if (field == 2) cfg.cap.max_path = 0;
    EXPECT_EQ(tdo_planner_footprint(&cfg), 0u) << "field " << field;
  }
}

// Each capacity that sizes a buffer, by field: the footprint never shrinks when it grows and grows
// when it grows by a thousand (every such item takes at least one byte).
TEST(Config, GivenOneCapacityIncreased_WhenFootprintAsked_ThenFootprintIsMonotone) {
  uint32_t tdo_capacity::*const fields[] = {&tdo_capacity::max_voxels, &tdo_capacity::max_boxes,
                                            &tdo_capacity::max_nodes, &tdo_capacity::max_path,
                                            &tdo_capacity::max_clear_cells};
  const char* names[] = {"max_voxels", "max_boxes", "max_nodes", "max_path", "max_clear_cells"};
  for (size_t f = 0; f < sizeof(fields) / sizeof(fields[0]); ++f) {
    tdo_planner_config cfg = small_config();
    size_t prev = tdo_planner_footprint(&cfg);
    for (int step = 0; step < 200; ++step) {
      cfg.cap.*fields[f] += 1u;
      const size_t now = tdo_planner_footprint(&cfg);
      ASSERT_GE(now, prev) << names[f] << " = " << cfg.cap.*fields[f];
      prev = now;
    }
    tdo_planner_config big = small_config();
    const size_t before = tdo_planner_footprint(&big);
    big.cap.*fields[f] += 1000u;
    EXPECT_GE(tdo_planner_footprint(&big), before + 1000u) << names[f];
  }
  // The expansion budget is a number, not a buffer: it may not shrink the footprint either.
  tdo_planner_config cfg = small_config();
  const size_t before = tdo_planner_footprint(&cfg);
  cfg.cap.max_expansions *= 10u;
  EXPECT_GE(tdo_planner_footprint(&cfg), before);
}

TEST(Config, GivenAllCapacitiesScaledUp_WhenFootprintAsked_ThenFootprintGrows) {
  size_t prev = 0;
  for (uint32_t n = 8; n <= 8192; n *= 2) {
    const tdo_planner_config cfg = config(make_cap(n, n, n, n, n, n));
    const size_t fp = tdo_planner_footprint(&cfg);
    EXPECT_GT(fp, prev) << "n = " << n;
    prev = fp;
  }
}

TEST(Planner, GivenAnArenaOneByteSmallerThanTheFootprint_WhenInit_ThenArenaTooSmall) {
  const tdo_planner_config cfgs[] = {small_config(), config(make_cap(1, 1, 1, 0, 1, 1)),
                                     config(make_cap(4096, 27u * 4096u, 500, 100, 2000, 100000))};
  for (const tdo_planner_config& cfg : cfgs) {
    const size_t fp = tdo_planner_footprint(&cfg);
    ASSERT_GT(fp, 1u);
    std::vector<unsigned char> mem(fp + TDO_ARENA_ALIGN);
    // Whatever the alignment of the caller's pointer.
    for (size_t off = 0; off < TDO_ARENA_ALIGN; ++off) {
      tdo_planner* p = nullptr;
      EXPECT_EQ(tdo_planner_init(&p, mem.data() + off, fp - 1u, &cfg), TDO_ERR_ARENA_TOO_SMALL)
          << "offset " << off << ", voxels " << cfg.cap.max_voxels;
    }
    tdo_planner* p = nullptr;
    EXPECT_EQ(tdo_planner_init(&p, mem.data(), 0u, &cfg), TDO_ERR_ARENA_TOO_SMALL);
  }
}

TEST(Planner, GivenExactlyTheFootprint_WhenInitAtAnyAlignment_ThenOkAndUsedWithinFootprint) {
  const tdo_planner_config cfgs[] = {small_config(), config(make_cap(1, 1, 1, 0, 1, 1)),
                                     config(make_cap(4096, 27u * 4096u, 500, 100, 2000, 100000))};
  for (const tdo_planner_config& cfg : cfgs) {
    const size_t fp = tdo_planner_footprint(&cfg);
    ASSERT_GT(fp, 0u);
    std::vector<unsigned char> mem(fp + TDO_ARENA_ALIGN);
    for (size_t off = 0; off < TDO_ARENA_ALIGN; ++off) {
      tdo_planner* p = nullptr;
      ASSERT_EQ(tdo_planner_init(&p, mem.data() + off, fp, &cfg), TDO_OK)
          << "offset " << off << ", voxels " << cfg.cap.max_voxels;
      ASSERT_NE(p, nullptr);
      const size_t used = tdo_planner_arena_used(p);
      EXPECT_GT(used, 0u);
      EXPECT_LE(used, fp) << "offset " << off;
      const auto* b = reinterpret_cast<const unsigned char*>(p);
      EXPECT_GE(b, mem.data() + off) << "the planner lives in the caller's arena";
      EXPECT_LT(b, mem.data() + off + fp);
      EXPECT_NE(tdo_planner_grid(p), nullptr);
      EXPECT_NE(tdo_planner_search(p), nullptr);
    }
  }
}

TEST(Planner, GivenZeroCapacities_WhenInit_ThenInvalidArgument) {
  std::vector<unsigned char> mem(1u << 20);
  const tdo_planner_config zero = config(tdo_capacity{});
  tdo_planner* p = nullptr;
  EXPECT_EQ(tdo_planner_init(&p, mem.data(), mem.size(), &zero), TDO_ERR_INVALID_ARGUMENT);
  for (int field = 0; field < 3; ++field) {
    tdo_planner_config cfg = small_config();
    if (field == 0) cfg.cap.max_voxels = 0;
    if (field == 1) cfg.cap.max_nodes = 0;
    if (field == 2) cfg.cap.max_path = 0;
    EXPECT_EQ(tdo_planner_init(&p, mem.data(), mem.size(), &cfg), TDO_ERR_INVALID_ARGUMENT)
        << "field " << field;
  }
}

TEST(Planner, GivenNullArguments_WhenInit_ThenInvalidArgument) {
  const tdo_planner_config cfg = small_config();
  std::vector<unsigned char> mem(tdo_planner_footprint(&cfg));
  tdo_planner* p = nullptr;
  EXPECT_EQ(tdo_planner_init(nullptr, mem.data(), mem.size(), &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_planner_init(&p, nullptr, mem.size(), &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_planner_init(&p, mem.data(), mem.size(), nullptr), TDO_ERR_INVALID_ARGUMENT);
}

// A planner used at every capacity at once must stay inside its footprint: canary bytes after the
// arena survive a full map, the widest clearance stencil and searches that fill the node pools.
TEST(Planner, GivenAPlannerUsedAtFullCapacity_WhenDone_ThenNothingOutsideTheArenaChanged) {
  const int32_t nx = 12, ny = 10, nz = 8;
  const uint32_t n = static_cast<uint32_t>(nx * ny * nz);
  const double clearance = 1.2;  // K = ceil(1.2 + 0.5) = 2: a 5^3 stencil
  const tdo_planner_config cfg = config(make_cap(n, 27u * n, n + 1u, 6, 125, 1u << 30));
  const size_t fp = tdo_planner_footprint(&cfg);
  ASSERT_GT(fp, 0u);
  const size_t canary = 256;
  std::vector<unsigned char> mem(fp + canary, 0xA5u);
  tdo_planner* p = nullptr;
  ASSERT_EQ(tdo_planner_init(&p, mem.data(), fp, &cfg), TDO_OK);
  tdo_grid* g = tdo_planner_grid(p);
  tdo_grid_desc d{nx, ny, nz, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
  for (int b = 0; b < 6; ++b) {
    const double x = 2.0 + 1.5 * b;
    const tdo_box box{tdo_vec3{x, 2.0, 3.0}, tdo_vec3{x + 0.3, 2.6, 3.7}};
    ASSERT_EQ(tdo_grid_add_box(g, &box), TDO_OK);
  }
  ASSERT_EQ(tdo_grid_add_voxel(g, 6, 7, 2), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(g, clearance), TDO_OK);
  tdo_search_output out{};
  for (int kind = 0; kind < 2; ++kind)
    for (double lambda : {0.0, 5.0, 50.0}) {
      const tdo_search_input in = tdo_test::make_input(
          g, tdo_vec3{0.5, 0.5, 0.5}, tdo_vec3{11.5, 9.5, 7.5}, static_cast<tdo_search_kind>(kind),
          lambda, lambda > 0.0 ? 20.0 : 0.0);
      EXPECT_EQ(tdo_search_run(tdo_planner_search(p), &in, &out), TDO_OK)
          << "kind " << kind << " lambda " << lambda;
    }
  for (size_t b = fp; b < mem.size(); ++b)
    ASSERT_EQ(mem[b], 0xA5u) << "byte " << (b - fp) << " after the arena was written";
}

TEST(Capacity, GivenAGrid_WhenCapacityForGrid_ThenVoxelsAndNodesMatchTheDocumentedFormula) {
  tdo_capacity cap{};
  tdo_capacity_for_grid(&cap, 10, 20, 5, 0.0, 1u, 0u);
  EXPECT_EQ(cap.max_voxels, 1000u);
  EXPECT_EQ(cap.max_nodes, 1000u);
  EXPECT_GE(cap.max_path, 10u + 20u + 5u);
  EXPECT_GT(cap.max_expansions, 0u);
  EXPECT_GE(cap.max_clear_cells, 1u);

  tdo_capacity_for_grid(&cap, 10, 20, 5, 0.0, 27u, 0u);
  EXPECT_EQ(cap.max_voxels, 1000u);
  EXPECT_EQ(cap.max_nodes, 27000u);

  EXPECT_EQ(cap.dense_headings, 1u) << "small grids keep the dense heading index";

  // Large grids: plain A*'s pool (one state per voxel) and per-voxel storage (no dense index).
  tdo_capacity_for_grid(&cap, 128, 128, 64, 0.0, 27u, 0u);
  EXPECT_EQ(cap.max_nodes, 128u * 128u * 64u);
  EXPECT_EQ(cap.dense_headings, 0u);
  tdo_capacity_for_grid(&cap, 64, 64, 32, 0.0, 27u, 0u);
  EXPECT_EQ(cap.max_nodes, 1u << 18) << "2^18 states at least once 27 per voxel exceed it";

  tdo_capacity_for_grid(&cap, 10, 20, 5, 0.0, 27u, 5000u);
  EXPECT_EQ(cap.max_nodes, 5000u) << "node_cap caps max_nodes";
  tdo_capacity_for_grid(&cap, 10, 20, 5, 0.0, 1u, 5000u);
  EXPECT_EQ(cap.max_nodes, 1000u) << "node_cap only caps, never raises";
}

// config.h: a turn-penalised search gets the retry's tables, and the coarse guide from
// TDO_GUIDE_MIN_VOXELS voxels on; a plain one neither; nothing else of the capacity changes.
TEST(Capacity, GivenAGridSize_WhenCapacityGuide_ThenTablesAndTheGuideAsDocumented) {
  tdo_capacity cap;
  std::memset(&cap, 0x5A, sizeof(cap));
  const tdo_capacity before = cap;
  tdo_capacity_guide(&cap, 20, 20, 20, 1);
  EXPECT_EQ(cap.exact_heuristic, 1u);
  EXPECT_EQ(cap.guide_shift, 0u) << "Map1-sized grids are not guided";
  tdo_capacity rest = cap;
  rest.exact_heuristic = before.exact_heuristic;
  rest.guide_shift = before.guide_shift;
  EXPECT_EQ(std::memcmp(&rest, &before, sizeof(cap)), 0) << "other fields changed";

  // The threshold, 2^19 voxels: one voxel short (2^19 - 1 is prime: a 1 x 1 x n grid) and at it.
  tdo_capacity_guide(&cap, 1, 1, static_cast<int32_t>(TDO_GUIDE_MIN_VOXELS - 1u), 1);
  EXPECT_EQ(cap.guide_shift, 0u);
  tdo_capacity_guide(&cap, 1, 1, static_cast<int32_t>(TDO_GUIDE_MIN_VOXELS), 1);
  EXPECT_EQ(cap.guide_shift, 2u);
  tdo_capacity_guide(&cap, 128, 64, 64, 1);
  EXPECT_EQ(cap.guide_shift, 2u);
  EXPECT_EQ(cap.exact_heuristic, 1u);
  tdo_capacity_guide(&cap, 2000, 2000, 1000, 1);  // 4e9 voxels: no 32-bit overflow
  EXPECT_EQ(cap.guide_shift, 2u);

  // Plain searches: neither, whatever was set before and however large the grid.
  tdo_capacity_guide(&cap, 128, 64, 64, 0);
  EXPECT_EQ(cap.exact_heuristic, 0u);
  EXPECT_EQ(cap.guide_shift, 0u);
  // No grid: neither; no capacity: nothing happens.
  for (int32_t bad : {0, -1}) {
    cap.exact_heuristic = cap.guide_shift = 7u;
    tdo_capacity_guide(&cap, bad, 64, 64, 1);
    EXPECT_EQ(cap.exact_heuristic, 0u);
    EXPECT_EQ(cap.guide_shift, 0u);
  }
  tdo_capacity_guide(nullptr, 8, 8, 8, 1);
}

// tdo_capacity_for_grid takes the same rule for heading states (27 headings) and none for plain
// searches, on both sides of the guide's threshold; a voxel-state planner (1 heading) that asks
// tdo_capacity_guide gets the guide's cells in its footprint (tdo-plan's and tdo-bench-scale's
// voxel states on large grids).
TEST(Capacity, GivenCapacityForGrid_WhenComparedWithCapacityGuide_ThenTheSameRule) {
  const int32_t sizes[][3] = {{20, 20, 20}, {50, 50, 20}, {128, 64, 63}, {128, 64, 64}};
  for (const auto& n : sizes) {
    for (uint32_t headings : {1u, 27u}) {
      tdo_capacity a{}, b{};
      tdo_capacity_for_grid(&a, n[0], n[1], n[2], 0.5, headings, 0u);
      b = a;
      tdo_capacity_guide(&b, n[0], n[1], n[2], headings == 27u ? 1 : 0);
      EXPECT_EQ(std::memcmp(&a, &b, sizeof(a)), 0) << n[0] << "x" << n[1] << "x" << n[2];
    }
  }
  tdo_planner_config plain{}, guided{};
  tdo_capacity_for_grid(&plain.cap, 128, 64, 64, 0.5, 1u, 0u);
  plain.cap.max_boxes = 1u;
  plain.cap.exact_heuristic = 1u;  // as the guide sets it: only guide_shift differs
  guided = plain;
  tdo_capacity_guide(&guided.cap, 128, 64, 64, 1);
  ASSERT_EQ(guided.cap.guide_shift, 2u);
  EXPECT_GT(tdo_planner_footprint(&guided), tdo_planner_footprint(&plain));
}

TEST(Capacity, GivenAClearanceRatio_WhenCapacityForGrid_ThenTheStencilCoversIt) {
  // config.h: (2K+1)^3 with K = ceil(clearance/res + 0.5) covers a clearance.
  const double ratios[] = {0.0, 0.3, 0.5, 1.0, 1.7, 3.0};
  for (double r : ratios) {
    tdo_capacity cap{};
    tdo_capacity_for_grid(&cap, 16, 16, 16, r, 1u, 0u);
    const uint32_t k = static_cast<uint32_t>(std::ceil(r + 0.5));
    EXPECT_GE(cap.max_clear_cells, (2u * k + 1u) * (2u * k + 1u) * (2u * k + 1u)) << "ratio " << r;
  }
}

// A planner sized by tdo_capacity_for_grid can load a voxel map of that grid at that clearance and
// plan corner to corner on it with both searches, with and without turn costs.
TEST(Capacity, GivenCapacityForGrid_WhenPlanningOnThatGrid_ThenEverythingFits) {
  const int32_t nx = 14, ny = 9, nz = 6;
  const double res = 0.5, ratio = 1.5;
  for (uint32_t headings : {1u, 27u}) {
    tdo_capacity cap{};
    tdo_capacity_for_grid(&cap, nx, ny, nz, ratio, headings, 0u);
    tdo_test::TestPlanner pl(cap);
    ASSERT_EQ(pl.status(), TDO_OK);
    tdo_test::VoxelMap m(nx, ny, nz, res, tdo_vec3{-1.0, 2.0, 0.0});
    m.set(7, 4, 3);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m, ratio * res), TDO_OK) << "headings " << headings;
    tdo_search_output out{};
    for (int kind = 0; kind < 2; ++kind) {
      const double lambda = headings > 1u ? 50.0 : 0.0;
      const tdo_search_input in = tdo_test::make_input(
          pl.grid(), m.center(tdo_voxel{0, 0, 0}), m.center(tdo_voxel{nx - 1, ny - 1, nz - 1}),
          static_cast<tdo_search_kind>(kind), lambda, headings > 1u ? 20.0 : 0.0);
      EXPECT_EQ(tdo_search_run(pl.search(), &in, &out), TDO_OK)
          << "headings " << headings << " kind " << kind;
    }
  }
}

}  // namespace
