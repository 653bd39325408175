// Stage 1 search (search.h, docs/design.md s.0-1): optimal costs against an independent reference
// Dijkstra, path validity, named statuses, budgets and capacities, determinism, and completeness
// with turn penalties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <queue>
#include <utility>
#include <vector>

#include "../../libtdo/src/search_tables.h"
#include "rng.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::kInf;
using tdo_test::make_cap;
using tdo_test::make_input;
using tdo_test::near_rel;
using tdo_test::Rng;
using tdo_test::TestPlanner;
using tdo_test::VoxelMap;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfty = std::numeric_limits<double>::infinity();
const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);
constexpr tdo_search_kind kKinds[] = {TDO_SEARCH_ASTAR, TDO_SEARCH_BIDIR};

uint64_t bits(double d) {
  uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return u;
}

/** A stored copy of one search result (out.path only lives until the next run). */
struct Result {
  tdo_status status = TDO_ERR_INVALID_ARGUMENT;
  tdo_search_output out{};
  std::vector<tdo_voxel> path;
};

Result run(tdo_search* s, const tdo_search_input& in) {
  Result r;
  r.status = tdo_search_run(s, &in, &r.out);
  if (r.status == TDO_OK && r.out.path != nullptr)
    r.path.assign(r.out.path, r.out.path + r.out.n_path);
  r.out.path = r.path.empty() ? nullptr : r.path.data();
  return r;
}

::testing::AssertionResult identical(const Result& a, const Result& b) {
  if (a.status != b.status)
    return ::testing::AssertionFailure()
           << "status " << tdo_status_str(a.status) << " vs " << tdo_status_str(b.status);
  if (a.out.expansions != b.out.expansions)
    return ::testing::AssertionFailure()
           << "expansions " << a.out.expansions << " vs " << b.out.expansions;
  if (bits(a.out.cost) != bits(b.out.cost) ||
      bits(a.out.penalized_cost) != bits(b.out.penalized_cost))
    return ::testing::AssertionFailure() << "cost " << a.out.cost << " vs " << b.out.cost;
  if (a.path.size() != b.path.size())
    return ::testing::AssertionFailure()
           << "path length " << a.path.size() << " vs " << b.path.size();
  for (size_t n = 0; n < a.path.size(); ++n)
    if (!tdo_test::same_voxel(a.path[n], b.path[n]))
      return ::testing::AssertionFailure() << "path differs at " << n;
  return ::testing::AssertionSuccess();
}

/** One random query on a random voxel map. */
struct Case {
  VoxelMap map;
  tdo_voxel s{}, g{};
  tdo_vec3 ps{}, pg{};
};

/** Random grid up to 9x9x5 with density in [0, 0.4]; start and goal are distinct free voxels. */
Case random_case(Rng& rng, int32_t max_xy = 9, int32_t max_z = 5) {
  const double resolutions[] = {1.0, 0.5, 0.3, 2.0};
  for (;;) {
    Case c;
    const int32_t nx = rng.range(1, max_xy), ny = rng.range(1, max_xy), nz = rng.range(1, max_z);
    const double density = rng.uniform(0.0, 0.4);
    c.map = tdo_test::random_voxel_map(rng, nx, ny, nz, resolutions[rng.below(4)], density);
    if (rng.uniform() < 0.1 && nx >= 3) {  // a wall across x: often splits the map in two
      const int32_t x = rng.range(1, nx - 2);
      for (int32_t k = 0; k < nz; ++k)
        for (int32_t j = 0; j < ny; ++j) c.map.set(x, j, k);
    }
    std::vector<size_t> free;
    for (size_t n = 0; n < c.map.size(); ++n)
      if (!c.map.blocked[n]) free.push_back(n);
    if (free.size() < 2) continue;
    const size_t a = free[rng.below(static_cast<uint32_t>(free.size()))];
    size_t b = a;
    while (b == a) b = free[rng.below(static_cast<uint32_t>(free.size()))];
    c.s = c.map.voxel(a);
    c.g = c.map.voxel(b);
    if (rng.uniform() < 0.3) {
      c.ps = c.map.center(c.s);
      c.pg = c.map.center(c.g);
    } else {
      c.ps = c.map.point_in(c.s, rng.uniform(0.02, 0.98), rng.uniform(0.02, 0.98),
                            rng.uniform(0.02, 0.98));
      c.pg = c.map.point_in(c.g, rng.uniform(0.02, 0.98), rng.uniform(0.02, 0.98),
                            rng.uniform(0.02, 0.98));
    }
    return c;
  }
}

class SearchTest : public ::testing::Test {
 protected:
  SearchTest() : pl_(make_cap(1024, 1024, 1025, 64, 20000, 1u << 30)) {}
  void SetUp() override { ASSERT_EQ(pl_.status(), TDO_OK); }
  tdo_grid* grid() { return pl_.grid(); }
  tdo_search* search() { return pl_.search(); }
  void load(const VoxelMap& m, double clearance = 0.0) {
    ASSERT_EQ(tdo_test::load_voxels(grid(), m, clearance), TDO_OK);
  }

  TestPlanner pl_;
};

// ---------------------------------------------------------------------------------------------
// Known answers, worked out by hand.

TEST_F(SearchTest, GivenAnEmptyGrid_WhenSearching_ThenCostsAreOctileDistances) {
  struct Q {
    tdo_voxel s, g;
    double cost;  // in voxel edges
  };
  const Q qs[] = {
      {{0, 0, 0}, {2, 2, 2}, 2.0 * kSqrt3}, {{0, 0, 0}, {2, 1, 0}, 1.0 + kSqrt2},
      {{0, 0, 0}, {2, 0, 0}, 2.0},          {{2, 0, 1}, {0, 2, 0}, kSqrt3 + kSqrt2},
      {{0, 0, 0}, {1, 0, 0}, 1.0},          {{0, 1, 2}, {1, 2, 1}, kSqrt3},
  };
  for (double res : {1.0, 0.5}) {
    const VoxelMap m(3, 3, 3, res, tdo_vec3{-1.0, 0.0, 2.0});
    load(m);
    for (const Q& q : qs)
      for (tdo_search_kind kind : kKinds) {
        const Result r = run(search(), make_input(grid(), m.center(q.s), m.center(q.g), kind));
        ASSERT_EQ(r.status, TDO_OK) << tdo_test::kind_name(kind);
        EXPECT_NEAR(r.out.cost, q.cost * res, 1e-12) << tdo_test::kind_name(kind);
        EXPECT_TRUE(tdo_test::valid_path(m, r.out, q.s, q.g));
      }
  }
}

TEST_F(SearchTest, GivenABlockedCornerIn2D_WhenSearchingDiagonally_ThenTheDiagonalIsNotTaken) {
  VoxelMap m(2, 2, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  m.set(1, 0, 0);
  load(m);
  for (tdo_search_kind kind : kKinds) {
    const Result r =
        run(search(), make_input(grid(), m.center({0, 0, 0}), m.center({1, 1, 0}), kind));
    ASSERT_EQ(r.status, TDO_OK);
    EXPECT_NEAR(r.out.cost, 2.0, 1e-12) << "no corner cutting: around via (0,1,0)";
    EXPECT_EQ(r.out.n_path, 3u);
  }
  m.set(0, 1, 0);
  load(m);
  for (tdo_search_kind kind : kKinds) {
    const Result r =
        run(search(), make_input(grid(), m.center({0, 0, 0}), m.center({1, 1, 0}), kind));
    EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << "the diagonal between two blocked voxels is closed";
  }
}

TEST_F(SearchTest, GivenOneBlockedVoxelOfA2x2x2Block_WhenSearchingTheCornerDiagonal_ThenItDetours) {
  VoxelMap m(2, 2, 2, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  m.set(1, 0, 0);
  load(m);
  for (tdo_search_kind kind : kKinds) {
    const Result r =
        run(search(), make_input(grid(), m.center({0, 0, 0}), m.center({1, 1, 1}), kind));
    ASSERT_EQ(r.status, TDO_OK);
    EXPECT_NEAR(r.out.cost, 1.0 + kSqrt2, 1e-12) << "no edge cutting through the 2x2x2 block";
    EXPECT_TRUE(tdo_test::valid_path(m, r.out, {0, 0, 0}, {1, 1, 1}));
  }
}

// ---------------------------------------------------------------------------------------------
// (a) optimal costs, (b) valid paths, (d) determinism, (e) expansions: seeded random grids.

TEST_F(SearchTest, GivenRandomGrids_WhenSearchingWithoutPenalties_ThenCostsMatchReferenceDijkstra) {
  Rng rng(0x7D0A5EA7C4ull);
  int reachable = 0, unreachable = 0;
  for (int round = 0; round < 1000; ++round) {
    const Case c = random_case(rng);
    load(c.map);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    const uint32_t n_free = c.map.free_count();
    (want < kInf ? reachable : unreachable)++;
    for (tdo_search_kind kind : kKinds) {
      const tdo_search_input in = make_input(grid(), c.ps, c.pg, kind);
      const Result r = run(search(), in);
      SCOPED_TRACE(::testing::Message()
                   << "round " << round << " " << tdo_test::kind_name(kind) << " grid " << c.map.nx
                   << "x" << c.map.ny << "x" << c.map.nz << " start " << tdo_test::str(c.s)
                   << " goal " << tdo_test::str(c.g));
      if (!(want < kInf)) {
        EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
      } else {
        ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status) << ", reference cost " << want;
        EXPECT_TRUE(near_rel(r.out.cost, want)) << "cost " << r.out.cost << " reference " << want;
        EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
        EXPECT_TRUE(near_rel(r.out.penalized_cost, r.out.cost))
            << "no penalties: penalized_cost " << r.out.penalized_cost << " cost " << r.out.cost;
      }
      // (e) one state per voxel without penalties: per direction, no voxel expanded twice.
      const uint32_t sides = kind == TDO_SEARCH_ASTAR ? 1u : 2u;
      EXPECT_LE(r.out.expansions, sides * n_free) << "free voxels " << n_free;
      // (d) the same query again gives the same answer.
      EXPECT_TRUE(identical(r, run(search(), in)));
    }
  }
  EXPECT_GE(reachable, 600);
  EXPECT_GE(unreachable, 50);
}

// Boxes plus clearance: the reference uses the brute-force blocked set (test_util.h).
TEST_F(SearchTest, GivenRandomBoxMapsWithClearance_WhenSearching_ThenCostsMatchReference) {
  Rng rng(99);
  int reachable = 0;
  for (int round = 0; round < 300; ++round) {
    const double res = rng.uniform() < 0.5 ? 1.0 : 0.5;
    VoxelMap m(rng.range(3, 10), rng.range(3, 10), rng.range(1, 5), res,
               tdo_vec3{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)});
    tdo_test::Obstacles obs;
    const int n_boxes = rng.range(1, 5);
    for (int b = 0; b < n_boxes; ++b) {
      const tdo_vec3 lo{m.origin.x + rng.uniform(0.0, m.nx * res),
                        m.origin.y + rng.uniform(0.0, m.ny * res),
                        m.origin.z + rng.uniform(0.0, m.nz * res)};
      obs.boxes.push_back(
          tdo_box{lo, tdo_vec3{lo.x + rng.uniform(0.1, 3.0), lo.y + rng.uniform(0.1, 3.0),
                               lo.z + rng.uniform(0.1, 3.0)}});
    }
    const double clearance = rng.uniform(0.0, 1.2);
    ASSERT_EQ(tdo_test::load_obstacles(grid(), m, obs, clearance), TDO_OK);
    m.blocked = tdo_test::brute_blocked(m, obs, clearance);
    std::vector<size_t> free;
    for (size_t n = 0; n < m.size(); ++n)
      if (!m.blocked[n]) free.push_back(n);
    if (free.size() < 2) continue;
    const tdo_voxel s = m.voxel(free[rng.below(static_cast<uint32_t>(free.size()))]);
    const tdo_voxel g = m.voxel(free[rng.below(static_cast<uint32_t>(free.size()))]);
    if (tdo_test::same_voxel(s, g)) continue;
    const double want = tdo_test::reference_cost(m, s, g);
    reachable += want < kInf ? 1 : 0;
    for (tdo_search_kind kind : kKinds) {
      const Result r = run(search(), make_input(grid(), m.center(s), m.center(g), kind));
      SCOPED_TRACE(::testing::Message() << "round " << round << " " << tdo_test::kind_name(kind));
      if (!(want < kInf)) {
        EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
      } else {
        ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
        EXPECT_TRUE(near_rel(r.out.cost, want)) << r.out.cost << " vs " << want;
        EXPECT_TRUE(tdo_test::valid_path(m, r.out, s, g));
      }
    }
  }
  EXPECT_GE(reachable, 100);
}

