// The deterministic simulator (sim.h): the motion rule's limits, exact integration, movers
// reflected at the bounds, collision flags, seeded disturbance, statuses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "rng.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

double norm3(tdo_vec3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
tdo_vec3 sub3(tdo_vec3 a, tdo_vec3 b) { return tdo_vec3{a.x - b.x, a.y - b.y, a.z - b.z}; }

struct Sim {
  std::vector<unsigned char> mem;
  tdo_arena arena{};
  tdo_sim* sim = nullptr;
  tdo_status status = TDO_ERR_INVALID_ARGUMENT;
  explicit Sim(uint32_t movers) {
    tdo_sim_config cfg{movers};
    mem.assign(tdo_sim_footprint(&cfg), 0u);
    tdo_arena_init(&arena, mem.data(), mem.size());
    status = tdo_sim_init(&sim, &arena, &cfg);
  }
};

tdo_sim_params box_params() {
  tdo_sim_params p;
  tdo_sim_params_default(&p);
  p.bounds = tdo_box{{0.0, 0.0, 0.0}, {10.0, 10.0, 5.0}};
  return p;
}

// GIVEN random states and desired accelerations WHEN limited THEN |a| <= a_max, the jerk step
// stays within j_max dt, |v| <= v_max, and p follows the trapezoid rule exactly.
TEST(Sim, MotionLimitKeepsTheLimits) {
  tdo_test::Rng rng(11);
  const double vmax = 3.0, amax = 3.0, jmax = 10.0, dt = 0.02;
  int speed_cut = 0;
  for (int i = 0; i < 20000; ++i) {
    tdo_vehicle_state s{};
    s.t = rng.uniform(0.0, 100.0);
    s.p = tdo_vec3{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    // Previous state within the limits.
    s.v = tdo_vec3{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-1, 1)};
    if (norm3(s.v) > vmax) continue;
    s.a = tdo_vec3{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-1, 1)};
    if (norm3(s.a) > amax) continue;
    const tdo_vec3 ad{rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20)};
    tdo_setpoint o{};
    tdo_motion_limit(&s, ad, vmax, amax, jmax, dt, &o);
    EXPECT_LE(norm3(o.a), amax * (1 + 1e-12));
    EXPECT_LE(norm3(o.v), vmax * (1 + 1e-12));
    const tdo_vec3 dv = sub3(o.v, s.v);
    if (norm3(tdo_vec3{s.v.x + o.a.x * dt, s.v.y + o.a.y * dt, s.v.z + o.a.z * dt}) <=
        vmax * (1 + 1e-12)) {
      EXPECT_LE(norm3(sub3(o.a, s.a)), jmax * dt * (1 + 1e-9));
      EXPECT_NEAR(norm3(sub3(dv, tdo_vec3{o.a.x * dt, o.a.y * dt, o.a.z * dt})), 0.0, 1e-12);
    } else {
      ++speed_cut;
    }
    const tdo_vec3 expect{s.p.x + (s.v.x + o.v.x) * dt / 2, s.p.y + (s.v.y + o.v.y) * dt / 2,
                          s.p.z + (s.v.z + o.v.z) * dt / 2};
    EXPECT_NEAR(norm3(sub3(o.p, expect)), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(o.t, s.t + dt);
  }
  // A NaN desire is treated as zero.
  tdo_vehicle_state s{};
  tdo_setpoint o{};
  tdo_motion_limit(&s, tdo_vec3{std::nan(""), 1.0, HUGE_VAL}, vmax, amax, jmax, dt, &o);
  EXPECT_TRUE(std::isfinite(o.a.x) && std::isfinite(o.a.z));
  EXPECT_DOUBLE_EQ(o.a.x, 0.0);
  EXPECT_NEAR(o.a.y, jmax * dt, 1e-15);
  EXPECT_EQ(speed_cut, 0);  // with these ranges the speed limit never needs to cut
}

