// Adapters between LCM messages and libtdo structs (apps/common adapters.h): round trips and every
// malformed case, each refused with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "rng.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"

namespace tdo_lcm {
// gtest prints reasons by name.
void PrintTo(Reason r, std::ostream* os) { *os << reason_str(r); }
}  // namespace tdo_lcm

namespace {

using tdo_lcm::Check;
using tdo_lcm::Reason;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

#define EXPECT_REASON(expr, r)                                                                \
  do {                                                                                        \
    const Check c_ = (expr);                                                                  \
    EXPECT_EQ(c_.reason, r) << "got " << tdo_lcm::reason_str(c_.reason) << ": " << c_.detail; \
  } while (0)

/** A planner whose grid fits 16 x 12 x 8 voxels, 4 boxes, clearance up to 2 voxels. */
class Planner {
 public:
  Planner() {
    tdo_planner_config cfg{};
    tdo_capacity_for_grid(&cfg.cap, 16, 12, 8, 2.0, 1u, 0u);
    cfg.cap.max_boxes = 4;
    cap_ = cfg.cap;
    bytes_ = tdo_planner_footprint(&cfg);
    arena_.reset(new std::max_align_t[bytes_ / sizeof(std::max_align_t) + 1]);
    EXPECT_EQ(tdo_planner_init(&planner_, arena_.get(), bytes_, &cfg), TDO_OK);
  }
  tdo_grid* grid() { return tdo_planner_grid(planner_); }
  const tdo_capacity& cap() const { return cap_; }