// (e) again, as a capacity: a node pool of one state per free voxel is enough without penalties.
TEST(SearchCapacity,
     GivenANodePoolOfOneStatePerFreeVoxel_WhenSearchingWithoutPenalties_ThenItFits) {
  Rng rng(4242);
  for (int round = 0; round < 200; ++round) {
    const Case c = random_case(rng, 8, 4);
    const uint32_t n_free = c.map.free_count();
    TestPlanner pl(make_cap(static_cast<uint32_t>(c.map.size()), n_free,
                            static_cast<uint32_t>(c.map.size()) + 1u, 4, 1000, 1u << 30));
    ASSERT_EQ(pl.status(), TDO_OK);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    for (tdo_search_kind kind : kKinds) {
      const Result r = run(pl.search(), make_input(pl.grid(), c.ps, c.pg, kind));
      SCOPED_TRACE(::testing::Message() << "round " << round << " " << tdo_test::kind_name(kind)
                                        << " free voxels " << n_free);
      EXPECT_EQ(r.status, want < kInf ? TDO_OK : TDO_ERR_NO_PATH) << tdo_status_str(r.status);
      if (r.status == TDO_OK) {
        EXPECT_TRUE(near_rel(r.out.cost, want));
      }
    }
  }
}

// (d) determinism across interleaved queries and across planner instances at other addresses.
TEST(SearchDeterminism,
     GivenTheSameQueries_WhenRepeatedInterleavedOrOnAnotherPlanner_ThenIdentical) {
  Rng rng(5);
  VoxelMap m = tdo_test::random_voxel_map(rng, 12, 11, 6, 0.5, 0.25);
  const tdo_capacity cap = make_cap(1024, 27u * 1024u, 1025, 4, 1000, 1u << 30);
  TestPlanner a(cap);
  ASSERT_EQ(a.status(), TDO_OK);
  ASSERT_EQ(tdo_test::load_voxels(a.grid(), m), TDO_OK);
  std::vector<tdo_search_input> queries;
  for (int q = 0; q < 40; ++q) {
    const tdo_vec3 s =
        m.point_in({rng.range(0, 11), rng.range(0, 10), rng.range(0, 5)}, rng.uniform(0.1, 0.9),
                   rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9));
    const tdo_vec3 g =
        m.point_in({rng.range(0, 11), rng.range(0, 10), rng.range(0, 5)}, rng.uniform(0.1, 0.9),
                   rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9));
    const double lambda = q % 3 == 0 ? 0.0 : (q % 3 == 1 ? 2.0 : 50.0);
    queries.push_back(make_input(a.grid(), s, g, kKinds[q % 2], lambda, q % 4 == 0 ? 0.0 : 20.0,
                                 q % 7 == 0 ? 40u : 0u));
  }
  std::vector<Result> first;
  int ok = 0;
  for (const tdo_search_input& in : queries) {
    first.push_back(run(a.search(), in));
    ok += first.back().status == TDO_OK ? 1 : 0;
  }
  ASSERT_GE(ok, 10) << "the map should allow most queries";
  for (size_t q = queries.size(); q-- > 0;)
    EXPECT_TRUE(identical(first[q], run(a.search(), queries[q]))) << "reverse order, query " << q;

  TestPlanner b(cap);
  ASSERT_EQ(b.status(), TDO_OK);
  ASSERT_EQ(tdo_test::load_voxels(b.grid(), m), TDO_OK);
  for (size_t q = 0; q < queries.size(); ++q) {
    tdo_search_input in = queries[q];
    in.grid = b.grid();
    EXPECT_TRUE(identical(first[q], run(b.search(), in))) << "second planner, query " << q;
  }
}

// ---------------------------------------------------------------------------------------------
// (f) turn penalties keep completeness; cost is never below the optimum.

// Direction constraints of docs/design.md s.1: unconstrained, theta_max = 45 degrees (the default),
// and 45 degrees plus the deviation threshold D_th = 0.5.
struct Constraint {
  double theta_max;  // rad
  double d_th;
};
const std::vector<Constraint> kUnconstrained = {{0.0, 0.0}};
const std::vector<Constraint> kConstrained = {{0.25 * 3.14159265358979323846, 0.0},
                                              {0.25 * 3.14159265358979323846, 0.5}};

void check_penalised(tdo_search* search, const tdo_grid* grid, const Case& c, double want,
                     const char* what, const std::vector<Constraint>& constraints,
                     int states = TDO_STATES_HEADING) {
  for (double lambda : {0.5, 50.0})
    for (double mu : {0.0, 20.0})
      for (const Constraint& con : constraints)
        for (tdo_search_kind kind : kKinds) {
          tdo_search_input in = make_input(grid, c.ps, c.pg, kind, lambda, mu);
          in.theta_max = con.theta_max;
          in.d_th = con.d_th;
          in.states = states;
          const Result r = run(search, in);
          SCOPED_TRACE(::testing::Message()
                       << what << " " << tdo_test::kind_name(kind) << " lambda " << lambda << " mu "
                       << mu << " theta_max " << con.theta_max << " d_th " << con.d_th << " states "
                       << states << " start " << tdo_test::str(c.s) << " goal "
                       << tdo_test::str(c.g));
          if (!(want < kInf)) {
            EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
            continue;
          }
          ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status) << ": lambda = 0 finds a path";
          EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
          EXPECT_GE(r.out.cost, want * (1.0 - 1e-9)) << "below the optimal length";
          // penalized_cost = length + lambda * sum (theta_i/pi)^2 + one surcharge per pivot (a
          // sharp turn, taken in place); every turn of the voxel path is paid exactly once.
          const double turns = tdo_test::turn_penalty(r.out, lambda);
          const double surcharge = r.out.pivots * tdo_search_pivot_cost(lambda, con.theta_max);
          EXPECT_TRUE(near_rel(r.out.penalized_cost, r.out.cost + turns + surcharge))
              << "penalized_cost " << r.out.penalized_cost << " != cost " << r.out.cost
              << " + lambda * sum (theta/pi)^2 = " << turns << " + " << r.out.pivots
              << " pivots * surcharge";
        }
}

// Voxel states (tdo_search_input.states) need one state per voxel and direction: their pool is
// sized as plain A*'s, so a heading state would overflow it.
uint32_t pool_for(int states) { return states == TDO_STATES_VOXEL ? 512u : 27u * 512u; }

void random_penalised(const std::vector<Constraint>& constraints, int states = TDO_STATES_HEADING) {
  TestPlanner pl(make_cap(512, pool_for(states), 513, 4, 1000, 1u << 30));
  ASSERT_EQ(pl.status(), TDO_OK);
  Rng rng(31337);
  for (int round = 0; round < 400; ++round) {
    const Case c = random_case(rng, 8, 4);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    check_penalised(pl.search(), pl.grid(), c, want, "random", constraints, states);
  }
}

