// Stage 3: curvature-constrained adaptive-radius corner smoothing (docs/design.md s.3, paper eq.
// 8-9).
//
// Per interior waypoint: deflection theta, radius r = k theta / (2 sin(theta/2)) R_min (eq. 8),
// corner curve tangent to both segments in their plane: the G2 cubic Bezier spiral pair of Yang and
// Sukkarieh (2010) or a circular arc. Corners are fitted into the room the neighbouring corners
// leave, checked for clearance and shrunk when needed; corners that cannot be filleted become stop
// points. Fixed memory from the arena, every loop bounded, deterministic.
//
// The G2 corner (derivation; the tests verify every property numerically). Let u_in, u_out be the
// unit directions into and out of the waypoint w, theta the deflection, beta = theta / 2, d the
// tangent length. The first Bezier is
//   B0 = w - d u_in,  B1 = w - (d - g) u_in,  B2 = w - (d - g - h) u_in,  B3 = J,
// the second one mirrors it about the bisector (E0 = w + d u_out, ...) and both meet at
//   J = (B2 + E2) / 2,
// so B2, J, E2 are collinear: tangent continuity at J by construction, equal curvature at J by
// symmetry. B0, B1, B2 collinear gives curvature 0 at the lines. With h = c3 d, g = c2 h:
//   kappa(J) = (2/3) h sin(beta) / k^2,  k = |J - B2| = (d - g - h) cos(beta) = q d cos(beta),
//   q = 1 - c3 (1 + c2),
// hence d = (2/3) c3 sin(beta) / (kappa_max q^2 cos^2(beta)). Yang and Sukkarieh write this as
// d = (c2 + 4)^2 sin(beta) / (54 c3 kappa_max cos^2(beta)) with k = 6 c3 cos(beta) d / (c2 + 4),
// which equals the geometric k only when c1 = (c2 + 1)(c2 + 4) = 7.2351427678...; the published
// c1 = 7.2364 is a rounding that makes J miss the midpoint or (with J the midpoint) lets the
// curvature overshoot 1/r by up to 3e-5 relative near the junction. With the exact c1 and
// c2 = 2 (sqrt 6 - 1) / 5 the curvature rises monotonically from 0 to kappa_max with dkappa/ds = 0
// at J, so the peak is exactly 1/r (verified in test_smooth.cpp for 0.1..170 degrees).
#include "tdo/smooth.h"

#include <math.h>
#include <string.h>

#include "arena_typed.h"
#include "collision_internal.h"
#include "g2_shape.h"
#include "scalar.h"
#include "smooth_clear.h"
#include "tdo/collision.h"
#include "vec3.h"

using namespace tdo_internal;  // vec3.h, scalar.h, arena_typed.h

namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr double kStraightAngle = 1e-7;  // rad; smaller deflections pass straight, no corner
constexpr double kNearPi = 1e-6;         // rad; deflections within this of pi always stop
constexpr double kDuplicate = 1e-9;      // m; consecutive waypoints closer than this are merged
constexpr double kMergeRel = 1e-9;       // lines shorter than this (relative, >= 1 m) are dropped
constexpr double kShrink = 0.6;          // radius factor per clearance shrink step
constexpr uint32_t kShrinkSteps = 4u;    // halvings of a shrink step (corner_time > 0)
constexpr double kDefaultMinRadius = 0.05;  // of R_min, when the input gives 0
constexpr double kAbsMinRadius = 1e-6;      // m; no corner radius below this, whatever the input
constexpr double kClearTolerance = 0.005;   // m; conservativeness allowed to the Bezier check
constexpr uint32_t kMaxChords = 64u;        // chords per arc clearance check
// Time-oriented corner shapes (tdo_smooth_input.corner_time): the inner control points at these
// fractions of the tangent length spread the curvature change over the whole curve (max|dkappa/ds|
// about 5x lower than Yang-Sukkarieh's for the same tangent length up to ~60 degrees).
constexpr double kGentleG = 0.32;  // |B1 - B0| / d
constexpr double kGentleH = 0.32;  // |B2 - B1| / d
constexpr int kShapeBlends = 4;    // shapes tried: Yang-Sukkarieh blended 0, 1/4, .., 1 of the way
constexpr double kTimeJerkShare = 0.4;  // of j_max: lateral jerk the jerk radius designs for
constexpr int kCoarseStep = 4;          // g2_shape_lower's sample step tried first

