// The E-APF follower and the classical APF baseline (apf.h): forces against finite differences of
// the potentials and an independent closest-point model, the potential along an executed path,
// the U-shaped trap, tracking accuracy, determinism, capacities and bad parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "rng.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::TestPlanner;

constexpr double kPi = 3.14159265358979323846;

double norm3(tdo_vec3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
tdo_vec3 sub3(tdo_vec3 a, tdo_vec3 b) { return tdo_vec3{a.x - b.x, a.y - b.y, a.z - b.z}; }

/** A follower in a heap block of exactly its footprint. */
struct Follower {
  std::vector<unsigned char> mem;
  tdo_arena arena{};
  tdo_apf* apf = nullptr;
  tdo_status init_status = TDO_ERR_INVALID_ARGUMENT;
  explicit Follower(uint32_t samples, uint32_t movers = 8u, uint32_t window = 100000u,
                    uint32_t switching = 0u) {
    tdo_apf_config cfg{samples, movers, window, switching};
    mem.assign(tdo_apf_footprint(&cfg), 0u);
    tdo_arena_init(&arena, mem.data(), mem.size());
    init_status = tdo_apf_init(&apf, &arena, &cfg);
  }
};

/** A simulator in a heap block of exactly its footprint. */
struct Sim {
  std::vector<unsigned char> mem;
  tdo_arena arena{};
  tdo_sim* sim = nullptr;
  explicit Sim(uint32_t movers) {
    tdo_sim_config cfg{movers};
    mem.assign(tdo_sim_footprint(&cfg), 0u);
    tdo_arena_init(&arena, mem.data(), mem.size());
    EXPECT_EQ(tdo_sim_init(&sim, &arena, &cfg), TDO_OK);
  }
};

/** Rest-to-rest half circle (radius 5 m, z = 2 m) in `T` s, quintic in the angle, every `dt`. */
std::vector<tdo_sample> arc_trajectory(double T, double dt, tdo_vec3 c = {10.0, 10.0, 2.0}) {
  std::vector<tdo_sample> s;
  const double R = 5.0;
  const int n = static_cast<int>(std::lround(T / dt));
  for (int i = 0; i <= n; ++i) {
    const double t = i * dt, u = t / T;
    const double th = kPi * (10 * u * u * u - 15 * u * u * u * u + 6 * u * u * u * u * u);
    const double thd = kPi * (30 * u * u - 60 * u * u * u + 30 * u * u * u * u) / T;
    const double thdd = kPi * (60 * u - 180 * u * u + 120 * u * u * u) / (T * T);
    tdo_sample x{};
    x.t = t;
    x.p = tdo_vec3{c.x + R * std::cos(th), c.y + R * std::sin(th), c.z};
    x.v = tdo_vec3{-R * std::sin(th) * thd, R * std::cos(th) * thd, 0.0};
    x.a = tdo_vec3{-R * (std::cos(th) * thd * thd + std::sin(th) * thdd),
                   R * (-std::sin(th) * thd * thd + std::cos(th) * thdd), 0.0};
    s.push_back(x);
  }
  return s;
}

/** A finished 20 x 20 x 6 m grid with the given boxes. */
void make_grid(TestPlanner* tp, const std::vector<tdo_box>& boxes) {
  ASSERT_EQ(tp->status(), TDO_OK);
  const tdo_grid_desc d{20, 20, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(tp->grid(), &d), TDO_OK);
  for (const auto& b : boxes) ASSERT_EQ(tdo_grid_add_box(tp->grid(), &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(tp->grid(), 0.5), TDO_OK);
}

tdo_capacity small_cap() { return tdo_test::make_cap(20u * 20u * 6u, 27u * 2400u, 2400u, 16u); }

/** Independent model: closest point of a box to p. */
tdo_vec3 box_closest(const tdo_box& b, tdo_vec3 p) {
  return tdo_vec3{std::fmin(std::fmax(p.x, b.min.x), b.max.x),
                  std::fmin(std::fmax(p.y, b.min.y), b.max.y),
                  std::fmin(std::fmax(p.z, b.min.z), b.max.z)};
}

// GIVEN the documented defaults WHEN they are checked THEN reset accepts them for both kinds.
TEST(Apf, DefaultsAreValid) {
  const auto traj = arc_trajectory(12.0, 0.01);
  Follower f(static_cast<uint32_t>(traj.size()));
  ASSERT_EQ(f.init_status, TDO_OK);
  for (tdo_follower_kind k : {TDO_FOLLOWER_EAPF, TDO_FOLLOWER_APF}) {
    tdo_apf_params p;
    tdo_apf_params_default(&p, k);
    EXPECT_EQ(p.kind, k);
    EXPECT_DOUBLE_EQ(p.dt, 0.02);  // 50 Hz
    EXPECT_DOUBLE_EQ(p.v_max, 3.0);
    EXPECT_DOUBLE_EQ(p.a_max, 3.0);
    EXPECT_DOUBLE_EQ(p.j_max, 10.0);
    tdo_apf_task task{traj.data(), static_cast<uint32_t>(traj.size()), traj.back().p, nullptr, 0.0};
    EXPECT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  }
}

TEST(Apf, FootprintAndInit) {
  tdo_apf_config bad{1u, 1u, 1u, 0u};
  EXPECT_EQ(tdo_apf_footprint(&bad), 0u);
  bad = tdo_apf_config{10u, 0u, 1u, 0u};
  EXPECT_EQ(tdo_apf_footprint(&bad), 0u);
  bad = tdo_apf_config{10u, 1u, 0u, 0u};
  EXPECT_EQ(tdo_apf_footprint(&bad), 0u);
  EXPECT_EQ(tdo_apf_footprint(nullptr), 0u);
  tdo_apf_config cfg{100u, 4u, 10u, 0u};
  const size_t fp = tdo_apf_footprint(&cfg);
  ASSERT_GT(fp, 100u * sizeof(tdo_sample));
  std::vector<unsigned char> mem(fp);
  tdo_arena a;
  tdo_arena_init(&a, mem.data(), fp - 1u);
  tdo_apf* apf = nullptr;
  EXPECT_EQ(tdo_apf_init(&apf, &a, &cfg), TDO_ERR_ARENA_TOO_SMALL);
  tdo_arena_init(&a, mem.data(), fp);
  EXPECT_EQ(tdo_apf_init(&apf, &a, &cfg), TDO_OK);
  EXPECT_EQ(tdo_apf_init(nullptr, &a, &cfg), TDO_ERR_INVALID_ARGUMENT);
  // Not reset yet.
  tdo_vehicle_state s{};
  tdo_setpoint sp{};
  EXPECT_EQ(tdo_apf_step(apf, &s, nullptr, 0u, &sp), TDO_ERR_NOT_CONFIGURED);
}

TEST(Apf, BadParametersAndCapacities) {
  const auto traj = arc_trajectory(12.0, 0.01);
  const uint32_t n = static_cast<uint32_t>(traj.size());
  Follower f(n, 2u);
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  tdo_apf_task task{traj.data(), n, traj.back().p, nullptr, 0.0};
  auto with = [&](auto mutate) {
    tdo_apf_params q = p;
    mutate(&q);
    return tdo_apf_reset(f.apf, &q, &task);
  };
  EXPECT_EQ(with([](tdo_apf_params* q) { q->dt = 0.0; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](tdo_apf_params* q) { q->k_a = -1.0; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](tdo_apf_params* q) { q->d_0 = std::nan(""); }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](tdo_apf_params* q) { q->v_max = HUGE_VAL; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](tdo_apf_params* q) { q->k_r = -0.1; }), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](tdo_apf_params* q) {
              const int bad = 7;  // not a tdo_follower_kind
              static_assert(sizeof(q->kind) == sizeof(bad), "enum size");
              std::memcpy(&q->kind, &bad, sizeof bad);
            }),
            TDO_ERR_INVALID_ARGUMENT);
  // A failed reset leaves the follower unconfigured.
  tdo_vehicle_state s{};
  s.p = traj[0].p;
  tdo_setpoint sp{};
  EXPECT_EQ(tdo_apf_step(f.apf, &s, nullptr, 0u, &sp), TDO_ERR_NOT_CONFIGURED);
  // Trajectory checks.
  tdo_apf_task t2 = task;
  t2.n_samples = 1u;
  EXPECT_EQ(tdo_apf_reset(f.apf, &p, &t2), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_sample> uneven = traj;
  uneven[5].t += 0.003;
  t2 = task;
  t2.samples = uneven.data();
  EXPECT_EQ(tdo_apf_reset(f.apf, &p, &t2), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_sample> longer = traj;
  longer.push_back(traj.back());
  longer.back().t = traj.back().t + 0.01;
  t2.samples = longer.data();
  t2.n_samples = n + 1u;
  EXPECT_EQ(tdo_apf_reset(f.apf, &p, &t2), TDO_ERR_SAMPLE_CAPACITY);
  // APF needs no trajectory but a finite goal.
  tdo_apf_params pa;
  tdo_apf_params_default(&pa, TDO_FOLLOWER_APF);
  tdo_apf_task ta{nullptr, 0u, tdo_vec3{1.0, 2.0, std::nan("")}, nullptr, 0.0};
  EXPECT_EQ(tdo_apf_reset(f.apf, &pa, &ta), TDO_ERR_INVALID_ARGUMENT);
  ta.goal.z = 3.0;
  EXPECT_EQ(tdo_apf_reset(f.apf, &pa, &ta), TDO_OK);
  // Unfinished grid.
  TestPlanner tp(small_cap());
  const tdo_grid_desc d{20, 20, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(tp.grid(), &d), TDO_OK);
  ta.grid = tp.grid();
  EXPECT_EQ(tdo_apf_reset(f.apf, &pa, &ta), TDO_ERR_MAP_NOT_READY);
  // Step: mover capacity and bad movers.
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  tdo_mover m[3] = {{1u, {0.0, 0.0, 2.0}, {0.0, 0.0, 0.0}, 0.5},
                    {2u, {1.0, 0.0, 2.0}, {0.0, 0.0, 0.0}, 0.5},
                    {3u, {2.0, 0.0, 2.0}, {0.0, 0.0, 0.0}, 0.5}};
  EXPECT_EQ(tdo_apf_step(f.apf, &s, m, 3u, &sp), TDO_ERR_OBSTACLE_CAPACITY);
  m[0].radius = 0.0;
  EXPECT_EQ(tdo_apf_step(f.apf, &s, m, 2u, &sp), TDO_ERR_INVALID_ARGUMENT);
  m[0].radius = 0.5;
  m[1].v.x = std::nan("");
  EXPECT_EQ(tdo_apf_step(f.apf, &s, m, 2u, &sp), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_apf_step(f.apf, &s, nullptr, 1u, &sp), TDO_ERR_INVALID_ARGUMENT);
  s.v.y = std::nan("");
  EXPECT_EQ(tdo_apf_step(f.apf, &s, nullptr, 0u, &sp), TDO_ERR_INVALID_ARGUMENT);
  s.v.y = 0.0;
  EXPECT_EQ(tdo_apf_step(f.apf, &s, m, 1u, &sp), TDO_OK);
}

// GIVEN a box, a trajectory and movers WHEN the field is evaluated at random points THEN every
// force equals minus the central difference of its potential, and the static repulsion matches
// an independent closest-point model of the box.
TEST(Apf, ForcesAreMinusGradients) {
  TestPlanner tp(small_cap());
  const tdo_box box{{9.0, 9.0, 0.0}, {11.0, 11.0, 3.0}};
  make_grid(&tp, {box});
  const auto traj = arc_trajectory(12.0, 0.01);
  Follower f(static_cast<uint32_t>(traj.size()));
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  p.d_0_static = 1.0;  // wide enough to sample the static field
  p.k_r_static = 0.7;
  tdo_apf_task task{traj.data(), static_cast<uint32_t>(traj.size()), traj.back().p, tp.grid(), 0.0};
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  tdo_test::Rng rng(7);
  int checked_static = 0, checked_movers = 0, checked_att = 0;
  for (int trial = 0; trial < 400; ++trial) {
    tdo_vehicle_state s{};
    // Points around the box face x = 11 (static) and near the arc.
    if (trial % 2 == 0)
      s.p = tdo_vec3{rng.uniform(11.3, 12.2), rng.uniform(8.0, 12.0), rng.uniform(0.5, 3.8)};
    else
      s.p = tdo_vec3{rng.uniform(4.0, 16.0), rng.uniform(10.5, 16.0), rng.uniform(1.0, 3.0)};
    s.v = tdo_vec3{rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), rng.uniform(-0.5, 0.5)};
    tdo_mover m[2] = {
        {1u,
         {s.p.x + rng.uniform(-3.0, 3.0), s.p.y + rng.uniform(-3.0, 3.0), s.p.z + 0.3},
         {rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), 0.0},
         0.6},
        {2u, {s.p.x + 2.5, s.p.y - 1.0, s.p.z}, {-1.0, 0.5, 0.0}, 0.8}};
    tdo_apf_terms t0{};
    ASSERT_EQ(tdo_apf_eval(f.apf, &s, m, 2u, &t0), TDO_OK);
    // Stay away from the floors and kinks of the potentials.
    if (t0.mover_pred_gap < 0.2 || t0.static_dist - p.vehicle_radius < 0.15) continue;
    const double h = 1e-5;
    tdo_vec3 g_att{}, g_guide{}, g_static{}, g_movers{};
    double* comps[4][3] = {{&g_att.x, &g_att.y, &g_att.z},
                           {&g_guide.x, &g_guide.y, &g_guide.z},
                           {&g_static.x, &g_static.y, &g_static.z},
                           {&g_movers.x, &g_movers.y, &g_movers.z}};
    for (int ax = 0; ax < 3; ++ax) {
      tdo_vehicle_state sp = s, sm = s;
      double* cp = ax == 0 ? &sp.p.x : ax == 1 ? &sp.p.y : &sp.p.z;
      double* cm = ax == 0 ? &sm.p.x : ax == 1 ? &sm.p.y : &sm.p.z;
      *cp += h;
      *cm -= h;
      // The movers are fixed in the world: evaluate with the same mover states.
      tdo_apf_terms tp1{}, tm1{};
      ASSERT_EQ(tdo_apf_eval(f.apf, &sp, m, 2u, &tp1), TDO_OK);
      ASSERT_EQ(tdo_apf_eval(f.apf, &sm, m, 2u, &tm1), TDO_OK);
      *comps[0][ax] = -(tp1.u_att - tm1.u_att) / (2 * h);
      *comps[1][ax] = -(tp1.u_guide - tm1.u_guide) / (2 * h);
      *comps[2][ax] = -(tp1.u_rep_static - tm1.u_rep_static) / (2 * h);
      *comps[3][ax] = -(tp1.u_rep_movers - tm1.u_rep_movers) / (2 * h);
    }
    auto close = [](tdo_vec3 a, tdo_vec3 b, double tol) {
      return norm3(sub3(a, b)) <= tol * (1.0 + norm3(b));
    };
    EXPECT_TRUE(close(t0.f_att, g_att, 1e-4)) << "trial " << trial;
    // The squared distance to the curve is smooth where the nearest point is unique: near it.
    if (t0.deviation < 1.5) {
      EXPECT_TRUE(close(t0.f_guide, g_guide, 1e-4)) << "trial " << trial;
    }
    ++checked_att;
    if (t0.u_rep_static > 0.0) {
      EXPECT_TRUE(close(t0.f_rep_static, g_static, 2e-3)) << "trial " << trial;
      // Independent model: one box, exact closest point.
      const tdo_vec3 q = box_closest(box, s.p);
      const tdo_vec3 r = sub3(s.p, q);
      const double dist = norm3(r);
      const double d = dist - p.vehicle_radius;
      const double mag = p.k_r_static * (1.0 / d - 1.0 / p.d_0_static) / (d * d);
      const tdo_vec3 expect{mag * r.x / dist, mag * r.y / dist, mag * r.z / dist};
      EXPECT_TRUE(close(t0.f_rep_static, expect, 2e-3)) << "trial " << trial;
      EXPECT_NEAR(t0.static_dist, dist, 1e-9);
      ++checked_static;
    }
    if (t0.u_rep_movers > 0.0) {
      EXPECT_TRUE(close(t0.f_rep_movers, g_movers, 1e-3)) << "trial " << trial;
      ++checked_movers;
    }
    // The total is the sum.
    EXPECT_NEAR(t0.u_total, t0.u_att + t0.u_guide + t0.u_rep_static + t0.u_rep_movers, 1e-12);
  }
  EXPECT_GT(checked_att, 100);
  EXPECT_GT(checked_static, 30);
  EXPECT_GT(checked_movers, 30);
}

