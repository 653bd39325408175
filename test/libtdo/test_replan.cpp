// Tests of replanning (replan.h): the blocked check on an updated grid and against movers, the
// takeover state, and the whole loop with the follower's switch (apf.h tdo_apf_switch): a wall
// published across the route mid-flight, a replan from the takeover state, a switch without a
// jump in the setpoint (independent finite differences), and no contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::TestPlanner;

double dist3(tdo_vec3 a, tdo_vec3 b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

/** Independent model: distance from p to a box. */
double box_dist(const tdo_box& b, tdo_vec3 p) {
  const tdo_vec3 c{std::fmin(std::fmax(p.x, b.min.x), b.max.x),
                   std::fmin(std::fmax(p.y, b.min.y), b.max.y),
                   std::fmin(std::fmax(p.z, b.min.z), b.max.z)};
  return dist3(p, c);
}

/** A 20 x 20 x 6 m hall at 1 m voxels, clearance 0.5 m, with a planner of every stage. */
class Replan : public ::testing::Test {
 protected:
  static tdo_capacity cap() {
    tdo_capacity c{};
    tdo_capacity_for_grid(&c, 20, 20, 6, 0.5, 27u, 0u);
    c.max_boxes = 16;
    return c;
  }
  Replan() : pl_(cap()) {}

 public:
  void SetUp() override {
    ASSERT_EQ(pl_.status(), TDO_OK);
    const tdo_grid_desc d{20, 20, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
    ASSERT_EQ(tdo_grid_reset(pl_.grid(), &d), TDO_OK);
    ASSERT_EQ(tdo_grid_finish(pl_.grid(), 0.5), TDO_OK);
  }
  /** Plan from start (moving with `st`) to goal into `out`. */
  tdo_status plan(tdo_vec3 start, tdo_start_state st, tdo_vec3 goal, std::vector<tdo_sample>* out) {
    tdo_plan_request r{};
    r.start = start;
    r.goal = goal;
    tdo_plan_params_default(&r.params);
    r.state = st;
    tdo_plan_result res{};
    const tdo_status s = tdo_planner_plan(pl_.planner(), &r, &res);
    if (s == TDO_OK) out->assign(res.samples, res.samples + res.n_samples);
    return s;
  }
  tdo_status add_box(const tdo_box& b) {
    tdo_grid_update u{};
    u.boxes = &b;
    u.n_boxes = 1u;
    return tdo_grid_apply_update(pl_.grid(), &u, nullptr);
  }
  tdo_replan_check_input check_in(const std::vector<tdo_sample>& s, double t, double h) {
    tdo_replan_check_input in{};
    in.grid = pl_.grid();
    in.samples = s.data();
    in.n_samples = static_cast<uint32_t>(s.size());
    in.t = t;
    in.horizon = h;
    in.clearance = 0.49;
    return in;
  }
  TestPlanner pl_;
};

const tdo_vec3 kStart{2.5, 10.5, 2.5}, kGoal{17.5, 10.5, 2.5};
const tdo_box kWall{{10.0, 6.0, 0.0}, {11.0, 15.0, 6.0}};  // across the route, a way round at y < 6

// GIVEN a straight plan on an empty hall WHEN a wall is added across it by a map update THEN the
// check reports it blocked (static) at the first piece that comes within the clearance (the
// independent box distance of the samples), not before; a horizon that ends earlier, or a check
// from beyond the wall, is clear.
TEST_F(Replan, WallAddedByAnUpdateBlocksThePlan) {
  std::vector<tdo_sample> s;
  ASSERT_EQ(plan(kStart, tdo_start_state{}, kGoal, &s), TDO_OK);
  tdo_replan_check_result r{};
  tdo_replan_check_input in = check_in(s, 0.0, 1e9);
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  EXPECT_EQ(r.blocked, 0);
  EXPECT_EQ(r.cause, TDO_REPLAN_CLEAR);
  EXPECT_EQ(r.pieces_checked, s.size() - 1u);
  ASSERT_EQ(add_box(kWall), TDO_OK);
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  ASSERT_EQ(r.blocked, 1);
  EXPECT_EQ(r.cause, TDO_REPLAN_STATIC);
  // Independent: the first sample closer than 0.49 m to the wall; the blocked piece ends there
  // or starts there.
  size_t first = 0;
  while (first < s.size() && box_dist(kWall, s[first].p) >= 0.49) ++first;
  ASSERT_LT(first, s.size());
  EXPECT_TRUE(r.index + 1u == first || r.index == first) << r.index << " vs " << first;
  EXPECT_NEAR(r.t_blocked, s[r.index].t, 1e-9);
  // A horizon ending before the blocked piece: clear.
  in.horizon = s[r.index].t - 0.5;
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  EXPECT_EQ(r.blocked, 0);
  // From a time past the wall: clear.
  size_t past = first;
  while (past < s.size() && box_dist(kWall, s[past].p) < 0.6) ++past;
  in = check_in(s, s[past].t, 1e9);
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  EXPECT_EQ(r.blocked, 0);
}

// Independent: distance from x to the segment a-b by ternary search on the segment parameter
// (the distance is convex along it).
double seg_dist(tdo_vec3 x, tdo_vec3 a, tdo_vec3 b) {
  double lo = 0.0, hi = 1.0;
  auto at = [&](double u) {
    return dist3(x, tdo_vec3{a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u, a.z + (b.z - a.z) * u});
  };
  for (int it = 0; it < 200; ++it) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (at(m1) < at(m2))
      hi = m2;
    else
      lo = m1;
  }
  return at(0.5 * (lo + hi));
}

// GIVEN a mover crossing the route and a box beside it WHEN its swept region over a window is
// listed THEN exactly the voxels an independent scan of the whole grid finds (centre within
// radius + pad of the swept segment, not occupied, outside the kept-free ball); a plan on the grid
// with them set keeps the planner's clearance from the region; clearing them restores every
// voxel's occupied and blocked state; a small buffer and bad input are named.
TEST_F(Replan, GivenAMoverRegion_WhenSetPlannedAndCleared_ThenThePlanAvoidsItAndTheGridIsRestored) {
  ASSERT_EQ(add_box(tdo_box{{9.0, 12.0, 0.0}, {11.0, 13.0, 6.0}}), TDO_OK);
  const tdo_grid_desc d = tdo_grid_get_desc(pl_.grid());
  std::vector<uint8_t> occ0, blk0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i) {
        occ0.push_back(static_cast<uint8_t>(tdo_grid_is_occupied(pl_.grid(), {i, j, k})));
        blk0.push_back(static_cast<uint8_t>(tdo_grid_is_blocked(pl_.grid(), {i, j, k})));
      }
  tdo_replan_mover_region rg{};
  rg.mover = tdo_mover{4u, {10.0, 4.0, 2.5}, {0.0, 1.0, 0.0}, 0.6};  // crosses y = 10.5 at t = 6.5
  rg.t0 = 5.5;
  rg.t1 = 7.5;
  rg.pad = 0.25;
  rg.keep_free = kStart;
  rg.keep_radius = 1.5;
  std::vector<tdo_voxel> cells(5000);
  uint32_t n = 0;
  ASSERT_EQ(tdo_replan_mover_voxels(pl_.grid(), &rg, cells.data(), 5000u, &n), TDO_OK);
  const tdo_vec3 a{10.0, 9.5, 2.5}, b{10.0, 11.5, 2.5};
  std::vector<tdo_voxel> want;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i) {
        const tdo_vec3 c{i + 0.5, j + 0.5, k + 0.5};
        if (seg_dist(c, a, b) <= 0.85 + 1e-9 && dist3(c, kStart) > 1.5 &&
            occ0[static_cast<size_t>((k * d.ny + j) * d.nx + i)] == 0u)
          want.push_back(tdo_voxel{i, j, k});
      }
  ASSERT_EQ(n, want.size());
  ASSERT_GT(n, 5u);
  for (uint32_t q = 0; q < n; ++q) {
    EXPECT_EQ(cells[q].i, want[q].i);
    EXPECT_EQ(cells[q].j, want[q].j);
    EXPECT_EQ(cells[q].k, want[q].k);
  }
  tdo_grid_update up{};
  up.set = cells.data();
  up.n_set = n;
  ASSERT_EQ(tdo_grid_apply_update(pl_.grid(), &up, nullptr), TDO_OK);
  std::vector<tdo_sample> s;
  ASSERT_EQ(plan(kStart, tdo_start_state{}, kGoal, &s), TDO_OK);
  for (const tdo_sample& x : s) {  // the plan keeps 0.49 m from every set cube
    for (uint32_t q = 0; q < n; ++q) {
      const tdo_box cube{{cells[q].i * 1.0, cells[q].j * 1.0, cells[q].k * 1.0},
                         {cells[q].i + 1.0, cells[q].j + 1.0, cells[q].k + 1.0}};
      ASSERT_GE(box_dist(cube, x.p), 0.49) << "t " << x.t;
    }
  }
  up.set = nullptr;
  up.n_set = 0u;
  up.clear = cells.data();
  up.n_clear = n;
  ASSERT_EQ(tdo_grid_apply_update(pl_.grid(), &up, nullptr), TDO_OK);
  size_t idx = 0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i, ++idx) {
        ASSERT_EQ(tdo_grid_is_occupied(pl_.grid(), {i, j, k}), occ0[idx]) << i << " " << j;
        ASSERT_EQ(tdo_grid_is_blocked(pl_.grid(), {i, j, k}), blk0[idx]) << i << " " << j;
      }
  // A buffer too small: named, the first ones listed.
  uint32_t m = 0;
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &rg, cells.data(), 3u, &m), TDO_ERR_MAP_CAPACITY);
  EXPECT_EQ(m, 3u);
  EXPECT_EQ(cells[0].i, want[0].i);
  // Bad input.
  tdo_replan_mover_region bad = rg;
  bad.t1 = 5.0;  // before t0
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &bad, cells.data(), 5000u, &m),
            TDO_ERR_INVALID_ARGUMENT);
  bad = rg;
  bad.mover.radius = 0.0;
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &bad, cells.data(), 5000u, &m),
            TDO_ERR_INVALID_ARGUMENT);
  bad = rg;
  bad.pad = std::nan("");
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &bad, cells.data(), 5000u, &m),
            TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_replan_mover_voxels(nullptr, &rg, cells.data(), 5000u, &m),
            TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &rg, nullptr, 5000u, &m), TDO_ERR_INVALID_ARGUMENT);
  // A region outside the grid: nothing.
  bad = rg;
  bad.mover.p = tdo_vec3{100.0, 100.0, 100.0};
  EXPECT_EQ(tdo_replan_mover_voxels(pl_.grid(), &bad, cells.data(), 5000u, &m), TDO_OK);
  EXPECT_EQ(m, 0u);
}