 private:
  tdo_capacity cap_{};
  std::size_t bytes_ = 0;
  std::unique_ptr<std::max_align_t[]> arena_;
  tdo_planner* planner_ = nullptr;
};

tdo_grid_desc small_desc() { return tdo_grid_desc{10, 8, 6, 0.5, {-1.0, 2.0, 0.0}}; }

/** A valid RLE map: a few occupied voxels and one box. */
tdo::map_t valid_map() {
  const tdo_grid_desc d = small_desc();
  std::vector<uint8_t> occ(static_cast<std::size_t>(d.nx * d.ny * d.nz), 0u);
  occ[0] = 1;
  occ[17] = 1;
  occ[18] = 1;
  occ[occ.size() - 1] = 1;
  const std::vector<tdo_box> boxes = {tdo_box{{0.0, 2.0, 0.0}, {0.6, 3.1, 1.2}}};
  tdo::map_t m{};
  EXPECT_TRUE(tdo_lcm::map_from_occupancy(d, occ, boxes, 0.25, &m).ok());
  m.map_id = 7;
  return m;
}

// ---- maps --------------------------------------------------------------------------------------

TEST(MapAdapter, SeededRandomOccupancyRoundTripsThroughTheGrid) {
  Planner p;
  tdo_test::Rng rng(21);
  for (int round = 0; round < 40; ++round) {
    tdo_grid_desc d{};
    d.nx = rng.range(1, 16);
    d.ny = rng.range(1, 12);
    d.nz = rng.range(1, 8);
    d.res = rng.uniform(0.1, 2.0);
    d.origin = tdo_vec3{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    std::vector<uint8_t> occ(static_cast<std::size_t>(d.nx * d.ny * d.nz));
    const double density = rng.uniform(0.0, 0.5);
    for (auto& v : occ) v = rng.uniform() < density ? 1u : 0u;
    tdo::map_t m{};
    ASSERT_TRUE(tdo_lcm::map_from_occupancy(d, occ, {}, 0.0, &m).ok());
    m.map_id = round;
    const Check c = tdo_lcm::map_to_grid(m, p.cap(), -1.0, p.grid());
    ASSERT_TRUE(c.ok()) << c.detail;
    EXPECT_EQ(tdo_lcm::grid_occupancy(p.grid()), occ) << "round " << round;
    const tdo_grid_desc got = tdo_grid_get_desc(p.grid());
    EXPECT_EQ(got.nx, d.nx);
    EXPECT_EQ(got.nz, d.nz);
    EXPECT_EQ(got.res, d.res);
    EXPECT_EQ(got.origin.y, d.origin.y);
  }
}

TEST(MapAdapter, BoxesAndClearanceReachTheGrid) {
  Planner p;
  tdo::map_t m = valid_map();
  ASSERT_TRUE(tdo_lcm::map_to_grid(m, p.cap(), -1.0, p.grid()).ok());
  EXPECT_EQ(tdo_grid_clearance(p.grid()), 0.25);  // the map's hint
  // The box covers voxels (2..3, 0..2, 0..2) of the 0.5 m grid at origin (-1, 2, 0).
  EXPECT_TRUE(tdo_grid_is_occupied(p.grid(), tdo_voxel{2, 1, 1}));
  EXPECT_TRUE(tdo_grid_is_occupied(p.grid(), tdo_voxel{0, 0, 0}));  // run-length voxel
  EXPECT_FALSE(tdo_grid_is_occupied(p.grid(), tdo_voxel{5, 5, 5}));
  // A requested clearance overrides the hint.
  ASSERT_TRUE(tdo_lcm::map_to_grid(m, p.cap(), 0.5, p.grid()).ok());
  EXPECT_EQ(tdo_grid_clearance(p.grid()), 0.5);
}

TEST(MapAdapter, NoRunsMeansEveryVoxelFree) {
  Planner p;
  tdo::map_t m{};
  ASSERT_TRUE(tdo_lcm::map_from_occupancy(small_desc(), {}, {}, 0.0, &m).ok());
  m.map_id = 1;
  EXPECT_EQ(m.n_runs, 0);
  ASSERT_TRUE(tdo_lcm::map_to_grid(m, p.cap(), -1.0, p.grid()).ok());
  EXPECT_EQ(tdo_grid_blocked_count(p.grid()), 0u);
}

// A map larger than the configured memory is refused with the bytes a planner would need for it:
// the footprint of the same capacities with room for its voxels, larger than the arena it has.
TEST(MapAdapter, GivenAMapLargerThanTheCapacity_WhenChecked_ThenTheMessageGivesTheBytesNeeded) {
  Planner p;
  tdo::map_t m = valid_map();
  m.size[0] = 100;
  m.size[1] = 100;
  m.size[2] = 100;
  m.runs = {1000000};
  m.n_runs = 1;
  const Check c = tdo_lcm::map_check(m, p.cap(), -1.0);
  EXPECT_EQ(c.reason, Reason::map_capacity);
  tdo_planner_config need{};
  need.cap = p.cap();
  need.cap.max_voxels = 1000000;
  const size_t bytes = tdo_planner_footprint(&need);
  tdo_planner_config have{};
  have.cap = p.cap();
  EXPECT_GT(bytes, tdo_planner_footprint(&have));
  EXPECT_EQ(c.detail, "100 x 100 x 100 = 1000000 voxels, more than the capacity of " +
                          std::to_string(p.cap().max_voxels) + "; it needs an arena of at least " +
                          std::to_string(bytes) + " bytes");
}

TEST(MapAdapter, EveryMalformedMapIsRefusedByName) {
  Planner p;
  const tdo_capacity cap = p.cap();
  struct Case {
    const char* what;
    void (*mutate)(tdo::map_t*);
    Reason reason;
  };
  const Case cases[] = {
      {"runs count", [](tdo::map_t* m) { m->n_runs += 1; }, Reason::count_mismatch},
      {"data count", [](tdo::map_t* m) { m->n_bytes = 3; }, Reason::count_mismatch},
      {"boxes count", [](tdo::map_t* m) { m->n_boxes = 0; }, Reason::count_mismatch},
      {"box width", [](tdo::map_t* m) { m->boxes[0].pop_back(); }, Reason::count_mismatch},
      {"negative map id", [](tdo::map_t* m) { m->map_id = -1; }, Reason::out_of_range},
      {"nan resolution", [](tdo::map_t* m) { m->resolution = kNaN; }, Reason::non_finite},
      {"zero resolution", [](tdo::map_t* m) { m->resolution = 0.0; }, Reason::out_of_range},
      {"inf origin", [](tdo::map_t* m) { m->origin[1] = kInf; }, Reason::non_finite},
      {"zero size", [](tdo::map_t* m) { m->size[2] = 0; }, Reason::out_of_range},
      {"negative size", [](tdo::map_t* m) { m->size[0] = -4; }, Reason::out_of_range},
      {"nan clearance", [](tdo::map_t* m) { m->clearance = kNaN; }, Reason::non_finite},
      {"negative clearance", [](tdo::map_t* m) { m->clearance = -0.1; }, Reason::out_of_range},
      {"nan box", [](tdo::map_t* m) { m->boxes[0][4] = kNaN; }, Reason::non_finite},
      {"inverted box", [](tdo::map_t* m) { m->boxes[0][3] = m->boxes[0][0]; },
       Reason::out_of_range},
      {"more voxels than the capacity",
       [](tdo::map_t* m) {
         m->size[0] = 100;
         m->size[1] = 100;
         m->size[2] = 100;
         m->runs = {1000000};
         m->n_runs = 1;
       },
       Reason::map_capacity},
      {"more boxes than the capacity",
       [](tdo::map_t* m) {
         m->boxes.assign(5, m->boxes[0]);
         m->n_boxes = 5;
       },
       Reason::map_capacity},
      {"clearance beyond the stencil", [](tdo::map_t* m) { m->clearance = 3.0; },
       Reason::map_capacity},
      {"unknown encoding", [](tdo::map_t* m) { m->encoding = 9; }, Reason::bad_encoding},
      {"octomap",
       [](tdo::map_t* m) {
         m->encoding = tdo::map_t::ENCODING_OCTOMAP_BT;
         m->runs.clear();
         m->n_runs = 0;
         m->data = {1, 2, 3};
         m->n_bytes = 3;
       },
       Reason::unsupported_encoding},
      {"rle with data",
       [](tdo::map_t* m) {
         m->data = {1};
         m->n_bytes = 1;
       },
       Reason::out_of_range},
      {"runs short", [](tdo::map_t* m) { m->runs.back() -= 1; }, Reason::rle_mismatch},
      {"runs long", [](tdo::map_t* m) { m->runs.back() += 1; }, Reason::rle_mismatch},
      {"negative run", [](tdo::map_t* m) { m->runs[1] = -1; }, Reason::out_of_range},
  };
  // GIVEN a grid holding a good map
  tdo::map_t good = valid_map();
  ASSERT_TRUE(tdo_lcm::map_to_grid(good, cap, -1.0, p.grid()).ok());
  const std::vector<uint8_t> before = tdo_lcm::grid_occupancy(p.grid());
  for (const Case& k : cases) {
    tdo::map_t m = valid_map();
    k.mutate(&m);
    // WHEN a malformed map arrives THEN it is refused by name and the grid keeps the good map
    EXPECT_REASON(tdo_lcm::map_check(m, cap, -1.0), k.reason);
    const Check c = tdo_lcm::map_to_grid(m, cap, -1.0, p.grid());
    EXPECT_EQ(c.reason, k.reason) << k.what << ": " << c.detail;
    EXPECT_FALSE(c.detail.empty()) << k.what;
    EXPECT_EQ(tdo_grid_clearance(p.grid()), 0.25) << k.what;
    EXPECT_EQ(tdo_lcm::grid_occupancy(p.grid()), before) << k.what;
  }
  // A non-finite requested clearance is refused too.
  EXPECT_REASON(tdo_lcm::map_check(good, cap, kNaN), Reason::non_finite);
}

TEST(MapAdapter, ClearanceCheckMirrorsTheLibraryStencil) {
  Planner p;
  tdo::map_t m = valid_map();
  ASSERT_TRUE(tdo_lcm::map_to_grid(m, p.cap(), -1.0, p.grid()).ok());
  // Every clearance the check accepts finishes; every one it refuses is refused by the library.
  for (double c = 0.0; c < 2.0; c += 0.0625) {
    const bool accepted = tdo_lcm::clearance_check(c, m.resolution, p.cap()).ok();
    const tdo_status st = tdo_grid_finish(p.grid(), c);
    EXPECT_EQ(accepted, st == TDO_OK) << "clearance " << c << ": " << tdo_status_str(st);
  }
}

TEST(MapAdapter, BuildingAMapChecksItsInput) {
  std::vector<uint8_t> occ(10, 0u);
  tdo::map_t m{};
  EXPECT_REASON(tdo_lcm::map_from_occupancy(small_desc(), occ, {}, 0.0, &m),
                Reason::count_mismatch);
  tdo_grid_desc d = small_desc();
  d.res = -1.0;
  EXPECT_REASON(tdo_lcm::map_from_occupancy(d, {}, {}, 0.0, &m), Reason::out_of_range);
  EXPECT_REASON(tdo_lcm::map_from_occupancy(small_desc(), {}, {}, kInf, &m), Reason::non_finite);
  const tdo_box inverted{{1, 1, 1}, {0, 2, 2}};
  EXPECT_REASON(tdo_lcm::map_from_occupancy(small_desc(), {}, {inverted}, 0.0, &m),
                Reason::out_of_range);
}

// ---- plan requests -----------------------------------------------------------------------------

tdo_plan_request sample_request() {
  tdo_plan_request r{};
  r.start = tdo_vec3{1.0, 2.0, 3.0};
  r.goal = tdo_vec3{4.0, 5.0, 6.5};
  tdo_plan_params& p = r.params;
  p.depth = TDO_PLAN_SMOOTH;
  p.search = TDO_SEARCH_ASTAR;
  p.lambda = 50.0;
  p.mu = 20.0;
  p.theta_max = 0.7;
  p.d_th = 0.3;
  p.h_weight = 1.5;
  p.first_meet = 1;
  p.grid_first = TDO_GRID_FIRST_TERMS;
  p.states = TDO_STATES_VOXEL;  // not the default: the round trip must carry it
  p.max_expansions = 12345;
  p.correction = TDO_CORRECT_GREEDY_LOS;
  p.shorten = 0;  // not the library's default: the round trip must carry it
  p.turn_threshold = 0.17;
  p.smoothing = TDO_SMOOTHING_ARC;
  p.k = 1.5;
  p.v_max = 3.0;
  p.a_max = 2.5;
  p.j_max = 10.0;
  p.a_lat_max = 2.0;
  p.v_cruise = 2.8;
  p.stop_angle = 2.6;
  p.dt = 0.02;
  p.corner_time = 0.5;
  return r;
}

tdo::plan_request_t sample_request_msg() {
  tdo::plan_request_t m{};
  m.request_id = 42;
  m.vehicle_id = 3;
  m.map_id = -1;
  tdo_lcm::plan_request_to_msg(sample_request(), 0.4, &m);
  return m;
}

TEST(RequestAdapter, RoundTripKeepsEveryParameter) {
  const tdo_plan_request in = sample_request();
  tdo::plan_request_t m{};
  tdo_lcm::plan_request_to_msg(in, 0.4, &m);
  m.vehicle_id = 3;
  tdo_plan_request out{};
  double clearance = 0.0;
  ASSERT_TRUE(tdo_lcm::plan_request_from_msg(m, 3, &out, &clearance).ok());
  EXPECT_EQ(clearance, 0.4);
  EXPECT_EQ(out.start.z, in.start.z);
  EXPECT_EQ(out.goal.x, in.goal.x);
  const tdo_plan_params& a = in.params;
  const tdo_plan_params& b = out.params;
  EXPECT_EQ(b.depth, a.depth);
  EXPECT_EQ(b.search, a.search);
  EXPECT_EQ(b.lambda, a.lambda);
  EXPECT_EQ(b.mu, a.mu);
  EXPECT_EQ(b.theta_max, a.theta_max);
  EXPECT_EQ(b.d_th, a.d_th);
  EXPECT_EQ(b.h_weight, a.h_weight);
  EXPECT_EQ(b.first_meet, a.first_meet);
  EXPECT_EQ(b.grid_first, a.grid_first);
  EXPECT_EQ(b.states, a.states);
  EXPECT_EQ(b.max_expansions, a.max_expansions);
  EXPECT_EQ(b.correction, a.correction);
  EXPECT_EQ(b.shorten, a.shorten);
  EXPECT_EQ(b.turn_threshold, a.turn_threshold);
  EXPECT_EQ(b.smoothing, a.smoothing);
  EXPECT_EQ(b.k, a.k);
  EXPECT_EQ(b.v_max, a.v_max);
  EXPECT_EQ(b.a_max, a.a_max);
  EXPECT_EQ(b.j_max, a.j_max);
  EXPECT_EQ(b.a_lat_max, a.a_lat_max);
  EXPECT_EQ(b.v_cruise, a.v_cruise);
  EXPECT_EQ(b.stop_angle, a.stop_angle);
  EXPECT_EQ(b.dt, a.dt);
  EXPECT_EQ(b.corner_time, a.corner_time);
}

TEST(RequestAdapter, GivenAMovingStart_WhenRoundTripped_ThenTheStateArrivesExactly) {
  // GIVEN a trajectory request from a vehicle in motion
  tdo_plan_request in = sample_request();
  in.params.depth = TDO_PLAN_TRAJECTORY;
  in.state.v = tdo_vec3{1.25, -0.5, 0.125};
  in.state.a = tdo_vec3{-0.75, 0.25, 1.5};
  tdo::plan_request_t m{};
  m.vehicle_id = 3;
  // WHEN it goes to the message and back
  tdo_lcm::plan_request_to_msg(in, 0.4, &m);
  tdo_plan_request out{};
  ASSERT_TRUE(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr).ok());
  // THEN velocity and acceleration are the same bits
  EXPECT_EQ(std::memcmp(&out.state, &in.state, sizeof(in.state)), 0);
  EXPECT_EQ(m.start_vel[0], 1.25);
  EXPECT_EQ(m.start_acc[2], 1.5);
}

TEST(RequestAdapter, GivenBadStartStates_WhenAdapted_ThenRefusedNamingTheField) {
  tdo::plan_request_t base = sample_request_msg();
  base.depth = tdo::plan_request_t::DEPTH_TRAJECTORY;
  tdo_plan_request out{};
  const auto field = [&](const tdo::plan_request_t& m) {
    return tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr).field;
  };
  tdo::plan_request_t m = base;
  m.start_vel[1] = kNaN;  // GIVEN a NaN velocity, THEN non_finite naming start_vel[1]
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::non_finite);
  EXPECT_EQ(field(m), "start_vel[1]");
  m = base;
  m.start_acc[2] = kInf;  // an infinite acceleration
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::non_finite);
  EXPECT_EQ(field(m), "start_acc[2]");
  m = base;
  m.start_vel[0] = 2.5;  // |v| = 3.2 m/s > v_max = 3
  m.start_vel[1] = 2.0;
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::out_of_range);
  EXPECT_EQ(field(m), "start_vel");
  m = base;
  m.start_acc[0] = 2.6;  // > a_max = 2.5
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::out_of_range);
  EXPECT_EQ(field(m), "start_acc");
  m = base;
  m.depth = tdo::plan_request_t::DEPTH_SMOOTH;  // a moving start without the trajectory stage
  m.start_vel[0] = 1.0;
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::out_of_range);
  EXPECT_EQ(field(m), "start_vel");
  m.start_vel[0] = 0.0;  // at rest, any depth
  EXPECT_TRUE(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr).ok());
}