// GIVEN the classical APF in a static scene (a box beside the straight line to the goal) WHEN it
// flies in the simulator THEN the total potential, sampled every 0.5 s, decreases until arrival.
TEST(Apf, StaticPotentialDecreasesAlongExecutedPath) {
  TestPlanner tp(small_cap());
  make_grid(&tp, {tdo_box{{8.0, 5.2, 0.0}, {10.0, 7.0, 6.0}}});
  Follower f(2u, 1u, 1u);
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_APF);
  const tdo_vec3 goal{17.0, 4.0, 3.0};
  tdo_apf_task task{nullptr, 0u, goal, tp.grid(), 0.0};
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  Sim sim(1u);
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.bounds = tdo_box{{0.0, 0.0, 0.0}, {20.0, 20.0, 6.0}};
  sp.grid = tp.grid();
  tdo_vehicle_state s0{};
  s0.p = tdo_vec3{2.0, 4.0, 3.0};
  ASSERT_EQ(tdo_sim_reset(sim.sim, &sp, &s0, nullptr, 0u), TDO_OK);
  tdo_vehicle_state s = s0;
  double last_u = HUGE_VAL;
  bool repulsed = false, arrived = false;
  for (int k = 0; k < 3000 && !arrived; ++k) {
    tdo_apf_input in{s, nullptr, 0u};
    tdo_apf_output out;
    ASSERT_EQ(tdo_apf_run(f.apf, &in, &out), TDO_OK);
    if (out.terms.u_rep_static > 0.0) repulsed = true;
    if (k % 25 == 0) {
      EXPECT_LT(out.terms.u_total, last_u) << "t = " << s.t;
      last_u = out.terms.u_total;
    }
    arrived = (out.events & TDO_APF_EVENT_GOAL_REACHED) != 0u;
    ASSERT_EQ(tdo_sim_step(sim.sim, &out.setpoint, &s), TDO_OK);
  }
  EXPECT_TRUE(arrived);
  EXPECT_TRUE(repulsed) << "the box must have acted on the path";
  EXPECT_LT(norm3(sub3(s.p, goal)), p.goal_tol);
}

