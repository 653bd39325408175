// Deterministic simulator: jerk-limited double integrator and constant-velocity spheres reflected
// at the bounds (sim.h).
#include "tdo/sim.h"

#include <math.h>
#include <string.h>

#include "arena_typed.h"
#include "scalar.h"
#include "tdo/collision.h"
#include "tdo/sense.h"
#include "vec3.h"

using namespace tdo_internal;  // vec3.h, scalar.h, arena_typed.h

struct tdo_sim {
  tdo_sim_config cfg;
  tdo_mover* movers;  // max_movers
  uint32_t n;
  tdo_sim_params prm;
  tdo_vehicle_state state;
  uint64_t rng;
  uint32_t steps;
  double t_start;  // s
  int braked;      // the last step braked
  double age;      // s, the last step's setpoint age
  int ready;
};

namespace {

constexpr double kStaticCap = 10.0;  // m, cap of the static distance query
constexpr int kMaxReflections = 4;   // per axis and step

// splitmix64 (Vigna).
uint64_t next_u64(uint64_t* s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Zero mean, unit variance: sum of four uniforms in [-0.5, 0.5) scaled by sqrt(3).
double noise(uint64_t* s) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    sum += static_cast<double>(next_u64(s) >> 11) * (1.0 / 9007199254740992.0) - 0.5;
  return sum * 1.7320508075688772;
}

void advance_mover(tdo_mover* m, const tdo_box& b, double dt) {
  for (int k = 0; k < 3; ++k) {
    const double lo = vec_axis(b.min, k), hi = vec_axis(b.max, k);
    double x = vec_axis(m->p, k) + vec_axis(m->v, k) * dt;
    double u = vec_axis(m->v, k);
    for (int r = 0; r < kMaxReflections; ++r) {
      if (x > hi) {
        x = 2.0 * hi - x;
        u = -u;
      } else if (x < lo) {
        x = 2.0 * lo - x;
        u = -u;
      } else {
        break;
      }
    }
    if (x > hi) x = hi;
    if (x < lo) x = lo;
    set_vec_axis(&m->p, k, x);
    set_vec_axis(&m->v, k, u);
  }
}

void fill_output(const tdo_sim* c, tdo_sim_output* out) {
  memset(out, 0, sizeof(*out));
  out->state = c->state;
  out->movers = c->movers;
  out->n_movers = c->n;
  out->steps = c->steps;
  out->mover_gap = HUGE_VAL;
  out->nearest_mover = 0u;
  for (uint32_t i = 0; i < c->n; ++i) {
    const double gap =
        norm(sub(c->state.p, c->movers[i].p)) - c->movers[i].radius - c->prm.vehicle_radius;
    if (gap < out->mover_gap) {
      out->mover_gap = gap;
      out->nearest_mover = c->movers[i].id;
    }
  }
  out->static_dist = HUGE_VAL;
  if (c->prm.grid != nullptr)
    out->static_dist = tdo_collision_point_distance(c->prm.grid, c->state.p, kStaticCap);
  double box_dist = HUGE_VAL;
  if (c->prm.n_boxes > 0u &&
      tdo_sense_distance(c->prm.boxes, c->prm.n_boxes, c->state.p, &box_dist) == TDO_OK)
    out->static_dist = dmin(out->static_dist, dmin(box_dist, kStaticCap));
  out->collision_mover = out->mover_gap < 0.0 ? 1 : 0;
  out->collision_static = out->static_dist < c->prm.static_clearance ? 1 : 0;
  out->braked = c->braked;
  out->setpoint_age = c->age;
}

// Whether a step at clock `now` must not fly `sp`: older than the bound (or without a time).
bool stale(const tdo_sim_params& q, const tdo_setpoint& sp, double now) {
  return q.setpoint_max_age > 0.0 && !(now - sp.t <= q.setpoint_max_age);
}

}  // namespace

namespace {

constexpr int kViableBisections = 12;  // bisection steps of the speed-viability search

// Whether (v + a dt, a) can still keep |v| <= v_max: the acceleration along the new velocity,
// x, must be removable by the jerk limit before the speed passes v_max, |v'| + x^2 / (2 j) <=
// v_max for x > 0 (else |v'| <= v_max; the sum over the discrete ramp-down steps is below
// x^2 / (2 j)). j is half of j_max: while the velocity turns, the perpendicular acceleration
// feeds the along component at |a_perp|^2 / |v| (up to a_max^2 / |v| near v_max), and the other
// half of the jerk budget covers that for the usual limits (a_max^2 / (v_max - a_max^2 / j_max)
// <= j_max / 2, e.g. 4.3 m/s^3 for 3 m/s, 3 m/s^2, 10 m/s^3).
bool speed_viable(tdo_vec3 v, tdo_vec3 a, double v_max, double j_max, double dt) {
  const tdo_vec3 v1 = add(v, mul(a, dt));
  const double s1 = norm(v1);
  const double x = s1 > 0.0 ? dot(a, v1) / s1 : 0.0;
  return s1 + (x > 0.0 ? x * x / j_max : 0.0) <= v_max;
}

// Move from `from` towards `to` by at most dmax, then clip to |a| <= a_max.
tdo_vec3 jerk_step(tdo_vec3 from, tdo_vec3 to, double dmax, double a_max) {
  tdo_vec3 da = sub(to, from);
  const double nda = norm(da);
  if (nda > dmax) da = mul(da, dmax / nda);
  tdo_vec3 a = add(from, da);
  const double na = norm(a);
  if (na > a_max) a = mul(a, a_max / na);
  return a;
}

}  // namespace

