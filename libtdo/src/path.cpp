// Evaluation of path segments by arclength (path.h): lines and arcs in closed form, cubic Beziers
// through an arclength -> t map built on the fly (adaptive Gauss-Legendre + safeguarded Newton).
// Pure functions: no state, no allocation, every loop bounded, deterministic.
#include "tdo/path.h"

#include <math.h>
#include <stdint.h>

#include "vec3.h"

using namespace tdo_internal;  // vec3.h

namespace {

constexpr tdo_vec3 kZero{0.0, 0.0, 0.0};

// 8-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree 15.
constexpr double kGlX[4] = {0.1834346424956498049394761, 0.5255324099163289858177390,
                            0.7966664774136267395915539, 0.9602898564975362316835609};
constexpr double kGlW[4] = {0.3626837833783619829651504, 0.3137066458778872873379622,
                            0.2223810344533744705443560, 0.1012285362903762591525314};

// Relative accuracy of the arclength quadrature per unit of t, scaled by the control polygon
// length (an upper bound of the curve length).
constexpr double kQuadRelTol = 1e-14;

/** Cubic Bezier with precomputed derivative coefficients. */
struct Bez {
  tdo_vec3 p[4];
  tdo_vec3 d[3];   // hodograph control points: B'(t) = 3 * sum Bernstein2_i(t) d[i]
  tdo_vec3 dd[2];  // second differences: B''(t) = 6 * ((1-t) dd[0] + t dd[1])
  tdo_vec3 ddd;    // B''' = 6 * ddd
  double poly;     // m, control polygon length
  double len;      // m, total arclength (filled by bez_setup)
};

inline tdo_vec3 bez_d1(const Bez& b, double t) {
  const double u = 1.0 - t;
  const tdo_vec3 h = add(add(mul(b.d[0], u * u), mul(b.d[1], 2.0 * u * t)), mul(b.d[2], t * t));
  return mul(h, 3.0);
}
inline tdo_vec3 bez_d2(const Bez& b, double t) {
  return mul(add(mul(b.dd[0], 1.0 - t), mul(b.dd[1], t)), 6.0);
}
inline tdo_vec3 bez_d3(const Bez& b) { return mul(b.ddd, 6.0); }
inline double bez_speed(const Bez& b, double t) { return norm(bez_d1(b, t)); }

inline tdo_vec3 bez_point(const Bez& b, double t) {
  if (t <= 0.0) return b.p[0];
  if (t >= 1.0) return b.p[3];
  // de Casteljau: numerically stable, exact at the ends.
  const tdo_vec3 a0 = lerp(b.p[0], b.p[1], t);
  const tdo_vec3 a1 = lerp(b.p[1], b.p[2], t);
  const tdo_vec3 a2 = lerp(b.p[2], b.p[3], t);
  const tdo_vec3 b0 = lerp(a0, a1, t);
  const tdo_vec3 b1 = lerp(a1, a2, t);
  return lerp(b0, b1, t);
}

/** 8-point Gauss-Legendre of |B'| over [a, b]. */
double gl8(const Bez& bz, double a, double b) {
  const double h = 0.5 * (b - a);
  const double m = 0.5 * (a + b);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double dx = h * kGlX[i];
    sum += kGlW[i] * (bez_speed(bz, m - dx) + bez_speed(bz, m + dx));
  }
  return sum * h;
}

/**
 * Arclength between parameters a <= b: adaptive halving with the 8-point rule, at most
 * TDO_PATH_MAX_QUAD_DEPTH levels. Depth-first with an explicit stack (right half pushed first),
 * so the panels are summed left to right in a fixed order.
 */