/** A U-shaped cup open towards -x; the goal lies behind its bottom wall. */
std::vector<tdo_box> cup() {
  return {tdo_box{{10.0, 6.0, 0.0}, {10.5, 14.0, 6.0}},   // bottom (x = 10..10.5)
          tdo_box{{5.0, 6.0, 0.0}, {10.5, 6.5, 6.0}},     // side y = 6
          tdo_box{{5.0, 13.5, 0.0}, {10.5, 14.0, 6.0}}};  // side y = 14
}

// GIVEN the classical APF inside a U-shaped cup with the goal behind it WHEN it flies THEN it is
// trapped: the detector fires (small force, no progress, far from the goal), escapes start, and
// the episode ends either at the goal or with TDO_ERR_LOCAL_MINIMUM; never a crash or a hang.
TEST(Apf, UTrapIsDetected) {
  TestPlanner tp(small_cap());
  make_grid(&tp, cup());
  for (uint32_t max_escapes : {0u, 3u}) {
    Follower f(2u, 1u, 1u);
    ASSERT_EQ(f.init_status, TDO_OK);
    tdo_apf_params p;
    tdo_apf_params_default(&p, TDO_FOLLOWER_APF);
    p.max_escapes = max_escapes;
    const tdo_vec3 goal{16.0, 10.0, 3.0};
    tdo_apf_task task{nullptr, 0u, goal, tp.grid(), 0.0};
    ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
    Sim sim(1u);
    tdo_sim_params sp;
    tdo_sim_params_default(&sp);
    sp.bounds = tdo_box{{0.0, 0.0, 0.0}, {20.0, 20.0, 6.0}};
    sp.grid = tp.grid();
    tdo_vehicle_state s{};
    s.p = tdo_vec3{7.0, 10.0, 3.0};
    ASSERT_EQ(tdo_sim_reset(sim.sim, &sp, &s, nullptr, 0u), TDO_OK);
    uint32_t detections = 0, escapes = 0;
    bool failed = false, arrived = false;
    double first_detection = -1.0;
    for (int k = 0; k < 6000 && !failed && !arrived; ++k) {  // 120 s
      tdo_apf_input in{s, nullptr, 0u};
      tdo_apf_output out;
      const tdo_status st = tdo_apf_run(f.apf, &in, &out);
      ASSERT_TRUE(st == TDO_OK || st == TDO_ERR_LOCAL_MINIMUM) << tdo_status_str(st);
      if ((out.events & TDO_APF_EVENT_LM_DETECTED) != 0u) {
        ++detections;
        if (first_detection < 0.0) {
          first_detection = s.t;
          // Detected where the field is weak, far from the goal, inside the cup.
          EXPECT_LT(s.p.x, 10.0);
          EXPECT_GT(norm3(sub3(s.p, goal)), p.lm_goal_dist);
        }
      }
      if ((out.events & TDO_APF_EVENT_ESCAPE_START) != 0u) ++escapes;
      if (st == TDO_ERR_LOCAL_MINIMUM) {
        failed = true;
        EXPECT_NE(out.events & TDO_APF_EVENT_ESCAPE_FAILED, 0u);
        EXPECT_EQ(out.mode, TDO_APF_MODE_STUCK);
        // The braking setpoint is still within the limits.
        EXPECT_LE(norm3(out.setpoint.a), p.a_max + 1e-9);
        EXPECT_LE(norm3(out.setpoint.v), p.v_max + 1e-9);
        // And the status stays.
        ASSERT_EQ(tdo_sim_step(sim.sim, &out.setpoint, &s), TDO_OK);
        tdo_setpoint again{};
        EXPECT_EQ(tdo_apf_step(f.apf, &s, nullptr, 0u, &again), TDO_ERR_LOCAL_MINIMUM);
      }
      arrived = (out.events & TDO_APF_EVENT_GOAL_REACHED) != 0u;
      ASSERT_EQ(tdo_sim_step(sim.sim, &out.setpoint, &s), TDO_OK);
    }
    EXPECT_GE(detections, 1u) << "max_escapes " << max_escapes;
    EXPECT_GT(first_detection, 0.0);
    EXPECT_LT(first_detection, 15.0);
    EXPECT_TRUE(failed || arrived) << "max_escapes " << max_escapes;
    EXPECT_LE(escapes, max_escapes);
    if (max_escapes == 0u) {
      EXPECT_TRUE(failed);
      EXPECT_EQ(escapes, 0u);
    } else {
      EXPECT_GE(escapes, 1u);
    }
  }
}

