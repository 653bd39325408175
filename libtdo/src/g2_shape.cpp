// The G2 corner shape (g2_shape.h): sampled and refined maxima of the unit corner's curvature and
// curvature rate, and the rate's lower bound from interval bounds of the curvature.
#include "g2_shape.h"

#include <math.h>

#include "scalar.h"

namespace tdo_internal {
namespace {

constexpr int kRateSamples = 32;  // t samples of the curvature-rate maximum search
constexpr int kRateGolden = 40;   // golden-section steps refining it (bracket 1/16 -> 1e-10)
constexpr double kRateMargin = 1.0 + 1e-6;      // safety factor on the found maximum
constexpr int kBoundPieces = 16;                // t intervals of the curvature bound
constexpr int kBoundSampleStep = 4;             // every 4th rate sample for the rate's lower bound
constexpr int kQuickPieces = 2;                 // the same for the quick bound: 2 intervals and the
constexpr int kQuickSampleStep = kRateSamples;  // rate samples at t = 0 and 1 only

/**
 * The first Bezier of the unit-radius G2 corner in the plane (u_in = x axis, turning left by
 * theta): control points on the x axis and at the junction, held as the differences its
 * derivatives are made of (the same operations, computed once per curve instead of once per t).
 */
struct PlanarBez {
  double a[2], b[2], e[2];  // c1 - c0, c2 - c1, c3 - c2
  double s[2], w[2];        // c2 - 2 c1 + c0, c3 - 2 c2 + c1
  double d3[2];             // third derivative
};

PlanarBez planar_bez(const double px[4], const double py[4]) {
  PlanarBez z;
  const double* p[2] = {px, py};
  for (int i = 0; i < 2; ++i) {
    const double* c = p[i];
    z.a[i] = c[1] - c[0];
    z.b[i] = c[2] - c[1];
    z.e[i] = c[3] - c[2];
    z.s[i] = c[2] - 2.0 * c[1] + c[0];
    z.w[i] = c[3] - 2.0 * c[2] + c[1];
    z.d3[i] = 6.0 * (c[3] - 3.0 * c[2] + 3.0 * c[1] - c[0]);
  }
  return z;
}

/** First and second derivative of a PlanarBez at parameter t. */
struct PlanarDeriv {
  double d1[2], d2[2];
};

inline PlanarDeriv planar_deriv(const PlanarBez& z, double t) {
  const double u = 1.0 - t;
  const double uu = u * u, ut2 = 2.0 * u * t, tt = t * t;
  PlanarDeriv d;
  for (int i = 0; i < 2; ++i) {
    d.d1[i] = 3.0 * (uu * z.a[i] + ut2 * z.b[i] + tt * z.e[i]);
    d.d2[i] = 6.0 * (u * z.s[i] + t * z.w[i]);
  }
  return d;
}

/** |dkappa/ds| of the curve with derivatives d (third derivative z.d3). */
inline double g2_rate_of(const PlanarBez& z, const PlanarDeriv& d) {
  const double* d1 = d.d1;
  const double* d2 = d.d2;
  const double sp2 = d1[0] * d1[0] + d1[1] * d1[1];
  const double sp = sqrt(sp2);
  if (!(sp > 0.0)) return 0.0;
  // Signed curvature kappa = c / sp^3 with c = d1 x d2 (>= 0 for a left turn), c' = d1 x d3.
  const double c = d1[0] * d2[1] - d1[1] * d2[0];
  const double cp = d1[0] * z.d3[1] - d1[1] * z.d3[0];
  const double sp3 = sp2 * sp;
  const double dk_dt = cp / sp3 - 3.0 * c * (d1[0] * d2[0] + d1[1] * d2[1]) / (sp3 * sp2);
  return fabs(dk_dt / sp);
}

/** kappa (signed, >= 0 for a left turn) of the curve with derivatives d. */
inline double g2_kappa_of(const PlanarDeriv& d) {
  const double* d1 = d.d1;
  const double* d2 = d.d2;
  const double sp2 = d1[0] * d1[0] + d1[1] * d1[1];
  if (!(sp2 > 0.0)) return 0.0;
  return (d1[0] * d2[1] - d1[1] * d2[0]) / (sp2 * sqrt(sp2));
}

inline double g2_rate_at(const PlanarBez& z, double t) { return g2_rate_of(z, planar_deriv(z, t)); }

inline double g2_kappa_at(const PlanarBez& z, double t) { return g2_kappa_of(planar_deriv(z, t)); }

/** Running maximum of the samples of max_on_unit. */
struct UnitSamples {
  int best = 0;
  double best_v = -HUGE_VAL;
  void add(int i, double v) {
    if (v > best_v) {
      best_v = v;
      best = i;
    }
  }
};

/** Golden-section refinement of f around the best sample s; the maximum found. */
template <typename F>
double refine_on_unit(F f, const UnitSamples& s) {
  const int best = s.best;
  double lo = static_cast<double>(best > 0 ? best - 1 : 0) / kRateSamples;
  double hi = static_cast<double>(best < kRateSamples ? best + 1 : kRateSamples) / kRateSamples;
  const double gr = 0.6180339887498948482;
  double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < kRateGolden; ++it) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + gr * (hi - lo);
      f2 = f(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - gr * (hi - lo);
      f1 = f(x1);
    }
  }
  return dmax(s.best_v, dmax(f1, f2));
}