// GIVEN a straight plan and a mover that will sit on it WHEN checked with the mover THEN blocked by
// that mover (its id); a mover moving away is clear.
TEST_F(Replan, MoverPredictedOnThePlanBlocksIt) {
  std::vector<tdo_sample> s;
  ASSERT_EQ(plan(kStart, tdo_start_state{}, kGoal, &s), TDO_OK);
  // Where the plan is at t = 3 s; the mover arrives there at t = 3 s from 3 m to the side.
  const tdo_vec3 at3 = s[300].p;
  tdo_mover m{7u, {at3.x, at3.y - 3.0, at3.z}, {0.0, 1.0, 0.0}, 0.5};
  tdo_replan_check_input in = check_in(s, 0.0, 5.0);
  in.movers = &m;
  in.n_movers = 1u;
  in.mover_clearance = 0.3;
  tdo_replan_check_result r{};
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  ASSERT_EQ(r.blocked, 1);
  EXPECT_EQ(r.cause, TDO_REPLAN_MOVER);
  EXPECT_EQ(r.mover_id, 7u);
  // Independent: the sample where the predicted centre first comes within 0.8 m.
  size_t k = 0;
  while (k < s.size()) {
    const tdo_vec3 q{m.p.x + m.v.x * s[k].t, m.p.y + m.v.y * s[k].t, m.p.z};
    if (dist3(q, s[k].p) < 0.8) break;
    ++k;
  }
  EXPECT_EQ(r.index, k);
  m.v = tdo_vec3{0.0, -1.0, 0.0};
  ASSERT_EQ(tdo_replan_check(&in, &r), TDO_OK);
  EXPECT_EQ(r.blocked, 0);
}