/** Fly `traj` with E-APF in the simulator; return the mean and max distance to the polyline. */
void fly_track(const std::vector<tdo_sample>& traj, const tdo_mover* movers, uint32_t n_movers,
               double* mean_dev, double* max_dev, std::vector<tdo_vehicle_state>* states,
               double* min_gap) {
  Follower f(static_cast<uint32_t>(traj.size()), 4u, 200u);
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  tdo_apf_task task{traj.data(), static_cast<uint32_t>(traj.size()), traj.back().p, nullptr, 0.0};
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  Sim sim(4u);
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.bounds = tdo_box{{0.0, 0.0, 0.0}, {20.0, 20.0, 6.0}};
  tdo_vehicle_state s{};
  s.p = traj[0].p;
  ASSERT_EQ(tdo_sim_reset(sim.sim, &sp, &s, movers, n_movers), TDO_OK);
  double sum = 0.0, mx = 0.0;
  int n = 0;
  *min_gap = HUGE_VAL;
  tdo_sim_output so;
  ASSERT_EQ(tdo_sim_get(sim.sim, &so), TDO_OK);
  for (int k = 0; k < 1500; ++k) {
    tdo_apf_input in{so.state, so.movers, so.n_movers};
    tdo_apf_output out;
    ASSERT_EQ(tdo_apf_run(f.apf, &in, &out), TDO_OK);
    tdo_sim_input si{out.setpoint};
    ASSERT_EQ(tdo_sim_run(sim.sim, &si, &so), TDO_OK);
    states->push_back(so.state);
    *min_gap = std::fmin(*min_gap, so.mover_gap);
    // Independent distance to the polyline.
    double best = HUGE_VAL;
    for (size_t i = 0; i + 1 < traj.size(); ++i) {
      const tdo_vec3 a = traj[i].p, b = traj[i + 1].p, ab = sub3(b, a), ap = sub3(so.state.p, a);
      const double l2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
      double u = l2 > 0 ? (ap.x * ab.x + ap.y * ab.y + ap.z * ab.z) / l2 : 0.0;
      u = std::fmin(1.0, std::fmax(0.0, u));
      best = std::fmin(best, norm3(sub3(ap, tdo_vec3{ab.x * u, ab.y * u, ab.z * u})));
    }
    sum += best;
    mx = std::fmax(mx, best);
    ++n;
  }
  *mean_dev = sum / n;
  *max_dev = mx;
}

