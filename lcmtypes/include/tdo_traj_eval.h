/*
 * tdo_traj_eval.h: sample a compact trajectory (tdo trajectory_t, its segment_* and piece_*
 * fields) at any time: position, velocity, acceleration and jerk.
 *
 * Header only, C99 (also compiles as C++), no allocation, no I/O, every loop bounded. It needs
 * <math.h> (link with -lm in C).
 *
 * The trajectory is a geometric path of segments parameterised by arclength s, and a speed profile
 * s(t) of constant-jerk pieces. Segment i (kind segment_kind[i], arclength segment_length[i] m,
 * starting at path arclength segment_s0[i] m) has 4 control points x y z in
 * segment_points[12 i .. 12 i + 11] (m, world frame):
 *   SEGMENT_LINE   (0): p0 -> p1 (p2, p3 zero);
 *   SEGMENT_BEZIER (1): cubic Bezier p0..p3, parameterised by arclength;
 *   SEGMENT_ARC    (2): circular arc p0 -> p1 about the centre p2 (sweep < pi).
 * Piece k covers t in [piece_t0[k], piece_t0[k] + piece_dur[k]) s with
 *   s(t) = piece_s0[k] + piece_v0[k] tau + piece_a0[k] tau^2 / 2 + piece_j[k] tau^3 / 6,
 *   tau = t - piece_t0[k].
 * The number of pieces per segment varies; nothing here assumes one.
 * From t = duration on, the vehicle is at the goal (the end of the path) at rest; before t = 0 at
 * the start at rest. At t = i * dt the result is the library's sample i (libtdo trajectory.h) to
 * about 1e-12 m; the library's samples take the same steps (test apps.TrajEval*).
 *
 * Usage (C, generated tdo_trajectory_t *m):
 *   tdo_traj_view v = {m->n_segments, m->segment_kind, m->segment_s0, m->segment_length,
 *                      m->segment_points, m->n_pieces, m->piece_t0, m->piece_dur, m->piece_s0,
 *                      m->piece_v0, m->piece_a0, m->piece_j, m->duration_s, m->path_length_m};
 *   if (tdo_traj_check(&v) == TDO_TRAJ_EVAL_OK) tdo_traj_eval(&v, t, &state);
 * C++ (tdo::trajectory_t m): the same with m.segment_kind.data(), ...
 */
#ifndef TDO_TRAJ_EVAL_H
#define TDO_TRAJ_EVAL_H

#include <math.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Pointers into a decoded message (arrays of n_segments, 12 n_segments or n_pieces values). */
typedef struct tdo_traj_view {
  int32_t n_segments;
  const int8_t* segment_kind;
  const double* segment_s0;     /* m */
  const double* segment_length; /* m */
  const double* segment_points; /* m, 12 per segment */
  int32_t n_pieces;
  const double* piece_t0;  /* s */
  const double* piece_dur; /* s */
  const double* piece_s0;  /* m */
  const double* piece_v0;  /* m/s */
  const double* piece_a0;  /* m/s^2 */
  const double* piece_j;   /* m/s^3 */
  double duration;         /* s, at the goal at rest from then on */
  double length;           /* m, path arclength (the end of the last segment) */
} tdo_traj_view;

/** State at one time. */
typedef struct tdo_traj_state {
  double t;    /* s */
  double p[3]; /* m */
  double v[3]; /* m/s */
  double a[3]; /* m/s^2 */
  double j[3]; /* m/s^3 */
  double s;    /* m, path arclength */
  int32_t segment; /* segment index */
  int32_t piece;   /* piece index */
} tdo_traj_state;

/** Result of tdo_traj_check. */
typedef enum tdo_traj_eval_status {
  TDO_TRAJ_EVAL_OK = 0,
  TDO_TRAJ_EVAL_EMPTY = 1,       /* no segment, no piece or a null array */
  TDO_TRAJ_EVAL_NON_FINITE = 2,  /* a NaN or infinity */
  TDO_TRAJ_EVAL_BAD_KIND = 3,    /* a segment kind other than 0, 1, 2 */
  TDO_TRAJ_EVAL_BAD_ORDER = 4,   /* lengths < 0, duration < 0, piece durations <= 0, knots or
                                    segment starts decreasing */
  TDO_TRAJ_EVAL_NO_LENGTH = 5    /* no segment of positive length */
} tdo_traj_eval_status;

