// Small inline scalar helpers of the library's stages (internal): minimum, maximum and the
// parameter checks "finite and positive" / "finite and not negative" (docs/design.md s.7).
#ifndef TDO_SRC_SCALAR_H
#define TDO_SRC_SCALAR_H

#include <math.h>

namespace tdo_internal {

// The smaller / larger of a and b. NaN: when either is NaN the comparison is false and the
// result is b (dmin(NaN, 1) = 1, dmin(1, NaN) = NaN). Callers that must not lose a NaN put it
// second; collision.cpp keeps its own pair, which returns a instead.
inline double dmin(double a, double b) { return a < b ? a : b; }
inline double dmax(double a, double b) { return a > b ? a : b; }

// Parameter checks: NaN and infinities fail both.
inline bool positive(double x) { return isfinite(x) && x > 0.0; }
inline bool non_negative(double x) { return isfinite(x) && x >= 0.0; }

}  // namespace tdo_internal

#endif  // TDO_SRC_SCALAR_H