extern "C" void tdo_motion_limit(const tdo_vehicle_state* s, tdo_vec3 a_des, double v_max,
                                 double a_max, double j_max, double dt, tdo_setpoint* out) {
  if (s == nullptr || out == nullptr) return;
  if (!isfinite(a_des.x)) a_des.x = 0.0;
  if (!isfinite(a_des.y)) a_des.y = 0.0;
  if (!isfinite(a_des.z)) a_des.z = 0.0;
  const double dmax = j_max * dt;
  // Jerk, then acceleration (the projection onto the a_max ball never lengthens the change).
  tdo_vec3 a = jerk_step(s->a, a_des, dmax, a_max);
  // Speed, within the same jerk budget: when the step would leave the speed-viable set, take the
  // point of the segment from it to the full along-velocity braking step (s->a less j_max dt
  // along v) that is nearest to it and still viable (bisection). The braking step is viable
  // whenever the state was; the hard clip below then never binds for a viable state.
  if (!speed_viable(s->v, a, v_max, j_max, dt)) {
    const double sp = norm(s->v);
    const tdo_vec3 vh = sp > 0.0 ? mul(s->v, 1.0 / sp) : mul(a, 0.0);
    const tdo_vec3 brake = jerk_step(s->a, sub(s->a, mul(vh, dmax)), dmax, a_max);
    if (speed_viable(s->v, brake, v_max, j_max, dt)) {
      double lo = 0.0, hi = 1.0;  // lo: viable (brake), hi: not (a)
      for (int i = 0; i < kViableBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (speed_viable(s->v, add(brake, mul(sub(a, brake), mid)), v_max, j_max, dt))
          lo = mid;
        else
          hi = mid;
      }
      a = add(brake, mul(sub(a, brake), lo));
    } else {
      a = brake;
    }
  }
  // Hard speed limit (binds only from a state that was not speed-viable).
  tdo_vec3 v = add(s->v, mul(a, dt));
  const double nv = norm(v);
  if (nv > v_max) {
    v = mul(v, v_max / nv);
    a = mul(sub(v, s->v), 1.0 / dt);
  }
  out->t = s->t + dt;
  out->a = a;
  out->v = v;
  out->p = add(s->p, mul(add(s->v, v), 0.5 * dt));
}

extern "C" void tdo_sim_params_default(tdo_sim_params* p) {
  if (p == nullptr) return;
  memset(p, 0, sizeof(*p));
  p->dt = 0.02;
  p->v_max = 3.0;
  p->a_max = 3.0;
  p->j_max = 10.0;
  p->bounds.min = v3(0.0, 0.0, 0.0);
  p->bounds.max = v3(1.0, 1.0, 1.0);
  p->vehicle_radius = 0.25;
  p->static_clearance = 0.25;
  p->grid = nullptr;
  p->boxes = nullptr;
  p->n_boxes = 0u;
  p->seed = 1u;
  p->accel_noise = 0.0;
  p->setpoint_max_age = 0.0;
  p->brake_gain = 2.0;
}

extern "C" size_t tdo_sim_footprint(const tdo_sim_config* cfg) {
  if (cfg == nullptr || cfg->max_movers == 0u || cfg->max_movers > 0x7FFFFFFFu) return 0;
  return tdo_arena_round(sizeof(tdo_sim)) +
         tdo_arena_round(static_cast<size_t>(cfg->max_movers) * sizeof(tdo_mover));
}