/* Work bounds. */
#define TDO_TRAJ_EVAL_NEWTON_STEPS 60 /* arclength inversion steps on a Bezier */
#define TDO_TRAJ_EVAL_MAX_PANELS 64   /* Gauss-Legendre panels per arclength integral */

/* ---- small vector helpers -------------------------------------------------------------------*/
static inline double tdo_te_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline double tdo_te_norm(const double a[3]) { return sqrt(tdo_te_dot(a, a)); }

/** @return TDO_TRAJ_EVAL_OK when `v` can be evaluated (call once per message). */
static inline tdo_traj_eval_status tdo_traj_check(const tdo_traj_view* v) {
  int32_t i, positive = 0;
  if (v == 0 || v->n_segments <= 0 || v->n_pieces <= 0 || v->segment_kind == 0 ||
      v->segment_s0 == 0 || v->segment_length == 0 || v->segment_points == 0 ||
      v->piece_t0 == 0 || v->piece_dur == 0 || v->piece_s0 == 0 || v->piece_v0 == 0 ||
      v->piece_a0 == 0 || v->piece_j == 0)
    return TDO_TRAJ_EVAL_EMPTY;
  if (!isfinite(v->duration) || !isfinite(v->length)) return TDO_TRAJ_EVAL_NON_FINITE;
  if (!(v->duration >= 0.0) || !(v->length >= 0.0)) return TDO_TRAJ_EVAL_BAD_ORDER;
  for (i = 0; i < v->n_segments; ++i) {
    int k;
    const int8_t kind = v->segment_kind[i];
    if (kind < 0 || kind > 2) return TDO_TRAJ_EVAL_BAD_KIND;
    if (!isfinite(v->segment_s0[i]) || !isfinite(v->segment_length[i]))
      return TDO_TRAJ_EVAL_NON_FINITE;
    for (k = 0; k < 12; ++k)
      if (!isfinite(v->segment_points[12 * i + k])) return TDO_TRAJ_EVAL_NON_FINITE;
    if (!(v->segment_length[i] >= 0.0)) return TDO_TRAJ_EVAL_BAD_ORDER;
    if (i > 0 && v->segment_s0[i] < v->segment_s0[i - 1]) return TDO_TRAJ_EVAL_BAD_ORDER;
    if (v->segment_length[i] > 0.0) ++positive;
  }
  if (positive == 0) return TDO_TRAJ_EVAL_NO_LENGTH;
  for (i = 0; i < v->n_pieces; ++i) {
    if (!isfinite(v->piece_t0[i]) || !isfinite(v->piece_dur[i]) || !isfinite(v->piece_s0[i]) ||
        !isfinite(v->piece_v0[i]) || !isfinite(v->piece_a0[i]) || !isfinite(v->piece_j[i]))
      return TDO_TRAJ_EVAL_NON_FINITE;
    if (!(v->piece_dur[i] > 0.0)) return TDO_TRAJ_EVAL_BAD_ORDER;
    if (i > 0 && !(v->piece_t0[i] >= v->piece_t0[i - 1])) return TDO_TRAJ_EVAL_BAD_ORDER;
  }
  return TDO_TRAJ_EVAL_OK;
}

/** Geometry of a segment at local arclength s: point, unit tangent T, dT/ds and d2T/ds2. */
typedef struct tdo_te_geom {
  double p[3], t[3], kn[3], dkn[3];
} tdo_te_geom;

static inline void tdo_te_zero(double a[3]) { a[0] = a[1] = a[2] = 0.0; }