/** Executed max speed, acceleration and jerk by finite differences of the positions. */
void executed_vaj(const std::vector<tdo_vehicle_state>& st, double dt, double* vmax, double* amax,
                  double* jmax) {
  *vmax = *amax = *jmax = 0.0;
  for (size_t i = 0; i + 3 < st.size(); ++i) {
    tdo_vec3 v[3], a[2];
    for (int k = 0; k < 3; ++k) {
      const tdo_vec3 d = sub3(st[i + k + 1].p, st[i + k].p);
      v[k] = tdo_vec3{d.x / dt, d.y / dt, d.z / dt};
    }
    for (int k = 0; k < 2; ++k) {
      const tdo_vec3 d = sub3(v[k + 1], v[k]);
      a[k] = tdo_vec3{d.x / dt, d.y / dt, d.z / dt};
    }
    *vmax = std::fmax(*vmax, norm3(v[0]));
    *amax = std::fmax(*amax, norm3(a[0]));
    *jmax = std::fmax(*jmax, norm3(sub3(a[1], a[0])) / dt);
  }
}

/** Rest-to-rest straight line from a to b in T s (quintic), every dt. */
std::vector<tdo_sample> line_trajectory(tdo_vec3 a, tdo_vec3 b, double T, double dt) {
  std::vector<tdo_sample> s;
  const int n = static_cast<int>(std::lround(T / dt));
  const tdo_vec3 d = sub3(b, a);
  for (int i = 0; i <= n; ++i) {
    const double t = i * dt, u = t / T;
    const double f = 10 * u * u * u - 15 * u * u * u * u + 6 * u * u * u * u * u;
    const double fd = (30 * u * u - 60 * u * u * u + 30 * u * u * u * u) / T;
    const double fdd = (60 * u - 180 * u * u + 120 * u * u * u) / (T * T);
    tdo_sample x{};
    x.t = t;
    x.p = tdo_vec3{a.x + d.x * f, a.y + d.y * f, a.z + d.z * f};
    x.v = tdo_vec3{d.x * fd, d.y * fd, d.z * fd};
    x.a = tdo_vec3{d.x * fdd, d.y * fdd, d.z * fdd};
    s.push_back(x);
  }
  return s;
}