extern "C" tdo_status tdo_sim_init(tdo_sim** out, tdo_arena* arena, const tdo_sim_config* cfg) {
  if (out == nullptr || arena == nullptr || cfg == nullptr || tdo_sim_footprint(cfg) == 0)
    return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  tdo_sim* c = arena_context<tdo_sim>(arena, *cfg);
  if (c == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  c->movers = arena_array<tdo_mover>(arena, cfg->max_movers);
  if (c->movers == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  *out = c;
  return TDO_OK;
}

extern "C" tdo_status tdo_sim_reset(tdo_sim* c, const tdo_sim_params* prm,
                                    const tdo_vehicle_state* initial, const tdo_mover* movers,
                                    uint32_t n_movers) {
  if (c == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  c->ready = 0;
  if (prm == nullptr || initial == nullptr || (n_movers > 0u && movers == nullptr))
    return TDO_ERR_INVALID_ARGUMENT;
  if (!positive(prm->dt) || !positive(prm->v_max) || !positive(prm->a_max) ||
      !positive(prm->j_max) || !non_negative(prm->vehicle_radius) ||
      !non_negative(prm->static_clearance) || !non_negative(prm->accel_noise) ||
      !non_negative(prm->setpoint_max_age) || !non_negative(prm->brake_gain) ||
      !finite3(prm->bounds.min) || !finite3(prm->bounds.max) ||
      !(prm->bounds.max.x > prm->bounds.min.x) || !(prm->bounds.max.y > prm->bounds.min.y) ||
      !(prm->bounds.max.z > prm->bounds.min.z))
    return TDO_ERR_INVALID_ARGUMENT;
  if (!isfinite(initial->t) || !finite3(initial->p) || !finite3(initial->v) || !finite3(initial->a))
    return TDO_ERR_INVALID_ARGUMENT;
  for (uint32_t i = 0; i < n_movers; ++i)
    if (!finite3(movers[i].p) || !finite3(movers[i].v) || !positive(movers[i].radius))
      return TDO_ERR_INVALID_ARGUMENT;
  if (n_movers > c->cfg.max_movers) return TDO_ERR_OBSTACLE_CAPACITY;
  if (prm->grid != nullptr && !(tdo_grid_clearance(prm->grid) >= 0.0)) return TDO_ERR_MAP_NOT_READY;
  if (prm->n_boxes > 0u) {  // the boxes are checked once: the steps cannot fail on them
    double d = 0.0;
    const tdo_status bs = tdo_sense_distance(prm->boxes, prm->n_boxes, initial->p, &d);
    if (bs != TDO_OK) return bs;
  }
  c->prm = *prm;
  c->state = *initial;
  c->t_start = initial->t;
  if (n_movers > 0u) memcpy(c->movers, movers, static_cast<size_t>(n_movers) * sizeof(tdo_mover));
  c->n = n_movers;
  c->rng = prm->seed;
  c->steps = 0u;
  c->braked = 0;
  c->age = 0.0;
  c->ready = 1;
  return TDO_OK;
}

namespace {

// One step with command `sp`, or braking towards a hover (sp null, or stale): a = -brake_gain v
// through the motion limits.
tdo_status advance(tdo_sim* c, const tdo_setpoint* sp, tdo_sim_output* out) {
  const tdo_sim_params& q = c->prm;
  const bool is_stale = sp != nullptr && stale(q, *sp, c->state.t);
  c->braked = (sp == nullptr || is_stale) ? 1 : 0;
  c->age = sp != nullptr ? c->state.t - sp->t : 0.0;
  const tdo_vec3 a_cmd = c->braked ? mul(c->state.v, -q.brake_gain) : sp->a;
  tdo_setpoint next;
  tdo_motion_limit(&c->state, a_cmd, q.v_max, q.a_max, q.j_max, q.dt, &next);
  if (q.accel_noise > 0.0) {
    const tdo_vec3 w = v3(noise(&c->rng), noise(&c->rng), noise(&c->rng));
    next.a = add(next.a, mul(w, q.accel_noise));
    tdo_vec3 v = add(c->state.v, mul(next.a, q.dt));
    const double nv = norm(v);
    if (nv > q.v_max) {
      v = mul(v, q.v_max / nv);
      next.a = mul(sub(v, c->state.v), 1.0 / q.dt);
    }
    next.v = v;
    next.p = add(c->state.p, mul(add(c->state.v, v), 0.5 * q.dt));
  }
  ++c->steps;
  c->state.t = c->t_start + static_cast<double>(c->steps) * q.dt;
  c->state.p = next.p;
  c->state.v = next.v;
  c->state.a = next.a;
  for (uint32_t i = 0; i < c->n; ++i) advance_mover(&c->movers[i], q.bounds, q.dt);
  fill_output(c, out);
  return is_stale ? TDO_ERR_SETPOINT_STALE : TDO_OK;
}

}  // namespace

extern "C" tdo_status tdo_sim_run(tdo_sim* c, const tdo_sim_input* in, tdo_sim_output* out) {
  if (c == nullptr || in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready) return TDO_ERR_NOT_CONFIGURED;
  return advance(c, &in->setpoint, out);
}

extern "C" tdo_status tdo_sim_hold(tdo_sim* c, tdo_sim_output* out) {
  if (c == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready) return TDO_ERR_NOT_CONFIGURED;
  return advance(c, nullptr, out);
}

extern "C" tdo_status tdo_sim_step(tdo_sim* c, const tdo_setpoint* setpoint,
                                   tdo_vehicle_state* state) {
  if (c == nullptr || setpoint == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  tdo_sim_input in;
  in.setpoint = *setpoint;
  tdo_sim_output out;
  const tdo_status s = tdo_sim_run(c, &in, &out);
  if ((s == TDO_OK || s == TDO_ERR_SETPOINT_STALE) && state != nullptr) *state = out.state;
  return s;
}

extern "C" tdo_status tdo_sim_get(const tdo_sim* c, tdo_sim_output* out) {
  if (c == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready) return TDO_ERR_NOT_CONFIGURED;
  fill_output(c, out);
  return TDO_OK;
}