static inline void tdo_te_line(const double* q, double len, double s, tdo_te_geom* g) {
  double d[3];
  int k;
  for (k = 0; k < 3; ++k) d[k] = q[3 + k] - q[k];
  {
    const double n = tdo_te_norm(d);
    for (k = 0; k < 3; ++k) {
      if (s >= len)
        g->p[k] = q[3 + k];
      else if (s <= 0.0 || !(n > 0.0))
        g->p[k] = q[k];
      else
        g->p[k] = q[k] + d[k] * (s / n);
      g->t[k] = n > 0.0 ? d[k] * (1.0 / n) : 0.0;
    }
  }
  tdo_te_zero(g->kn);
  tdo_te_zero(g->dkn);
}

static inline void tdo_te_arc(const double* q, double len, double s, tdo_te_geom* g) {
  double r0[3], r1[3], u[3], w[3], vv[3], c[3];
  double r, r1n, wn, cs, sweep, ang, ca, sa;
  int k;
  for (k = 0; k < 3; ++k) {
    r0[k] = q[k] - q[6 + k];
    r1[k] = q[3 + k] - q[6 + k];
  }
  r = tdo_te_norm(r0);
  r1n = tdo_te_norm(r1);
  tdo_te_zero(g->kn);
  tdo_te_zero(g->dkn);
  tdo_te_zero(g->t);
  if (!(r > 0.0) || !(r1n > 0.0)) { /* degenerate: evaluated as the end points */
    for (k = 0; k < 3; ++k) g->p[k] = s >= len ? q[3 + k] : q[k];
    return;
  }
  for (k = 0; k < 3; ++k) {
    u[k] = r0[k] * (1.0 / r);
    vv[k] = r1[k] * (1.0 / r1n);
  }
  cs = tdo_te_dot(vv, u);
  for (k = 0; k < 3; ++k) w[k] = vv[k] - u[k] * cs;
  wn = tdo_te_norm(w);
  c[0] = u[1] * vv[2] - u[2] * vv[1];
  c[1] = u[2] * vv[0] - u[0] * vv[2];
  c[2] = u[0] * vv[1] - u[1] * vv[0];
  sweep = atan2(tdo_te_norm(c), cs);
  if (!(wn > 1e-300) || !(sweep > 0.0)) {
    for (k = 0; k < 3; ++k) g->p[k] = s >= len ? q[3 + k] : q[k];
    return;
  }
  ang = s / r;
  ca = cos(ang);
  sa = sin(ang);
  for (k = 0; k < 3; ++k) {
    const double wk = w[k] * (1.0 / wn);
    const double radial = u[k] * ca + wk * sa;
    if (s >= len)
      g->p[k] = q[3 + k];
    else if (s <= 0.0)
      g->p[k] = q[k];
    else
      g->p[k] = q[6 + k] + radial * r;
    g->t[k] = wk * ca - u[k] * sa;
    g->kn[k] = radial * (-1.0 / r);
    g->dkn[k] = -g->t[k] / (r * r);
  }
}

/* Bezier: B'(u) = h0 + u (h1 + u h2); B'' = h1 + 2 u h2; B''' = 2 h2. */
static inline void tdo_te_bez_d(const double h[3][3], double u, double d1[3], double d2[3]) {
  int k;
  for (k = 0; k < 3; ++k) {
    d1[k] = h[0][k] + u * (h[1][k] + u * h[2][k]);
    d2[k] = h[1][k] + 2.0 * u * h[2][k];
  }
}

static inline double tdo_te_bez_speed(const double h[3][3], double u) {
  double d1[3], d2[3];
  tdo_te_bez_d(h, u, d1, d2);
  return tdo_te_norm(d1);
}