// GIVEN a vehicle at v_max and a desired acceleration that jumps to a random direction every
// 0.2-1 s WHEN limited step after step THEN every executed step keeps |a - a_prev| <= j_max dt,
// |a| <= a_max and |v| <= v_max together (the speed limit never clips outside the jerk budget),
// also in the finite differences of the positions (paper eq. 15-17).
TEST(Sim, MotionLimitReachesTheSpeedLimitWithinTheJerkLimit) {
  tdo_test::Rng rng(23);
  const double vmax = 3.0, amax = 3.0, jmax = 10.0, dt = 0.02;
  tdo_vehicle_state s{};
  s.v = tdo_vec3{vmax, 0.0, 0.0};
  tdo_vec3 ad{0.0, 0.0, 0.0};
  std::vector<tdo_vec3> pos{s.p};
  int hold = 0;
  for (int i = 0; i < 5000; ++i) {
    if (hold-- <= 0) {
      ad = tdo_vec3{rng.uniform(-30, 30), rng.uniform(-30, 30), rng.uniform(-10, 10)};
      hold = rng.range(10, 50);
    }
    tdo_setpoint o{};
    tdo_motion_limit(&s, ad, vmax, amax, jmax, dt, &o);
    ASSERT_LE(norm3(sub3(o.a, s.a)), jmax * dt * (1 + 1e-9)) << "step " << i;
    ASSERT_LE(norm3(o.a), amax * (1 + 1e-12));
    ASSERT_LE(norm3(o.v), vmax * (1 + 1e-12));
    s.t = o.t;
    s.p = o.p;
    s.v = o.v;
    s.a = o.a;
    pos.push_back(s.p);
  }
  double jfd = 0.0, vfd = 0.0;
  for (size_t i = 0; i + 3 < pos.size(); ++i) {
    tdo_vec3 v[3];
    for (int k = 0; k < 3; ++k) {
      const tdo_vec3 d = sub3(pos[i + k + 1], pos[i + k]);
      v[k] = tdo_vec3{d.x / dt, d.y / dt, d.z / dt};
    }
    const tdo_vec3 a0 = sub3(v[1], v[0]), a1 = sub3(v[2], v[1]);
    jfd = std::fmax(jfd, norm3(sub3(a1, a0)) / (dt * dt));
    vfd = std::fmax(vfd, norm3(v[0]));
  }
  EXPECT_LE(jfd, jmax * 1.01);
  EXPECT_LE(vfd, vmax * 1.01);
}

// GIVEN a mover heading for a wall WHEN stepped THEN it bounces: position and velocity match the
// closed-form mirror solution, and it never leaves the bounds.
TEST(Sim, MoversReflectAtTheBounds) {
  Sim s(2u);
  ASSERT_EQ(s.status, TDO_OK);
  const tdo_mover m[2] = {{7u, {9.0, 5.0, 2.5}, {1.5, 0.0, 0.0}, 0.5},
                          {8u, {1.0, 1.0, 1.0}, {-0.7, -0.3, 0.4}, 0.3}};
  tdo_vehicle_state v0{};
  v0.p = tdo_vec3{5.0, 5.0, 2.5};
  const tdo_sim_params p = box_params();
  ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, m, 2u), TDO_OK);
  const tdo_sim_input hold{};
  tdo_sim_output out{};
  for (int k = 1; k <= 200; ++k) {  // 4 s
    ASSERT_EQ(tdo_sim_run(s.sim, &hold, &out), TDO_OK);
    const double t = k * 0.02;
    // Mover 7: x(t) = 9 + 1.5 t until 10 at t = 2/3 s, then 11 - 1.5 t.
    const double x = 9.0 + 1.5 * t <= 10.0 ? 9.0 + 1.5 * t : 11.0 - 1.5 * t;
    EXPECT_NEAR(out.movers[0].p.x, x, 1e-9) << "t = " << t;
    EXPECT_NEAR(out.movers[0].v.x, 9.0 + 1.5 * t <= 10.0 ? 1.5 : -1.5, 0.0);
    for (uint32_t i = 0; i < out.n_movers; ++i) {
      EXPECT_GE(out.movers[i].p.x, 0.0);
      EXPECT_LE(out.movers[i].p.x, 10.0);
      EXPECT_GE(out.movers[i].p.y, 0.0);
      EXPECT_GE(out.movers[i].p.z, 0.0);
      EXPECT_LE(out.movers[i].p.z, 5.0);
    }
  }
  EXPECT_EQ(out.movers[0].id, 7u);
  EXPECT_EQ(out.steps, 200u);
  EXPECT_NEAR(out.state.t, 4.0, 1e-12);
  // Mover 8 bounced off x = 0 and y = 0: its velocity flipped there.
  EXPECT_GT(out.movers[1].v.x, 0.0);
  EXPECT_GT(out.movers[1].v.y, 0.0);
}