void narrow_penalised(const std::vector<Constraint>& constraints, int states = TDO_STATES_HEADING) {
  TestPlanner pl(make_cap(512, pool_for(states), 513, 4, 1000, 1u << 30));
  ASSERT_EQ(pl.status(), TDO_OK);
  {
    // A 2D serpentine: walls at y = 1, 3, 5, 7 with one-voxel gaps alternating at x = 8 and x = 0,
    // so every gap forces a U-turn.
    Case c;
    c.map = VoxelMap(9, 9, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
    for (int32_t y : {1, 3, 5, 7})
      for (int32_t x = 0; x < 9; ++x)
        if (x != ((y / 2) % 2 == 0 ? 8 : 0)) c.map.set(x, y, 0);
    c.s = {0, 0, 0};
    c.g = {0, 8, 0};
    c.ps = c.map.center(c.s);
    c.pg = c.map.center(c.g);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    ASSERT_LT(want, kInf);
    check_penalised(pl.search(), pl.grid(), c, want, "serpentine", constraints, states);
  }
  {
    // 3D: floors at z = 2 and z = 5 with single holes in opposite corners, start behind the goal.
    Case c;
    c.map = VoxelMap(5, 5, 8, 1.0, tdo_vec3{0.0, 0.0, 0.0});
    for (int32_t y = 0; y < 5; ++y)
      for (int32_t x = 0; x < 5; ++x) {
        if (!(x == 4 && y == 4)) c.map.set(x, y, 2);
        if (!(x == 0 && y == 0)) c.map.set(x, y, 5);
      }
    c.s = {1, 1, 0};
    c.g = {1, 1, 7};
    c.ps = c.map.center(c.s);
    c.pg = c.map.center(c.g);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    ASSERT_LT(want, kInf);
    check_penalised(pl.search(), pl.grid(), c, want, "shafts", constraints, states);
  }
  {
    // A straight row meeting a two-voxel-wide diagonal corridor at 135 degrees: an acute turn.
    Case c;
    c.map = VoxelMap(8, 6, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
    for (int32_t y = 0; y < 6; ++y)
      for (int32_t x = 0; x < 8; ++x) {
        const bool row = y == 0 && x <= 6;
        const bool diagonal = y >= 1 && (x + y == 6 || x + y == 7);
        c.map.set(x, y, 0, !(row || diagonal));
      }
    c.s = {0, 0, 0};
    c.g = {1, 5, 0};
    c.ps = c.map.center(c.s);
    c.pg = c.map.center(c.g);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    ASSERT_LT(want, kInf);
    check_penalised(pl.search(), pl.grid(), c, want, "acute", constraints, states);
  }
}

TEST(SearchPenalty,
     GivenRandomGrids_WhenSearchingWithTurnPenalties_ThenAPathIsFoundWheneverOneExists) {
  random_penalised(kUnconstrained);
}

// Random grids of up to 8 x 8 x 4 voxels, the optimal stop (first_meet = 0), mu = 0 and no
// direction constraint: both kinds must return the optimal turn-penalised cost of the test's own
// reference (or no_path where it finds none) in their first try. Returns how many of the queries
// with lambda > 10 have a path.
int optimal_penalised_rounds(TestPlanner& pl, uint64_t seed, int rounds,
                             std::initializer_list<double> lambdas, int grid_first) {
  Rng rng(seed);
  int reachable = 0;
  for (int round = 0; round < rounds; ++round) {
    const Case c = random_case(rng, 8, 4);
    EXPECT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    for (double lambda : lambdas) {
      const double want = tdo_test::reference_penalised_cost(c.map, c.s, c.g, lambda);
      if (want < kInf && lambda > 10.0) ++reachable;
      for (tdo_search_kind kind : kKinds) {
        tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, kind, lambda, 0.0);
        in.first_meet = 0;
        in.grid_first = grid_first;
        const Result r = run(pl.search(), in);
        SCOPED_TRACE(::testing::Message() << "round " << round << " " << tdo_test::kind_name(kind)
                                          << " lambda " << lambda << " start " << tdo_test::str(c.s)
                                          << " goal " << tdo_test::str(c.g));
        if (!(want < kInf)) {
          EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
          continue;
        }
        EXPECT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
        EXPECT_EQ(r.out.fallback, 0u);
        EXPECT_TRUE(near_rel(r.out.penalized_cost, want))
            << "penalized_cost " << r.out.penalized_cost << " reference " << want;
      }
    }
    if (::testing::Test::HasFailure()) break;
  }
  return reachable;
}

// The optimal stop (first_meet = 0) with mu = 0 and no direction constraint must return the
// optimal turn-penalised cost, so the turn part of h must stay a lower bound (docs/design.md s.1).
TEST(SearchPenalty, GivenRandomGrids_WhenSearchingWithTheOptimalStop_ThenPenalisedCostsAreOptimal) {
  TestPlanner pl(make_cap(512, 27u * 512u, 513, 4, 1000, 1u << 30));
  ASSERT_EQ(pl.status(), TDO_OK);
  EXPECT_GE(optimal_penalised_rounds(pl, 0x0D71A1ull, 3000, {0.5, 5.0, 50.0}, TDO_GRID_FIRST_OFF),
            1500);
}

TEST(SearchPenalty, GivenNarrowPassagesNeedingSharpTurns_WhenSearchingWithPenalties_ThenPathFound) {
  narrow_penalised(kUnconstrained);
}

// docs/design.md s.1: the direction constraint (theta_max) and the deviation threshold (D_th) must
// never cost completeness, and a pivot must not make a turn cheaper than lambda * (theta/pi)^2.
TEST(SearchConstrained,
     GivenRandomGrids_WhenSearchingWithDirectionConstraints_ThenAPathIsFoundWheneverOneExists) {
  random_penalised(kConstrained);
}

TEST(SearchConstrained,
     GivenNarrowPassagesNeedingSharpTurns_WhenSearchingWithDirectionConstraints_ThenPathFound) {
  narrow_penalised(kConstrained);
}

// Voxel states: the same completeness on the same maps, with plain A*'s pool (one state per
// voxel), with and without the direction constraint (a sharp step costs the pivot surcharge).
TEST(SearchVoxelStates,
     GivenRandomGridsAndAnAStarPool_WhenSearchingWithVoxelStates_ThenAPathWheneverOneExists) {
  random_penalised(kUnconstrained, TDO_STATES_VOXEL);
  random_penalised(kConstrained, TDO_STATES_VOXEL);
}

TEST(SearchVoxelStates,
     GivenNarrowPassagesAndAnAStarPool_WhenSearchingWithVoxelStates_ThenAPathIsFound) {
  narrow_penalised(kUnconstrained, TDO_STATES_VOXEL);
  narrow_penalised(kConstrained, TDO_STATES_VOXEL);
}

TEST(SearchVoxelStates, GivenAStateSpaceOutOfRange_WhenSearching_ThenInvalidArgument) {
  TestPlanner pl(make_cap(512, 512u, 513, 4, 1000, 1u << 30));
  ASSERT_EQ(pl.status(), TDO_OK);
  Case c;
  c.map = VoxelMap(8, 8, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  c.ps = c.map.center({0, 0, 0});
  c.pg = c.map.center({7, 7, 0});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
  for (int states : {-1, 2}) {
    tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
    in.states = states;
    EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_INVALID_ARGUMENT) << "states " << states;
  }
  tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
  in.states = TDO_STATES_VOXEL;
  const Result r = run(pl.search(), in);
  EXPECT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
  EXPECT_LE(r.out.peak_nodes, 64u) << "one state per voxel at most";
}

// Capacities of the flood tests for n voxels, with the obstacle-aware retry: 27 states per voxel,
// or in the 16-bit build the largest pool (2^15 - 1 per direction). The walls test fills it (a
// full pool starts the retry as a spent budget share does, so the retry's Dijkstra runs with
// 16-bit indices too); the pillar field fits, because partial expansion creates about as many
// states as the search expands.
tdo_capacity retry_cap(uint32_t n) {
#if defined(TDO_SEARCH_INDEX16)
  tdo_capacity cap = make_cap(n, 0x7FFFu, n + 1u);
#else
  tdo_capacity cap = make_cap(n, 27u * n, n + 1u);
#endif
  cap.exact_heuristic = 1u;
  return cap;
}

// 64 x 32 x 8 voxels crossed by seven full walls whose one-voxel holes alternate between opposite
// corners, start and goal at the two ends (`sealed`: no holes, so no path).
constexpr int32_t kWallsNx = 64, kWallsNy = 32, kWallsNz = 8;
Case walls_with_holes(bool sealed) {
  Case c;
  c.map = VoxelMap(kWallsNx, kWallsNy, kWallsNz, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  for (int32_t x = 8; x < kWallsNx; x += 8) {
    const bool low = (x / 8) % 2 == 1;  // holes alternate between (y, z) = (0, 0) and (31, 7)
    for (int32_t z = 0; z < kWallsNz; ++z)
      for (int32_t y = 0; y < kWallsNy; ++y) {
        const bool hole = low ? (y == 0 && z == 0) : (y == kWallsNy - 1 && z == kWallsNz - 1);
        if (sealed || !hole) c.map.set(x, y, z);
      }
  }
  c.s = {2, 16, 4};
  c.g = {61, 16, 4};
  c.ps = c.map.center(c.s);
  c.pg = c.map.center(c.g);
  return c;
}

// Voxel states with grid_first: the grid-distance tables in h. On random grids a path whenever
// one exists, with the penalised cost recomputed from the path; behind the walls the octile guide
// cannot see, PLAIN (tables, weight 2, no deviation terms) expands fewer states than the octile
// guide, and the sealed walls are no_path either way.
TEST(SearchVoxelStates, GivenGridFirst_WhenSearchingWithVoxelStates_ThenCompleteAndGuidedByTables) {
  const uint32_t n = static_cast<uint32_t>(kWallsNx * kWallsNy * kWallsNz);
  tdo_capacity cap = make_cap(n, n, n + 1u);
  cap.exact_heuristic = 1u;
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  Rng rng(4242);
  for (int round = 0; round < 200; ++round) {
    const Case c = random_case(rng, 8, 4);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double want = tdo_test::reference_cost(c.map, c.s, c.g);
    for (int first : {TDO_GRID_FIRST_PLAIN, TDO_GRID_FIRST_TERMS}) {
      tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
      in.theta_max = 0.25 * 3.14159265358979323846;
      in.states = TDO_STATES_VOXEL;
      in.grid_first = first;
      const Result r = run(pl.search(), in);
      SCOPED_TRACE(::testing::Message() << "round " << round << " grid_first " << first);
      if (!(want < kInf)) {
        EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
        continue;
      }
      ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
      EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
      const double turns = tdo_test::turn_penalty(r.out, 50.0);
      const double surcharge = r.out.pivots * tdo_search_pivot_cost(50.0, in.theta_max);
      EXPECT_TRUE(near_rel(r.out.penalized_cost, r.out.cost + turns + surcharge));
    }
  }
  for (bool sealed : {false, true}) {
    const Case c = walls_with_holes(sealed);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
    in.states = TDO_STATES_VOXEL;
    const Result octile = run(pl.search(), in);
    in.grid_first = TDO_GRID_FIRST_PLAIN;
    const Result tables = run(pl.search(), in);
    if (sealed) {
      EXPECT_EQ(octile.status, TDO_ERR_NO_PATH);
      EXPECT_EQ(tables.status, TDO_ERR_NO_PATH);
      continue;
    }
    ASSERT_EQ(octile.status, TDO_OK);
    ASSERT_EQ(tables.status, TDO_OK);
    EXPECT_TRUE(tdo_test::valid_path(c.map, tables.out, c.s, c.g));
    EXPECT_LT(tables.out.expansions, octile.out.expansions) << "the tables guide through the holes";
  }
}

// Walls that the octile heuristic cannot see: the turn-penalised search floods behind them, and
// its retry with the obstacle-aware heuristic (tdo_search_output.fallback) must still find a valid
// path, deterministically; plain searches never retry and stay optimal.
TEST(SearchPenalty, GivenWallsWithHolesInOppositeCorners_WhenTheOctileTryFloods_ThenARetryFinds) {
  TestPlanner pl(retry_cap(static_cast<uint32_t>(kWallsNx * kWallsNy * kWallsNz)));
  ASSERT_EQ(pl.status(), TDO_OK);
  const Case c = walls_with_holes(false);
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
  const double want = tdo_test::reference_cost(c.map, c.s, c.g);
  ASSERT_LT(want, kInf);
  for (tdo_search_kind kind : kKinds) {
    SCOPED_TRACE(tdo_test::kind_name(kind));
    const Result plain = run(pl.search(), make_input(pl.grid(), c.ps, c.pg, kind));
    ASSERT_EQ(plain.status, TDO_OK);
    EXPECT_EQ(plain.out.fallback, 0u);
    EXPECT_TRUE(near_rel(plain.out.cost, want)) << plain.out.cost << " vs " << want;
    tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, kind, 50.0, 20.0);
    in.theta_max = 0.25 * 3.14159265358979323846;
    const Result r = run(pl.search(), in);
    ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
    EXPECT_GE(r.out.fallback, 1u) << r.out.expansions << " expansions";
    // The flood is seen early (search.cpp, kTryProbe): the octile try and the retry together
    // expand fewer states than the try alone was given (kTryMin = 20000 on a grid this small).
    EXPECT_LT(r.out.expansions, 20000u) << "the octile try ran to its end before the retry";
    EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
    EXPECT_GE(r.out.cost, want * (1.0 - 1e-9)) << "below the optimal length";
    EXPECT_TRUE(identical(r, run(pl.search(), in))) << "a second run differs";
  }
}

// grid_first skips the octile try: the search starts as the retry would, so on the walls above it
// returns the retry's path (same voxels, same costs) with the octile try's expansions saved; with
// the holes sealed the grid-distance tables show that no path exists; without tables it is refused.
TEST(SearchPenalty, GivenGridFirst_WhenSearchingBehindWalls_ThenTheRetrysPathWithoutTheOctileTry) {
  TestPlanner pl(retry_cap(static_cast<uint32_t>(kWallsNx * kWallsNy * kWallsNz)));
  ASSERT_EQ(pl.status(), TDO_OK);
  const Case c = walls_with_holes(false);
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
  for (tdo_search_kind kind : kKinds) {
    SCOPED_TRACE(tdo_test::kind_name(kind));
    tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, kind, 50.0, 20.0);
    in.theta_max = 0.25 * 3.14159265358979323846;
    const Result a = run(pl.search(), in);
    in.grid_first = 1;
    const Result b = run(pl.search(), in);
    ASSERT_EQ(a.status, TDO_OK) << tdo_status_str(a.status);
    ASSERT_EQ(b.status, TDO_OK) << tdo_status_str(b.status);
    ASSERT_GE(a.out.fallback, 1u);
    EXPECT_EQ(b.out.fallback, a.out.fallback);
    EXPECT_TRUE(tdo_test::valid_path(c.map, b.out, c.s, c.g));
    EXPECT_EQ(bits(b.out.cost), bits(a.out.cost));
    EXPECT_EQ(bits(b.out.penalized_cost), bits(a.out.penalized_cost));
    ASSERT_EQ(b.path.size(), a.path.size());
    for (size_t k = 0; k < a.path.size(); ++k)
      EXPECT_TRUE(tdo_test::same_voxel(a.path[k], b.path[k])) << "path differs at " << k;
    EXPECT_LT(b.out.expansions, a.out.expansions) << "the octile try was not skipped";
    EXPECT_TRUE(identical(b, run(pl.search(), in))) << "a second run differs";
  }
  const Case sealed = walls_with_holes(true);
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), sealed.map), TDO_OK);
  tdo_search_input in = make_input(pl.grid(), sealed.ps, sealed.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
  in.theta_max = 0.25 * 3.14159265358979323846;
  in.grid_first = 1;
  EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_NO_PATH);
  tdo_capacity cap = retry_cap(static_cast<uint32_t>(kWallsNx * kWallsNy * kWallsNz));
  cap.exact_heuristic = 0u;
  TestPlanner no_tables(cap);
  ASSERT_EQ(no_tables.status(), TDO_OK);
  ASSERT_EQ(tdo_test::load_voxels(no_tables.grid(), c.map), TDO_OK);
  in = make_input(no_tables.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
  in.grid_first = 1;
  EXPECT_EQ(run(no_tables.search(), in).status, TDO_ERR_INVALID_ARGUMENT);
}

