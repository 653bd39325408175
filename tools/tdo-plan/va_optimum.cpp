// The v/a time optimum along a sampled path. See va_optimum.h.
#include "va_optimum.h"

#include <algorithm>
#include <cmath>

namespace tdo_tools {
namespace {

constexpr double kDuplicate = 1e-12;  // m: consecutive points closer than this are one point
constexpr double kTolerance = 0.01;   // the trajectory check's tolerance on v, a and j
constexpr int kScan = 4096;           // speed steps of jerk_cap

tdo_vec3 sub(const tdo_vec3& a, const tdo_vec3& b) {
  return tdo_vec3{a.x - b.x, a.y - b.y, a.z - b.z};
}
tdo_vec3 cross(const tdo_vec3& a, const tdo_vec3& b) {
  return tdo_vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const tdo_vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

/** 1/m, curvature of the circle through a, b, c (0 when two of them coincide). */
double menger(const tdo_vec3& a, const tdo_vec3& b, const tdo_vec3& c) {
  const tdo_vec3 ab = sub(b, a), ac = sub(c, a), bc = sub(c, b);
  const double den = norm(ab) * norm(ac) * norm(bc);
  if (!(den > 0.0)) return 0.0;
  return 2.0 * norm(cross(ab, ac)) / den;
}

/** m/s^2, tangential acceleration left by the centripetal part kappa v^2 of a_max. */
double tangential(double a_max, double kappa, double v) {
  const double an = kappa * v * v;
  return an >= a_max ? 0.0 : std::sqrt(a_max * a_max - an * an);
}

/** s, rest-to-rest time of the forward/backward pass over the points at arclengths s with
 *  curvatures kappa, speed limits lim and total acceleration a_max. */
double pass_time(const std::vector<double>& s, const std::vector<double>& kappa,
                 const std::vector<double>& lim, double a_max) {
  const std::size_t n = s.size();
  std::vector<double> fwd(n, 0.0), bwd(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double ds = s[i + 1] - s[i];
    const double at = tangential(a_max, std::max(kappa[i], kappa[i + 1]), fwd[i]);
    fwd[i + 1] = std::min(lim[i + 1], std::sqrt(fwd[i] * fwd[i] + 2.0 * at * ds));
  }
  for (std::size_t i = n - 1; i > 0; --i) {
    const double ds = s[i] - s[i - 1];
    const double at = tangential(a_max, std::max(kappa[i], kappa[i - 1]), bwd[i]);
    bwd[i - 1] = std::min(lim[i - 1], std::sqrt(bwd[i] * bwd[i] + 2.0 * at * ds));
  }
  double t = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double v0 = std::min(fwd[i], bwd[i]), v1 = std::min(fwd[i + 1], bwd[i + 1]);
    // Constant acceleration over the step: exact time 2 ds / (v0 + v1).
    if (v0 + v1 > 0.0) t += 2.0 * (s[i + 1] - s[i]) / (v0 + v1);
  }
  return t;
}

/** m/s, the highest speed in [0, cap] at which a curve point (curvature kappa, rate dkappa) can be
 *  flown with a normal jerk |3 kappa v a_t + dkappa v^3| <= j and |a_t| <= sqrt(a^2 - (kappa
 *  v^2)^2): the normal jerk of every such flight is at least dkappa v^3 - 3 kappa v |a_t|.
 *  Scanned downwards from cap in kScan steps and rounded up one step (an upper bound). */
double jerk_cap(double kappa, double dkappa, double cap, double a, double j) {
  const auto ok = [&](double v) {
    return dkappa * v * v * v - 3.0 * kappa * v * tangential(a, kappa, v) <= j;
  };
  if (!(dkappa > 0.0) || ok(cap)) return cap;
  const double step = cap / kScan;
  for (int i = kScan - 1; i > 0; --i)
    if (ok(step * i)) return std::min(cap, step * (i + 1));
  return step;
}

}  // namespace

VaOptimum va_optimum(const std::vector<tdo_vec3>& points, double v_max, double a_max, double span,
                     double j_max) {
  VaOptimum r;
  if (!(v_max > 0.0) || !(a_max > 0.0) || !(span > 0.0)) return r;
  std::vector<tdo_vec3> p;
  std::vector<double> s;  // m, arclength of each distinct point
  p.reserve(points.size());
  s.reserve(points.size());
  for (const tdo_vec3& q : points) {
    if (!p.empty()) {
      const double d = norm(sub(q, p.back()));
      if (!(d > kDuplicate)) continue;
      s.push_back(s.back() + d);
    } else {
      s.push_back(0.0);
    }
    p.push_back(q);
  }
  const std::size_t n = p.size();
  r.nodes = n;
  if (n < 2) return r;
  r.length_m = s.back();
  // Curvature at every interior point from the neighbours about `span` before and after it.
  std::vector<double> kappa(n, 0.0), lim(n, 0.0);
  std::vector<std::size_t> before(n, 0), after(n, n - 1);
  std::size_t j = 0, k = 0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    while (j + 1 < i && s[i] - s[j + 1] >= span) ++j;
    if (k <= i) k = i + 1;
    while (k + 1 < n && s[k] - s[i] < span) ++k;
    kappa[i] = menger(p[j], p[i], p[k]);
    before[i] = j;
    after[i] = k;
    r.max_kappa = std::max(r.max_kappa, kappa[i]);
  }
  for (std::size_t i = 0; i < n; ++i)
    lim[i] = kappa[i] > 0.0 ? std::min(v_max, std::sqrt(a_max / kappa[i])) : v_max;
  r.time_s = pass_time(s, kappa, lim, a_max);
  if (j_max > 0.0) {
    // The same pass under the limits raised by the check's tolerance and the pointwise speed cap
    // of the normal jerk, with dkappa/ds from the curvatures of the same neighbours.
    const double vt = v_max * (1.0 + kTolerance), at = a_max * (1.0 + kTolerance);
    const double jt = j_max * (1.0 + kTolerance);
    for (std::size_t i = 0; i < n; ++i) {
      const double cap = kappa[i] > 0.0 ? std::min(vt, std::sqrt(at / kappa[i])) : vt;
      double dk = 0.0;
      if (i > 0 && i + 1 < n && s[after[i]] > s[before[i]])
        dk = std::fabs(kappa[after[i]] - kappa[before[i]]) / (s[after[i]] - s[before[i]]);
      lim[i] = jerk_cap(kappa[i], dk, cap, at, jt);
    }
    r.jerk_bound_s = pass_time(s, kappa, lim, at);
  }
  return r;
}

}  // namespace tdo_tools