enum CornerKind : uint8_t {
  kCornerStraight = 0,  // no turn: the lines meet end to end
  kCornerStop = 1,      // polyline corner, vehicle at rest there
  kCornerCurve = 2      // filleted
};

/** Per-waypoint state. Index 0 and n-1 are start and goal (kCornerStraight, no room needed). */
struct Corner {
  tdo_vec3 w;            // m, waypoint
  tdo_vec3 u;            // unit direction of the segment from this waypoint to the next
  double len;            // m, length of that segment
  double gf, hf;         // G2 shape: |B1 - B0| and |B2 - B1| as fractions of the tangent length
  double tau;            // tangent length per metre of radius (dimensionless)
  double rate;           // max|dkappa/ds| * r^2 of the G2 shape (dimensionless); 0 for arcs
  double r_des;          // m, wanted radius
  double t_des;          // m, wanted tangent length
  double r;              // m, final radius
  double t;              // m, final tangent length
  double v;              // m/s, speed cap of the corner curve
  tdo_vec3 entry, exit;  // m, where the curve leaves the incoming line and joins the outgoing one
  uint8_t kind;          // CornerKind
  uint8_t shrunk;        // 1 when r < r_des
};

tdo_path_segment blank_segment(tdo_segment_kind kind) {
  tdo_path_segment s;
  memset(&s, 0, sizeof(s));
  s.kind = kind;
  return s;
}

/** The two Beziers of a G2 corner at waypoint w with tangent length d from entry to exit. */
void g2_corner(const tdo_vec3& w, const tdo_vec3& u_in, const tdo_vec3& u_out, double gf, double hf,
               double d, const tdo_vec3& entry, const tdo_vec3& exit, tdo_path_segment out[2]) {
  const double h = hf * d, g = gf * d;
  const tdo_vec3 b1 = sub(w, mul(u_in, d - g));
  const tdo_vec3 b2 = sub(w, mul(u_in, d - g - h));
  const tdo_vec3 e1 = add(w, mul(u_out, d - g));
  const tdo_vec3 e2 = add(w, mul(u_out, d - g - h));
  const tdo_vec3 j = mul(add(b2, e2), 0.5);
  out[0] = blank_segment(TDO_SEGMENT_BEZIER);
  out[0].p[0] = entry;
  out[0].p[1] = b1;
  out[0].p[2] = b2;
  out[0].p[3] = j;
  out[1] = blank_segment(TDO_SEGMENT_BEZIER);
  out[1].p[0] = j;
  out[1].p[1] = e2;
  out[1].p[2] = e1;
  out[1].p[3] = exit;
}

/** The arc of radius r at waypoint w with tangent length t, from entry to exit. */
tdo_path_segment arc_corner(const tdo_vec3& w, const tdo_vec3& u_in, const tdo_vec3& u_out,
                            double r, double t, const tdo_vec3& entry, const tdo_vec3& exit) {
  tdo_path_segment s = blank_segment(TDO_SEGMENT_ARC);
  const tdo_vec3 n_raw =
      sub(u_out, mul(u_in, dot(u_in, u_out)));  // in-plane normal towards the turn
  const tdo_vec3 n = mul(n_raw, 1.0 / norm(n_raw));
  const tdo_vec3 c = add(sub(w, mul(u_in, t)), mul(n, r));
  s.p[0] = entry;
  s.p[1] = exit;
  s.p[2] = c;
  return s;
}

}  // namespace

struct tdo_smooth {
  tdo_smooth_config cfg;
  tdo_path_segment* seg;  // max_segments, the output path
  Corner* corner;         // max_waypoints
};