TEST_F(Replan, BadInputIsNamed) {
  std::vector<tdo_sample> s;
  ASSERT_EQ(plan(kStart, tdo_start_state{}, kGoal, &s), TDO_OK);
  tdo_replan_check_result r{};
  EXPECT_EQ(tdo_replan_check(nullptr, &r), TDO_ERR_INVALID_ARGUMENT);
  tdo_replan_check_input in = check_in(s, std::nan(""), 1.0);
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_INVALID_ARGUMENT);
  in = check_in(s, 0.0, -1.0);
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_INVALID_ARGUMENT);
  in = check_in(s, 0.0, 1.0);
  in.n_samples = 1u;
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_INVALID_ARGUMENT);
  in = check_in(s, 0.0, 1.0);
  const tdo_mover bad{1u, {1, 1, 1}, {0, 0, 0}, 0.0};
  in.movers = &bad;
  in.n_movers = 1u;
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_sample> skewed = s;
  skewed.back().t += 0.5;
  in = check_in(skewed, 0.0, 1.0);
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_INVALID_ARGUMENT);
  tdo_replan_takeover_result k{};
  EXPECT_EQ(tdo_replan_takeover(s.data(), 1u, 0.0, 0.1, &k), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_replan_takeover(s.data(), static_cast<uint32_t>(s.size()), 0.0, -0.1, &k),
            TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_replan_takeover(nullptr, 5u, 0.0, 0.1, &k), TDO_ERR_INVALID_ARGUMENT);
  // An unfinished grid.
  const tdo_grid_desc d{20, 20, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(pl_.grid(), &d), TDO_OK);
  in = check_in(s, 0.0, 1.0);
  EXPECT_EQ(tdo_replan_check(&in, &r), TDO_ERR_MAP_NOT_READY);
}