TEST(RequestAdapter, AnotherVehicleIsNamedFirst) {
  tdo::plan_request_t m = sample_request_msg();
  m.start[0] = kNaN;  // even a broken request for another vehicle is just not ours
  tdo_plan_request out{};
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 4, &out, nullptr), Reason::other_vehicle);
}

TEST(RequestAdapter, EveryNonFiniteNumberIsNamed) {
  double tdo::plan_request_t::*fields[] = {&tdo::plan_request_t::clearance,
                                           &tdo::plan_request_t::lambda_turn,
                                           &tdo::plan_request_t::mu,
                                           &tdo::plan_request_t::theta_max,
                                           &tdo::plan_request_t::d_th,
                                           &tdo::plan_request_t::h_weight,
                                           &tdo::plan_request_t::turn_threshold,
                                           &tdo::plan_request_t::k,
                                           &tdo::plan_request_t::v_max,
                                           &tdo::plan_request_t::a_max,
                                           &tdo::plan_request_t::j_max,
                                           &tdo::plan_request_t::a_lat_max,
                                           &tdo::plan_request_t::v_cruise,
                                           &tdo::plan_request_t::stop_angle,
                                           &tdo::plan_request_t::dt,
                                           &tdo::plan_request_t::corner_time};
  tdo_plan_request out{};
  for (double bad : {kNaN, kInf, -kInf}) {
    for (auto f : fields) {
      tdo::plan_request_t m = sample_request_msg();
      m.*f = bad;
      EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::non_finite);
    }
    for (int axis = 0; axis < 3; ++axis) {
      tdo::plan_request_t m = sample_request_msg();
      m.start[axis] = bad;
      const Check c = tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr);
      EXPECT_EQ(c.reason, Reason::non_finite);
      EXPECT_NE(c.detail.find("start[" + std::to_string(axis) + "]"), std::string::npos)
          << c.detail;
      m = sample_request_msg();
      m.goal[axis] = bad;
      EXPECT_REASON(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr), Reason::non_finite);
    }
  }
}

