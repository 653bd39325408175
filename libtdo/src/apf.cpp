// Online follower: trajectory-guided enhanced APF and the classical APF baseline
// (docs/design.md s.4, paper eq. 10-14). See apf.h for the exact field, command and local-minimum
// rules.
#include "tdo/apf.h"

#include <math.h>
#include <string.h>

#include <type_traits>

#include "arena_typed.h"
#include "scalar.h"
#include "tdo/collision.h"
#include "tdo/sim.h"
#include "vec3.h"

using namespace tdo_internal;  // vec3.h, scalar.h, arena_typed.h

struct tdo_apf {
  tdo_apf_config cfg;
  tdo_sample* samples;  // max_samples, copied at reset
  double* arc;          // m, arclength of each sample along the polyline
  tdo_apf_params prm;
  int ready;
  uint32_t n;            // samples
  double sample_dt;      // s
  double t_end;          // s, time of the last sample
  tdo_vec3 goal;         // m
  const tdo_grid* grid;  // static map or NULL
  double t0;             // s
  // Running state.
  int started;
  double prev_t;      // s, vehicle time of the previous step
  double tau;         // s, trajectory clock
  uint32_t near_seg;  // segment of the last nearest point
  double near_t;      // s, trajectory time of the last nearest point
  tdo_apf_mode mode;
  double win_t;       // s, start of the progress window
  double win_p;       // m, progress at the window start
  tdo_vec3 win_pos;   // m, position at the window start
  tdo_vec3 win_f;     // m/s^2, sum of F_total over the window's steps
  uint32_t win_n;     // steps in the window
  double goal_d0;     // m, goal distance at the first step
  double best_goal;   // m, best goal distance so far
  double escape_end;  // s
  double escape_p;    // m, progress at the escape start
  tdo_vec3 escape_axis;
  tdo_vec3 escape_n;  // last repulsion normal seen during the escape
  uint32_t fails_in_row;
  uint32_t lm_detections;
  uint32_t escapes;
  uint32_t steps;
  int arrived_reported;
  int braked;  // the safety filter changed the previous step's command
  // Staged next plan (tdo_apf_switch; arrays only with cfg.switching).
  tdo_sample* next_samples;
  double* next_arc;
  int next_ready;
  uint32_t next_n;
  double next_dt;      // s
  double next_switch;  // s, active plan's trajectory time aligned with the next plan's 0
  const tdo_grid* next_grid;
};

namespace {

constexpr double kEps = 1e-12;
constexpr double kFdStep = 1e-4;      // m, central-difference step of the static distance gradient
constexpr double kArriveSpeed = 0.1;  // m/s
constexpr double kMaxElapsedSteps = 10.0;  // the clock advances at most this many dt per step
constexpr double kWallZone = 2.0;          // m beyond vehicle_radius: braking before walls
constexpr double kWallFade = 1.0;          // m beyond vehicle_radius: no corrective push into walls
constexpr double kOnPlan = 0.2;            // m: closer than this to the plan, no wall terms (E-APF)
constexpr int kWallProbes = 4;             // look-ahead probes along the velocity
constexpr double kWallProbeDt = 0.2;       // s between them
constexpr uint32_t kMaxRolloutSteps = 1000u;  // bound of a safety roll-out
constexpr double kRolloutCap = 1.0;           // m beyond the safety threshold: distance query cap
constexpr double kRestSpeed = 1e-3;           // m/s: a roll-out below this speed and
constexpr double kRestAcc = 1e-2;             // m/s^2 this acceleration has stopped
constexpr int kSafetyBisections = 6;
constexpr int kEvadeSteps = 20;   // evasion look-ahead steps
constexpr double kEvadeDt = 0.1;  // s per evasion step (2 s horizon)

// Distance (m) from p to the grid's bounds [origin, origin + n res], walls for the E-APF: 0 on and
// outside them.
double bounds_distance(const tdo_grid* grid, const tdo_vec3& p) {
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  const double lo[3] = {p.x - d.origin.x, p.y - d.origin.y, p.z - d.origin.z};
  const double n[3] = {static_cast<double>(d.nx), static_cast<double>(d.ny),
                       static_cast<double>(d.nz)};
  double best = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    const double hi = n[a] * d.res - lo[a];
    const double w = lo[a] < hi ? lo[a] : hi;
    if (w < best) best = w;
  }
  return best > 0.0 ? best : 0.0;
}

// Capped distance (m) from p to the static map of follower c as its safety sees it (the wall
// terms, the safety filter's roll-outs, the evasion scores): the obstacle geometry and, for the
// E-APF, the map bounds as walls (docs/design.md s.4), so that a mover cannot push the vehicle out
// of the map (up through the ceiling, say). With `bounds` false, or for the classical APF
// baseline, the obstacles only: the static repulsion U_rep (apf.h) keeps the exact obstacle
// distance.
double static_distance(const tdo_apf* c, const tdo_vec3& p, double cap, bool bounds = true) {
  const double d = tdo_collision_point_distance(c->grid, p, cap);
  if (!bounds || c->prm.kind != TDO_FOLLOWER_EAPF) return d;
  const double w = bounds_distance(c->grid, p);
  return w < d ? w : d;
}

// Central-difference gradient of static_distance at p.
tdo_vec3 distance_gradient(const tdo_apf* c, const tdo_vec3& p, double cap, bool bounds = true) {
  const double h = kFdStep;
  return v3((static_distance(c, v3(p.x + h, p.y, p.z), cap, bounds) -
             static_distance(c, v3(p.x - h, p.y, p.z), cap, bounds)) /
                (2.0 * h),
            (static_distance(c, v3(p.x, p.y + h, p.z), cap, bounds) -
             static_distance(c, v3(p.x, p.y - h, p.z), cap, bounds)) /
                (2.0 * h),
            (static_distance(c, v3(p.x, p.y, p.z + h), cap, bounds) -
             static_distance(c, v3(p.x, p.y, p.z - h), cap, bounds)) /
                (2.0 * h));
}