// GIVEN a plan WHEN the takeover is asked at t + latency THEN it is the first sample at or after
// that time, exactly (p, v, a), and the last sample past the end.
TEST_F(Replan, TakeoverIsTheNextSampleExactly) {
  std::vector<tdo_sample> s;
  ASSERT_EQ(plan(kStart, tdo_start_state{}, kGoal, &s), TDO_OK);
  const uint32_t n = static_cast<uint32_t>(s.size());
  tdo_replan_takeover_result k{};
  ASSERT_EQ(tdo_replan_takeover(s.data(), n, 1.234, 0.2, &k), TDO_OK);
  EXPECT_EQ(k.index, 144u);  // 1.434 s rounded up to 0.01 s samples
  EXPECT_NEAR(k.t, 1.44, 1e-12);
  EXPECT_EQ(std::memcmp(&k.p, &s[144].p, sizeof(tdo_vec3)), 0);
  EXPECT_EQ(std::memcmp(&k.state.v, &s[144].v, sizeof(tdo_vec3)), 0);
  EXPECT_EQ(std::memcmp(&k.state.a, &s[144].a, sizeof(tdo_vec3)), 0);
  ASSERT_EQ(tdo_replan_takeover(s.data(), n, 1.5, 0.0, &k), TDO_OK);
  EXPECT_EQ(k.index, 150u) << "a sample time itself is not rounded up";
  ASSERT_EQ(tdo_replan_takeover(s.data(), n, s.back().t, 5.0, &k), TDO_OK);
  EXPECT_EQ(k.index, n - 1u);
}

struct Flight {
  std::vector<tdo_setpoint> sp;  // setpoints in order
  std::vector<tdo_vec3> ref;     // the follower's reference point per step
  std::vector<tdo_vehicle_state> st;
  int switch_step = -1;  // step whose output carried TDO_APF_EVENT_SWITCHED
  int switches = 0;
  double min_static = HUGE_VAL;
  bool arrived = false;
  double takeover_t = 0.0;  // s, trajectory time of the takeover
  tdo_status replan = TDO_ERR_NOT_CONFIGURED;
};