/** Maximum over t in [0, 1] of f: kRateSamples + 1 samples, golden-section refinement. */
template <typename F>
double max_on_unit(F f) {
  UnitSamples s;
  for (int i = 0; i <= kRateSamples; ++i) s.add(i, f(static_cast<double>(i) / kRateSamples));
  return refine_on_unit(f, s);
}

/** The first Bezier of the unit corner with inner fractions gf, hf (tangent length 1). */
PlanarBez unit_bez(double beta, double gf, double hf) {
  const double theta = 2.0 * beta;
  const double b2 = 1.0 - gf - hf;  // unit tangent length
  const double px[4] = {-1.0, -(1.0 - gf), -b2, 0.5 * (-b2 + b2 * cos(theta))};
  const double py[4] = {0.0, 0.0, 0.0, 0.5 * (b2 * sin(theta))};
  return planar_bez(px, py);
}

/** Closed interval [lo, hi]. */
struct Iv {
  double lo, hi;
};

inline Iv iv_hull(double a, double b) { return a < b ? Iv{a, b} : Iv{b, a}; }

inline Iv iv_mul(const Iv& x, const Iv& y) {
  const double p[4] = {x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi};
  Iv r{p[0], p[0]};
  for (int i = 1; i < 4; ++i) {
    r.lo = dmin(r.lo, p[i]);
    r.hi = dmax(r.hi, p[i]);
  }
  return r;
}

inline double iv_mag(const Iv& x) { return dmax(fabs(x.lo), fabs(x.hi)); }

// Smallest |v| over x: 0 when x holds 0.
inline double iv_mig(const Iv& x) { return x.lo > 0.0 ? x.lo : (x.hi < 0.0 ? -x.hi : 0.0); }

// Range of p0 + p1 t + p2 t^2 over [ta, tb], widened by `slack` (absolute) for the rounding.
Iv quad_range(double p0, double p1, double p2, double ta, double tb, double slack) {
  const double fa = p0 + ta * (p1 + ta * p2), fb = p0 + tb * (p1 + tb * p2);
  Iv r = iv_hull(fa, fb);
  if (p2 < 0.0 || p2 > 0.0) {
    const double tv = -p1 / (2.0 * p2);
    if (tv > ta && tv < tb) {
      const double fv = p0 + tv * (p1 + tv * p2);
      r.lo = dmin(r.lo, fv);
      r.hi = dmax(r.hi, fv);
    }
  }
  return Iv{r.lo - slack, r.hi + slack};
}

// Upper bound of the true curvature (signed, left turn) of z over [0, 1], with a relative margin
// far above the rounding with which g2_kappa_of evaluates it at any t; HUGE_VAL when the speed
// may vanish. On each of `pieces` intervals: ranges of the first derivative (quadratic in t)
// and second (linear) per axis, interval arithmetic for the cross product and the speed.
double kappa_upper(const PlanarBez& z, int pieces) {
  double best = 0.0;
  for (int k = 0; k < pieces; ++k) {
    const double ta = static_cast<double>(k) / pieces;
    const double tb = static_cast<double>(k + 1) / pieces;
    Iv d1[2], d2[2];
    for (int i = 0; i < 2; ++i) {
      // d1 = 3 (a + 2 (b - a) t + (a - 2 b + e) t^2), d2 = 6 ((b - a) + (e - 2 b + a) t).
      const double p0 = 3.0 * z.a[i], p1 = 6.0 * (z.b[i] - z.a[i]);
      const double p2 = 3.0 * (z.a[i] - 2.0 * z.b[i] + z.e[i]);
      const double q0 = 6.0 * (z.b[i] - z.a[i]), q1 = 6.0 * (z.e[i] - 2.0 * z.b[i] + z.a[i]);
      const double s1 = 1e-12 * (fabs(p0) + fabs(p1) + fabs(p2)) + 1e-300;
      const double s2 = 1e-12 * (fabs(q0) + fabs(q1)) + 1e-300;
      d1[i] = quad_range(p0, p1, p2, ta, tb, s1);
      d2[i] = quad_range(q0, q1, 0.0, ta, tb, s2);
    }
    const Iv c1 = iv_mul(d1[0], d2[1]), c2 = iv_mul(d1[1], d2[0]);
    // The cross product, widened by the cancellation error of its evaluation.
    const double cross =
        dmax(fabs(c1.hi - c2.lo), fabs(c1.lo - c2.hi)) + 1e-12 * (iv_mag(c1) + iv_mag(c2));
    const double m0 = iv_mig(d1[0]), m1 = iv_mig(d1[1]);
    const double sp2 = m0 * m0 + m1 * m1;
    if (!(sp2 > 0.0)) return HUGE_VAL;
    best = dmax(best, cross / (sp2 * sqrt(sp2)));
  }
  return best * (1.0 + 1e-9);
}