TEST(RequestAdapter, EnumsAndRanges) {
  tdo_plan_request out{};
  auto with = [](void (*mutate)(tdo::plan_request_t*)) {
    tdo::plan_request_t m = sample_request_msg();
    mutate(&m);
    return m;
  };
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(with([](tdo::plan_request_t* m) { m->depth = 4; }),
                                               3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(with([](tdo::plan_request_t* m) { m->depth = -1; }),
                                               3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(with([](tdo::plan_request_t* m) { m->search = 2; }),
                                               3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(
                    with([](tdo::plan_request_t* m) { m->correction = 3; }), 3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(
                    with([](tdo::plan_request_t* m) { m->smoothing = -2; }), 3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(
                    with([](tdo::plan_request_t* m) { m->grid_first = 3; }), 3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(
                    with([](tdo::plan_request_t* m) { m->grid_first = -1; }), 3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(with([](tdo::plan_request_t* m) { m->states = 2; }),
                                               3, &out, nullptr),
                Reason::bad_enum);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(
                    with([](tdo::plan_request_t* m) { m->max_expansions = -1; }), 3, &out, nullptr),
                Reason::out_of_range);
  EXPECT_REASON(tdo_lcm::plan_request_from_msg(with([](tdo::plan_request_t* m) { m->map_id = -2; }),
                                               3, &out, nullptr),
                Reason::out_of_range);
  // A negative clearance is valid: "the map's hint".
  EXPECT_TRUE(tdo_lcm::plan_request_from_msg(
                  with([](tdo::plan_request_t* m) { m->clearance = -1.0; }), 3, &out, nullptr)
                  .ok());
}

// ---- answers -----------------------------------------------------------------------------------

/** A synthetic plan result whose arrays live in this struct. */
struct FakeResult {
  std::vector<tdo_vec3> grid_path = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}};
  std::vector<tdo_vec3> waypoints = {{0, 0, 0}, {2, 1, 0}};
  std::vector<tdo_sample> samples;
  std::vector<tdo_violation> violations = {{0.5, TDO_QUANTITY_JERK, 12.0, 10.0}};
  tdo_plan_result r{};

  FakeResult() {
    for (int i = 0; i < 5; ++i) {
      const double t = 0.1 * i;
      samples.push_back(tdo_sample{t, {t, 2 * t, 0}, {1, 2, 0}, {0, 0, 0.5}});
    }
    r.status = TDO_OK;
    r.reached = TDO_PLAN_TRAJECTORY;
    r.search.cost = 2.41;
    r.search.expansions = 77;
    link();
    r.feasibility.ok = 1;
    r.feasibility.max_speed = 2.2;
    r.feasibility.max_acc = 1.0;
    r.feasibility.max_jerk = 3.0;
    r.feasibility.min_turn_radius = HUGE_VAL;
    r.feasibility.min_clearance = 0.8;
    r.feasibility.n_violations_total = 3;
    r.refinements = 1;
    r.metrics.length_m = 2.3;
    r.metrics.turns = 1;
    r.metrics.min_clearance_m = HUGE_VAL;  // documented: not computed
    r.metrics.smoothness = 0.9;
    r.metrics.flight_time_s = 0.4;
  }
  void link() {
    r.grid_path = grid_path.data();
    r.n_grid_path = static_cast<uint32_t>(grid_path.size());
    r.waypoints = waypoints.data();
    r.n_waypoints = static_cast<uint32_t>(waypoints.size());
    r.samples = samples.data();
    r.n_samples = static_cast<uint32_t>(samples.size());
    r.feasibility.violations = violations.data();
    r.feasibility.n_violations = static_cast<uint32_t>(violations.size());
  }
};

tdo_lcm::AnswerIds ids() {
  tdo_lcm::AnswerIds a;
  a.utime = 5;
  a.request_id = 42;
  a.vehicle_id = 3;
  a.map_id = 7;
  return a;
}

TEST(AnswerAdapter, TrajectoryRoundTrip) {
  FakeResult f;
  tdo::trajectory_t t{};
  ASSERT_TRUE(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 1.25, &t).ok());
  EXPECT_TRUE(tdo_lcm::check_counts(t).ok());
  EXPECT_EQ(t.request_id, 42);
  EXPECT_EQ(t.vehicle_id, 3);
  EXPECT_EQ(t.map_id, 7);
  EXPECT_EQ(t.status_code, 0);
  EXPECT_EQ(t.status, "ok");
  EXPECT_EQ(t.reached, tdo::plan_request_t::DEPTH_TRAJECTORY);
  EXPECT_EQ(t.n_grid_path, 3);
  EXPECT_EQ(t.grid_path[2], (std::vector<double>{2, 1, 0}));
  EXPECT_EQ(t.n_waypoints, 2);
  EXPECT_EQ(t.dt, 0.02);
  EXPECT_EQ(t.plan_time_ms, 1.25);
  EXPECT_EQ(t.expansions, 77);
  EXPECT_EQ(t.search_cost, 2.41);
  EXPECT_TRUE(std::isinf(t.min_clearance_m));
  std::vector<tdo_sample> back;
  ASSERT_TRUE(tdo_lcm::samples_from_msg(t, &back).ok());
  ASSERT_EQ(back.size(), f.samples.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].t, f.samples[i].t);
    EXPECT_EQ(back[i].p.y, f.samples[i].p.y);
    EXPECT_EQ(back[i].v.y, f.samples[i].v.y);
    EXPECT_EQ(back[i].a.z, f.samples[i].a.z);
  }
}