/** Fly the plan with E-APF; at t = 1.5 s publish the wall, check, take over at ref time + 0.2 s,
 *  replan, and switch with the switch time moved by `misalign` s (0: the takeover time). */
void fly_with_wall(Replan* fx, TestPlanner* pl, double misalign, Flight* f) {
  std::vector<tdo_sample> a;
  ASSERT_EQ(fx->plan(kStart, tdo_start_state{}, kGoal, &a), TDO_OK);
  tdo_apf_config cfg{4000u, 1u, 200u, 1u};
  tdo_sim_config scfg{1u};
  std::vector<unsigned char> mem(tdo_apf_footprint(&cfg) + tdo_sim_footprint(&scfg));
  tdo_arena arena;
  tdo_arena_init(&arena, mem.data(), mem.size());
  tdo_apf* apf = nullptr;
  ASSERT_EQ(tdo_apf_init(&apf, &arena, &cfg), TDO_OK);
  tdo_sim* sim = nullptr;
  ASSERT_EQ(tdo_sim_init(&sim, &arena, &scfg), TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  tdo_apf_task task{a.data(), static_cast<uint32_t>(a.size()), kGoal, pl->grid(), 0.0};
  ASSERT_EQ(tdo_apf_reset(apf, &p, &task), TDO_OK);
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.bounds = tdo_box{{0, 0, 0}, {20, 20, 6}};
  sp.grid = pl->grid();  // the same grid: the wall counts for the simulator too once published
  tdo_vehicle_state s0{};
  s0.p = kStart;
  ASSERT_EQ(tdo_sim_reset(sim, &sp, &s0, nullptr, 0u), TDO_OK);
  tdo_sim_output so{};
  ASSERT_EQ(tdo_sim_get(sim, &so), TDO_OK);
  std::vector<tdo_sample> b;
  for (int k = 0; k < 1500; ++k) {
    tdo_apf_input in{so.state, nullptr, 0u};
    tdo_apf_output out;
    ASSERT_EQ(tdo_apf_run(apf, &in, &out), TDO_OK);
    if ((out.events & TDO_APF_EVENT_SWITCHED) != 0u) {
      f->switch_step = k;
      ++f->switches;
    }
    f->sp.push_back(out.setpoint);
    f->ref.push_back(out.terms.ref);
    if (k == 75) {  // t = 1.5 s: the wall appears
      ASSERT_EQ(fx->add_box(kWall), TDO_OK);
      tdo_replan_check_input ci = fx->check_in(a, out.ref_time, 1e9);
      tdo_replan_check_result cr{};
      ASSERT_EQ(tdo_replan_check(&ci, &cr), TDO_OK);
      ASSERT_EQ(cr.blocked, 1);
      tdo_replan_takeover_result tk{};
      ASSERT_EQ(
          tdo_replan_takeover(a.data(), static_cast<uint32_t>(a.size()), out.ref_time, 0.2, &tk),
          TDO_OK);
      f->takeover_t = tk.t;
      f->replan = fx->plan(tk.p, tk.state, kGoal, &b);
      ASSERT_EQ(f->replan, TDO_OK);
      // Item 1's guarantee, which the switch relies on: the new plan starts in that state.
      ASSERT_EQ(std::memcmp(&b[0].p, &tk.p, sizeof(tdo_vec3)), 0);
      ASSERT_EQ(std::memcmp(&b[0].v, &tk.state.v, sizeof(tdo_vec3)), 0);
      ASSERT_EQ(std::memcmp(&b[0].a, &tk.state.a, sizeof(tdo_vec3)), 0);
      tdo_apf_task tb{b.data(), static_cast<uint32_t>(b.size()), kGoal, pl->grid(), 0.0};
      ASSERT_EQ(tdo_apf_switch(apf, &tb, tk.t + misalign), TDO_OK);
    }
    tdo_sim_input si{out.setpoint};
    ASSERT_EQ(tdo_sim_run(sim, &si, &so), TDO_OK);
    f->st.push_back(so.state);
    if (k > 75) f->min_static = std::fmin(f->min_static, so.static_dist);
    if (dist3(so.state.p, kGoal) < 0.2 && k > 200) {
      f->arrived = true;
      break;
    }
  }
}

/** Largest jump of the second finite difference of a point sequence within `w` steps of `k`,
 *  over dt^2 (m/s^2): a jump in position or velocity shows up as a spike. */
double max_fd_acc(const std::vector<tdo_vec3>& x, int k, int w, double dt) {
  double m = 0.0;
  for (int i = std::max(1, k - w); i < std::min(static_cast<int>(x.size()) - 1, k + w); ++i) {
    const tdo_vec3 d{x[i + 1].x - 2 * x[i].x + x[i - 1].x, x[i + 1].y - 2 * x[i].y + x[i - 1].y,
                     x[i + 1].z - 2 * x[i].z + x[i - 1].z};
    m = std::fmax(m, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z) / (dt * dt));
  }
  return m;
}