bool params_ok(const tdo_apf_params* p) {
  // Read the enum's bytes as an int: a C caller may have stored any value there.
  // The underlying type has the enum's size on every ABI (short enums on arm-none-eabi).
  using Kind = std::underlying_type<tdo_follower_kind>::type;
  Kind kind = 0;
  static_assert(sizeof(kind) == sizeof(p->kind), "enum size");
  memcpy(&kind, &p->kind, sizeof kind);
  if (kind != static_cast<Kind>(TDO_FOLLOWER_EAPF) && kind != static_cast<Kind>(TDO_FOLLOWER_APF))
    return false;
  return positive(p->dt) && positive(p->k_a) && positive(p->att_dist) && non_negative(p->k_r) &&
         positive(p->d_0) && positive(p->d_0_static) && positive(p->d_min) &&
         non_negative(p->k_g) && positive(p->k_d) && non_negative(p->lookahead) &&
         positive(p->hold_dist) && non_negative(p->horizon) && non_negative(p->vehicle_radius) &&
         non_negative(p->mover_margin) && positive(p->v_max) && positive(p->a_max) &&
         positive(p->j_max) && positive(p->goal_tol) && positive(p->lm_window) &&
         positive(p->lm_progress) && positive(p->lm_force) && positive(p->lm_speed) &&
         positive(p->lm_goal_dist) && non_negative(p->k_t) && positive(p->escape_time) &&
         non_negative(p->k_r_static) && non_negative(p->safety_margin) && p->safety <= 1u;
}

bool state_ok(const tdo_vehicle_state* s) {
  return isfinite(s->t) && finite3(s->p) && finite3(s->v) && finite3(s->a);
}

bool movers_ok(const tdo_mover* m, uint32_t n) {
  if (n > 0u && m == nullptr) return false;
  for (uint32_t i = 0; i < n; ++i)
    if (!finite3(m[i].p) || !finite3(m[i].v) || !positive(m[i].radius)) return false;
  return true;
}

// Trajectory sample interpolated at time t (clamped to [0, t_end]).
void traj_at(const tdo_apf* c, double t, tdo_vec3* p, tdo_vec3* v, tdo_vec3* a) {
  if (!(t > 0.0)) t = 0.0;
  if (t > c->t_end) t = c->t_end;
  double fi = t / c->sample_dt;
  uint32_t i = static_cast<uint32_t>(fi);
  if (i >= c->n - 1u) i = c->n - 2u;
  double u = fi - static_cast<double>(i);
  if (u < 0.0) u = 0.0;
  if (u > 1.0) u = 1.0;
  const tdo_sample& s0 = c->samples[i];
  const tdo_sample& s1 = c->samples[i + 1u];
  *p = lerp(s0.p, s1.p, u);
  *v = lerp(s0.v, s1.v, u);
  *a = lerp(s0.a, s1.a, u);
}

// Nearest point of the polyline, searching the segments within nearest_window of `seg0`.
void nearest_point(const tdo_apf* c, tdo_vec3 p, uint32_t seg0, tdo_vec3* out, uint32_t* seg_out,
                   double* arc_out, double* t_out) {
  const uint32_t nseg = c->n - 1u;
  const uint32_t w = c->cfg.nearest_window;
  const uint32_t lo = seg0 > w ? seg0 - w : 0u;
  uint32_t hi = seg0 + w;  // inclusive
  if (hi >= nseg || hi < seg0) hi = nseg - 1u;
  double best = HUGE_VAL;
  for (uint32_t i = lo; i <= hi; ++i) {
    const tdo_vec3 a = c->samples[i].p, b = c->samples[i + 1u].p;
    const tdo_vec3 ab = sub(b, a);
    const double l2 = dot(ab, ab);
    double u = l2 > kEps ? dot(sub(p, a), ab) / l2 : 0.0;
    if (u < 0.0) u = 0.0;
    if (u > 1.0) u = 1.0;
    const tdo_vec3 q = add(a, mul(ab, u));
    const tdo_vec3 d = sub(p, q);
    const double dd = dot(d, d);
    if (dd < best) {
      best = dd;
      *out = q;
      *seg_out = i;
      *arc_out = c->arc[i] + u * (c->arc[i + 1u] - c->arc[i]);
      *t_out = (static_cast<double>(i) + u) * c->sample_dt;
    }
  }
}

// 1/2 k_r (1/d - 1/d0)^2 and its derivative magnitude k_r (1/d - 1/d0) / d^2 (d floored).
void rep_profile(double k_r, double d, double d0, double d_min, double* u, double* g) {
  if (d >= d0) {
    *u = 0.0;
    *g = 0.0;
    return;
  }
  if (d < d_min) d = d_min;
  const double s = 1.0 / d - 1.0 / d0;
  *u = 0.5 * k_r * s * s;
  *g = k_r * s / (d * d);
}

struct Near {
  uint32_t seg;
  double arc;
  double t;         // s, trajectory time of the nearest point
  tdo_vec3 wall_n;  // unit normal away from the static geometry (valid when wall_w < 1)
  double wall_w;    // 1 outside the wall zone, falling linearly to 0 at contact
  double wall_d;    // m, distance beyond vehicle_radius (valid when wall_w < 1)
};