// GIVEN a mover and a static box near the vehicle WHEN reported THEN the gaps and flags match
// an independent computation.
TEST(Sim, CollisionFlags) {
  tdo_test::TestPlanner tp(tdo_test::make_cap(10u * 10u * 5u, 27u * 500u, 500u, 8u));
  ASSERT_EQ(tp.status(), TDO_OK);
  const tdo_grid_desc d{10, 10, 5, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(tp.grid(), &d), TDO_OK);
  const tdo_box b{{6.0, 0.0, 0.0}, {7.0, 10.0, 5.0}};
  ASSERT_EQ(tdo_grid_add_box(tp.grid(), &b), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(tp.grid(), 0.5), TDO_OK);
  Sim s(1u);
  tdo_sim_params p = box_params();
  p.grid = tp.grid();
  p.static_clearance = 0.3;
  tdo_vehicle_state v0{};
  v0.p = tdo_vec3{5.8, 5.0, 2.5};  // 0.2 m from the box: static collision
  const tdo_mover m{3u, {4.0, 5.0, 2.5}, {0.0, 0.0, 0.0}, 1.0};  // gap 1.8 - 1.25 = 0.55
  ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, &m, 1u), TDO_OK);
  tdo_sim_output o{};
  ASSERT_EQ(tdo_sim_get(s.sim, &o), TDO_OK);
  EXPECT_NEAR(o.static_dist, 0.2, 1e-9);
  EXPECT_EQ(o.collision_static, 1);
  EXPECT_NEAR(o.mover_gap, 1.8 - 1.0 - 0.25, 1e-12);
  EXPECT_EQ(o.nearest_mover, 3u);
  EXPECT_EQ(o.collision_mover, 0);
  v0.p = tdo_vec3{4.9, 5.0, 2.5};
  ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, &m, 1u), TDO_OK);
  ASSERT_EQ(tdo_sim_get(s.sim, &o), TDO_OK);
  EXPECT_EQ(o.collision_mover, 1);
  EXPECT_EQ(o.collision_static, 0);
}

// GIVEN the true world as boxes off the voxel lattice (no grid) WHEN the vehicle steps past them
// THEN the static distance is the exact distance to the nearest box (independent per-axis gaps)
// at every step, the flag follows static_clearance, and a bad box is refused at the reset.
TEST(Sim, StaticCheckAgainstBoxesIsExact) {
  const std::vector<tdo_box> boxes{tdo_box{{6.13, 0.0, 0.0}, {7.0, 4.0, 5.0}},
                                   tdo_box{{6.13, 6.0, 0.0}, {7.0, 10.0, 5.0}}};
  Sim s(1u);
  tdo_sim_params p = box_params();
  p.boxes = boxes.data();
  p.n_boxes = 2u;
  p.static_clearance = 0.3;
  tdo_vehicle_state v0{};
  v0.p = tdo_vec3{5.0, 4.2, 2.5};  // 0.2 m from the first box's face y = 4
  ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_OK);
  tdo_sim_input in{};
  in.setpoint.a = tdo_vec3{1.0, 0.0, 0.0};
  bool flagged = false, clear = false;
  for (int k = 0; k < 100; ++k) {
    tdo_sim_output o{};
    ASSERT_EQ(tdo_sim_run(s.sim, &in, &o), TDO_OK);
    const tdo_vec3 q = o.state.p;
    const double gx = std::fmax(0.0, std::fmax(6.13 - q.x, q.x - 7.0));
    const double gy = 1.0 - std::fabs(q.y - 5.0);  // gap to y = 4 or y = 6 (between them)
    const double want = std::fmin(std::hypot(gx, gy), 10.0);
    ASSERT_NEAR(o.static_dist, want, 1e-12) << "step " << k;
    EXPECT_EQ(o.collision_static, want < 0.3 ? 1 : 0);
    flagged = flagged || o.collision_static != 0;
    clear = clear || o.collision_static == 0;
  }
  EXPECT_TRUE(flagged);
  EXPECT_TRUE(clear);
  const tdo_box bad{{1.0, 1.0, 1.0}, {0.0, 2.0, 2.0}};
  p.boxes = &bad;
  p.n_boxes = 1u;
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_ERR_INVALID_BOX);
  p.boxes = nullptr;
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_ERR_INVALID_ARGUMENT);
}