// GIVEN E-APF flying a plan when a wall is published across it at t = 1.5 s WHEN the check finds
// it blocked, a new plan is made from the takeover state 0.2 s ahead and handed over with
// tdo_apf_switch THEN the switch happens once, at the takeover time, the reference and the
// setpoints pass without a jump (finite differences of positions: acceleration within a_max and
// the jerk within j_max across the switch), and the vehicle goes round the wall to the goal
// without coming within its radius of it. A switch time misaligned by 0.3 s makes the reference
// jump (the check can fail).
TEST_F(Replan, GivenAWallMidFlight_WhenReplannedAndSwitched_ThenNoJumpAndNoContact) {
  Flight f;
  fly_with_wall(this, &pl_, 0.0, &f);
  ASSERT_EQ(f.replan, TDO_OK);
  EXPECT_EQ(f.switches, 1);
  ASSERT_GT(f.switch_step, 75);
  // The reference time reached the takeover time at that step: 0.2 s (10 steps) after the
  // trigger, within one step.
  EXPECT_NEAR(f.switch_step, 75 + 10, 1);
  const double dt = 0.02;
  // Reference positions: their second differences stay within a_max (1 %) around the switch.
  EXPECT_LE(max_fd_acc(f.ref, f.switch_step, 10, dt), 3.0 * 1.01);
  // Setpoints: positions' second differences (acceleration) within a_max, the setpoint's own
  // v and a continuous (a within j_max dt per step, v within a_max dt).
  std::vector<tdo_vec3> sp_p;
  for (const auto& x : f.sp) sp_p.push_back(x.p);
  EXPECT_LE(max_fd_acc(sp_p, f.switch_step, 10, dt), 3.0 * 1.01);
  for (int i = f.switch_step - 10; i < f.switch_step + 10; ++i) {
    const tdo_setpoint& u = f.sp[static_cast<size_t>(i)];
    const tdo_setpoint& w = f.sp[static_cast<size_t>(i) + 1u];
    EXPECT_LE(dist3(w.a, u.a), 10.0 * dt * 1.01) << "step " << i;
    EXPECT_LE(dist3(w.v, u.v), 3.0 * dt * 1.01) << "step " << i;
    // p, v and a agree with each other: the position step is the mean velocity times dt.
    const tdo_vec3 vm{(u.v.x + w.v.x) / 2, (u.v.y + w.v.y) / 2, (u.v.z + w.v.z) / 2};
    EXPECT_NEAR(dist3(w.p, tdo_vec3{u.p.x + vm.x * dt, u.p.y + vm.y * dt, u.p.z + vm.z * dt}), 0.0,
                1e-9);
  }
  EXPECT_TRUE(f.arrived);
  EXPECT_GE(f.min_static, 0.25) << "came within the vehicle radius of the wall";
  // Control: the same switch misaligned by 0.3 s: the reference jumps.
  SetUp();
  Flight g;
  fly_with_wall(this, &pl_, -0.3, &g);
  ASSERT_EQ(g.switches, 1);
  EXPECT_GT(max_fd_acc(g.ref, g.switch_step, 2, dt), 3.0 * 2.0)
      << "a misaligned switch must show as a jump of the reference";
}

}  // namespace