// The whole field at `st` for the follower's current clock; `near` gets the nearest point.
void compute_terms(const tdo_apf* c, const tdo_vehicle_state* st, const tdo_mover* movers,
                   uint32_t n_movers, double ref_time, tdo_apf_terms* t, Near* near) {
  const tdo_apf_params& q = c->prm;
  memset(t, 0, sizeof(*t));
  const tdo_vec3 p = st->p;
  near->seg = c->near_seg;
  near->arc = 0.0;
  near->t = c->near_t;
  near->wall_n = v3(0.0, 0.0, 0.0);
  near->wall_w = 1.0;
  near->wall_d = HUGE_VAL;
  // Attraction.
  if (q.kind == TDO_FOLLOWER_EAPF) {
    tdo_vec3 rv, ra;
    traj_at(c, ref_time, &t->ref, &rv, &ra);
  } else {
    t->ref = c->goal;
  }
  const tdo_vec3 e = sub(t->ref, p);
  const double dg = norm(e);
  if (dg <= q.att_dist) {
    t->u_att = 0.5 * q.k_a * dg * dg;
    t->f_att = mul(e, q.k_a);
  } else {
    t->u_att = q.k_a * q.att_dist * (dg - 0.5 * q.att_dist);
    t->f_att = mul(e, q.k_a * q.att_dist / dg);
  }
  // Guidance.
  if (q.kind == TDO_FOLLOWER_EAPF) {
    nearest_point(c, p, c->near_seg, &t->nearest, &near->seg, &near->arc, &near->t);
    const tdo_vec3 d = sub(t->nearest, p);
    t->deviation = norm(d);
    t->u_guide = q.k_g * t->deviation * t->deviation;
    t->f_guide = mul(d, 2.0 * q.k_g);
  } else {
    t->nearest = c->goal;
  }
  // Static repulsion.
  t->static_dist = HUGE_VAL;
  if (c->grid != nullptr) {
    const double cap =
        q.vehicle_radius + (q.d_0_static > kWallZone ? q.d_0_static : kWallZone) + 0.5;
    const double dist = static_distance(c, p, cap, false);  // U_rep: the obstacles
    t->static_dist = dist;
    const double d = dist - q.vehicle_radius;
    const bool repel = d < q.d_0_static && dist > 0.0;
    if (repel) {
      double u, g;
      rep_profile(q.k_r_static, d, q.d_0_static, q.d_min, &u, &g);
      t->u_rep_static = u;
      t->f_rep_static = mul(distance_gradient(c, p, cap, false), g);
    }
    // The wall terms: the obstacles and the map bounds.
    const double wall = static_distance(c, p, cap);
    const double dw = wall - q.vehicle_radius;
    if (dw < kWallZone && wall > 0.0) {
      const tdo_vec3 grad = distance_gradient(c, p, cap);
      const double ng = norm(grad);
      if (ng > 1e-9) {
        near->wall_n = mul(grad, 1.0 / ng);
        near->wall_w = dw > 0.0 ? dw / kWallZone : 0.0;
        near->wall_d = dw;
      }
    }
    // Look ahead along the velocity: a corner or another face may come closer than the face
    // nearest now. The closest predicted point (if closer than now) sets the wall normal, and the
    // distance left along it is its distance plus the approach covered until then.
    double best = wall;
    double best_tau = 0.0;
    for (int k = 1; k <= kWallProbes; ++k) {
      const double tau = kWallProbeDt * k;
      const double dk = static_distance(c, add(p, mul(st->v, tau)), cap);
      if (dk < best) {
        best = dk;
        best_tau = tau;
      }
    }
    if (best_tau > 0.0 && best - q.vehicle_radius < kWallZone && best < wall - 1e-3) {
      const tdo_vec3 x = add(p, mul(st->v, best_tau));
      const tdo_vec3 g2 = distance_gradient(c, x, cap);
      const double n2 = norm(g2);
      if (n2 > 1e-9) {
        const tdo_vec3 n = mul(g2, 1.0 / n2);
        const double v_n = -dot(st->v, n);
        double left = best - q.vehicle_radius + (v_n > 0.0 ? v_n * best_tau : 0.0);
        if (left < 0.0) left = 0.0;
        if (left < near->wall_d) {
          near->wall_n = n;
          near->wall_d = left;
          near->wall_w = left / kWallZone;
        }
      }
    }
  }
  // Moving spheres: predicted closest approach within the horizon.
  t->mover_gap = HUGE_VAL;
  t->mover_pred_gap = HUGE_VAL;
  for (uint32_t i = 0; i < n_movers; ++i) {
    const tdo_mover& m = movers[i];
    const tdo_vec3 r = sub(p, m.p);
    const tdo_vec3 w = sub(st->v, m.v);
    const double reach = m.radius + q.vehicle_radius;
    const double gap = norm(r) - reach;
    if (gap < t->mover_gap) t->mover_gap = gap;
    const double w2 = dot(w, w);
    double ts = w2 > kEps ? -dot(r, w) / w2 : 0.0;
    if (ts < 0.0) ts = 0.0;
    if (ts > q.horizon) ts = q.horizon;
    const tdo_vec3 rs = add(r, mul(w, ts));
    const double nrs = norm(rs);
    const double d = nrs - reach - q.mover_margin;
    if (d < t->mover_pred_gap) t->mover_pred_gap = d;
    if (d >= q.d_0) continue;
    double u, g;
    rep_profile(q.k_r, d, q.d_0, q.d_min, &u, &g);
    // Direction: away from the predicted closest point; head-on (rs ~ 0): sideways, horizontal.
    tdo_vec3 side = unit_or(cross(v3(0.0, 0.0, 1.0), w), v3(1.0, 0.0, 0.0), 1e-9);
    tdo_vec3 dir = unit_or(rs, unit_or(r, side, 1e-9), 1e-9);
    t->u_rep_movers += u;
    t->f_rep_movers = add(t->f_rep_movers, mul(dir, g));
  }
  t->f_total = add(add(t->f_att, t->f_guide), add(t->f_rep_static, t->f_rep_movers));
  t->u_total = t->u_att + t->u_guide + t->u_rep_static + t->u_rep_movers;
}

// Braking policy of the safety filter: decelerate against v at a_max, proportionally below the
// speed a_max^2 / (2 j_max) (the speed the jerk limit needs to bring a_max back to zero).
tdo_vec3 brake_des(const tdo_apf_params& q, tdo_vec3 v) {
  const double s = norm(v);
  const double v_lin = q.a_max * q.a_max / (2.0 * q.j_max);
  return mul(v, -(s > v_lin ? q.a_max / s : q.a_max / v_lin));
}

// Steps of a braking roll-out: enough to stop from v_max with the acceleration ramps, plus 1 s.
uint32_t rollout_steps(const tdo_apf_params& q) {
  const double t = q.v_max / q.a_max + 2.0 * q.a_max / q.j_max + 1.0;
  const double n = ceil(t / q.dt);
  return n < static_cast<double>(kMaxRolloutSteps) ? static_cast<uint32_t>(n) : kMaxRolloutSteps;
}

// Margin of the braking roll-out that starts with setpoint `sp` from state `st`: the smallest
// static distance at the roll-out's positions (every step, as the simulator checks them) less
// vehicle_radius + safety_margin. A position is queried only when the distance at the last
// query, less the path flown since, could be below the threshold (distance is 1-Lipschitz), so
// far from walls one query covers many steps. Stops early at the first position below.
double rollout_margin(const tdo_apf* c, const tdo_setpoint& sp) {
  const tdo_apf_params& q = c->prm;
  const double thresh = q.vehicle_radius + q.safety_margin;
  const double cap = thresh + kRolloutCap;
  tdo_vehicle_state x;
  x.t = sp.t;
  x.p = sp.p;
  x.v = sp.v;
  x.a = sp.a;
  double best = HUGE_VAL, d_last = 0.0, since = 0.0;
  bool queried = false;
  const uint32_t n = rollout_steps(q);
  for (uint32_t k = 0; k <= n; ++k) {
    if (k > 0u) {
      tdo_setpoint nx;
      tdo_motion_limit(&x, brake_des(q, x.v), q.v_max, q.a_max, q.j_max, q.dt, &nx);
      since += norm(sub(nx.p, x.p));
      x.t = nx.t;
      x.p = nx.p;
      x.v = nx.v;
      x.a = nx.a;
    }
    if (!queried || d_last - since < thresh) {
      d_last = static_distance(c, x.p, cap);
      since = 0.0;
      queried = true;
      if (d_last < best) best = d_last;
      if (best < thresh) break;
    }
    if (norm(x.v) < kRestSpeed && norm(x.a) < kRestAcc) break;
  }
  return best - thresh;
}