struct GridFlight {
  double min_static = HUGE_VAL;  // m, simulator's distance to the static geometry
  double min_gap = HUGE_VAL;     // m, simulator's smallest mover gap
  bool collision = false;        // the simulator's flags (static or mover)
  bool arrived = false;          // within 0.2 m of the goal at the end
  uint32_t safety_steps = 0;     // steps with TDO_APF_EVENT_SAFETY
  uint32_t evade_steps = 0;      // steps with TDO_APF_EVENT_EVADE
  std::vector<tdo_vehicle_state> states;
};

/** Fly `traj` with E-APF over `grid` among `movers`; `safety` sets the filter. */
void fly_grid(const std::vector<tdo_sample>& traj, const tdo_grid* grid, const tdo_mover* movers,
              uint32_t n_movers, uint32_t safety, int steps, GridFlight* r) {
  Follower f(static_cast<uint32_t>(traj.size()), 4u, 200u);
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  p.safety = safety;
  tdo_apf_task task{traj.data(), static_cast<uint32_t>(traj.size()), traj.back().p, grid, 0.0};
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  Sim sim(4u);
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.bounds = tdo_box{{0.0, 0.0, 0.0}, {20.0, 20.0, 6.0}};
  sp.grid = grid;
  tdo_vehicle_state s{};
  s.p = traj[0].p;
  ASSERT_EQ(tdo_sim_reset(sim.sim, &sp, &s, movers, n_movers), TDO_OK);
  tdo_sim_output so;
  ASSERT_EQ(tdo_sim_get(sim.sim, &so), TDO_OK);
  for (int k = 0; k < steps; ++k) {
    tdo_apf_input in{so.state, so.movers, so.n_movers};
    tdo_apf_output out;
    ASSERT_EQ(tdo_apf_run(f.apf, &in, &out), TDO_OK);
    if ((out.events & TDO_APF_EVENT_SAFETY) != 0u) ++r->safety_steps;
    if ((out.events & TDO_APF_EVENT_EVADE) != 0u) ++r->evade_steps;
    tdo_sim_input si{out.setpoint};
    ASSERT_EQ(tdo_sim_run(sim.sim, &si, &so), TDO_OK);
    r->states.push_back(so.state);
    r->min_static = std::fmin(r->min_static, so.static_dist);
    r->min_gap = std::fmin(r->min_gap, so.mover_gap);
    if (so.collision_static || so.collision_mover) r->collision = true;
  }
  r->arrived = norm3(sub3(so.state.p, traj.back().p)) <= 0.2;
}

// GIVEN a straight plan 1 m beside a column and a mover that crosses the plan from the other
// side just before the column, so that its repulsion pushes the vehicle towards the column WHEN
// E-APF flies it THEN with the safety filter the vehicle never comes within vehicle_radius +
// safety_margin of the column (simulator distance), keeps clear of the mover and arrives; without
// the filter (same field) the same push violates the 0.3 m the filter keeps, so the scenario is
// a real threat and the filter is what prevents it.
TEST(Apf, SafetyFilterHoldsTheColumnClearanceWhenAMoverPushes) {
  TestPlanner tp(small_cap());
  const tdo_box column{{9.0, 11.0, 0.0}, {10.0, 12.0, 6.0}};
  make_grid(&tp, {column});
  const auto traj = line_trajectory({3.0, 10.0, 2.0}, {17.0, 10.0, 2.0}, 9.0, 0.01);
  // Comes up from -y under the column's x range, slowly (0.5 m/s), reaching the plan as the vehicle
  // passes (x = 9.5 at about t = 4.3 s): its repulsion pushes the vehicle towards the column.
  const tdo_mover m{1u, {9.5, 7.0, 2.0}, {0.0, 0.5, 0.0}, 0.6};
  GridFlight on, off;
  fly_grid(traj, tp.grid(), &m, 1u, 1u, 700, &on);
  fly_grid(traj, tp.grid(), &m, 1u, 0u, 700, &off);
  tdo_apf_params d;
  tdo_apf_params_default(&d, TDO_FOLLOWER_EAPF);
  const double keep = d.vehicle_radius + d.safety_margin;
  EXPECT_FALSE(on.collision);
  EXPECT_GE(on.min_static, keep - 1e-9);
  EXPECT_GT(on.min_gap, 0.0);
  EXPECT_TRUE(on.arrived);
  EXPECT_GT(on.safety_steps + on.evade_steps, 0u) << "the filter never acted";
  EXPECT_LT(off.min_static, keep) << "without the filter the push does not threaten the column";
  double v = 0, a = 0, j = 0;
  executed_vaj(on.states, 0.02, &v, &a, &j);
  EXPECT_LE(v, 3.0 * 1.01);
  EXPECT_LE(a, 3.0 * 1.01);
  EXPECT_LE(j, 10.0 * 1.01);
}