namespace {

/** What a corner's clearance checks hand on to the next check of the same corner. */
struct ClearState {
  int first;     // G2 half to check first: the one that failed last
  uint32_t box;  // bezier_clear_hinted's hints: the box and the cube that failed last
  uint32_t cube;
};

/**
 * Clearance of a corner curve; counts the queries. `margin` (m) is added to the clearance: it
 * covers the at most kMergeRel * max(1, L) shift of an end point that step 4 may snap onto its
 * neighbour's (along the line, so the curve moves by no more than that). `st`: carried from
 * the corner's previous check (zeros to start).
 */
int corner_clear(const tdo_smooth_input& in, const Corner& c, const Corner& prev, double margin,
                 uint32_t* checks, ClearState* st) {
  if (in.grid == nullptr) return 1;
  const double clearance = in.clearance + margin;
  const tdo_vec3 entry = sub(c.w, mul(prev.u, c.t));
  const tdo_vec3 exit = add(c.w, mul(c.u, c.t));
  if (in.mode == TDO_SMOOTHING_G2) {
    tdo_path_segment b[2];
    g2_corner(c.w, prev.u, c.u, c.gf, c.hf, c.t, entry, exit, b);
    // Both halves must be clear: the one that failed the corner's last check goes first. The
    // certificates answer as the exact check would; it runs when neither decides.
    for (int q = 0; q < 2; ++q) {
      const int i = q == 0 ? st->first : 1 - st->first;
      ++*checks;
      if (bezier_surely_clear(in.grid, b[i].p, clearance, kClearTolerance)) continue;
      if (bezier_surely_blocked(in.grid, b[i].p, clearance, i == 0 ? 1 : 0) ||
          !bezier_clear_hinted(in.grid, b[i].p, clearance, kClearTolerance, &st->box, &st->cube)) {
        st->first = i;
        return 0;
      }
    }
    return 1;
  }
  // Arc: chords of the arc, each checked at clearance + sagitta. Every arc point lies within the
  // sagitta of its chord, so a clear chord proves its arc piece clear.
  tdo_path_segment a = arc_corner(c.w, prev.u, c.u, c.r, c.t, entry, exit);
  a.length = tdo_segment_length(&a);
  const double sweep = a.length / c.r;
  uint32_t m = 1u;
  if (kClearTolerance < c.r) {
    const double step = 2.0 * acos(1.0 - kClearTolerance / c.r);
    const double need = ceil(sweep / step);
    m = need >= static_cast<double>(kMaxChords) ? kMaxChords
                                                : (need < 1.0 ? 1u : static_cast<uint32_t>(need));
  }
  const double sag = c.r * (1.0 - cos(0.5 * sweep / m));
  tdo_vec3 p0 = a.p[0];
  for (uint32_t i = 1; i <= m; ++i) {
    const tdo_vec3 p1 = i == m ? a.p[1] : tdo_segment_point(&a, a.length * i / m);
    ++*checks;
    if (!tdo_collision_segment_clear(in.grid, p0, p1, clearance + sag)) return 0;
    p0 = p1;
  }
  return 1;
}

/** What g2_choose's blends share. */
struct Blends {
  const tdo_smooth_input* in;
  double beta, r8, v_c, half_room, j_design;
};

// Inner fractions of blend b (0: Yang-Sukkarieh, kShapeBlends: corner_time of the way to gentle).
void blend_fractions(const Blends& s, int b, double* gf, double* hf) {
  const double ys_g = kC2 * kC3, ys_h = kC3;
  const double lam = s.in->corner_time * b / kShapeBlends;
  *gf = ys_g + lam * (kGentleG - ys_g);
  *hf = ys_h + lam * (kGentleH - ys_h);
}

// Speed of a blend's curve with the tangent length it can surely have, and its wanted radius.
double blend_speed(const Blends& s, double tau, double rate, double* r_des) {
  const double v_c = s.v_c;
  *r_des = dmax(s.r8, sqrt(v_c * v_c * v_c * rate / s.j_design));
  const double r = dmin(*r_des, s.half_room / tau);  // the radius it surely fits with
  return dmin(sqrt(s.in->a_lat_max * r), cbrt(s.j_design * r * r / rate));
}

// True when v_last beats every middle blend's speed (b = 1 .. kShapeBlends - 1) by more than the
// comparison's 1e-9. A blend's speed is at most its speed at r = half_room / tau, that is
// min(sqrt(a_lat half_room / tau), cbrt(j_design half_room^2 / f)) with f = tau^2 rate, and its
// tau and f are at least g2_shape_lower's (a 1e-6 margin covers the rounding): from every
// kCoarseStep-th sample first (mostly enough), from all where that does not decide.
bool middle_blends_slower(const Blends& s, double v_last) {
  for (int b = kShapeBlends - 1; b >= 1; --b) {
    double gf, hf, tau_lower, f_lower;
    blend_fractions(s, b, &gf, &hf);
    for (int step = kCoarseStep;; step = 1) {
      g2_shape_lower(s.beta, gf, hf, &tau_lower, &f_lower, step);
      const double upper = dmin(sqrt(s.in->a_lat_max * s.half_room / tau_lower),
                                cbrt(s.j_design * s.half_room * s.half_room / f_lower));
      if (v_last > upper * (1.0 + 1e-6) * (1.0 + 1e-9)) break;
      if (step == 1) return false;
    }
  }
  return true;
}

void take_blend(const Blends& s, int b, double tau, double rate, double r_des, Corner* k) {
  blend_fractions(s, b, &k->gf, &k->hf);
  k->tau = tau;
  k->rate = rate;
  k->r_des = r_des;
}

/**
 * Shape, tau, rate and wanted radius of a G2 corner. corner_time 0: the Yang-Sukkarieh shape, the
 * radius the larger of eq. 8's and the jerk radius for j_max. Otherwise the blends of it with the
 * gentle shape, up to corner_time of the way, each with the jerk radius for kTimeJerkShare j_max,
 * and the one whose curve allows the highest speed (lateral acceleration and jerk) with the
 * tangent length it can surely have (at most half of each neighbouring line): ties keep the
 * shape closer to Yang-Sukkarieh.
 */
void g2_choose(const tdo_smooth_input& in, double theta, double r8, double v_c, double half_room,
               Corner* k) {
  const double beta = 0.5 * theta;
  if (!(in.corner_time > 0.0)) {
    k->gf = kC2 * kC3;
    k->hf = kC3;
    k->tau = g2_tau(beta);
    k->rate = g2_rate(beta);
    k->r_des = dmax(r8, sqrt(v_c * v_c * v_c * k->rate / in.j_max));
    return;
  }
  const Blends s{&in, beta, r8, v_c, half_room, kTimeJerkShare * in.j_max};
  // A shape whose rate puts its jerk radius above r8 has r_des = that radius, so its speed is at
  // most min(.., cbrt(j_design r_des^2 / rate)) = v_c up to rounding: once the best speed is v_c,
  // such a blend cannot pass the comparison below (it needs 1e-9 more) and is not computed. Its
  // rate is bounded from below, by the quick bound first (it mostly decides), then the tight one.
  const double rate_r8 = r8 * r8 * s.j_design / (v_c * v_c * v_c);  // rate whose jerk radius is r8
  const double rate_skip = rate_r8 * (1.0 + 1e-9);
  double r_des;
  double best_v = -1.0;
  const double tau0 = g2_tau(beta), rate0 = g2_rate(beta);
  const double v0 = blend_speed(s, tau0, rate0, &r_des);
  if (v0 > best_v * (1.0 + 1e-9)) {
    best_v = v0;
    take_blend(s, 0, tau0, rate0, r_des, k);
  }
  // Below v_c the last blend is computed next: when it beats bounds of the middle ones' speeds,
  // it is the one the comparisons would pick (skips drop only blends that cannot win).
  double last_tau = 0.0, last_rate = 0.0;
  if (best_v < v_c * (1.0 - 1e-10)) {
    double gf, hf;
    blend_fractions(s, kShapeBlends, &gf, &hf);
    g2_shape(beta, gf, hf, &last_tau, &last_rate);
    const double v = blend_speed(s, last_tau, last_rate, &r_des);
    if (v > best_v * (1.0 + 1e-9) && middle_blends_slower(s, v)) {
      take_blend(s, kShapeBlends, last_tau, last_rate, r_des, k);
      return;
    }
  }
  for (int b = 1; b <= kShapeBlends; ++b) {
    double gf, hf;
    blend_fractions(s, b, &gf, &hf);
    if (best_v >= v_c * (1.0 - 1e-10) &&
        (g2_rate_lower_quick(beta, gf, hf) > rate_skip || g2_rate_lower(beta, gf, hf) > rate_skip))
      continue;
    double tau = last_tau, rate = last_rate;
    if (b < kShapeBlends || !(last_tau > 0.0)) g2_shape(beta, gf, hf, &tau, &rate);
    const double v = blend_speed(s, tau, rate, &r_des);
    if (v > best_v * (1.0 + 1e-9)) {
      best_v = v;
      take_blend(s, b, tau, rate, r_des, k);
    }
  }
}

bool valid_input(const tdo_smooth_input& in) {
  if (in.waypoints == nullptr || in.n_waypoints < 2u) return false;
  if (in.mode != TDO_SMOOTHING_G2 && in.mode != TDO_SMOOTHING_ARC && in.mode != TDO_SMOOTHING_NONE)
    return false;
  if (!isfinite(in.clearance) || in.clearance < 0.0) return false;
  if (!positive(in.k) || !positive(in.v_cruise) || !positive(in.v_max) || !positive(in.a_lat_max) ||
      !positive(in.j_max) || !positive(in.stop_angle))
    return false;
  if (!isfinite(in.min_radius) || in.min_radius < 0.0) return false;
  if (!(in.corner_time >= 0.0 && in.corner_time <= 1.0)) return false;
  // R_min and the jerk radius must stay finite.
  const double r_min = in.v_cruise * in.v_cruise / in.a_lat_max;
  if (!positive(r_min) || !positive(r_min * in.k)) return false;
  return true;
}

}  // namespace