// grid_first TERMS keeps the first try's f and only adds the grid distances to h: with mu = 0 and
// the optimal stop it must still return the optimal turn-penalised cost (the tables and the turn
// bound stay lower bounds together), as the octile try does (the test above).
TEST(SearchPenalty, GivenGridFirstTerms_WhenSearchingRandomGridsWithTheOptimalStop_ThenOptimal) {
  tdo_capacity cap = make_cap(512, 27u * 512u, 513, 4, 1000, 1u << 30);
  cap.exact_heuristic = 1u;
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  EXPECT_GE(optimal_penalised_rounds(pl, 0x7AB1E5ull, 800, {0.5, 50.0}, TDO_GRID_FIRST_TERMS), 300);
}

// 48 x 24 x 8 voxels, one full wall across x = 24 but for a window along its side (y < 2): the
// octile try heads for the wall's middle and floods in front of it.
Case wall_with_side_window() {
  Case c;
  c.map = VoxelMap(48, 24, 8, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  for (int32_t z = 0; z < 8; ++z)
    for (int32_t y = 2; y < 24; ++y) c.map.set(24, y, z);
  c.s = {2, 12, 4};
  c.g = {45, 12, 4};
  c.ps = c.map.center(c.s);
  c.pg = c.map.center(c.g);
  return c;
}

// Without obstacles the grid distances equal the octile distance (the tables keep 1e-12 below
// it), so TERMS must be the octile try bit for bit. In front of a wall it must expand fewer states
// than the octile try and find the path in its first try (fallback 0: the retries drop the
// deviation term, this try keeps it). Values outside tdo_grid_first are refused.
TEST(SearchPenalty,
     GivenGridFirstTerms_WhenComparedWithTheOctileTry_ThenSameInTheOpenFewerAtAWall) {
  const Case wall = wall_with_side_window();
  Case open = wall;
  open.map = VoxelMap(48, 24, 8, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  TestPlanner pl(retry_cap(static_cast<uint32_t>(48 * 24 * 8)));
  ASSERT_EQ(pl.status(), TDO_OK);
  for (tdo_search_kind kind : kKinds) {
    SCOPED_TRACE(tdo_test::kind_name(kind));
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), open.map), TDO_OK);
    tdo_search_input in = make_input(pl.grid(), open.ps, open.pg, kind, 50.0, 20.0);
    in.theta_max = 0.25 * 3.14159265358979323846;
    const Result octile = run(pl.search(), in);
    in.grid_first = TDO_GRID_FIRST_TERMS;
    const Result terms = run(pl.search(), in);
    ASSERT_EQ(octile.status, TDO_OK) << tdo_status_str(octile.status);
    EXPECT_TRUE(identical(terms, octile)) << "open map";

    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), wall.map), TDO_OK);
    in = make_input(pl.grid(), wall.ps, wall.pg, kind, 50.0, 20.0);
    in.theta_max = 0.25 * 3.14159265358979323846;
    const Result a = run(pl.search(), in);
    in.grid_first = TDO_GRID_FIRST_TERMS;
    const Result b = run(pl.search(), in);
    ASSERT_EQ(a.status, TDO_OK) << tdo_status_str(a.status);
    ASSERT_EQ(b.status, TDO_OK) << tdo_status_str(b.status);
    EXPECT_EQ(b.out.fallback, 0u);
    EXPECT_TRUE(tdo_test::valid_path(wall.map, b.out, wall.s, wall.g));
    EXPECT_LT(4u * b.out.expansions, a.out.expansions)
        << "the octile try expands " << a.out.expansions << " states, TERMS " << b.out.expansions;
    EXPECT_TRUE(identical(b, run(pl.search(), in))) << "a second run differs";
    for (int bad : {-1, 3}) {
      in.grid_first = bad;
      EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_INVALID_ARGUMENT) << "grid_first " << bad;
    }
  }
}

// The flood test must leave a first try alone that progresses steadily: a field of pillars that
// the octile try crosses in 6,700 to 9,000 expansions (within kTryMin = 20,000, whose half a
// projection must exceed to stop the try, and long enough for the test to be applied: more than
// kTryMin / kTryProbe = 2,500, search.cpp) keeps the octile try's path (fallback 0). A test that
// gave up at a smaller projection would retry.
TEST(SearchPenalty, GivenAFieldOfPillars_WhenTheOctileTryProgresses_ThenItIsNotGivenUp) {
  const int32_t nx = 200, ny = 24, nz = 6;
  TestPlanner pl(retry_cap(static_cast<uint32_t>(nx * ny * nz)));
  ASSERT_EQ(pl.status(), TDO_OK);
  Case c;
  c.map = VoxelMap(nx, ny, nz, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  Rng rng(7u);  // 2 x 2 columns, full height, on one 40th of the floor
  for (int32_t k = 0; k < nx * ny / 160; ++k) {
    const int32_t x = 4 + static_cast<int32_t>(rng.next() % static_cast<uint64_t>(nx - 9));
    const int32_t y = static_cast<int32_t>(rng.next() % static_cast<uint64_t>(ny - 1));
    for (int32_t z = 0; z < nz; ++z)
      for (int32_t dx = 0; dx < 2; ++dx)
        for (int32_t dy = 0; dy < 2; ++dy) c.map.set(x + dx, y + dy, z);
  }
  c.s = {1, 12, 3};
  c.g = {nx - 2, 11, 2};
  c.ps = c.map.center(c.s);
  c.pg = c.map.center(c.g);
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
  for (tdo_search_kind kind : kKinds) {  // the optimal stop: the bidirectional search runs long
    SCOPED_TRACE(tdo_test::kind_name(kind));
    tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, kind, 50.0, 20.0);
    in.theta_max = 0.25 * 3.14159265358979323846;
    const Result r = run(pl.search(), in);
    ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
    EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
    EXPECT_GT(r.out.expansions, 2500u) << "too short for the flood test to be applied";
    EXPECT_EQ(r.out.fallback, 0u) << r.out.expansions << " expansions";
  }
}