// GIVEN a vehicle that has arrived and holds its goal 1.5 m under the ceiling of a 6 m high map,
// and a mover rising from the floor straight at it, so that its repulsion pushes the vehicle up
// WHEN E-APF runs on THEN the map bounds are walls: the vehicle stays inside them with the safety
// filter's clearance (vehicle_radius + safety_margin) on every axis and keeps clear of the mover;
// without a static map (no walls) the same push takes it closer to the ceiling than that, so the
// scenario is a real threat.
TEST(Apf, GivenAMoverPushingTheVehicleUp_WhenHovering_ThenItStaysInsideTheBounds) {
  TestPlanner tp(small_cap());
  make_grid(&tp, {});
  const auto traj = line_trajectory({5.0, 10.0, 4.5}, {7.0, 10.0, 4.5}, 3.0, 0.01);
  const tdo_mover m{1u, {7.0, 10.0, 0.5}, {0.0, 0.0, 1.0}, 0.8};
  GridFlight on, bare;
  fly_grid(traj, tp.grid(), &m, 1u, 1u, 600, &on);
  fly_grid(traj, nullptr, &m, 1u, 1u, 600, &bare);
  tdo_apf_params d;
  tdo_apf_params_default(&d, TDO_FOLLOWER_EAPF);
  const double keep = d.vehicle_radius + d.safety_margin;
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {20.0, 20.0, 6.0};
  double top = -HUGE_VAL, bare_top = -HUGE_VAL, worst = HUGE_VAL;
  for (const tdo_vehicle_state& s : on.states) {
    const double p[3] = {s.p.x, s.p.y, s.p.z};
    for (int a = 0; a < 3; ++a) worst = std::fmin(worst, std::fmin(p[a] - lo[a], hi[a] - p[a]));
    top = std::fmax(top, s.p.z);
  }
  for (const tdo_vehicle_state& s : bare.states) bare_top = std::fmax(bare_top, s.p.z);
  EXPECT_GE(worst, keep - 1e-9) << "highest z " << top;
  EXPECT_FALSE(on.collision);
  EXPECT_GT(on.min_gap, 0.0);
  EXPECT_GT(top, 4.5 + 0.1) << "the mover did not push the vehicle up";
  EXPECT_GT(bare_top, hi[2] - keep) << "without a map the push does not threaten the ceiling";
}

// GIVEN a vehicle that has arrived and holds its goal 1 m from a wall, and a mover coming straight
// at it from the open side, towards the wall (it would pin the vehicle against it) WHEN E-APF
// runs on THEN the vehicle gets out of the way sideways: no contact with the mover, and the wall
// clearance of the safety filter (vehicle_radius + safety_margin) holds.
TEST(Apf, HoveringVehicleClearsAMoverPinningItToAWall) {
  TestPlanner tp(small_cap());
  make_grid(&tp, {tdo_box{{4.0, 11.0, 0.0}, {10.0, 12.0, 6.0}}});
  const auto traj = line_trajectory({5.0, 10.0, 2.0}, {7.0, 10.0, 2.0}, 3.0, 0.01);
  // Towards the wall, reaching the goal at about t = 6 s.
  const tdo_mover m{1u, {7.0, 4.0, 2.0}, {0.0, 1.0, 0.0}, 0.7};
  GridFlight on;
  fly_grid(traj, tp.grid(), &m, 1u, 1u, 600, &on);
  tdo_apf_params d;
  tdo_apf_params_default(&d, TDO_FOLLOWER_EAPF);
  EXPECT_FALSE(on.collision);
  EXPECT_GT(on.min_gap, 0.0);
  EXPECT_GE(on.min_static, d.vehicle_radius + d.safety_margin - 1e-9);
}

// GIVEN a feasible curved trajectory and no mover WHEN E-APF follows it THEN the mean deviation
// is below 0.1 m and the executed v, a, j (finite differences of positions) stay within limits.
TEST(Apf, EapfTracksWithoutMovers) {
  const auto traj = arc_trajectory(12.0, 0.01);
  double mean_dev = 0, max_dev = 0, gap = 0;
  std::vector<tdo_vehicle_state> st;
  fly_track(traj, nullptr, 0u, &mean_dev, &max_dev, &st, &gap);
  EXPECT_LT(mean_dev, 0.1);
  EXPECT_LT(max_dev, 0.3);
  EXPECT_LT(norm3(sub3(st.back().p, traj.back().p)), 0.2);
  double vmax = 0, amax = 0, jmax = 0;
  executed_vaj(st, 0.02, &vmax, &amax, &jmax);
  EXPECT_LE(vmax, 3.0 * 1.01);
  EXPECT_LE(amax, 3.0 * 1.01);
  EXPECT_LE(jmax, 10.0 * 1.01);
}

// GIVEN a mover crossing the arc WHEN E-APF follows THEN it keeps clear of the mover, deviates
// while avoiding and still reaches the goal; and the whole episode is bit-identical when re-run.
TEST(Apf, EapfAvoidsACrossingMoverDeterministically) {
  const auto traj = arc_trajectory(12.0, 0.01);
  // Crosses the top of the arc (10, 15, 2) at about t = 6 s, moving along -x... towards +y.
  const tdo_mover m{1u, {10.0, 9.0, 2.0}, {0.0, 1.0, 0.0}, 0.7};
  double mean1 = 0, max1 = 0, gap1 = 0, mean2 = 0, max2 = 0, gap2 = 0;
  std::vector<tdo_vehicle_state> a, b;
  fly_track(traj, &m, 1u, &mean1, &max1, &a, &gap1);
  fly_track(traj, &m, 1u, &mean2, &max2, &b, &gap2);
  EXPECT_GT(gap1, 0.0) << "collision with the mover";
  EXPECT_GT(max1, 0.2) << "the mover must have pushed the vehicle off the trajectory";
  EXPECT_LT(norm3(sub3(a.back().p, traj.back().p)), 0.2);
  // Executed v, a, j within the limits also while avoiding (1 % for the finite differences).
  double vx = 0, ax = 0, jx = 0;
  executed_vaj(a, 0.02, &vx, &ax, &jx);
  EXPECT_LE(vx, 3.0 * 1.01);
  EXPECT_LE(ax, 3.0 * 1.01);
  EXPECT_LE(jx, 10.0 * 1.01);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(tdo_vehicle_state)), 0);
}