TEST(AnswerAdapter, FailedPlansKeepTheirStatus) {
  FakeResult f;
  f.r.status = TDO_ERR_NO_PATH;
  f.r.n_grid_path = 0;
  f.r.n_waypoints = 0;
  f.r.n_samples = 0;
  tdo::trajectory_t t{};
  ASSERT_TRUE(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t).ok());
  EXPECT_EQ(t.status, "no_path");
  EXPECT_EQ(t.status_code, TDO_ERR_NO_PATH);
  EXPECT_EQ(t.reached, -1);
  EXPECT_EQ(t.n_samples, 0);
}

TEST(AnswerAdapter, BadLibraryOutputIsRefused) {
  tdo::trajectory_t t{};
  {
    FakeResult f;
    f.samples[2].v.x = kNaN;
    f.link();
    EXPECT_REASON(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t),
                  Reason::non_finite);
  }
  {
    FakeResult f;
    f.waypoints[1].z = kInf;
    f.link();
    EXPECT_REASON(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t),
                  Reason::non_finite);
  }
  {
    FakeResult f;
    f.r.metrics.energy = kNaN;
    EXPECT_REASON(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t),
                  Reason::non_finite);
  }
  {
    FakeResult f;
    f.r.samples = nullptr;
    EXPECT_REASON(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t),
                  Reason::count_mismatch);
  }
  {
    FakeResult f;
    f.r.n_samples = 0x80000000u;  // more than a message can count
    EXPECT_REASON(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &t),
                  Reason::too_large);
  }
}