// Largest lo in [0, 1] (of kSafetyBisections halvings) for which the command lerp(from, to, lo),
// limited, keeps a safe roll-out; `from` must be safe. The limited command goes to *sp.
void bisect_safe(const tdo_apf* c, const tdo_vehicle_state* st, const tdo_setpoint& from,
                 tdo_vec3 to, tdo_setpoint* sp) {
  const tdo_apf_params& q = c->prm;
  double lo = 0.0, hi = 1.0;
  *sp = from;
  for (int i = 0; i < kSafetyBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    tdo_setpoint m;
    tdo_motion_limit(st, lerp(from.a, to, mid), q.v_max, q.a_max, q.j_max, q.dt, &m);
    if (rollout_margin(c, m) >= 0.0) {
      lo = mid;
      *sp = m;
    } else {
      hi = mid;
    }
  }
}

// Static safety filter (E-APF): the command is kept only when the vehicle can still stop, under
// the same v/a/j limits, before coming within vehicle_radius + safety_margin of the static
// geometry (braking roll-out). Otherwise, with n the unit normal away from the nearest geometry:
// the "sliding" command (the desired acceleration without its component along n, at most a_max,
// plus the braking command's component along n) when that is safe, moved back towards the
// command as far as safe (bisection), so the field can still move the vehicle along the wall
// (away from a mover); else the applied acceleration moves from braking towards the sliding
// command as far as safe. Braking is safe whenever the previous step's command was (its roll-out
// is the previous one, one step on). When even braking is not safe (a state the filter did not
// produce), the candidate with the largest margin among the command, braking, sliding and full
// acceleration away from the geometry is taken. Returns true when the command changed.
bool safety_filter(const tdo_apf* c, const tdo_vehicle_state* st, tdo_vec3 a_des,
                   tdo_setpoint* sp) {
  const tdo_apf_params& q = c->prm;
  const double m_cmd = rollout_margin(c, *sp);
  if (m_cmd >= 0.0) return false;
  const tdo_vec3 b_des = brake_des(q, st->v);
  tdo_setpoint b;
  tdo_motion_limit(st, b_des, q.v_max, q.a_max, q.j_max, q.dt, &b);
  const double mb = rollout_margin(c, b);
  const double cap = q.vehicle_radius + q.safety_margin + kRolloutCap;
  const tdo_vec3 g = distance_gradient(c, st->p, cap);
  const double ng = norm(g);
  const bool have_n = ng > 1e-9;
  tdo_setpoint sl = b;
  double m_sl = -HUGE_VAL;
  if (have_n) {
    const tdo_vec3 n = mul(g, 1.0 / ng);
    tdo_vec3 tan = sub(a_des, mul(n, dot(a_des, n)));
    const double nt = norm(tan);
    if (nt > q.a_max) tan = mul(tan, q.a_max / nt);
    tdo_motion_limit(st, add(tan, mul(n, dot(b_des, n))), q.v_max, q.a_max, q.j_max, q.dt, &sl);
    m_sl = rollout_margin(c, sl);
    if (m_sl >= 0.0) {
      bisect_safe(c, st, sl, sp->a, sp);
      return true;
    }
  }
  if (mb >= 0.0) {
    bisect_safe(c, st, b, have_n ? sl.a : sp->a, sp);
    return true;
  }
  double best_m = m_cmd;
  tdo_setpoint best = *sp;
  if (mb > best_m) {
    best_m = mb;
    best = b;
  }
  if (have_n && m_sl > best_m) {
    best_m = m_sl;
    best = sl;
  }
  if (have_n) {
    tdo_setpoint aw;
    tdo_motion_limit(st, mul(g, q.a_max / ng), q.v_max, q.a_max, q.j_max, q.dt, &aw);
    if (rollout_margin(c, aw) > best_m) best = aw;
  }
  *sp = best;
  return true;
}

// Smallest predicted gap (as the field's d: less radius, vehicle_radius and mover_margin) to the
// movers within the horizon if the vehicle stood still at p. m; HUGE_VAL without movers.
double standing_gap(const tdo_apf_params& q, tdo_vec3 p, const tdo_mover* movers, uint32_t n) {
  double best = HUGE_VAL;
  for (uint32_t i = 0; i < n; ++i) {
    const tdo_mover& m = movers[i];
    const tdo_vec3 r = sub(p, m.p);
    const tdo_vec3 w = mul(m.v, -1.0);
    const double w2 = dot(w, w);
    double ts = w2 > kEps ? -dot(r, w) / w2 : 0.0;
    if (ts < 0.0) ts = 0.0;
    if (ts > q.horizon) ts = q.horizon;
    const double d = norm(add(r, mul(w, ts))) - m.radius - q.vehicle_radius - q.mover_margin;
    if (d < best) best = d;
  }
  return best;
}

// Score of holding the desired acceleration `a_cmd` for the evasion horizon (same v/a/j rule,
// steps of kEvadeDt, movers at constant velocity): the smallest predicted surface gap to a mover
// (|p - q| - radius - vehicle_radius) and, with a grid, static distance less vehicle_radius +
// safety_margin, over the steps. m.
double evasion_score(const tdo_apf* c, const tdo_vehicle_state* st, const tdo_mover* movers,
                     uint32_t n_movers, tdo_vec3 a_cmd) {
  const tdo_apf_params& q = c->prm;
  const double thresh = q.vehicle_radius + q.safety_margin;
  tdo_vehicle_state x = *st;
  double score = HUGE_VAL;
  for (int k = 1; k <= kEvadeSteps; ++k) {
    tdo_setpoint nx;
    tdo_motion_limit(&x, a_cmd, q.v_max, q.a_max, q.j_max, kEvadeDt, &nx);
    x.t = nx.t;
    x.p = nx.p;
    x.v = nx.v;
    x.a = nx.a;
    const double tk = kEvadeDt * k;
    for (uint32_t i = 0; i < n_movers; ++i) {
      const tdo_vec3 qm = add(movers[i].p, mul(movers[i].v, tk));
      const double gap = norm(sub(x.p, qm)) - movers[i].radius - q.vehicle_radius;
      if (gap < score) score = gap;
    }
    if (c->grid != nullptr) {
      const double d = static_distance(c, x.p, thresh + kRolloutCap) - thresh;
      if (d < score) score = d;
    }
  }
  return score;
}