TEST(Sim, StatusesAndBadParameters) {
  tdo_sim_config cfg{0u};
  EXPECT_EQ(tdo_sim_footprint(&cfg), 0u);
  tdo_sim* sim = nullptr;
  std::vector<unsigned char> mem(64);
  tdo_arena a;
  tdo_arena_init(&a, mem.data(), mem.size());
  cfg.max_movers = 100u;
  EXPECT_EQ(tdo_sim_init(&sim, &a, &cfg), TDO_ERR_ARENA_TOO_SMALL);
  Sim s(2u);
  ASSERT_EQ(s.status, TDO_OK);
  tdo_setpoint sp{};
  EXPECT_EQ(tdo_sim_step(s.sim, &sp, nullptr), TDO_ERR_NOT_CONFIGURED);
  tdo_vehicle_state v0{};
  tdo_mover m[3] = {{1u, {1, 1, 1}, {0, 0, 0}, 0.5},
                    {2u, {2, 2, 2}, {0, 0, 0}, 0.5},
                    {3u, {3, 3, 3}, {0, 0, 0}, 0.5}};
  tdo_sim_params p = box_params();
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, m, 3u), TDO_ERR_OBSTACLE_CAPACITY);
  EXPECT_EQ(tdo_sim_step(s.sim, &sp, nullptr), TDO_ERR_NOT_CONFIGURED);
  m[1].radius = -1.0;
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, m, 2u), TDO_ERR_INVALID_ARGUMENT);
  m[1].radius = 0.5;
  tdo_sim_params q = p;
  q.dt = 0.0;
  EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, m, 2u), TDO_ERR_INVALID_ARGUMENT);
  q = p;
  q.bounds.max.y = q.bounds.min.y;
  EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, m, 2u), TDO_ERR_INVALID_ARGUMENT);
  q = p;
  q.accel_noise = -0.1;
  EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, m, 2u), TDO_ERR_INVALID_ARGUMENT);
  v0.v.x = std::nan("");
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, m, 2u), TDO_ERR_INVALID_ARGUMENT);
  v0.v.x = 0.0;
  tdo_test::TestPlanner tp(tdo_test::make_cap(1000u, 1000u, 100u));
  const tdo_grid_desc d{10, 10, 10, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(tp.grid(), &d), TDO_OK);
  q = p;
  q.grid = tp.grid();
  EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, m, 2u), TDO_ERR_MAP_NOT_READY);
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, m, 2u), TDO_OK);
  EXPECT_EQ(tdo_sim_step(s.sim, nullptr, nullptr), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_sim_step(s.sim, &sp, nullptr), TDO_OK);
}

// GIVEN a seeded disturbance WHEN the same episode runs twice THEN the states are bit-identical;
// another seed gives another run; the disturbance has roughly the requested spread.
TEST(Sim, SeededDisturbanceIsDeterministic) {
  auto fly = [](uint64_t seed, std::vector<tdo_vehicle_state>* out) {
    Sim s(1u);
    tdo_sim_params p = box_params();
    p.seed = seed;
    p.accel_noise = 0.5;
    p.v_max = 100.0;  // let the noise through
    p.a_max = 100.0;
    p.j_max = 1e9;  // the limited command is exactly zero: what remains is the disturbance
    tdo_vehicle_state v0{};
    v0.p = tdo_vec3{5, 5, 2};
    ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_OK);
    tdo_setpoint zero{};
    tdo_vehicle_state st{};
    for (int k = 0; k < 2000; ++k) {
      ASSERT_EQ(tdo_sim_step(s.sim, &zero, &st), TDO_OK);
      out->push_back(st);
    }
  };
  std::vector<tdo_vehicle_state> a, b, c;
  fly(5u, &a);
  fly(5u, &b);
  fly(6u, &c);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(tdo_vehicle_state)), 0);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(tdo_vehicle_state)), 0);
  double s2 = 0.0;
  for (const auto& s : a) s2 += s.a.x * s.a.x;
  const double sd = std::sqrt(s2 / static_cast<double>(a.size()));
  EXPECT_GT(sd, 0.46);
  EXPECT_LT(sd, 0.54);
}

}  // namespace