TEST(AnswerAdapter, FeasibilityReport) {
  FakeResult f;
  tdo::feasibility_t q{};
  ASSERT_TRUE(tdo_lcm::feasibility_to_msg(f.r, sample_request(), 0.3, ids(), &q).ok());
  EXPECT_TRUE(tdo_lcm::check_counts(q).ok());
  EXPECT_TRUE(q.checked);
  EXPECT_TRUE(q.ok);
  EXPECT_EQ(q.request_id, 42);
  EXPECT_EQ(q.max_speed, 2.2);
  EXPECT_TRUE(std::isinf(q.min_turn_radius));
  EXPECT_EQ(q.v_max, 3.0);
  EXPECT_EQ(q.a_max, 2.5);
  EXPECT_EQ(q.clearance, 0.3);
  EXPECT_EQ(q.refinements, 1);
  EXPECT_EQ(q.n_violations_total, 3);
  ASSERT_EQ(q.n_violations, 1);
  EXPECT_EQ(q.violation_what[0], tdo::feasibility_t::QUANTITY_JERK);
  EXPECT_EQ(q.violation_value[0], 12.0);
  EXPECT_EQ(q.violation_limit[0], 10.0);

  f.r.reached = TDO_PLAN_SMOOTH;  // no trajectory: nothing was checked
  ASSERT_TRUE(tdo_lcm::feasibility_to_msg(f.r, sample_request(), 0.3, ids(), &q).ok());
  EXPECT_FALSE(q.checked);
  EXPECT_FALSE(q.ok);

  f.r.feasibility.violations = nullptr;
  EXPECT_REASON(tdo_lcm::feasibility_to_msg(f.r, sample_request(), 0.3, ids(), &q),
                Reason::count_mismatch);
  f.link();
  f.r.feasibility.max_jerk = kNaN;
  EXPECT_REASON(tdo_lcm::feasibility_to_msg(f.r, sample_request(), 0.3, ids(), &q),
                Reason::non_finite);
}