// Mover evasion (E-APF with the safety filter): when the field predicts that a mover comes within
// mover_margin, the desired acceleration is kept if holding it keeps that gap (evasion_score);
// otherwise the best of a_max along 18 fixed directions (8 horizontal, up, down, 8 at +-45
// degrees) by evasion_score replaces it (the first best wins ties). Returns true when replaced.
bool evade_movers(const tdo_apf* c, const tdo_vehicle_state* st, const tdo_mover* movers,
                  uint32_t n_movers, tdo_vec3* a_des) {
  const tdo_apf_params& q = c->prm;
  tdo_vec3 a0 = *a_des;
  const double n0 = norm(a0);
  if (n0 > q.a_max) a0 = mul(a0, q.a_max / n0);
  const double s0 = evasion_score(c, st, movers, n_movers, a0);
  if (s0 >= q.mover_margin) return false;
  static const double kDirs[18][3] = {{1, 0, 0},
                                      {0.7071067811865476, 0.7071067811865476, 0},
                                      {0, 1, 0},
                                      {-0.7071067811865476, 0.7071067811865476, 0},
                                      {-1, 0, 0},
                                      {-0.7071067811865476, -0.7071067811865476, 0},
                                      {0, -1, 0},
                                      {0.7071067811865476, -0.7071067811865476, 0},
                                      {0, 0, 1},
                                      {0, 0, -1},
                                      {0.7071067811865476, 0, 0.7071067811865476},
                                      {0, 0.7071067811865476, 0.7071067811865476},
                                      {-0.7071067811865476, 0, 0.7071067811865476},
                                      {0, -0.7071067811865476, 0.7071067811865476},
                                      {0.7071067811865476, 0, -0.7071067811865476},
                                      {0, 0.7071067811865476, -0.7071067811865476},
                                      {-0.7071067811865476, 0, -0.7071067811865476},
                                      {0, -0.7071067811865476, -0.7071067811865476}};
  double best = s0;
  tdo_vec3 pick = a0;
  for (const auto& d : kDirs) {
    const tdo_vec3 a = mul(v3(d[0], d[1], d[2]), q.a_max);
    const double sc = evasion_score(c, st, movers, n_movers, a);
    if (sc > best) {
      best = sc;
      pick = a;
    }
  }
  if (best <= s0) return false;
  *a_des = pick;
  return true;
}

double ref_time_of(const tdo_apf* c) {
  if (c->prm.kind != TDO_FOLLOWER_EAPF) return 0.0;
  double r = c->tau + c->prm.lookahead;
  return r < c->t_end ? r : c->t_end;
}

}  // namespace

extern "C" void tdo_apf_params_default(tdo_apf_params* p, tdo_follower_kind kind) {
  if (p == nullptr) return;
  memset(p, 0, sizeof(*p));
  const bool eapf = kind != TDO_FOLLOWER_APF;
  p->kind = eapf ? TDO_FOLLOWER_EAPF : TDO_FOLLOWER_APF;
  p->dt = 0.02;
  p->k_a = eapf ? 4.0 : 1.0;
  p->att_dist = eapf ? 2.0 : 4.0;
  p->k_r = 1.5;
  p->d_0 = 2.5;
  p->d_0_static = eapf ? 0.25 : 2.0;
  p->d_min = 0.05;
  p->k_g = eapf ? 2.0 : 0.0;
  p->k_d = eapf ? 4.0 : 2.0;
  p->lookahead = 0.1;
  p->hold_dist = 1.0;
  p->horizon = 2.5;
  p->vehicle_radius = 0.25;
  p->mover_margin = 0.5;
  p->v_max = 3.0;
  p->a_max = 3.0;
  p->j_max = 10.0;
  p->goal_tol = 0.2;
  p->lm_window = 2.0;
  p->lm_progress = 0.3;
  p->lm_force = 0.5;
  p->lm_speed = 0.2;
  p->lm_goal_dist = 1.0;
  p->k_t = 2.0;
  p->escape_time = 3.0;
  p->max_escapes = 3u;
  p->k_r_static = eapf ? 0.0025 : 1.5;
  p->safety = eapf ? 1u : 0u;
  p->safety_margin = 0.05;
}

extern "C" size_t tdo_apf_footprint(const tdo_apf_config* cfg) {
  if (cfg == nullptr || cfg->max_samples < 2u || cfg->max_movers == 0u ||
      cfg->nearest_window == 0u || cfg->max_samples > 0x7FFFFFFFu)
    return 0;
  if (cfg->switching > 1u) return 0;
  const size_t ns = cfg->max_samples;
  const size_t plans = cfg->switching != 0u ? 2u : 1u;
  return tdo_arena_round(sizeof(tdo_apf)) +
         plans * (tdo_arena_round(ns * sizeof(tdo_sample)) + tdo_arena_round(ns * sizeof(double)));
}