double arclen_fwd(const Bez& bz, double a, double b) {
  if (!(b > a)) return 0.0;
  struct Panel {
    double a, b, whole;
    uint32_t depth;
  };
  Panel stack[TDO_PATH_MAX_QUAD_DEPTH + 2u];
  uint32_t top = 0;
  stack[top++] = Panel{a, b, gl8(bz, a, b), 0u};
  double total = 0.0;
  const double tol_per_t = kQuadRelTol * (bz.poly > 0.0 ? bz.poly : 0.0);
  // Each panel is either accepted or split; splits stop at the depth bound, so at most
  // 2^(depth+1) panels are visited. The loop bound below is that count.
  const uint32_t max_visits = 2u << TDO_PATH_MAX_QUAD_DEPTH;
  for (uint32_t visit = 0; visit < max_visits && top > 0; ++visit) {
    const Panel p = stack[--top];
    const double m = 0.5 * (p.a + p.b);
    const double left = gl8(bz, p.a, m);
    const double right = gl8(bz, m, p.b);
    const double halves = left + right;
    if (p.depth >= TDO_PATH_MAX_QUAD_DEPTH || fabs(halves - p.whole) <= tol_per_t * (p.b - p.a) ||
        top + 2u > TDO_PATH_MAX_QUAD_DEPTH + 2u) {
      total += halves;
      continue;
    }
    stack[top++] = Panel{m, p.b, right, p.depth + 1u};
    stack[top++] = Panel{p.a, m, left, p.depth + 1u};
  }
  return total;
}

/** Signed arclength from parameter a to b. */
double arclen(const Bez& bz, double a, double b) {
  return b >= a ? arclen_fwd(bz, a, b) : -arclen_fwd(bz, b, a);
}

Bez bez_setup(const tdo_path_segment& seg) {
  Bez b;
  for (int i = 0; i < 4; ++i) b.p[i] = seg.p[i];
  for (int i = 0; i < 3; ++i) b.d[i] = sub(b.p[i + 1], b.p[i]);
  b.dd[0] = sub(b.d[1], b.d[0]);
  b.dd[1] = sub(b.d[2], b.d[1]);
  b.ddd = sub(b.dd[1], b.dd[0]);
  b.poly = norm(b.d[0]) + norm(b.d[1]) + norm(b.d[2]);
  b.len = 0.0;
  return b;
}

/**
 * Parameter t with arclength(0, t) = s, for 0 < s < total. Newton on L(t) - s with a bisection
 * bracket [lo, hi]; each step integrates only the short stretch between the old and new t.
 */
double bez_invert(const Bez& bz, double s, double total) {
  double lo = 0.0, hi = 1.0;
  double t = s / total;
  double lt = arclen(bz, 0.0, t);  // arclength at t
  const double tol = 1e-13 * (total > 1.0 ? total : 1.0);
  for (uint32_t it = 0; it < TDO_PATH_MAX_INVERSION_STEPS; ++it) {
    const double f = lt - s;
    if (fabs(f) <= tol) break;
    if (f > 0.0)
      hi = t;
    else
      lo = t;
    const double sp = bez_speed(bz, t);
    double tn = sp > 0.0 ? t - f / sp : 0.5 * (lo + hi);
    if (tn > lo && tn < hi) {
      // Newton step: the arclength at tn misses s by g''/2 * dt^2 with |g''| = |d|B'|/dt| <=
      // max |B''| over the step. When that is far below tol, take tn without integrating again.
      const double dt = tn - t;
      const double b2 = norm(bez_d2(bz, t)) + norm(bez_d3(bz)) * fabs(dt);
      if (0.5 * b2 * dt * dt <= 0.1 * tol) {
        t = tn;
        break;
      }
    } else {
      tn = 0.5 * (lo + hi);
      if (!(tn > lo && tn < hi)) break;  // bracket collapsed to adjacent doubles
    }
    lt += arclen(bz, t, tn);
    t = tn;
  }
  return t;
}

/** Arc frame: centre c, radius r, unit u (to the start), unit w (in-plane, towards the end). */
struct Arc {
  tdo_vec3 c, u, w;
  double r, sweep;  // m, rad
  int ok;           // 0: degenerate (zero radius or sweep), evaluated as a line
};

