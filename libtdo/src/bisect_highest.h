// The highest speed that fits, by bisection with its steps decided from a bracket where one
// already decides them (trajectory.cpp's move_reach and move_peak). Internal to libtdo.
#ifndef TDO_SRC_BISECT_HIGHEST_H
#define TDO_SRC_BISECT_HIGHEST_H

#include "scalar.h"

namespace tdo_internal {

constexpr int kBisections = 30;          // bisection steps (speed resolution ~ 2^-30 of the range)
constexpr int kBracketSteps = 12;        // false-position steps before them, at most
constexpr double kBracketClip = 8.0;     // of the length: the largest excess they interpolate
constexpr double kBracketTol = 0x1p-30;  // of the range: the bracket they stop at

/** The highest v in [lo, hi] with lhs(v) <= len (fits), as kBisections bisection steps find it;
 *  `lo` must fit, `hi` not (lhs(hi) = lhs_hi > len), and lhs must grow with v. The steps are the
 *  same, but a step is decided without evaluating lhs where a bracket [a, b] (a fits, b does not,
 *  both evaluated) already decides it: by the growth, every v <= a fits and every v >= b does not.
 *  False position (Illinois) narrows the bracket first, to about the bisection's last step, so
 *  few steps are left to evaluate; the result is the plain bisection's, bit for bit. */
template <class Lhs>
double bisect_highest(double lo, double hi, double len, double lhs_hi, const Lhs& lhs) {
  double a = lo, b = hi;
  const double lhs_lo = lhs(lo);
  if (lhs_lo <= len && lhs_hi > len) {
    // Near a ceiling lhs grows steeply (the limits left there vanish): excesses are clipped to a
    // few lengths, or the interpolation would crawl along the side that fits.
    double fa = lhs_lo - len, fb = dmin(lhs_hi - len, kBracketClip * len);
    const double tol = (hi - lo) * kBracketTol;
    int side = 0;
    for (int i = 0; i < kBracketSteps && b - a > tol; ++i) {
      double x = b - fb * ((b - a) / (fb - fa));
      if (!(x > a && x < b)) x = 0.5 * (a + b);
      if (!(x > a && x < b)) break;
      const double l = lhs(x);
      if (l <= len) {
        a = x;
        fa = l - len;
        if (side < 0) fb *= 0.5;
        side = -1;
      } else {
        b = x;
        fb = dmin(l - len, kBracketClip * len);
        if (side > 0) fa *= 0.5;
        side = 1;
      }
    }
  }
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    bool fits;
    if (mid <= a && a > lo)
      fits = true;
    else if (mid >= b && b < hi)
      fits = false;
    else
      fits = lhs(mid) <= len;
    if (fits)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_BISECT_HIGHEST_H