TEST(AnswerAdapter, ErrorAnswers) {
  tdo::trajectory_t t{};
  tdo::feasibility_t q{};
  tdo_lcm::error_answer(ids(), tdo::trajectory_t::STATUS_REJECTED, "no_map", "no map yet", &t, &q);
  EXPECT_EQ(t.request_id, 42);
  EXPECT_EQ(t.status_code, -1);
  EXPECT_EQ(t.status, "no_map");
  EXPECT_EQ(t.detail, "no map yet");
  EXPECT_EQ(t.reached, -1);
  EXPECT_EQ(q.status, "no_map");
  EXPECT_FALSE(q.checked);
  EXPECT_TRUE(tdo_lcm::check_counts(t).ok());
  EXPECT_TRUE(tdo_lcm::check_counts(q).ok());
}

TEST(AnswerAdapter, SamplesFromAMessageAreChecked) {
  FakeResult f;
  tdo::trajectory_t good{};
  ASSERT_TRUE(tdo_lcm::trajectory_to_msg(f.r, sample_request(), ids(), 0.0, &good).ok());
  std::vector<tdo_sample> out;
  tdo::trajectory_t t = good;
  t.n_samples += 1;
  EXPECT_REASON(tdo_lcm::samples_from_msg(t, &out), Reason::count_mismatch);
  t = good;
  t.samples[1].pop_back();
  EXPECT_REASON(tdo_lcm::samples_from_msg(t, &out), Reason::count_mismatch);
  t = good;
  t.samples[3][5] = kNaN;
  EXPECT_REASON(tdo_lcm::samples_from_msg(t, &out), Reason::non_finite);
  t = good;
  t.samples[3][0] = t.samples[2][0];
  EXPECT_REASON(tdo_lcm::samples_from_msg(t, &out), Reason::out_of_range);
}