extern "C" size_t tdo_smooth_footprint(const tdo_smooth_config* cfg) {
  if (cfg == nullptr || cfg->max_waypoints < 2u || cfg->max_segments == 0u) return 0;
  return tdo_arena_round(sizeof(tdo_smooth)) +
         tdo_arena_round(static_cast<size_t>(cfg->max_segments) * sizeof(tdo_path_segment)) +
         tdo_arena_round(static_cast<size_t>(cfg->max_waypoints) * sizeof(Corner));
}

extern "C" tdo_status tdo_smooth_init(tdo_smooth** out, tdo_arena* arena,
                                      const tdo_smooth_config* cfg) {
  if (out == nullptr || arena == nullptr || cfg == nullptr || cfg->max_waypoints < 2u ||
      cfg->max_segments == 0u)
    return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  if (arena->used > arena->size || arena->size - arena->used < tdo_smooth_footprint(cfg))
    return TDO_ERR_ARENA_TOO_SMALL;
  tdo_smooth* ctx = arena_context<tdo_smooth>(arena, *cfg);
  if (ctx == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  ctx->seg = arena_array<tdo_path_segment>(arena, cfg->max_segments);
  ctx->corner = arena_array<Corner>(arena, cfg->max_waypoints);
  if (ctx->seg == nullptr || ctx->corner == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  *out = ctx;
  return TDO_OK;
}

namespace {

// Step 1. Waypoints into c[0..n), consecutive duplicates merged (the exact goal is kept), with the
// direction and length of each line.
tdo_status load_waypoints(const tdo_smooth_input& in, Corner* c, uint32_t* n_out) {
  uint32_t n = 0;
  for (uint32_t i = 0; i < in.n_waypoints; ++i) {
    const tdo_vec3& p = in.waypoints[i];
    if (!finite3(p)) return TDO_ERR_INVALID_ARGUMENT;
    if (n > 0u && norm(sub(p, c[n - 1u].w)) <= kDuplicate) {
      if (i + 1u == in.n_waypoints && n >= 2u) c[n - 1u].w = p;
      continue;
    }
    memset(&c[n], 0, sizeof(Corner));
    c[n].w = p;
    ++n;
  }
  if (n < 2u) return TDO_ERR_INVALID_ARGUMENT;  // start == goal
  for (uint32_t i = 0; i + 1u < n; ++i) {
    const tdo_vec3 d = sub(c[i + 1u].w, c[i].w);
    c[i].len = norm(d);
    c[i].u = mul(d, 1.0 / c[i].len);
  }
  *n_out = n;
  return TDO_OK;
}

// Step 2. Kind, shape, wanted radius and tangent length of every interior corner.
void want_corners(const tdo_smooth_input& in, double r_min, Corner* c, uint32_t n) {
  const double v_c = dmin(in.v_cruise, in.v_max);
  for (uint32_t i = 1; i + 1u < n; ++i) {
    Corner& k = c[i];
    const tdo_vec3& u_in = c[i - 1u].u;
    const double theta = atan2(norm(cross(u_in, k.u)), dot(u_in, k.u));
    if (theta < kStraightAngle) {
      k.kind = kCornerStraight;
      continue;
    }
    if (in.mode == TDO_SMOOTHING_NONE || theta > in.stop_angle || theta > kPi - kNearPi) {
      k.kind = kCornerStop;
      continue;
    }
    k.kind = kCornerCurve;
    const double r8 = in.k * theta / (2.0 * sin(0.5 * theta)) * r_min;  // paper eq. 8
    if (in.mode == TDO_SMOOTHING_G2) {
      const double half_room = 0.5 * dmin(c[i - 1u].len, k.len);
      g2_choose(in, theta, r8, v_c, half_room, &k);
    } else {
      k.tau = tan(0.5 * theta);
      k.rate = 0.0;
      k.r_des = r8;
    }
    k.t_des = k.tau * k.r_des;
  }
}

// Step 3 for corner i: fit it into the room its neighbours leave, shrink it until its curve keeps
// the clearance (at most max_shrinks times, not below r_floor), else make it a stop point. Sets
// the corner's speed cap.
void fit_corner(const tdo_smooth_input& in, uint32_t max_shrinks, double r_floor, Corner* c,
                uint32_t i, uint32_t* checks) {
  Corner& k = c[i];
  const double l_in = c[i - 1u].len, l_out = k.len;
  const double room_in = dmax(0.5 * l_in, l_in - c[i - 1u].t_des);
  const double room_out = dmax(0.5 * l_out, l_out - c[i + 1u].t_des);
  const double room = dmin(room_in, room_out);
  const double margin = kMergeRel * dmax(1.0, dmax(l_in, l_out));
  double r = k.r_des;
  if (k.tau * r > room) {
    r = room / k.tau;
    k.shrunk = 1u;
  }
  int ok = 0;
  ClearState st{0, 0u, 0u};
  double r_fail = 0.0;  // m, the last radius that did not keep the clearance (0: none)
  for (uint32_t attempt = 0; attempt <= max_shrinks; ++attempt) {
    if (!(r >= r_floor)) break;
    k.r = r;
    k.t = dmin(k.tau * r, room);
    if (corner_clear(in, k, c[i - 1u], margin, checks, &st)) {
      ok = 1;
      break;
    }
    r_fail = r;
    r *= kShrink;
    k.shrunk = 1u;
  }
  // Time-oriented corners (corner_time > 0): a shrunk corner takes the largest radius between the
  // one that keeps the clearance and the one that did not, to kShrinkSteps halvings of the ratio
  // (a larger corner changes its curvature more slowly, so it is flown faster).
  if (ok && r_fail > 0.0 && in.corner_time > 0.0) {
    double lo = k.r, hi = r_fail;
    for (uint32_t step = 0; step < kShrinkSteps; ++step) {
      const double mid = sqrt(lo * hi);
      k.r = mid;
      k.t = dmin(k.tau * mid, room);
      if (corner_clear(in, k, c[i - 1u], margin, checks, &st))
        lo = mid;
      else
        hi = mid;
    }
    k.r = lo;
    k.t = dmin(k.tau * lo, room);
  }
  if (!ok) {
    k.kind = kCornerStop;
    k.r = 0.0;
    k.t = 0.0;
    k.shrunk = 0u;
    return;
  }
  double v = dmin(in.v_max, sqrt(in.a_lat_max * k.r));
  if (k.rate > 0.0) v = dmin(v, cbrt(in.j_max * k.r * k.r / k.rate));
  k.v = v;
}

// True when the line from corner a to corner b keeps more than kMergeRel (relative, >= 1 m) of
// its length between the two curves.
bool line_left(const Corner& a, const Corner& b) {
  const double gap = a.len - a.t - b.t;
  return gap > kMergeRel * dmax(1.0, a.len);
}

// Step 4. Cut points. A line left shorter than kMergeRel collapses to one point, preferring an
// exact waypoint (start, goal, stop) so those stay bit-exact.
void cut_points(Corner* c, uint32_t n) {
  for (uint32_t i = 0; i < n; ++i) {
    c[i].entry = c[i].w;
    c[i].exit = c[i].w;
    if (c[i].kind == kCornerCurve) {
      c[i].entry = sub(c[i].w, mul(c[i - 1u].u, c[i].t));
      c[i].exit = add(c[i].w, mul(c[i].u, c[i].t));
    }
  }
  for (uint32_t j = 0; j + 1u < n; ++j) {
    Corner& a = c[j];
    Corner& b = c[j + 1u];
    if (line_left(a, b)) continue;
    if (a.kind != kCornerCurve)
      b.entry = a.exit;
    else
      a.exit = b.entry;  // b.entry is b.w unless b is a curve; then either will do
  }
}

// Step 5. The segments in flight order into ctx->seg: per line what is left of it, then the
// corner curve at its end; counts corners, shrunk corners and stops into `out`.
tdo_status emit_segments(tdo_smooth* ctx, const tdo_smooth_input& in, const Corner* c, uint32_t n,
                         tdo_smooth_output* out) {
  tdo_path_segment* const seg = ctx->seg;
  const uint32_t cap = ctx->cfg.max_segments;
  uint32_t ns = 0;
  double total = 0.0;
  uint32_t n_corners = 0, n_shrunk = 0, n_stops = 0;
  for (uint32_t j = 0; j + 1u < n; ++j) {
    const Corner& a = c[j];
    const Corner& b = c[j + 1u];
    const bool stop_b = b.kind == kCornerStop;
    if (line_left(a, b)) {
      if (ns >= cap) return TDO_ERR_PATH_CAPACITY;
      tdo_path_segment s = blank_segment(TDO_SEGMENT_LINE);
      s.p[0] = a.exit;
      s.p[1] = b.entry;
      s.v_limit = in.v_max;
      s.stop_at_end = stop_b ? 1 : 0;
      s.length = tdo_segment_length(&s);
      seg[ns++] = s;
      total += s.length;
    } else if (stop_b && ns > 0u) {
      seg[ns - 1u].stop_at_end = 1;  // the previous corner curve runs right into the stop point
    }
    if (stop_b) ++n_stops;
    if (b.kind != kCornerCurve) continue;
    ++n_corners;
    if (b.shrunk) ++n_shrunk;
    tdo_path_segment cs[2];
    uint32_t m = 1u;
    if (in.mode == TDO_SMOOTHING_G2) {
      g2_corner(b.w, a.u, b.u, b.gf, b.hf, b.t, b.entry, b.exit, cs);
      m = 2u;
    } else {
      cs[0] = arc_corner(b.w, a.u, b.u, b.r, b.t, b.entry, b.exit);
    }
    for (uint32_t q = 0; q < m; ++q) {
      if (ns >= cap) return TDO_ERR_PATH_CAPACITY;
      cs[q].v_limit = b.v;
      cs[q].length = tdo_segment_length(&cs[q]);
      seg[ns++] = cs[q];
      total += cs[q].length;
    }
  }
  out->path.seg = seg;
  out->path.n = ns;
  out->path.length = total;
  out->n_corners = n_corners;
  out->n_shrunk = n_shrunk;
  out->n_stops = n_stops;
  return TDO_OK;
}

}  // namespace

extern "C" tdo_status tdo_smooth_run(tdo_smooth* ctx, const tdo_smooth_input* in_ptr,
                                     tdo_smooth_output* out) {
  if (ctx == nullptr || in_ptr == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  const tdo_smooth_input& in = *in_ptr;
  if (!valid_input(in)) return TDO_ERR_INVALID_ARGUMENT;
  if (in.n_waypoints > ctx->cfg.max_waypoints) return TDO_ERR_PATH_CAPACITY;
  Corner* const c = ctx->corner;
  uint32_t n = 0;
  const tdo_status loaded = load_waypoints(in, c, &n);
  if (loaded != TDO_OK) return loaded;

  const double r_min = in.v_cruise * in.v_cruise / in.a_lat_max;  // m, R_min
  const double r_floor =
      dmax(in.min_radius > 0.0 ? in.min_radius : kDefaultMinRadius * r_min, kAbsMinRadius);
  want_corners(in, r_min, c, n);

  uint32_t checks = 0;
  for (uint32_t i = 1; i + 1u < n; ++i)
    if (c[i].kind == kCornerCurve) fit_corner(in, ctx->cfg.max_shrinks, r_floor, c, i, &checks);

  cut_points(c, n);
  const tdo_status emitted = emit_segments(ctx, in, c, n, out);
  if (emitted != TDO_OK) return emitted;
  out->n_clear_checks = checks;
  return TDO_OK;
}
