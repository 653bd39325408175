// Small inline vector helpers of the library's stages (internal).
#ifndef TDO_SRC_VEC3_H
#define TDO_SRC_VEC3_H

#include <math.h>

#include "tdo/types.h"

namespace tdo_internal {

inline tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }
inline tdo_vec3 add(tdo_vec3 a, tdo_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
inline tdo_vec3 sub(tdo_vec3 a, tdo_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline tdo_vec3 mul(tdo_vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
inline double dot(tdo_vec3 a, tdo_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline tdo_vec3 cross(tdo_vec3 a, tdo_vec3 b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline double norm(tdo_vec3 a) { return sqrt(dot(a, a)); }
inline bool finite3(tdo_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
// Every component exactly +-0 (a NaN is not zero).
inline bool zero3(tdo_vec3 a) { return fabs(a.x) <= 0.0 && fabs(a.y) <= 0.0 && fabs(a.z) <= 0.0; }
// a / |a|, or `fallback` when |a| <= eps.
inline tdo_vec3 unit_or(tdo_vec3 a, tdo_vec3 fallback, double eps) {
  const double n = norm(a);
  return n > eps ? mul(a, 1.0 / n) : fallback;
}
inline tdo_vec3 lerp(tdo_vec3 a, tdo_vec3 b, double u) { return add(a, mul(sub(b, a), u)); }
// Component k of v (0 x, 1 y, otherwise z), read and written.
inline double vec_axis(tdo_vec3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }
inline void set_vec_axis(tdo_vec3* v, int k, double x) {
  if (k == 0)
    v->x = x;
  else if (k == 1)
    v->y = x;
  else
    v->z = x;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_VEC3_H