// A lower bound of g2_shape's rate: its rate samples every `step`, over kappa_upper on `pieces`.
double rate_lower(double beta, double gf, double hf, int pieces, int step) {
  const PlanarBez z = unit_bez(beta, gf, hf);
  // g2_shape's rate is f / (k k): f its refined rate maximum (at least its best sample) times
  // kRateMargin, k its refined curvature maximum (at most the true maximum, up to the rounding
  // kappa_upper covers) times kRateMargin. Every operation below rounds the same way or towards a
  // smaller result.
  double f = 0.0;
  for (int i = 0; i <= kRateSamples; i += step)
    f = dmax(f, g2_rate_of(z, planar_deriv(z, static_cast<double>(i) / kRateSamples)));
  const double k = kappa_upper(z, pieces) * kRateMargin;
  if (!(k < HUGE_VAL) || !(k > 0.0)) return 0.0;
  return (f * kRateMargin) / (k * k);
}

// The curvature (sk) and curvature-rate (sf) samples of z that g2_shape refines.
void shape_samples(const PlanarBez& z, UnitSamples* sk, UnitSamples* sf, int step = 1) {
  for (int i = 0; i <= kRateSamples; i += step) {
    const PlanarDeriv d = planar_deriv(z, static_cast<double>(i) / kRateSamples);
    sk->add(i, g2_kappa_of(d));
    sf->add(i, g2_rate_of(z, d));
  }
}

}  // namespace

/** Tangent length per metre of radius of the G2 corner with half-deflection beta. */
double g2_tau(double beta) {
  const double cb = cos(beta);
  return (2.0 / 3.0) * kC3 * sin(beta) / (kQ * kQ * cb * cb);
}

/**
 * max |dkappa/ds| of the unit-radius G2 corner (both halves are mirror images): max_on_unit over
 * the first half, with a 1e-6 relative safety margin.
 * Scale: a corner of radius r has max |dkappa/ds| = g2_rate(beta) / r^2.
 */
double g2_rate(double beta) {
  const double d = g2_tau(beta);
  const double h = kC3 * d, g = kC2 * h;
  const double theta = 2.0 * beta;
  // Waypoint at the origin, incoming along +x, outgoing along (cos theta, sin theta).
  const double b2 = d - g - h;
  const double px[4] = {-d, -(d - g), -b2, 0.5 * (-b2 + b2 * cos(theta))};
  const double py[4] = {0.0, 0.0, 0.0, 0.5 * (b2 * sin(theta))};
  const PlanarBez z = planar_bez(px, py);
  return max_on_unit([&](double t) { return g2_rate_at(z, t); }) * kRateMargin;
}

/**
 * Tangent length per metre of radius (tau) and rate = max|dkappa/ds| r^2 of the G2 corner whose
 * inner control points sit at fractions gf, hf of the tangent length, with half-deflection beta:
 * "radius" r = 1 / max kappa, so that the corner of radius r has tangent length tau r, peak
 * curvature 1/r and max|dkappa/ds| = rate / r^2, as for the Yang-Sukkarieh shape. The two maxima
 * share their samples (each the same value max_on_unit would find).
 */
void g2_shape(double beta, double gf, double hf, double* tau, double* rate) {
  const PlanarBez z = unit_bez(beta, gf, hf);
  UnitSamples sk, sf;
  shape_samples(z, &sk, &sf);
  const double k = refine_on_unit([&](double t) { return g2_kappa_at(z, t); }, sk) * kRateMargin;
  const double f = refine_on_unit([&](double t) { return g2_rate_at(z, t); }, sf) * kRateMargin;
  *tau = k;             // d = 1 has peak curvature k: radius 1/k, so d = k r
  *rate = f / (k * k);  // max|dkappa/ds| = f / d^2 = f / (k r)^2
}

double g2_rate_lower(double beta, double gf, double hf) {
  return rate_lower(beta, gf, hf, kBoundPieces, kBoundSampleStep);
}

void g2_shape_lower(double beta, double gf, double hf, double* tau_lower, double* f_lower,
                    int step) {
  const PlanarBez z = unit_bez(beta, gf, hf);
  UnitSamples sk, sf;
  shape_samples(z, &sk, &sf, step);
  // g2_shape refines from all these samples: its maxima are at least the best ones.
  *tau_lower = sk.best_v * kRateMargin;
  *f_lower = sf.best_v * kRateMargin;
}

double g2_rate_lower_quick(double beta, double gf, double hf) {
  return rate_lower(beta, gf, hf, kQuickPieces, kQuickSampleStep);
}

}  // namespace tdo_internal