// Partial expansion (search.cpp, expand_headed): a turn-penalised expansion creates states only
// for the children whose f is near the smallest queued f and defers the rest behind one item, so
// a search holds about as many states as it expands. With full expansion (every direct step and
// pivot a state, about 4.5 per expansion on Map1) a pool of 3/2 of the expansions runs out; here
// the result must be the unlimited one bit for bit.
TEST(SearchPenalty, GivenAPoolOfThreeHalvesTheExpansions_WhenSearchingWithPenalties_ThenTheSame) {
  const int32_t nx = 24, ny = 24, nz = 12;
  const uint32_t n = static_cast<uint32_t>(nx * ny * nz);
  VoxelMap map(nx, ny, nz, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  Rng rng(11u);  // 3 x 3 columns up to random heights
  for (int32_t k = 0; k < 24; ++k) {
    const int32_t x = 2 + static_cast<int32_t>(rng.next() % static_cast<uint64_t>(nx - 6));
    const int32_t y = 2 + static_cast<int32_t>(rng.next() % static_cast<uint64_t>(ny - 6));
    const int32_t h = 2 + static_cast<int32_t>(rng.next() % static_cast<uint64_t>(nz - 2));
    for (int32_t z = 0; z < h; ++z)
      for (int32_t dx = 0; dx < 3; ++dx)
        for (int32_t dy = 0; dy < 3; ++dy) map.set(x + dx, y + dy, z);
  }
  const tdo_voxel s{0, 0, 1}, g{nx - 1, ny - 1, nz - 2};
  TestPlanner big(make_cap(n, 4u * n, n + 1u));  // 4 n: below the 16-bit build's limit
  ASSERT_EQ(big.status(), TDO_OK);
  ASSERT_EQ(tdo_test::load_voxels(big.grid(), map), TDO_OK);
  int checked = 0;
  for (tdo_search_kind kind : kKinds)
    for (int first_meet : {0, 1}) {
      if (kind == TDO_SEARCH_ASTAR && first_meet == 1) continue;
      SCOPED_TRACE(std::string(tdo_test::kind_name(kind)) + " first_meet " +
                   std::to_string(first_meet));
      tdo_search_input in = make_input(big.grid(), map.center(s), map.center(g), kind, 50.0, 20.0);
      in.theta_max = 0.25 * 3.14159265358979323846;
      in.first_meet = first_meet;
      const Result r = run(big.search(), in);
      ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
      ASSERT_TRUE(tdo_test::valid_path(map, r.out, s, g));
      ASSERT_GT(r.out.expansions, 200u) << "too short a query to tell";
      TestPlanner small(make_cap(n, r.out.expansions * 3u / 2u, n + 1u));
      ASSERT_EQ(small.status(), TDO_OK);
      ASSERT_EQ(tdo_test::load_voxels(small.grid(), map), TDO_OK);
      in.grid = small.grid();
      EXPECT_TRUE(identical(r, run(small.search(), in)));
      ++checked;
    }
  EXPECT_EQ(checked, 3);
}

// ---------------------------------------------------------------------------------------------
// (c) named statuses

TEST_F(SearchTest, GivenStartOrGoalOutsideTheBounds_WhenSearching_ThenOutOfBounds) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  load(m);
  const tdo_vec3 inside{1.5, 1.5, 1.5};
  const tdo_vec3 outside[] = {{-0.1, 1.5, 1.5}, {4.0, 1.5, 1.5},   {1.5, -2.0, 1.5},
                              {1.5, 4.0, 1.5},  {1.5, 1.5, -1e-9}, {1.5, 1.5, 4.0}};
  for (const tdo_vec3& p : outside)
    for (tdo_search_kind kind : kKinds) {
      tdo_search_output out{};
      tdo_search_input in = make_input(grid(), p, inside, kind);
      EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_START_OUT_OF_BOUNDS)
          << p.x << "," << p.y << "," << p.z;
      in = make_input(grid(), inside, p, kind);
      EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_GOAL_OUT_OF_BOUNDS)
          << p.x << "," << p.y << "," << p.z;
    }
}

TEST_F(SearchTest, GivenStartOrGoalBlocked_WhenSearching_ThenStartBlockedOrGoalBlocked) {
  VoxelMap m(5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  m.set(2, 2, 2);
  const tdo_vec3 free_point{0.5, 0.5, 0.5};
  const tdo_vec3 occupied{2.5, 2.5, 2.5};
  const tdo_vec3 near{3.2, 2.5, 2.5};  // voxel (3,2,2): 0.5 m from the cube, free at clearance 0
  load(m, 0.0);
  for (tdo_search_kind kind : kKinds) {
    tdo_search_output out{};
    tdo_search_input in = make_input(grid(), occupied, free_point, kind);
    EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_START_BLOCKED);
    in = make_input(grid(), free_point, occupied, kind);
    EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_GOAL_BLOCKED);
    in = make_input(grid(), near, free_point, kind);
    EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_OK) << "clearance 0: (3,2,2) is free";
  }
  load(m, 0.6);  // now (3,2,2) is blocked by clearance alone
  for (tdo_search_kind kind : kKinds) {
    tdo_search_output out{};
    tdo_search_input in = make_input(grid(), near, free_point, kind);
    EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_START_BLOCKED);
    in = make_input(grid(), free_point, near, kind);
    EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_GOAL_BLOCKED);
  }
}

TEST_F(SearchTest, GivenIdenticalStartAndGoal_WhenSearching_ThenStartEqualsGoal) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  load(m);
  for (const tdo_vec3& p :
       {tdo_vec3{1.5, 1.5, 1.5}, tdo_vec3{1.0, 2.0, 3.0}, tdo_vec3{0.1, 3.9, 0.7}})
    for (tdo_search_kind kind : kKinds) {
      tdo_search_output out{};
      const tdo_search_input in = make_input(grid(), p, p, kind);
      EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_START_EQUALS_GOAL);
    }
}

TEST_F(SearchTest, GivenDistinctPointsInOneVoxel_WhenSearching_ThenAOneVoxelPathOfZeroCost) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  load(m);
  for (tdo_search_kind kind : kKinds) {
    const Result r =
        run(search(), make_input(grid(), tdo_vec3{1.2, 1.2, 1.2}, tdo_vec3{1.8, 1.7, 1.6}, kind));
    ASSERT_EQ(r.status, TDO_OK);
    ASSERT_EQ(r.out.n_path, 1u);
    EXPECT_TRUE(tdo_test::same_voxel(r.path[0], tdo_voxel{1, 1, 1}));
    EXPECT_NEAR(r.out.cost, 0.0, 1e-15);
  }
}

// The budget is exact: a query that needed E expansions succeeds with budget E and stops with
// TDO_ERR_BUDGET at E - 1; the same holds for proving that there is no path.
TEST_F(SearchTest, GivenABudgetOneBelowWhatTheQueryNeeds_WhenSearching_ThenBudget) {
  Rng rng(8);
  int checked = 0, checked_no_path = 0;
  for (int round = 0; round < 200; ++round) {
    const Case c = random_case(rng);
    load(c.map);
    for (tdo_search_kind kind : kKinds) {
      const Result full = run(search(), make_input(grid(), c.ps, c.pg, kind));
      ASSERT_TRUE(full.status == TDO_OK || full.status == TDO_ERR_NO_PATH)
          << tdo_status_str(full.status);
      const uint32_t e = full.out.expansions;
      ASSERT_GE(e, 1u);
      SCOPED_TRACE(::testing::Message() << "round " << round << " " << tdo_test::kind_name(kind)
                                        << " needs " << e << " expansions");
      EXPECT_TRUE(identical(full, run(search(), make_input(grid(), c.ps, c.pg, kind, 0, 0, e))))
          << "budget exactly E";
      if (e < 2) continue;
      const Result cut = run(search(), make_input(grid(), c.ps, c.pg, kind, 0, 0, e - 1));
      EXPECT_EQ(cut.status, TDO_ERR_BUDGET) << tdo_status_str(cut.status);
      const Result one = run(search(), make_input(grid(), c.ps, c.pg, kind, 0, 0, 1));
      EXPECT_EQ(one.status, TDO_ERR_BUDGET) << tdo_status_str(one.status);
      ++checked;
      checked_no_path += full.status == TDO_ERR_NO_PATH ? 1 : 0;
    }
  }
  EXPECT_GE(checked, 250);
  EXPECT_GE(checked_no_path, 10);
}