extern "C" tdo_status tdo_apf_init(tdo_apf** out, tdo_arena* arena, const tdo_apf_config* cfg) {
  if (out == nullptr || arena == nullptr || cfg == nullptr || tdo_apf_footprint(cfg) == 0)
    return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  tdo_apf* c = arena_context<tdo_apf>(arena, *cfg);
  if (c == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  c->samples = arena_array<tdo_sample>(arena, cfg->max_samples);
  c->arc = arena_array<double>(arena, cfg->max_samples);
  if (c->samples == nullptr || c->arc == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  c->next_samples = nullptr;
  c->next_arc = nullptr;
  c->next_ready = 0;
  if (cfg->switching != 0u) {
    c->next_samples = arena_array<tdo_sample>(arena, cfg->max_samples);
    c->next_arc = arena_array<double>(arena, cfg->max_samples);
    if (c->next_samples == nullptr || c->next_arc == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  }
  *out = c;
  return TDO_OK;
}

namespace {

// Samples uniform in time from 0 (1e-6 relative) with finite p, v, a; *dt their period (0 for
// fewer than 2 samples).
bool samples_ok(const tdo_sample* samples, uint32_t n, double* dt) {
  *dt = 0.0;
  if (n < 2u) return true;
  const double sdt = samples[1].t - samples[0].t;
  if (!(fabs(samples[0].t) <= 1e-9) || !positive(sdt)) return false;
  for (uint32_t i = 0; i < n; ++i) {
    const tdo_sample& s = samples[i];
    const double expect = static_cast<double>(i) * sdt;
    if (!isfinite(s.t) || fabs(s.t - expect) > 1e-6 * (expect > 1.0 ? expect : 1.0) ||
        !finite3(s.p) || !finite3(s.v) || !finite3(s.a))
      return false;
  }
  *dt = sdt;
  return true;
}

// Copy n samples and their arclengths along the polyline.
void copy_samples(const tdo_sample* src, uint32_t n, tdo_sample* dst, double* arc) {
  if (n == 0u) return;
  memcpy(dst, src, static_cast<size_t>(n) * sizeof(tdo_sample));
  arc[0] = 0.0;
  for (uint32_t i = 1; i < n; ++i) arc[i] = arc[i - 1u] + norm(sub(dst[i].p, dst[i - 1u].p));
}

}  // namespace

extern "C" tdo_status tdo_apf_reset(tdo_apf* c, const tdo_apf_params* prm,
                                    const tdo_apf_task* task) {
  if (c == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  c->ready = 0;
  if (prm == nullptr || task == nullptr || !params_ok(prm) || !isfinite(task->t0))
    return TDO_ERR_INVALID_ARGUMENT;
  const bool eapf = prm->kind == TDO_FOLLOWER_EAPF;
  if (eapf) {
    if (task->samples == nullptr || task->n_samples < 2u) return TDO_ERR_INVALID_ARGUMENT;
  } else if (!finite3(task->goal) || (task->n_samples > 0u && task->samples == nullptr)) {
    return TDO_ERR_INVALID_ARGUMENT;
  }
  if (task->n_samples > c->cfg.max_samples) return TDO_ERR_SAMPLE_CAPACITY;
  if (task->grid != nullptr && !(tdo_grid_clearance(task->grid) >= 0.0))
    return TDO_ERR_MAP_NOT_READY;
  const uint32_t n = task->n_samples;
  double sdt = 0.0;
  if (!samples_ok(task->samples, n, &sdt)) return TDO_ERR_INVALID_ARGUMENT;
  copy_samples(task->samples, n, c->samples, c->arc);
  c->n = n;
  c->sample_dt = sdt;
  c->t_end = n >= 2u ? static_cast<double>(n - 1u) * sdt : 0.0;
  c->next_ready = 0;
  c->prm = *prm;
  c->goal = eapf ? c->samples[n - 1u].p : task->goal;
  c->grid = task->grid;
  c->t0 = task->t0;
  c->started = 0;
  c->prev_t = 0.0;
  c->tau = 0.0;
  c->near_seg = 0u;
  c->near_t = 0.0;
  c->mode = TDO_APF_MODE_TRACK;
  c->win_t = 0.0;
  c->win_p = 0.0;
  c->win_pos = v3(0.0, 0.0, 0.0);
  c->win_f = v3(0.0, 0.0, 0.0);
  c->win_n = 0u;
  c->goal_d0 = 0.0;
  c->best_goal = 0.0;
  c->escape_end = 0.0;
  c->escape_p = 0.0;
  c->escape_axis = v3(0.0, 0.0, 1.0);
  c->escape_n = v3(1.0, 0.0, 0.0);
  c->fails_in_row = 0u;
  c->lm_detections = 0u;
  c->escapes = 0u;
  c->steps = 0u;
  c->arrived_reported = 0;
  c->braked = 0;
  c->ready = 1;
  return TDO_OK;
}

extern "C" tdo_status tdo_apf_switch(tdo_apf* c, const tdo_apf_task* task, double t_switch) {
  if (c == nullptr || task == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready || c->cfg.switching == 0u) return TDO_ERR_NOT_CONFIGURED;
  if (c->prm.kind != TDO_FOLLOWER_EAPF || !non_negative(t_switch) || task->samples == nullptr ||
      task->n_samples < 2u)
    return TDO_ERR_INVALID_ARGUMENT;
  if (task->n_samples > c->cfg.max_samples) return TDO_ERR_SAMPLE_CAPACITY;
  if (task->grid != nullptr && !(tdo_grid_clearance(task->grid) >= 0.0))
    return TDO_ERR_MAP_NOT_READY;
  double sdt = 0.0;
  if (!samples_ok(task->samples, task->n_samples, &sdt)) return TDO_ERR_INVALID_ARGUMENT;
  copy_samples(task->samples, task->n_samples, c->next_samples, c->next_arc);
  c->next_n = task->n_samples;
  c->next_dt = sdt;
  c->next_switch = t_switch;
  c->next_grid = task->grid;
  c->next_ready = 1;
  return TDO_OK;
}

extern "C" tdo_status tdo_apf_eval(const tdo_apf* c, const tdo_vehicle_state* st,
                                   const tdo_mover* movers, uint32_t n_movers, tdo_apf_terms* out) {
  if (c == nullptr || st == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready) return TDO_ERR_NOT_CONFIGURED;
  if (n_movers > c->cfg.max_movers) return TDO_ERR_OBSTACLE_CAPACITY;
  if (!state_ok(st) || !movers_ok(movers, n_movers)) return TDO_ERR_INVALID_ARGUMENT;
  Near near;
  compute_terms(c, st, movers, n_movers, ref_time_of(c), out, &near);
  return TDO_OK;
}

namespace {

// Starts the trajectory clock at the first step; later steps advance it by the elapsed time
// (E-APF only) unless the vehicle is too far from the clock's point. Returns the step's events.
uint32_t advance_clock(tdo_apf* c, const tdo_vehicle_state* state, bool eapf) {
  const tdo_apf_params& prm = c->prm;
  const tdo_vec3 pos = state->p;
  uint32_t events = 0u;
  if (!c->started) {
    c->started = 1;
    double tau = state->t - c->t0;
    if (!(tau > 0.0)) tau = 0.0;
    c->tau = tau < c->t_end ? tau : c->t_end;
    c->goal_d0 = norm(sub(pos, c->goal));
    c->best_goal = c->goal_d0;
    c->win_t = state->t;
    c->win_pos = pos;
  } else if (eapf) {
    double elapsed = state->t - c->prev_t;
    if (!(elapsed > 0.0)) elapsed = 0.0;
    if (elapsed > kMaxElapsedSteps * prm.dt) elapsed = kMaxElapsedSteps * prm.dt;
    // Far from the clock's point (pushed away), the reference never lags the nearest trajectory
    // point: the vehicle may rejoin the plan further along. Not while tracking: near a corner the
    // nearest point may lie on a later, nearby part of the plan.
    tdo_vec3 clock_p, clock_v, clock_a;
    traj_at(c, c->tau, &clock_p, &clock_v, &clock_a);
    if (norm(sub(clock_p, pos)) > 0.5 * prm.hold_dist && c->near_t - prm.lookahead > c->tau) {
      c->tau = c->near_t - prm.lookahead;
      traj_at(c, c->tau, &clock_p, &clock_v, &clock_a);
    }
    if (norm(sub(clock_p, pos)) <= prm.hold_dist) {
      c->tau += elapsed;
      if (c->tau > c->t_end) c->tau = c->t_end;
    } else {
      events |= TDO_APF_EVENT_CLOCK_HELD;
    }
  }
  c->prev_t = state->t;
  return events;
}

// The staged plan takes over once the reference time reaches its switch time (or the active
// plan's end): the clock moves to the new plan at clock - t_switch. Returns the step's events.
uint32_t take_staged_plan(tdo_apf* c) {
  if (!c->next_ready) return 0u;
  const double at = c->next_switch < c->t_end ? c->next_switch : c->t_end;
  if (c->tau + c->prm.lookahead < at && c->tau < c->t_end) return 0u;
  tdo_sample* s = c->samples;
  double* arc = c->arc;
  c->samples = c->next_samples;
  c->arc = c->next_arc;
  c->next_samples = s;
  c->next_arc = arc;
  c->next_ready = 0;
  c->n = c->next_n;
  c->sample_dt = c->next_dt;
  c->t_end = static_cast<double>(c->n - 1u) * c->sample_dt;
  c->goal = c->samples[c->n - 1u].p;
  c->grid = c->next_grid;
  c->tau -= c->next_switch;
  if (c->tau > c->t_end) c->tau = c->t_end;
  double seg = c->tau > 0.0 ? floor(c->tau / c->sample_dt) : 0.0;
  if (seg > static_cast<double>(c->n - 2u)) seg = static_cast<double>(c->n - 2u);
  c->near_seg = static_cast<uint32_t>(seg);
  c->near_t = seg * c->sample_dt;
  c->mode = TDO_APF_MODE_TRACK;
  c->fails_in_row = 0u;
  c->arrived_reported = 0;
  return TDO_APF_EVENT_SWITCHED;
}

// Opens a new progress window of the local-minimum detector at the vehicle's state.
void restart_window(tdo_apf* c, const tdo_vehicle_state* state, double progress) {
  c->win_t = state->t;
  c->win_p = progress;
  c->win_pos = state->p;
  c->win_f = v3(0.0, 0.0, 0.0);
  c->win_n = 0u;
}

// Enters escape mode: turn about (repulsion normal) x (direction to the reference), towards the
// goal side; head-on (the two opposite): about z, i.e. sideways.
void start_escape(tdo_apf* c, const tdo_vehicle_state* state, const tdo_apf_terms* terms,
                  tdo_vec3 f_rep, double progress) {
  c->mode = TDO_APF_MODE_ESCAPE;
  c->escape_end = state->t + c->prm.escape_time;
  c->escape_p = progress;
  const tdo_vec3 to_ref = unit_or(sub(terms->ref, state->p), v3(1.0, 0.0, 0.0), 1e-9);
  const tdo_vec3 normal = unit_or(f_rep, mul(to_ref, -1.0), 1e-9);
  tdo_vec3 axis = cross(normal, to_ref);
  if (norm(axis) <= 1e-6) axis = v3(0.0, 0.0, 1.0);
  if (norm(cross(axis, normal)) <= 1e-6) axis = v3(1.0, 0.0, 0.0);
  c->escape_axis = unit_or(axis, v3(0.0, 0.0, 1.0), 1e-12);
  c->escape_n = normal;
}

// Local-minimum detector (track mode) and escape bookkeeping. Returns the step's events.
uint32_t detect_local_minimum(tdo_apf* c, const tdo_vehicle_state* state,
                              const tdo_apf_terms* terms, tdo_vec3 f_rep, double progress,
                              double goal_dist, double speed) {
  const tdo_apf_params& prm = c->prm;
  uint32_t events = 0u;
  if (c->mode == TDO_APF_MODE_ESCAPE && state->t >= c->escape_end) {
    c->mode = TDO_APF_MODE_TRACK;
    if (progress - c->escape_p >= prm.lm_progress) {
      events |= TDO_APF_EVENT_ESCAPE_OK;
      c->fails_in_row = 0u;
    }
    restart_window(c, state, progress);
  }
  if (c->mode != TDO_APF_MODE_TRACK || state->t - c->win_t < prm.lm_window) return events;
  const bool no_progress = progress - c->win_p < prm.lm_progress;
  const bool far = goal_dist > prm.lm_goal_dist;
  // Small force or slow: also over the window, so that an oscillation in front of an obstacle
  // (large force and speed at every instant, none on average) counts.
  const double span = state->t - c->win_t;
  const double mean_f = c->win_n > 0u ? norm(c->win_f) / static_cast<double>(c->win_n) : 0.0;
  const double mean_v = norm(sub(state->p, c->win_pos)) / span;
  const bool weak = norm(terms->f_total) < prm.lm_force || speed < prm.lm_speed ||
                    mean_f < prm.lm_force || mean_v < prm.lm_speed;
  if (no_progress && far && weak) {
    ++c->lm_detections;
    events |= TDO_APF_EVENT_LM_DETECTED;
    if (c->fails_in_row >= prm.max_escapes) {
      c->mode = TDO_APF_MODE_STUCK;
      events |= TDO_APF_EVENT_ESCAPE_FAILED;
    } else {
      ++c->fails_in_row;
      ++c->escapes;
      events |= TDO_APF_EVENT_ESCAPE_START;
      start_escape(c, state, terms, f_rep, progress);
    }
  } else if (!no_progress && c->fails_in_row > 0u) {
    events |= TDO_APF_EVENT_ESCAPE_OK;
    c->fails_in_row = 0u;
  }
  restart_window(c, state, progress);
  return events;
}

// The mode's desired acceleration before the wall terms: escape (repulsion, tangential push and
// damping), stuck (repulsion and damping) or track (field, damping towards the reference
// velocity and, for E-APF, the trajectory's feed-forward acceleration).
tdo_vec3 mode_command(tdo_apf* c, const tdo_vehicle_state* state, const tdo_apf_terms* terms,
                      tdo_vec3 f_rep, tdo_vec3 v_ref, tdo_vec3 a_ref, bool eapf) {
  const tdo_apf_params& prm = c->prm;
  tdo_vec3 a_des;
  switch (c->mode) {
    case TDO_APF_MODE_ESCAPE: {
      if (norm(f_rep) > 1e-9) c->escape_n = unit_or(f_rep, c->escape_n, 1e-9);
      const tdo_vec3 tan = unit_or(cross(c->escape_axis, c->escape_n), v3(0.0, 0.0, 0.0), 1e-9);
      a_des = add(add(f_rep, mul(tan, prm.k_t)), mul(state->v, -prm.k_d));
      break;
    }
    case TDO_APF_MODE_STUCK:
      a_des = add(f_rep, mul(state->v, -prm.k_d));
      break;
    default:
      a_des = add(terms->f_total, mul(sub(state->v, v_ref), -prm.k_d));
      if (eapf) a_des = add(a_des, a_ref);
      break;
  }
  return a_des;
}

// Wall terms of the command (not on the plan: E-APF within kOnPlan of it, tracking, where the
// plan vouches for the clearance).
tdo_vec3 apply_wall_terms(const tdo_apf* c, const tdo_vehicle_state* state, const Near& near,
                          tdo_vec3 a_des, tdo_vec3 a_ref, bool eapf, bool on_plan) {
  if (on_plan) return a_des;
  const tdo_apf_params& prm = c->prm;
  // Near a wall (within kWallFade beyond vehicle_radius) the corrective command's component
  // into the wall (everything but the trajectory's own feed-forward acceleration) fades out, to
  // zero at contact: the field may move the vehicle along or away from a wall, not into it.
  if (near.wall_d < kWallFade) {
    const tdo_vec3 ff = (c->mode == TDO_APF_MODE_TRACK && eapf) ? a_ref : v3(0.0, 0.0, 0.0);
    const tdo_vec3 corr = sub(a_des, ff);
    const double into = dot(corr, near.wall_n);
    const double keep = near.wall_d > 0.0 ? near.wall_d / kWallFade : 0.0;
    if (into < 0.0) a_des = sub(a_des, mul(near.wall_n, into * (1.0 - keep)));
  }
  // Braking at walls (in every mode): approaching the static geometry at normal speed v_n within
  // the wall zone asks for the deceleration that stops within the remaining distance (less the
  // distance covered while the jerk limit builds it up).
  if (near.wall_w < 1.0) {
    const double v_n = -dot(state->v, near.wall_n);
    if (v_n > 0.0) {
      double room = near.wall_d - v_n * (prm.a_max / prm.j_max);
      if (room < prm.d_min) room = prm.d_min;
      a_des = add(a_des, mul(near.wall_n, v_n * v_n / (2.0 * room)));
    }
  }
  return a_des;
}

}  // namespace

extern "C" tdo_status tdo_apf_run(tdo_apf* c, const tdo_apf_input* in, tdo_apf_output* out) {
  if (c == nullptr || in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!c->ready) return TDO_ERR_NOT_CONFIGURED;
  if (in->n_movers > c->cfg.max_movers) return TDO_ERR_OBSTACLE_CAPACITY;
  const tdo_vehicle_state* state = &in->state;
  if (!state_ok(state) || !movers_ok(in->movers, in->n_movers)) return TDO_ERR_INVALID_ARGUMENT;
  const tdo_apf_params& prm = c->prm;
  const bool eapf = prm.kind == TDO_FOLLOWER_EAPF;
  memset(out, 0, sizeof(*out));

  uint32_t events = advance_clock(c, state, eapf);
  events |= take_staged_plan(c);
  const double ref_time = ref_time_of(c);

  // Field.
  Near near;
  tdo_apf_terms* terms = &out->terms;
  compute_terms(c, state, in->movers, in->n_movers, ref_time, terms, &near);
  if (eapf) {
    c->near_seg = near.seg;
    c->near_t = near.t;
  }
  const double goal_dist = norm(sub(state->p, c->goal));
  if (goal_dist < c->best_goal) c->best_goal = goal_dist;
  const double progress = eapf ? near.arc : c->goal_d0 - c->best_goal;
  if ((events & TDO_APF_EVENT_SWITCHED) != 0u) restart_window(c, state, progress);
  if (terms->mover_pred_gap < prm.d_0) events |= TDO_APF_EVENT_REPULSED;
  c->win_f = add(c->win_f, terms->f_total);
  ++c->win_n;

  // Reference velocity and feed-forward.
  tdo_vec3 v_ref = v3(0.0, 0.0, 0.0), a_ref = v3(0.0, 0.0, 0.0);
  if (eapf) {
    tdo_vec3 ref_p;
    traj_at(c, ref_time, &ref_p, &v_ref, &a_ref);
  }
  const double speed = norm(state->v);
  const tdo_vec3 f_rep = add(terms->f_rep_static, terms->f_rep_movers);

  // Arrival.
  const bool clock_done = !eapf || c->tau >= c->t_end;
  if (c->mode == TDO_APF_MODE_TRACK && clock_done && goal_dist <= prm.goal_tol &&
      speed < kArriveSpeed) {
    c->mode = TDO_APF_MODE_ARRIVED;
    if (!c->arrived_reported) events |= TDO_APF_EVENT_GOAL_REACHED;
    c->arrived_reported = 1;
  }
  events |= detect_local_minimum(c, state, terms, f_rep, progress, goal_dist, speed);

  // Command.
  const bool on_plan = eapf && terms->deviation < kOnPlan && c->mode == TDO_APF_MODE_TRACK;
  tdo_vec3 a_des = mode_command(c, state, terms, f_rep, v_ref, a_ref, eapf);
  a_des = apply_wall_terms(c, state, near, a_des, a_ref, eapf, on_plan);
  // Evasion when a mover is predicted within mover_margin, or, while the safety filter is
  // braking, when it would come that close to the vehicle standing still.
  const bool threat =
      terms->mover_pred_gap < 0.0 || (c->braked && in->n_movers > 0u &&
                                      standing_gap(prm, state->p, in->movers, in->n_movers) < 0.0);
  if (eapf && prm.safety != 0u && in->n_movers > 0u && threat) {
    if (evade_movers(c, state, in->movers, in->n_movers, &a_des)) events |= TDO_APF_EVENT_EVADE;
  }
  out->a_des = a_des;
  tdo_motion_limit(state, a_des, prm.v_max, prm.a_max, prm.j_max, prm.dt, &out->setpoint);
  if (prm.safety != 0u && c->grid != nullptr) {
    if (safety_filter(c, state, a_des, &out->setpoint)) events |= TDO_APF_EVENT_SAFETY;
  }
  c->braked = (events & TDO_APF_EVENT_SAFETY) != 0u ? 1 : 0;

  ++c->steps;
  out->ref_time = ref_time;
  out->progress = progress;
  out->mode = c->mode;
  out->events = events;
  out->lm_detections = c->lm_detections;
  out->escapes = c->escapes;
  out->steps = c->steps;
  return c->mode == TDO_APF_MODE_STUCK ? TDO_ERR_LOCAL_MINIMUM : TDO_OK;
}

extern "C" tdo_status tdo_apf_step(tdo_apf* c, const tdo_vehicle_state* state,
                                   const tdo_mover* movers, uint32_t n_movers,
                                   tdo_setpoint* setpoint) {
  if (state == nullptr || setpoint == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  tdo_apf_input in;
  in.state = *state;
  in.movers = movers;
  in.n_movers = n_movers;
  tdo_apf_output out;
  const tdo_status s = tdo_apf_run(c, &in, &out);
  if (s == TDO_OK || s == TDO_ERR_LOCAL_MINIMUM) *setpoint = out.setpoint;
  return s;
}