/** m, signed arclength between parameters a and b: 8-point Gauss-Legendre on panels <= 1/64. */
static inline double tdo_te_bez_arclen(const double h[3][3], double a, double b) {
  static const double x[4] = {0.1834346424956498049394761, 0.5255324099163289858177390,
                              0.7966664774136267395915539, 0.9602898564975362316835609};
  static const double wt[4] = {0.3626837833783619829651504, 0.3137066458778872873379622,
                               0.2223810344533744705443560, 0.1012285362903762591525314};
  const double span = b - a;
  int panels = (int)ceil(fabs(span) * TDO_TRAJ_EVAL_MAX_PANELS), p, i;
  double hw, total = 0.0;
  if (panels < 1) panels = 1;
  if (panels > TDO_TRAJ_EVAL_MAX_PANELS) panels = TDO_TRAJ_EVAL_MAX_PANELS;
  hw = span / panels;
  for (p = 0; p < panels; ++p) {
    const double m = a + hw * (p + 0.5);
    double sum = 0.0;
    for (i = 0; i < 4; ++i) {
      const double dx = 0.5 * hw * x[i];
      sum += wt[i] * (tdo_te_bez_speed(h, m - dx) + tdo_te_bez_speed(h, m + dx));
    }
    total += 0.5 * hw * sum;
  }
  return total;
}

/** Bezier parameter at arclength s in (0, len): Newton on the arclength, bisection safeguard. */
static inline double tdo_te_bez_param(const double h[3][3], double s, double len) {
  double lo = 0.0, hi = 1.0, u = s / len, at;
  const double tol = 1e-13 * (len > 1.0 ? len : 1.0);
  int it;
  at = tdo_te_bez_arclen(h, 0.0, u);
  for (it = 0; it < TDO_TRAJ_EVAL_NEWTON_STEPS; ++it) {
    const double f = at - s;
    double sp, un;
    if (fabs(f) <= tol) break;
    if (f > 0.0)
      hi = u;
    else
      lo = u;
    sp = tdo_te_bez_speed(h, u);
    un = sp > 0.0 ? u - f / sp : 0.5 * (lo + hi);
    if (!(un > lo && un < hi)) un = 0.5 * (lo + hi);
    if (!(un > lo && un < hi)) break; /* bracket down to adjacent doubles */
    at += tdo_te_bez_arclen(h, u, un);
    u = un;
  }
  return u;
}

static inline void tdo_te_bezier(const double* q, double len, double s, tdo_te_geom* g) {
  double h[3][3], d1[3], d2[3], d3[3], tn[3], dtn[3];
  double u, sp, td2, td3, dtd2;
  int k;
  for (k = 0; k < 3; ++k) {
    const double e0 = q[3 + k] - q[k], e1 = q[6 + k] - q[3 + k], e2 = q[9 + k] - q[6 + k];
    h[0][k] = 3.0 * e0;
    h[1][k] = 6.0 * (e1 - e0);
    h[2][k] = 3.0 * (e0 - 2.0 * e1 + e2);
  }
  if (s <= 0.0)
    u = 0.0;
  else if (s >= len)
    u = 1.0;
  else
    u = tdo_te_bez_param(h, s, len);
  for (k = 0; k < 3; ++k) { /* de Casteljau, exact at the ends */
    const double a0 = q[k] + (q[3 + k] - q[k]) * u, a1 = q[3 + k] + (q[6 + k] - q[3 + k]) * u;
    const double a2 = q[6 + k] + (q[9 + k] - q[6 + k]) * u;
    const double b0 = a0 + (a1 - a0) * u, b1 = a1 + (a2 - a1) * u;
    g->p[k] = u <= 0.0 ? q[k] : (u >= 1.0 ? q[9 + k] : b0 + (b1 - b0) * u);
  }
  tdo_te_bez_d(h, u, d1, d2);
  for (k = 0; k < 3; ++k) d3[k] = 2.0 * h[2][k];
  sp = tdo_te_norm(d1);
  if (!(sp > 0.0)) {
    tdo_te_zero(g->t);
    tdo_te_zero(g->kn);
    tdo_te_zero(g->dkn);
    return;
  }
  for (k = 0; k < 3; ++k) tn[k] = d1[k] / sp;
  td2 = tdo_te_dot(tn, d2);
  for (k = 0; k < 3; ++k) dtn[k] = (d2[k] - tn[k] * td2) / sp; /* dT/du */
  td3 = tdo_te_dot(tn, d3);
  dtd2 = tdo_te_dot(dtn, d2) + td3; /* d(T.B'')/du */
  for (k = 0; k < 3; ++k) {
    const double perp = d2[k] - tn[k] * td2;
    const double dperp = d3[k] - dtn[k] * td2 - tn[k] * dtd2; /* d(perp)/du */
    g->t[k] = tn[k];
    g->kn[k] = perp / (sp * sp);                                   /* dT/ds */
    g->dkn[k] = (dperp / (sp * sp) - 2.0 * perp * td2 / (sp * sp * sp)) / sp; /* d(dT/ds)/ds */
  }
}