TEST(SearchCapacity, GivenAZeroInputBudget_WhenSearching_ThenTheConfiguredBudgetApplies) {
  TestPlanner pl(make_cap(1000, 1000, 1000, 4, 1000, 3));  // default budget: 3 expansions
  ASSERT_EQ(pl.status(), TDO_OK);
  const VoxelMap m(10, 10, 10, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
  for (tdo_search_kind kind : kKinds) {
    const tdo_vec3 s{0.5, 0.5, 0.5}, g{9.5, 9.5, 9.5};
    EXPECT_EQ(run(pl.search(), make_input(pl.grid(), s, g, kind)).status, TDO_ERR_BUDGET);
    const Result r = run(pl.search(), make_input(pl.grid(), s, g, kind, 0, 0, 100000));
    EXPECT_EQ(r.status, TDO_OK) << "an explicit input budget overrides the default";
  }
}

TEST(SearchCapacity, GivenATinyNodePool_WhenSearchingFar_ThenNodeCapacity) {
  TestPlanner pl(make_cap(1000, 8, 1000));
  ASSERT_EQ(pl.status(), TDO_OK);
  const VoxelMap m(10, 10, 10, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
  for (tdo_search_kind kind : kKinds)
    for (double lambda : {0.0, 50.0}) {
      const Result r = run(pl.search(), make_input(pl.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                   tdo_vec3{9.5, 9.5, 9.5}, kind, lambda));
      EXPECT_EQ(r.status, TDO_ERR_NODE_CAPACITY)
          << tdo_test::kind_name(kind) << " lambda " << lambda << ": " << tdo_status_str(r.status);
    }
}

// The state budget: a pool of one state per voxel (plain A*'s) is too small for the heading states
// of a constrained search on an open grid. With a pool of the grid's voxels the search ends in
// voxel states (fallback 3) and finds a path wherever plain A* does; a pool below the voxels stops
// with node_capacity and reports how far it got (states, peak, expansions), never a path.
TEST(SearchCapacity, GivenAHeadingPoolTooSmall_WhenSearching_ThenVoxelStatesOrNodeCapacity) {
  Rng rng(77);
  int fell_back = 0, stopped = 0;
  for (int round = 0; round < 40; ++round) {
    const Case c = random_case(rng, 12, 6);
    const uint32_t nvox = static_cast<uint32_t>(c.map.size());
    TestPlanner ref(make_cap(nvox, nvox, 1000));
    ASSERT_EQ(ref.status(), TDO_OK);
    ASSERT_EQ(tdo_test::load_voxels(ref.grid(), c.map), TDO_OK);
    const Result astar = run(ref.search(), make_input(ref.grid(), c.ps, c.pg, TDO_SEARCH_ASTAR));
    for (tdo_search_kind kind : kKinds) {
      tdo_search_input in = make_input(ref.grid(), c.ps, c.pg, kind, 50.0, 20.0);
      in.theta_max = 0.25 * 3.14159265358979323846;
      const Result big = [&] {
        TestPlanner pl(make_cap(nvox, 27u * nvox, 1000));
        EXPECT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
        in.grid = pl.grid();
        return run(pl.search(), in);
      }();
      if (big.status != TDO_OK || big.out.peak_nodes <= 2u) continue;
      for (uint32_t pool : {nvox, big.out.peak_nodes - 1u}) {
        if (pool < 2u || (pool == nvox && big.out.peak_nodes <= nvox)) continue;
        TestPlanner pl(make_cap(nvox, pool, 1000));
        ASSERT_EQ(pl.status(), TDO_OK);
        ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
        in.grid = pl.grid();
        const Result r = run(pl.search(), in);
        SCOPED_TRACE(::testing::Message() << "round " << round << " pool " << pool << " of " << nvox
                                          << " voxels, heading peak " << big.out.peak_nodes);
        if (pool >= nvox) {
          ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
          EXPECT_EQ(astar.status, TDO_OK);
          EXPECT_EQ(r.out.fallback, 3u);
          EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
          ++fell_back;
        } else {
          EXPECT_EQ(r.status, TDO_ERR_NODE_CAPACITY) << tdo_status_str(r.status);
          EXPECT_EQ(r.out.peak_nodes, pool);
          EXPECT_GT(r.out.expansions, 0u);
          EXPECT_GE(r.out.states, pool);
          ++stopped;
        }
      }
    }
  }
  EXPECT_GE(fell_back, 5);
  EXPECT_GE(stopped, 20);
}

// A capacity the search reports it needs (peak_open for max_open, peak_nodes for max_nodes) is
// exactly that: with the capacity at the peak the result is the unlimited one bit for bit, one less
// stops with the capacity's status (the planners live in exactly footprint-sized blocks, so ASan
// sees any write past the smaller arrays). Checks random queries of both kinds, with and without
// turn penalties; returns the largest peak seen.
uint32_t check_reported_peaks(bool nodes_not_open) {
  Rng rng(31);
  int checked = 0;
  uint32_t largest = 0;
  for (int round = 0; round < 12; ++round) {
    const Case c = random_case(rng, 12, 6);
    for (tdo_search_kind kind : kKinds)
      for (double lambda : {0.0, 50.0}) {
        const uint32_t nodes = 27u * 12u * 12u * 6u;
        tdo_capacity cap = make_cap(12u * 12u * 6u, nodes, 1000);
        TestPlanner free_pl(cap);
        EXPECT_EQ(free_pl.status(), TDO_OK);
        EXPECT_EQ(tdo_test::load_voxels(free_pl.grid(), c.map), TDO_OK);
        const Result full =
            run(free_pl.search(), make_input(free_pl.grid(), c.ps, c.pg, kind, lambda, lambda));
        if (full.status != TDO_OK) continue;
        const uint32_t peak = nodes_not_open ? full.out.peak_nodes : full.out.peak_open;
        if (peak < 2u) continue;  // a one-step query never holds more than the root
        // Every expansion closes a state it created (both roots included).
        EXPECT_GE(full.out.states, full.out.expansions);
        EXPECT_LE(full.out.peak_nodes, full.out.states);
        SCOPED_TRACE(::testing::Message() << "round " << round << " " << tdo_test::kind_name(kind)
                                          << " lambda " << lambda << " peak " << peak);
        for (uint32_t limit : {peak, peak - 1u}) {
          (nodes_not_open ? cap.max_nodes : cap.max_open) = limit;
          TestPlanner pl(cap);
          EXPECT_EQ(pl.status(), TDO_OK);
          EXPECT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
          const Result r =
              run(pl.search(), make_input(pl.grid(), c.ps, c.pg, kind, lambda, lambda));
          if (limit == peak) {
            EXPECT_TRUE(identical(full, r));
            EXPECT_EQ(nodes_not_open ? r.out.peak_nodes : r.out.peak_open, peak);
            EXPECT_EQ(r.out.states, full.out.states);
          } else if (nodes_not_open && lambda > 0.0 && limit >= c.map.size()) {
            // A pool that holds every voxel: the heading states' overflow ends in voxel states.
            EXPECT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
            EXPECT_EQ(r.out.fallback, 3u);
            EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
          } else {
            EXPECT_EQ(r.status, nodes_not_open ? TDO_ERR_NODE_CAPACITY : TDO_ERR_OPEN_CAPACITY)
                << tdo_status_str(r.status);
          }
        }
        largest = peak > largest ? peak : largest;
        ++checked;
      }
  }
  EXPECT_GE(checked, 20);
  return largest;
}

TEST(SearchCapacity, GivenANodePoolOneShortOfThePeak_WhenSearching_ThenNodeCapacityElseTheSame) {
  EXPECT_GE(check_reported_peaks(true), 100u);  // some queries held many states
}

TEST(SearchCapacity, GivenAnOpenListOneShortOfThePeak_WhenSearching_ThenOpenCapacityElseTheSame) {
  EXPECT_GE(check_reported_peaks(false), 100u);  // some queries had a real open list
  // The open list is carved for max_open + 27 items only.
  tdo_planner_config a{}, b{};
  a.cap = make_cap(1000, 27000, 100);
  b.cap = a.cap;
  b.cap.max_open = 1000;
#if defined(TDO_SEARCH_INDEX16)
  constexpr size_t kItemBytes = 14u;  // 16-bit node index
#else
  constexpr size_t kItemBytes = 16u;
#endif
  // two directions, each array rounded up to the arena's 16-byte alignment
  EXPECT_EQ(tdo_planner_footprint(&a) - tdo_planner_footprint(&b),
            2u * (tdo_arena_round(kItemBytes * 27000u) - tdo_arena_round(kItemBytes * 1027u)))
      << "two directions of " << kItemBytes << "-byte items";
}

TEST(SearchCapacity, GivenAPathBufferOneShort_WhenSearching_ThenPathCapacityElseItFitsExactly) {
  // A straight corridor of 12 voxels: the only path has 12 voxels.
  const VoxelMap m(12, 1, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  for (uint32_t max_path : {5u, 11u, 12u}) {
    TestPlanner pl(make_cap(12, 12, max_path));
    ASSERT_EQ(pl.status(), TDO_OK);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
    for (tdo_search_kind kind : kKinds) {
      const Result r = run(pl.search(), make_input(pl.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                   tdo_vec3{11.5, 0.5, 0.5}, kind));
      if (max_path < 12u) {
        EXPECT_EQ(r.status, TDO_ERR_PATH_CAPACITY)
            << "max_path " << max_path << " " << tdo_test::kind_name(kind);
      } else {
        ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
        EXPECT_EQ(r.out.n_path, 12u);
        EXPECT_TRUE(tdo_test::valid_path(m, r.out, {0, 0, 0}, {11, 0, 0}));
      }
    }
  }
  // With turn penalties and enough nodes for every heading the same rule holds.
  for (uint32_t max_path : {11u, 12u}) {
    TestPlanner pl(make_cap(12, 27u * 12u, max_path));
    ASSERT_EQ(pl.status(), TDO_OK);
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
    for (tdo_search_kind kind : kKinds) {
      const Result r = run(pl.search(), make_input(pl.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                   tdo_vec3{11.5, 0.5, 0.5}, kind, 50.0, 20.0));
      EXPECT_EQ(r.status, max_path < 12u ? TDO_ERR_PATH_CAPACITY : TDO_OK)
          << "max_path " << max_path << " " << tdo_test::kind_name(kind) << ": "
          << tdo_status_str(r.status);
    }
  }
}

TEST(SearchStatus, GivenAMapThatIsNotFinished_WhenSearching_ThenMapNotReady) {
  TestPlanner pl(make_cap(1000, 1000, 1000));
  ASSERT_EQ(pl.status(), TDO_OK);
  const tdo_vec3 s{0.5, 0.5, 0.5}, g{3.5, 3.5, 3.5};
  for (tdo_search_kind kind : kKinds) {
    EXPECT_EQ(run(pl.search(), make_input(pl.grid(), s, g, kind)).status, TDO_ERR_MAP_NOT_READY)
        << "fresh planner, no map loaded";
  }
  const tdo_grid_desc d{5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  for (tdo_search_kind kind : kKinds)
    EXPECT_EQ(run(pl.search(), make_input(pl.grid(), s, g, kind)).status, TDO_ERR_MAP_NOT_READY)
        << "reset but not finished";
  ASSERT_EQ(tdo_grid_add_voxel(pl.grid(), 2, 2, 2), TDO_OK);
  for (tdo_search_kind kind : kKinds)
    EXPECT_EQ(run(pl.search(), make_input(pl.grid(), s, g, kind)).status, TDO_ERR_MAP_NOT_READY)
        << "obstacles added, not finished";
  ASSERT_EQ(tdo_grid_finish(pl.grid(), 0.0), TDO_OK);
  for (tdo_search_kind kind : kKinds)
    EXPECT_EQ(run(pl.search(), make_input(pl.grid(), s, g, kind)).status, TDO_OK);
  // An obstacle added after finish must never be silently ignored.
  const tdo_box on_goal{tdo_vec3{3.2, 3.2, 3.2}, tdo_vec3{3.8, 3.8, 3.8}};
  ASSERT_EQ(tdo_grid_add_box(pl.grid(), &on_goal), TDO_OK);
  for (tdo_search_kind kind : kKinds) {
    const tdo_status st = run(pl.search(), make_input(pl.grid(), s, g, kind)).status;
    EXPECT_TRUE(st == TDO_ERR_MAP_NOT_READY || st == TDO_ERR_GOAL_BLOCKED) << tdo_status_str(st);
  }
}

// ---------------------------------------------------------------------------------------------
// Legal steps computed on first use (grid.h, tdo_grid_prepare; docs/design.md s.0).

TEST(SearchPrepare, GivenGridsNeverPrepared_WhenSearching_ThenTheSameAsOnPreparedGrids) {
  Rng rng(20261207);
  const tdo_capacity cap = make_cap(1024, 27u * 1024u, 1025, 4, 1000, 1u << 30);
  TestPlanner lazy(cap), prepared(cap);
  ASSERT_EQ(lazy.status(), TDO_OK);
  ASSERT_EQ(prepared.status(), TDO_OK);
  int solved = 0;
  for (int round = 0; round < 40; ++round) {
    const Case c = random_case(rng, 12, 6);
    const double clearance = round % 3 == 0 ? rng.uniform(0.0, 0.6 * c.map.res) : 0.0;
    // The lazy planner searched this map at another clearance first: its steps were computed for
    // that finish and must not survive the next one (nor the previous round's map).
    ASSERT_EQ(tdo_test::load_voxels(lazy.grid(), c.map, clearance + 0.7 * c.map.res), TDO_OK);
    (void)run(lazy.search(), make_input(lazy.grid(), c.ps, c.pg, TDO_SEARCH_ASTAR));
    ASSERT_EQ(tdo_grid_finish(lazy.grid(), clearance), TDO_OK);
    ASSERT_EQ(tdo_test::load_voxels(prepared.grid(), c.map, clearance), TDO_OK);
    ASSERT_EQ(tdo_grid_prepare(prepared.grid()), TDO_OK);
    for (int q = 0; q < 4; ++q) {
      const tdo_search_kind kind = kKinds[q % 2];
      const double lambda = q < 2 ? 0.0 : 50.0, mu = q < 2 ? 0.0 : 20.0;
      const Result a = run(lazy.search(), make_input(lazy.grid(), c.ps, c.pg, kind, lambda, mu));
      const Result b =
          run(prepared.search(), make_input(prepared.grid(), c.ps, c.pg, kind, lambda, mu));
      EXPECT_TRUE(identical(a, b)) << "round " << round << " query " << q;
      solved += a.status == TDO_OK ? 1 : 0;
    }
  }
  EXPECT_GE(solved, 80) << "most queries should have a path";
}

TEST(SearchPrepare, GivenGridsInEveryState_WhenPrepared_ThenOkOnlyOnceFinished) {
  EXPECT_EQ(tdo_grid_prepare(nullptr), TDO_ERR_INVALID_ARGUMENT);
  TestPlanner pl(make_cap(1000, 1000, 1000));
  ASSERT_EQ(pl.status(), TDO_OK);
  EXPECT_EQ(tdo_grid_prepare(pl.grid()), TDO_ERR_MAP_NOT_READY) << "no map loaded";
  const tdo_grid_desc d{5, 5, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl.grid(), &d), TDO_OK);
  ASSERT_EQ(tdo_grid_add_voxel(pl.grid(), 2, 2, 2), TDO_OK);
  EXPECT_EQ(tdo_grid_prepare(pl.grid()), TDO_ERR_MAP_NOT_READY) << "not finished";
  ASSERT_EQ(tdo_grid_finish(pl.grid(), 0.0), TDO_OK);
  EXPECT_EQ(tdo_grid_prepare(pl.grid()), TDO_OK);
  EXPECT_EQ(tdo_grid_prepare(pl.grid()), TDO_OK) << "a second call has nothing left to do";
  // The voxel in the middle is an obstacle: the straight line along x goes round it.
  const Result r = run(pl.search(), make_input(pl.grid(), tdo_vec3{0.5, 2.5, 2.5},
                                               tdo_vec3{4.5, 2.5, 2.5}, TDO_SEARCH_ASTAR));
  ASSERT_EQ(r.status, TDO_OK);
  EXPECT_TRUE(near_rel(r.out.cost, 2.0 + 2.0 * kSqrt2)) << r.out.cost;
}

TEST_F(SearchTest, GivenNullPointers_WhenSearching_ThenInvalidArgument) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  load(m);
  tdo_search_output out{};
  tdo_search_input in =
      make_input(grid(), tdo_vec3{0.5, 0.5, 0.5}, tdo_vec3{3.5, 3.5, 3.5}, TDO_SEARCH_ASTAR);
  EXPECT_EQ(tdo_search_run(nullptr, &in, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_search_run(search(), nullptr, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_search_run(search(), &in, nullptr), TDO_ERR_INVALID_ARGUMENT);
  in.grid = nullptr;
  EXPECT_EQ(tdo_search_run(search(), &in, &out), TDO_ERR_INVALID_ARGUMENT);
}

TEST_F(SearchTest, GivenNegativeOrNonFiniteParameters_WhenSearching_ThenInvalidArgument) {
  const VoxelMap m(4, 4, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  load(m);
  const tdo_vec3 s{0.5, 0.5, 0.5}, g{3.5, 3.5, 3.5};
  for (tdo_search_kind kind : kKinds) {
    for (double bad : {-1.0, -1e-300, kNan, kInfty, -kInfty}) {
      EXPECT_EQ(run(search(), make_input(grid(), s, g, kind, bad, 0.0)).status,
                TDO_ERR_INVALID_ARGUMENT)
          << "lambda " << bad;
      EXPECT_EQ(run(search(), make_input(grid(), s, g, kind, 0.0, bad)).status,
                TDO_ERR_INVALID_ARGUMENT)
          << "mu " << bad;
    }
    for (double bad : {kNan, kInfty, -kInfty}) {
      EXPECT_EQ(run(search(), make_input(grid(), tdo_vec3{bad, 0.5, 0.5}, g, kind)).status,
                TDO_ERR_INVALID_ARGUMENT)
          << "start.x " << bad;
      EXPECT_EQ(run(search(), make_input(grid(), s, tdo_vec3{3.5, 3.5, bad}, kind)).status,
                TDO_ERR_INVALID_ARGUMENT)
          << "goal.z " << bad;
    }
  }
}

// The index width bounds the capacities: 2^31 - 1 states per direction with 32-bit indices (one
// bit flags items of deferred children and closed slots), 2^15 - 1 with 16-bit ones (tdo_index16),
// which also need max_voxels < 2^16 and grid axes < 256. Beyond: a named status, at init or at the
// query.
TEST(SearchCapacity, GivenCapacitiesAtAndBeyondTheIndexWidth_WhenInitialising_ThenRefusedBeyond) {
#if defined(TDO_SEARCH_INDEX16)
  const uint32_t max_nodes = 0x7FFFu, max_voxels = 0xFFFFu;
#else
  const uint32_t max_nodes = 0x7FFFFFFFu, max_voxels = 64u;  // no 2^32-voxel test
#endif
  const auto init = [](uint32_t voxels, uint32_t nodes) {
    const tdo_search_config cfg{voxels, nodes, 16u, 0u, 0u, 0u, 1000u};
    const size_t bytes = tdo_search_footprint(&cfg);
    std::vector<unsigned char> memory(bytes > 0 && bytes < (size_t{1} << 27) ? bytes : 1u);
    tdo_arena arena;
    tdo_arena_init(&arena, memory.data(), memory.size());
    tdo_search* s = nullptr;
    return tdo_search_init(&s, &arena, &cfg);
  };
  if (max_nodes < 0x100000u) {  // a 2^31-state pool is not carved here: only its refusal is
    EXPECT_EQ(init(max_voxels, max_nodes), TDO_OK);
  }
  EXPECT_EQ(init(max_voxels, max_nodes + 1u), TDO_ERR_INVALID_ARGUMENT);
#if defined(TDO_SEARCH_INDEX16)
  EXPECT_EQ(init(max_voxels + 1u, 64u), TDO_ERR_INVALID_ARGUMENT);
  // 8-bit coordinates: an axis of 255 voxels is searched, one of 256 refused.
  for (int32_t nx : {255, 256}) {
    TestPlanner pl(make_cap(256, 256, 256));
    ASSERT_EQ(pl.status(), TDO_OK);
    const VoxelMap m(nx, 1, 1, 1.0, tdo_vec3{0.0, 0.0, 0.0});
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
    const Result r = run(pl.search(), make_input(pl.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                 tdo_vec3{nx - 0.5, 0.5, 0.5}, TDO_SEARCH_ASTAR));
    EXPECT_EQ(r.status, nx < 256 ? TDO_OK : TDO_ERR_MAP_CAPACITY) << "nx " << nx;
    if (nx < 256) {
      EXPECT_EQ(r.out.n_path, 255u);
    }
  }
#endif
}

TEST(SearchCapacity, GivenAGridLargerThanTheSearchContext_WhenSearching_ThenRefused) {
  TestPlanner small(make_cap(64, 64, 64));
  TestPlanner big(make_cap(1000, 1000, 1000));
  ASSERT_EQ(small.status(), TDO_OK);
  ASSERT_EQ(big.status(), TDO_OK);
  const VoxelMap m(10, 10, 10, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  ASSERT_EQ(tdo_test::load_voxels(big.grid(), m), TDO_OK);
  for (tdo_search_kind kind : kKinds) {
    const tdo_status st = run(small.search(), make_input(big.grid(), tdo_vec3{0.5, 0.5, 0.5},
                                                         tdo_vec3{9.5, 9.5, 9.5}, kind))
                              .status;
    EXPECT_TRUE(st == TDO_ERR_MAP_CAPACITY || st == TDO_ERR_INVALID_ARGUMENT) << tdo_status_str(st);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Corridors (tdo_search_input.corridor): the search enters only the corridor's coarse cells.

/** A corridor over cells of 2^shift voxels: the cells in `in` (1 = in), masks built here. */
struct TestCorridor {
  int32_t shift = 2, cnx = 1, cny = 1, cnz = 1;
  std::vector<uint8_t> in;
  std::vector<uint32_t> cells;
  tdo_search_corridor c{};

  TestCorridor(const VoxelMap& m, int32_t sh) : shift(sh) {
    const int32_t e = (1 << sh) - 1;
    cnx = (m.nx + e) >> sh;
    cny = (m.ny + e) >> sh;
    cnz = (m.nz + e) >> sh;
    in.assign(static_cast<size_t>(cnx) * cny * cnz, 0u);
  }
  size_t cell(int32_t i, int32_t j, int32_t k) const {
    return static_cast<size_t>(i + cnx * (j + cny * k));
  }
  size_t cell_of_voxel(const tdo_voxel& v) const {
    return cell(v.i >> shift, v.j >> shift, v.k >> shift);
  }
  const tdo_search_corridor* finish() {
    cells.assign(in.size(), 0u);
    for (int32_t k = 0; k < cnz; ++k)
      for (int32_t j = 0; j < cny; ++j)
        for (int32_t i = 0; i < cnx; ++i) {
          if (!in[cell(i, j, k)]) continue;
          uint32_t mask = 0;
          for (int32_t dz = -1; dz <= 1; ++dz)
            for (int32_t dy = -1; dy <= 1; ++dy)
              for (int32_t dx = -1; dx <= 1; ++dx) {
                const int32_t x = i + dx, y = j + dy, z = k + dz;
                if (x >= 0 && y >= 0 && z >= 0 && x < cnx && y < cny && z < cnz &&
                    in[cell(x, y, z)])
                  mask |= 1u << ((dz + 1) * 9 + (dy + 1) * 3 + (dx + 1));
              }
          cells[cell(i, j, k)] = mask;
        }
    c.cells = cells.data();
    c.shift = shift;
    c.cnx = cnx;
    c.cny = cny;
    return &c;
  }
};

// Random maps of up to 16 x 16 x 8 voxels, random corridors of 4^3 cells holding the start and the
// goal. Plain A* and bidir in the corridor: every voxel of the path lies in it, the path is legal
// on the map, and its cost lies between the map's optimum and the optimum of the map with every
// voxel outside the corridor blocked (which also forbids cutting past those voxels, so it may cost
// more); a path exists whenever that restricted map has one, and none is found when even the whole
// map has none. Turn-penalised searches (heading and voxel states) keep to the corridor too.
TEST(SearchCorridor,
     GivenARandomCorridor_WhenSearching_ThenThePathStaysInItAndIsFoundWhenOneExists) {
#if defined(TDO_SEARCH_INDEX16)
  TestPlanner pl(make_cap(2048, 0x7FFFu, 2049u, 4, 1000, 1u << 30));  // the 16-bit pool's limit
#else
  TestPlanner pl(make_cap(2048, 27u * 2048u, 2049u, 4, 1000, 1u << 30));
#endif
  ASSERT_EQ(pl.status(), TDO_OK);
  Rng rng(2718);
  int found = 0;
  for (int round = 0; round < 300; ++round) {
    const Case c = random_case(rng, 16, 8);
    TestCorridor tc(c.map, 2);
    const double keep = rng.uniform(0.3, 0.9);
    for (auto& b : tc.in) b = rng.uniform() < keep ? 1u : 0u;
    tc.in[tc.cell_of_voxel(c.s)] = 1u;
    tc.in[tc.cell_of_voxel(c.g)] = 1u;
    const tdo_search_corridor* corridor = tc.finish();
    VoxelMap restricted = c.map;
    for (size_t n = 0; n < restricted.size(); ++n)
      if (!tc.in[tc.cell_of_voxel(restricted.voxel(n))]) restricted.blocked[n] = 1u;
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), c.map), TDO_OK);
    const double best = tdo_test::reference_cost(c.map, c.s, c.g);
    const double inside = tdo_test::reference_cost(restricted, c.s, c.g);
    SCOPED_TRACE(::testing::Message() << "round " << round);
    for (tdo_search_kind kind : kKinds) {
      tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, kind);
      in.corridor = corridor;
      const Result r = run(pl.search(), in);
      if (!(best < kInf)) {
        EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
        continue;
      }
      if (inside < kInf) {
        ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
      }
      if (r.status != TDO_OK) {
        EXPECT_EQ(r.status, TDO_ERR_NO_PATH) << tdo_status_str(r.status);
        continue;
      }
      ++found;
      EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
      for (const tdo_voxel& v : r.path) EXPECT_TRUE(tc.in[tc.cell_of_voxel(v)]) << tdo_test::str(v);
      EXPECT_GE(r.out.cost, best - 1e-9);
      if (inside < kInf) {
        EXPECT_LE(r.out.cost, inside + 1e-9);
      }
    }
    for (int states : {TDO_STATES_HEADING, TDO_STATES_VOXEL}) {
      tdo_search_input in = make_input(pl.grid(), c.ps, c.pg, TDO_SEARCH_BIDIR, 50.0, 20.0);
      in.theta_max = 0.25 * 3.14159265358979323846;
      in.states = states;
      in.corridor = corridor;
      const Result r = run(pl.search(), in);
#if defined(TDO_SEARCH_INDEX16)
      // 2^15 - 1 states per direction hold fewer than 27 headings of 2048 voxels.
      if (states == TDO_STATES_HEADING && r.status == TDO_ERR_NODE_CAPACITY) continue;
#endif
      if (inside < kInf) {
        ASSERT_EQ(r.status, TDO_OK) << tdo_status_str(r.status);
      }
      if (r.status != TDO_OK) continue;
      EXPECT_TRUE(tdo_test::valid_path(c.map, r.out, c.s, c.g));
      for (const tdo_voxel& v : r.path) EXPECT_TRUE(tc.in[tc.cell_of_voxel(v)]) << tdo_test::str(v);
    }
  }
  EXPECT_GT(found, 100);  // the rounds exercise the corridor, not just the no-path case
}

// A corridor that leaves out the start's or the goal's cell, or does not fit the grid, is refused.
TEST(SearchCorridor, GivenACorridorWithoutTheEnds_WhenSearching_ThenInvalidArgument) {
  TestPlanner pl(make_cap(1024, 1024, 1025, 4, 1000, 1u << 30));
  ASSERT_EQ(pl.status(), TDO_OK);
  const VoxelMap m(16, 8, 4, 1.0, tdo_vec3{0.0, 0.0, 0.0});
  ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
  TestCorridor tc(m, 2);
  tc.in[tc.cell(0, 0, 0)] = 1u;  // the start's cell only
  tdo_search_input in =
      make_input(pl.grid(), m.center({1, 1, 1}), m.center({14, 6, 2}), TDO_SEARCH_BIDIR);
  in.corridor = tc.finish();
  EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_INVALID_ARGUMENT);
  tc.in[tc.cell(3, 1, 0)] = 1u;  // the goal's cell too, but not the cells between: no path
  in.corridor = tc.finish();
  EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_NO_PATH);
  tdo_search_corridor wrong = *tc.finish();
  wrong.cnx = 5;  // not the grid's coarse width
  in.corridor = &wrong;
  EXPECT_EQ(run(pl.search(), in).status, TDO_ERR_INVALID_ARGUMENT);
}

// The retry's float tables (search_tables.cpp, store_lower_bounds, vectorised where the processor
// allows): every key becomes the largest float not above it, whatever the position in the table
// (lengths that are not multiples of the vector widths) and the magnitude (exact floats, +inf,
// beyond the float range, subnormal).
TEST(SearchTables, GivenDistanceKeys_WhenStoredAsFloats_ThenEachIsTheLargestFloatNotAbove) {
  tdo_test::Rng rng(20261207u);
  for (uint32_t n : {1u, 3u, 4u, 7u, 8u, 9u, 17u, 1003u}) {
    std::vector<double> dist(n);
    for (uint32_t v = 0; v < n; ++v) {
      switch (rng.below(6)) {
        case 0:
          dist[v] = static_cast<double>(static_cast<float>(rng.uniform(0.0, 100.0)));
          break;
        case 1:
          dist[v] = std::numeric_limits<double>::infinity();
          break;
        case 2:
          dist[v] = rng.uniform(1e39, 1e40);
          break;
        case 3:
          dist[v] = rng.uniform(0.0, 1e-40);
          break;
        default:
          dist[v] = rng.uniform(0.0, 1000.0);
          break;
      }
    }
    std::vector<float> table(n + 1u, -1.0f);  // one more: nothing written past n
    tdo_internal::store_lower_bounds(dist.data(), n, table.data());
    for (uint32_t v = 0; v < n; ++v) {
      const float f = table[v];
      EXPECT_LE(static_cast<double>(f), dist[v]) << "n " << n << " v " << v;
      if (std::isinf(dist[v])) continue;
      EXPECT_GT(static_cast<double>(std::nextafter(f, std::numeric_limits<float>::infinity())),
                dist[v])
          << "n " << n << " v " << v;
    }
    EXPECT_EQ(table[n], -1.0f);
  }
}

// The retry's grid distances (search_tables.cpp, exact_lower_bounds: a bucketed Dijkstra, walked
// by blocks of 3x3x3 voxels, rows of them near the table's ends) against a binary-heap Dijkstra
// over the independent legal steps: the same sums in the same precision, so bit for bit the same
// keys. Settled (distance at most twice the other end's): the distance less 1e-12 relative; the
// rest, when the Dijkstra stopped at that radius, the smallest distance beyond it; +inf where it
// ran out. Random grids, thin ones (every voxel near an end of the table) and open ones (the
// radius cuts the flood), both ends at random, the same voxel too.
std::vector<double> reference_grid_distances(const VoxelMap& m, const tdo_voxel& root) {
  std::vector<double> dist(m.size(), kInfty);
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  dist[m.idx(root)] = 0.0;
  open.push(Item{0.0, m.idx(root)});
  while (!open.empty()) {
    const Item top = open.top();
    open.pop();
    if (top.first > dist[top.second]) continue;
    const tdo_voxel u = m.voxel(top.second);
    for (int32_t dz = -1; dz <= 1; ++dz)
      for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx) {
          const tdo_voxel w{u.i + dx, u.j + dy, u.k + dz};
          if (!tdo_test::legal_step(m, u, w)) continue;
          const double nd = top.first + tdo_test::step_length(m.res, u, w);
          if (nd < dist[m.idx(w)]) {
            dist[m.idx(w)] = nd;
            open.push(Item{nd, m.idx(w)});
          }
        }
  }
  return dist;
}

TEST(SearchTables, GivenRandomGrids_WhenComputingGridDistances_ThenTheKeysOfAReferenceDijkstra) {
  const uint32_t n = 20u * 20u * 8u;
  tdo_capacity cap = make_cap(n, 27u * n, n + 1u);
#if defined(TDO_SEARCH_INDEX16)
  cap.max_nodes = 0x7FFFu;
#endif
  cap.exact_heuristic = 1u;
  TestPlanner pl(cap);
  ASSERT_EQ(pl.status(), TDO_OK);
  Rng rng(20261207u);
  const double resolutions[] = {1.0, 0.5, 0.3, 2.0};
  int cut = 0, ran_out = 0, unreachable = 0;
  for (int round = 0; round < 300; ++round) {
    const int shape = round % 3;  // 0: small, 1: thin (one to three layers or rows), 2: open
    const int32_t nx = shape == 2 ? rng.range(8, 20) : rng.range(1, 12);
    const int32_t ny = shape == 2   ? rng.range(8, 20)
                       : shape == 1 ? rng.range(1, 3)
                                    : rng.range(1, 9);
    const int32_t nz = shape == 2 ? rng.range(3, 8) : rng.range(1, 3);
    const double density = shape == 2 ? rng.uniform(0.0, 0.15) : rng.uniform(0.0, 0.4);
    const VoxelMap m =
        tdo_test::random_voxel_map(rng, nx, ny, nz, resolutions[rng.below(4)], density);
    std::vector<size_t> free;
    for (size_t v = 0; v < m.size(); ++v)
      if (!m.blocked[v]) free.push_back(v);
    if (free.size() < 2) continue;
    const size_t root = free[rng.below(static_cast<uint32_t>(free.size()))];
    size_t other = free[rng.below(static_cast<uint32_t>(free.size()))];
    if (round % 10 == 0) other = root;
    ASSERT_EQ(tdo_test::load_voxels(pl.grid(), m), TDO_OK);
    // A search sets up the context's step tables for this grid (and builds its legal steps).
    size_t far = root;
    while (far == root) far = free[rng.below(static_cast<uint32_t>(free.size()))];
    tdo_search_input in = make_input(pl.grid(), m.center(m.voxel(root)), m.center(m.voxel(far)),
                                     TDO_SEARCH_BIDIR, 50.0, 20.0);
    run(pl.search(), in);
    SCOPED_TRACE(::testing::Message() << "round " << round << " grid " << nx << "x" << ny << "x"
                                      << nz << " root " << root << " other " << other);
    const std::vector<double> want = reference_grid_distances(m, m.voxel(root));
    tdo_search* ctx = pl.search();
    const bool reached = tdo_internal::exact_lower_bounds(
        ctx, pl.grid(), static_cast<uint32_t>(root), static_cast<uint32_t>(other));
    ASSERT_EQ(reached, want[other] < kInfty);
    if (!reached) {
      ++unreachable;
      continue;
    }
    const double limit = 2.0 * want[other];
    double rest = kInfty;  // the smallest distance beyond the radius
    for (double d : want)
      if (d > limit && d < rest) rest = d;
    (rest < kInfty ? cut : ran_out)++;
    for (size_t v = 0; v < m.size(); ++v) {
      const double expect = want[v] <= limit ? want[v] * (1.0 - 1e-12) : rest;
      ASSERT_EQ(bits(ctx->dj_dist[v]), bits(expect))
          << "voxel " << v << " got " << ctx->dj_dist[v] << " want " << expect;
    }
  }
  EXPECT_GT(cut, 20);
  EXPECT_GT(ran_out, 20);
  EXPECT_GT(unreachable, 5);
}