TEST(Counts, EveryArrayOfEveryPublishedType) {
  tdo::trajectory_t t{};
  EXPECT_TRUE(tdo_lcm::check_counts(t).ok());
  t.n_waypoints = 1;
  EXPECT_REASON(tdo_lcm::check_counts(t), Reason::count_mismatch);
  t.waypoints = {{1.0, 2.0}};
  EXPECT_REASON(tdo_lcm::check_counts(t), Reason::count_mismatch);
  t.waypoints = {{1.0, 2.0, 3.0}};
  EXPECT_TRUE(tdo_lcm::check_counts(t).ok());

  tdo::status_t s{};
  s.n_reasons = 1;
  s.reason = {"x"};
  EXPECT_REASON(tdo_lcm::check_counts(s), Reason::count_mismatch);
  s.reason_count = {1};
  EXPECT_TRUE(tdo_lcm::check_counts(s).ok());

  tdo::obstacles_t o{};
  o.n = 1;
  o.id = {1};
  o.position = {{0, 0, 0}};
  o.velocity = {{0, 0, 0}};
  EXPECT_REASON(tdo_lcm::check_counts(o), Reason::count_mismatch);
  o.radius = {1.0};
  EXPECT_TRUE(tdo_lcm::check_counts(o).ok());

  tdo::feasibility_t q{};
  q.n_violations = 1;
  q.violation_t = {0.0};
  q.violation_what = {0};
  q.violation_value = {0.0};
  EXPECT_REASON(tdo_lcm::check_counts(q), Reason::count_mismatch);
}

TEST(Reasons, EveryReasonHasAName) {
  for (int r = 0; r <= static_cast<int>(Reason::too_large); ++r)
    EXPECT_STRNE(tdo_lcm::reason_str(static_cast<Reason>(r)), "unknown_reason") << r;
  EXPECT_STREQ(tdo_lcm::reason_str(Reason::non_finite), "non_finite");
}

}  // namespace