Arc arc_setup(const tdo_path_segment& seg) {
  Arc a;
  a.c = seg.p[2];
  const tdo_vec3 r0 = sub(seg.p[0], a.c);
  const tdo_vec3 r1 = sub(seg.p[1], a.c);
  a.r = norm(r0);
  a.ok = 0;
  a.u = kZero;
  a.w = kZero;
  a.sweep = 0.0;
  const double r1n = norm(r1);
  if (!(a.r > 0.0) || !(r1n > 0.0)) return a;
  a.u = mul(r0, 1.0 / a.r);
  const tdo_vec3 v = mul(r1, 1.0 / r1n);
  const tdo_vec3 wr = sub(v, mul(a.u, dot(v, a.u)));
  const double wn = norm(wr);
  a.sweep = atan2(norm(cross(a.u, v)), dot(a.u, v));
  if (!(wn > 1e-300) || !(a.sweep > 0.0)) return a;
  a.w = mul(wr, 1.0 / wn);
  a.ok = 1;
  return a;
}

inline double clamp_s(const tdo_path_segment* seg, double s) {
  const double len = seg->length > 0.0 ? seg->length : 0.0;
  if (!(s > 0.0)) return 0.0;  // also maps NaN to 0
  return s < len ? s : len;
}

/** Evaluates everything; `s` already clamped. */
int eval(const tdo_path_segment* seg, double s, tdo_segment_state* out) {
  out->kn = tdo_vec3{0.0, 0.0, 0.0};
  out->kappa = 0.0;
  out->dkappa_ds = 0.0;
  out->t = tdo_vec3{0.0, 0.0, 0.0};
  const double len = seg->length > 0.0 ? seg->length : 0.0;
  switch (seg->kind) {
    case TDO_SEGMENT_LINE: {
      const tdo_vec3 a = seg->p[0];
      const tdo_vec3 b = seg->p[1];
      const tdo_vec3 d = sub(b, a);
      const double n = norm(d);
      if (s >= len)
        out->p = seg->p[1];
      else if (s <= 0.0 || !(n > 0.0))
        out->p = seg->p[0];
      else
        out->p = add(a, mul(d, s / n));
      if (!(n > 0.0)) return 0;
      out->t = mul(d, 1.0 / n);
      return 1;
    }
    case TDO_SEGMENT_ARC: {
      const Arc a = arc_setup(*seg);
      if (!a.ok) {
        out->p = s >= len ? seg->p[1] : seg->p[0];
        return 0;
      }
      const double ang = s / a.r;
      const double ca = cos(ang), sa = sin(ang);
      const tdo_vec3 radial = add(mul(a.u, ca), mul(a.w, sa));  // unit, centre -> point
      if (s >= len)
        out->p = seg->p[1];
      else if (s <= 0.0)
        out->p = seg->p[0];
      else
        out->p = add(a.c, mul(radial, a.r));
      out->t = sub(mul(a.w, ca), mul(a.u, sa));
      out->kappa = 1.0 / a.r;
      out->kn = mul(radial, -1.0 / a.r);
      return 1;
    }
    case TDO_SEGMENT_BEZIER: {
      const Bez bz = bez_setup(*seg);
      double t;
      if (s <= 0.0)
        t = 0.0;
      else if (s >= len)
        t = 1.0;
      else
        t = bez_invert(bz, s, len);
      out->p = bez_point(bz, t);
      const tdo_vec3 d1 = bez_d1(bz, t);
      const tdo_vec3 d2 = bez_d2(bz, t);
      const double sp = norm(d1);
      if (!(sp > 0.0)) return 0;
      const tdo_vec3 tan = mul(d1, 1.0 / sp);
      out->t = tan;
      // dT/ds = (B'' - (B''.T) T) / |B'|^2
      const tdo_vec3 perp = sub(d2, mul(tan, dot(d2, tan)));
      const double sp2 = sp * sp;
      out->kn = mul(perp, 1.0 / sp2);
      const tdo_vec3 c = cross(d1, d2);
      const double cn = norm(c);
      const double sp3 = sp2 * sp;
      out->kappa = cn / sp3;
      // kappa = |c| / |B'|^3 with c = B' x B'', c' = B' x B''' (B'' x B'' = 0).
      const tdo_vec3 cp = cross(d1, bez_d3(bz));
      double dcn;  // d|c|/dt
      if (cn > 1e-12 * (norm(cp) + sp3 / (len > 0.0 ? len : 1.0)))
        dcn = dot(c, cp) / cn;
      else
        dcn = t < 0.5 ? norm(cp) : -norm(cp);  // one-sided limit where kappa = 0
      const double dk_dt = dcn / sp3 - 3.0 * cn * dot(d1, d2) / (sp3 * sp2);
      out->dkappa_ds = dk_dt / sp;
      return 1;
    }
  }
  out->p = seg->p[0];
  return 0;
}

}  // namespace