namespace {

// A flight towards a wall (x = 7) whose setpoint stream starves after 1 s: the follower's last
// setpoint (a = 2 m/s^2 along +x, stamped with the time of the state it answered) is all the
// simulator gets from then on.
struct StarvedRun {
  std::vector<tdo_status> status;   // phase 2, per step
  std::vector<tdo_sim_output> out;  // phase 2, per step
  std::vector<tdo_vehicle_state> before;
  bool collided = false;
};

StarvedRun starved_run(double max_age) {
  StarvedRun r;
  Sim s(1u);
  EXPECT_EQ(s.status, TDO_OK);
  const tdo_box wall{{7.0, 0.0, 0.0}, {8.0, 10.0, 5.0}};
  tdo_sim_params p = box_params();
  p.boxes = &wall;
  p.n_boxes = 1u;
  p.setpoint_max_age = max_age;
  tdo_vehicle_state v0{};
  v0.p = tdo_vec3{2.0, 5.0, 2.5};
  EXPECT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_OK);
  tdo_sim_input in{};
  in.setpoint.a = tdo_vec3{2.0, 0.0, 0.0};
  tdo_sim_output o{};
  EXPECT_EQ(tdo_sim_get(s.sim, &o), TDO_OK);
  for (int k = 0; k < 50; ++k) {  // fresh: each answers the state it is flown from
    in.setpoint.t = o.state.t;
    EXPECT_EQ(tdo_sim_run(s.sim, &in, &o), TDO_OK);
    EXPECT_EQ(o.braked, 0);
    EXPECT_EQ(o.setpoint_age, 0.0);
    r.collided = r.collided || o.collision_static != 0;
  }
  for (int k = 0; k < 250; ++k) {  // starved: the last setpoint again and again, 5 s
    r.before.push_back(o.state);
    r.status.push_back(tdo_sim_run(s.sim, &in, &o));
    r.out.push_back(o);
    r.collided = r.collided || o.collision_static != 0;
  }
  return r;
}

// GIVEN a setpoint stream that starves WHEN the last setpoint is older than setpoint_max_age
// THEN each step says setpoint_stale, brakes with a = -brake_gain v through the motion limits
// and the vehicle comes to a hover short of the wall; without the age check it flies the old
// command into the wall.
TEST(Sim, StaleSetpointBrakesToAHoverAndIsNamed) {
  const double dt = 0.02, max_age = 3 * dt;
  const StarvedRun r = starved_run(max_age);
  ASSERT_EQ(r.out.size(), 250u);
  for (size_t k = 0; k < r.out.size(); ++k) {
    SCOPED_TRACE("starved step " + std::to_string(k + 1));
    const double age = r.before[k].t - (r.before[0].t - dt);  // the setpoint answered step 0's
    EXPECT_NEAR(r.out[k].setpoint_age, age, 1e-12);
    if (k < 2) {  // 0.02 and 0.04 s old: still flown
      EXPECT_EQ(r.status[k], TDO_OK);
      EXPECT_EQ(r.out[k].braked, 0);
      continue;
    }
    if (k == 2) continue;  // 0.06 s: at the bound (rounding decides)
    EXPECT_STREQ(tdo_status_str(r.status[k]), "setpoint_stale");
    EXPECT_EQ(r.out[k].braked, 1);
    // The braking command through the motion limits (sim.h), from the state before the step.
    const tdo_vec3 v = r.before[k].v;
    tdo_setpoint want{};
    tdo_motion_limit(&r.before[k], tdo_vec3{-2.0 * v.x, -2.0 * v.y, -2.0 * v.z}, 3.0, 3.0, 10.0, dt,
                     &want);
    EXPECT_EQ(std::memcmp(&want.p, &r.out[k].state.p, sizeof want.p), 0);
    EXPECT_EQ(std::memcmp(&want.v, &r.out[k].state.v, sizeof want.v), 0);
  }
  EXPECT_FALSE(r.collided);
  const tdo_sim_output& end = r.out.back();
  EXPECT_LT(norm3(end.state.v), 0.01) << "not hovering after 5 s of braking";
  EXPECT_LT(norm3(sub3(end.state.p, r.out[r.out.size() - 50].state.p)), 0.01)
      << "still moving in the last second: not a hover in place";
  EXPECT_GE(end.static_dist, 0.25);

  // The same starvation without the age check: the old command flies into the wall.
  const StarvedRun blind = starved_run(0.0);
  for (size_t k = 0; k < blind.out.size(); ++k) {
    EXPECT_EQ(blind.status[k], TDO_OK);
    EXPECT_EQ(blind.out[k].braked, 0);
  }
  EXPECT_TRUE(blind.collided);
}