/** Index of the last element of a[0..n) that is <= x (0 when none); binary search. */
static inline int32_t tdo_te_find(const double* a, int32_t n, double x) {
  int32_t lo = 0, hi = n - 1;
  while (lo < hi) { /* at most 32 steps */
    const int32_t mid = lo + (hi - lo + 1) / 2;
    if (a[mid] <= x)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

/**
 * @brief State at time t (s; clamped to [0, duration]). `v` must have passed tdo_traj_check.
 *        Bounded work: two binary searches and, on a Bezier, at most TDO_TRAJ_EVAL_NEWTON_STEPS
 *        Newton steps of at most TDO_TRAJ_EVAL_MAX_PANELS quadrature panels.
 */
static inline void tdo_traj_eval(const tdo_traj_view* v, double t, tdo_traj_state* out) {
  const int end = !(t < v->duration);
  int32_t k = 0, i, seg;
  double tau, s, sd, sdd, sddd, local, len;
  const double* q;
  tdo_te_geom g;
  if (!(t > 0.0)) t = 0.0;
  if (end) t = v->duration;
  k = tdo_te_find(v->piece_t0, v->n_pieces, t);
  tau = t - v->piece_t0[k];
  if (tau < 0.0) tau = 0.0;
  if (tau > v->piece_dur[k]) tau = v->piece_dur[k];
  s = v->piece_s0[k] + tau * (v->piece_v0[k] + tau * (0.5 * v->piece_a0[k] + tau * v->piece_j[k] / 6.0));
  sd = v->piece_v0[k] + tau * (v->piece_a0[k] + 0.5 * tau * v->piece_j[k]);
  sdd = v->piece_a0[k] + tau * v->piece_j[k];
  sddd = v->piece_j[k];
  if (end) {
    s = v->length;
    sd = sdd = sddd = 0.0;
  }
  if (sd < 0.0) sd = 0.0; /* rounding at the end of a deceleration */
  /* The segment: the last one of positive length starting at or before s. */
  seg = tdo_te_find(v->segment_s0, v->n_segments, s);
  while (seg > 0 && !(v->segment_length[seg] > 0.0)) --seg;
  while (!(v->segment_length[seg] > 0.0) && seg + 1 < v->n_segments) ++seg;
  if (end) { /* the last segment of positive length, at its end */
    seg = v->n_segments - 1;
    while (seg > 0 && !(v->segment_length[seg] > 0.0)) --seg;
  }
  len = v->segment_length[seg];
  local = s - v->segment_s0[seg];
  if (local < 0.0) local = 0.0;
  if (local > len || end) local = len;
  q = v->segment_points + 12 * seg;
  if (v->segment_kind[seg] == 1)
    tdo_te_bezier(q, len, local, &g);
  else if (v->segment_kind[seg] == 2)
    tdo_te_arc(q, len, local, &g);
  else
    tdo_te_line(q, len, local, &g);
  out->t = t;
  out->s = s;
  out->segment = seg;
  out->piece = k;
  for (i = 0; i < 3; ++i) {
    out->p[i] = g.p[i];
    out->v[i] = g.t[i] * sd;
    out->a[i] = g.t[i] * sdd + g.kn[i] * (sd * sd);
    out->j[i] = g.t[i] * sddd + 3.0 * g.kn[i] * sd * sdd + g.dkn[i] * (sd * sd * sd);
  }
}

#ifdef __cplusplus
}
#endif

#endif /* TDO_TRAJ_EVAL_H */