extern "C" double tdo_segment_length(const tdo_path_segment* seg) {
  if (seg == nullptr) return 0.0;
  switch (seg->kind) {
    case TDO_SEGMENT_LINE:
      if (!finite3(seg->p[0]) || !finite3(seg->p[1])) return 0.0;
      return norm(sub(seg->p[1], seg->p[0]));
    case TDO_SEGMENT_ARC: {
      if (!finite3(seg->p[0]) || !finite3(seg->p[1]) || !finite3(seg->p[2])) return 0.0;
      const Arc a = arc_setup(*seg);
      return a.ok ? a.r * a.sweep : norm(sub(seg->p[1], seg->p[0]));
    }
    case TDO_SEGMENT_BEZIER: {
      for (int i = 0; i < 4; ++i)
        if (!finite3(seg->p[i])) return 0.0;
      const Bez bz = bez_setup(*seg);
      return arclen_fwd(bz, 0.0, 1.0);
    }
  }
  return 0.0;
}

extern "C" int tdo_segment_eval(const tdo_path_segment* seg, double s, tdo_segment_state* out) {
  if (seg == nullptr || out == nullptr) return 0;
  return eval(seg, clamp_s(seg, s), out);
}

extern "C" tdo_vec3 tdo_segment_point(const tdo_path_segment* seg, double s) {
  if (seg == nullptr) return tdo_vec3{0.0, 0.0, 0.0};
  s = clamp_s(seg, s);
  if (seg->kind == TDO_SEGMENT_BEZIER) {
    // Position only: skip the derivative work of eval.
    const double len = seg->length;
    if (s <= 0.0) return seg->p[0];
    if (s >= len) return seg->p[3];
    const Bez bz = bez_setup(*seg);
    return bez_point(bz, bez_invert(bz, s, len));
  }
  tdo_segment_state st;
  eval(seg, s, &st);
  return st.p;
}

extern "C" double tdo_segment_curvature(const tdo_path_segment* seg, double s) {
  if (seg == nullptr) return 0.0;
  tdo_segment_state st;
  eval(seg, clamp_s(seg, s), &st);
  return st.kappa;
}

extern "C" tdo_vec3 tdo_segment_tangent(const tdo_path_segment* seg, double s) {
  if (seg == nullptr) return tdo_vec3{0.0, 0.0, 0.0};
  tdo_segment_state st;
  eval(seg, clamp_s(seg, s), &st);
  return st.t;
}

extern "C" double tdo_segment_param(const tdo_path_segment* seg, double s) {
  if (seg == nullptr) return 0.0;
  s = clamp_s(seg, s);
  const double len = seg->length;
  if (s <= 0.0) return 0.0;
  if (s >= len) return 1.0;
  if (seg->kind != TDO_SEGMENT_BEZIER) return s / len;
  const Bez bz = bez_setup(*seg);
  return bez_invert(bz, s, len);
}

extern "C" uint32_t tdo_path_locate(const tdo_path* path, double s, double* local_s) {
  if (path == nullptr || path->seg == nullptr || path->n == 0u) return UINT32_MAX;
  if (!(s > 0.0)) s = 0.0;
  double acc = 0.0;
  for (uint32_t i = 0; i < path->n; ++i) {
    const double len = path->seg[i].length > 0.0 ? path->seg[i].length : 0.0;
    if (s < acc + len || i + 1u == path->n) {
      if (local_s != nullptr) {
        const double ls = s - acc;
        *local_s = ls < 0.0 ? 0.0 : (ls > len ? len : ls);
      }
      return i;
    }
    acc += len;
  }
  return path->n - 1u;  // not reached
}