// GIVEN a stale setpoint WHEN a fresh one comes THEN it is flown again; tdo_sim_hold brakes with
// TDO_OK; a negative or non-finite bound or gain is refused.
TEST(Sim, FreshSetpointAfterStaleAndHoldAndBadBounds) {
  Sim s(1u);
  ASSERT_EQ(s.status, TDO_OK);
  tdo_sim_params p = box_params();
  p.setpoint_max_age = 0.05;
  tdo_vehicle_state v0{};
  v0.p = tdo_vec3{5.0, 5.0, 2.5};
  ASSERT_EQ(tdo_sim_reset(s.sim, &p, &v0, nullptr, 0u), TDO_OK);
  tdo_sim_input in{};
  in.setpoint.t = -1.0;  // 1 s old
  in.setpoint.a = tdo_vec3{1.0, 0.0, 0.0};
  tdo_sim_output o{};
  EXPECT_EQ(tdo_sim_run(s.sim, &in, &o), TDO_ERR_SETPOINT_STALE);
  EXPECT_EQ(o.braked, 1);
  EXPECT_EQ(o.state.v.x, 0.0);  // braking from rest: stays at rest
  in.setpoint.t = o.state.t;
  EXPECT_EQ(tdo_sim_run(s.sim, &in, &o), TDO_OK);
  EXPECT_EQ(o.braked, 0);
  EXPECT_GT(o.state.a.x, 0.0);  // flying the command again
  tdo_sim_output got{};
  ASSERT_EQ(tdo_sim_get(s.sim, &got), TDO_OK);
  EXPECT_EQ(got.braked, 0);
  const double v_before = o.state.v.x;
  EXPECT_EQ(tdo_sim_hold(s.sim, &o), TDO_OK);
  EXPECT_EQ(o.braked, 1);
  EXPECT_EQ(o.setpoint_age, 0.0);
  EXPECT_LT(o.state.a.x, got.state.a.x);  // the acceleration turns towards -2 v
  EXPECT_GT(v_before, 0.0);
  EXPECT_EQ(tdo_sim_hold(nullptr, &o), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_sim_hold(s.sim, nullptr), TDO_ERR_INVALID_ARGUMENT);
  in.setpoint.t = std::nan("");  // no time: never fresh
  EXPECT_EQ(tdo_sim_run(s.sim, &in, &o), TDO_ERR_SETPOINT_STALE);
  tdo_vehicle_state st{};
  EXPECT_EQ(tdo_sim_step(s.sim, &in.setpoint, &st), TDO_ERR_SETPOINT_STALE);
  EXPECT_EQ(st.t, o.state.t + 0.02);  // stepped, the state out
  for (double bad : {-0.01, std::nan(""), HUGE_VAL}) {
    tdo_sim_params q = p;
    q.setpoint_max_age = bad;
    EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, nullptr, 0u), TDO_ERR_INVALID_ARGUMENT);
    q = p;
    q.brake_gain = bad;
    EXPECT_EQ(tdo_sim_reset(s.sim, &q, &v0, nullptr, 0u), TDO_ERR_INVALID_ARGUMENT);
  }
}

}  // namespace