// GIVEN a follower configured without switching, or not reset, or a classical APF WHEN a plan is
// staged THEN each is refused by name; GIVEN one with switching THEN bad samples, a negative
// switch time and too many samples are named and the active plan stays.
TEST(Apf, SwitchRefusalsAreNamed) {
  const auto traj = arc_trajectory(12.0, 0.01);
  const uint32_t n = static_cast<uint32_t>(traj.size());
  tdo_apf_params p;
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  tdo_apf_task task{traj.data(), n, traj.back().p, nullptr, 0.0};
  Follower plain(n);
  ASSERT_EQ(plain.init_status, TDO_OK);
  EXPECT_EQ(tdo_apf_switch(plain.apf, &task, 1.0), TDO_ERR_NOT_CONFIGURED);  // not reset
  ASSERT_EQ(tdo_apf_reset(plain.apf, &p, &task), TDO_OK);
  EXPECT_EQ(tdo_apf_switch(plain.apf, &task, 1.0), TDO_ERR_NOT_CONFIGURED);  // no switching
  Follower f(n, 8u, 100000u, 1u);
  ASSERT_EQ(f.init_status, TDO_OK);
  tdo_apf_config c1{n, 8u, 100000u, 1u}, c0{n, 8u, 100000u, 0u}, c2{n, 8u, 100000u, 2u};
  EXPECT_GT(tdo_apf_footprint(&c1), tdo_apf_footprint(&c0) + n * sizeof(tdo_sample));
  EXPECT_EQ(tdo_apf_footprint(&c2), 0u);
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  EXPECT_EQ(tdo_apf_switch(f.apf, &task, -1.0), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_apf_switch(f.apf, &task, std::nan("")), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_apf_switch(nullptr, &task, 1.0), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_sample> bad = traj;
  bad[5].t += 0.003;
  tdo_apf_task tb{bad.data(), n, traj.back().p, nullptr, 0.0};
  EXPECT_EQ(tdo_apf_switch(f.apf, &tb, 1.0), TDO_ERR_INVALID_ARGUMENT);
  std::vector<tdo_sample> longer = arc_trajectory(13.0, 0.01);
  tdo_apf_task tl{longer.data(), static_cast<uint32_t>(longer.size()), longer.back().p, nullptr,
                  0.0};
  EXPECT_EQ(tdo_apf_switch(f.apf, &tl, 1.0), TDO_ERR_SAMPLE_CAPACITY);
  tdo_apf_params_default(&p, TDO_FOLLOWER_APF);
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  EXPECT_EQ(tdo_apf_switch(f.apf, &task, 1.0), TDO_ERR_INVALID_ARGUMENT);
  // None of the refused calls staged anything: an E-APF run of the whole arc never switches.
  tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
  ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
  EXPECT_EQ(tdo_apf_switch(f.apf, &tb, 0.0), TDO_ERR_INVALID_ARGUMENT);
  tdo_vehicle_state s{};
  s.p = traj[0].p;
  for (int k = 0; k < 700; ++k) {
    tdo_apf_input in{s, nullptr, 0u};
    tdo_apf_output out;
    ASSERT_EQ(tdo_apf_run(f.apf, &in, &out), TDO_OK);
    EXPECT_EQ(out.events & TDO_APF_EVENT_SWITCHED, 0u);
    s.t = out.setpoint.t;
    s.p = out.setpoint.p;
    s.v = out.setpoint.v;
    s.a = out.setpoint.a;
  }
}

// GIVEN E-APF flying a straight plan over an empty grid WHEN a wall across the plan arrives by a
// map update (tdo_grid_apply_update on the follower's grid) mid-flight and nothing replans THEN
// the static safety filter stops the vehicle before the wall: it never comes within
// vehicle_radius + safety_margin of it (independent box distance). Without the update the same
// flight passes through where the wall is (so the update is what stopped it).
TEST(Apf, SafetyFilterSeesObstaclesFromMapUpdates) {
  const auto traj = line_trajectory({3.0, 10.0, 2.0}, {17.0, 10.0, 2.0}, 9.0, 0.01);
  const tdo_box wall{{11.0, 5.0, 0.0}, {12.0, 15.0, 6.0}};
  double closest[2] = {HUGE_VAL, HUGE_VAL};
  for (int with_update = 0; with_update < 2; ++with_update) {
    TestPlanner tp(small_cap());
    make_grid(&tp, {});
    Follower f(static_cast<uint32_t>(traj.size()), 1u, 200u);
    ASSERT_EQ(f.init_status, TDO_OK);
    tdo_apf_params p;
    tdo_apf_params_default(&p, TDO_FOLLOWER_EAPF);
    tdo_apf_task task{traj.data(), static_cast<uint32_t>(traj.size()), traj.back().p, tp.grid(),
                      0.0};
    ASSERT_EQ(tdo_apf_reset(f.apf, &p, &task), TDO_OK);
    tdo_vehicle_state s{};
    s.p = traj[0].p;
    for (int k = 0; k < 700; ++k) {
      if (k == 100 && with_update) {  // t = 2 s, the vehicle near x = 4.5, 6 m before the wall
        tdo_grid_update u{};
        u.boxes = &wall;
        u.n_boxes = 1u;
        ASSERT_EQ(tdo_grid_apply_update(tp.grid(), &u, nullptr), TDO_OK);
      }
      tdo_apf_input in{s, nullptr, 0u};
      tdo_apf_output out;
      ASSERT_EQ(tdo_apf_run(f.apf, &in, &out), TDO_OK);
      s.t = out.setpoint.t;
      s.p = out.setpoint.p;
      s.v = out.setpoint.v;
      s.a = out.setpoint.a;
      closest[with_update] =
          std::fmin(closest[with_update], norm3(sub3(s.p, box_closest(wall, s.p))));
    }
  }
  EXPECT_LE(closest[0], 0.0) << "without the update the vehicle flies through the wall's place";
  tdo_apf_params d;
  tdo_apf_params_default(&d, TDO_FOLLOWER_EAPF);
  EXPECT_GE(closest[1], d.vehicle_radius + d.safety_margin - 1e-9);
}

}  // namespace
