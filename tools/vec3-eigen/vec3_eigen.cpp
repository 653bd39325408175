// vec3-eigen: measures what replacing the library's vec3.h (plain tdo_vec3 and inline functions)
// by Eigen's fixed-size Eigen::Vector3d would cost, on kernels written once for both types: the
// cubic Bezier evaluation of path.cpp (de Casteljau point, first and second derivative, curvature
// vector), the point-to-segment distance of metrics.cpp and apf.cpp, and the arc point of path.cpp.
// Host: same-process time ratio (best of 21 interleaved runs each, process CPU time) and bit
// identity of the results. Built with -DVEC3_EIGEN_KERNELS_ONLY it is the object whose per-kernel
// code sizes tools/vec3-eigen/sizes.sh reads for the Cortex-M7. docs/design.md s.7 holds the
// decision and the figures.
#define EIGEN_NO_MALLOC  // fixed-size types only: any heap use aborts
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vec3.h"  // libtdo/src: the library's internal vector helpers

namespace {

// The vector operations the kernels use, for each type.
namespace ops_plain {
using tdo_internal::add;
using tdo_internal::cross;
using tdo_internal::dot;
using tdo_internal::lerp;
using tdo_internal::mul;
using tdo_internal::norm;
using tdo_internal::sub;
inline tdo_vec3 make(double x, double y, double z) { return tdo_vec3{x, y, z}; }
inline double x_of(const tdo_vec3& a) { return a.x; }
inline double y_of(const tdo_vec3& a) { return a.y; }
inline double z_of(const tdo_vec3& a) { return a.z; }
}  // namespace ops_plain

namespace ops_eigen {
using V = Eigen::Vector3d;
inline V make(double x, double y, double z) { return V(x, y, z); }
inline V add(const V& a, const V& b) { return a + b; }
inline V sub(const V& a, const V& b) { return a - b; }
inline V mul(const V& a, double s) { return a * s; }
inline double dot(const V& a, const V& b) { return a.dot(b); }
inline V cross(const V& a, const V& b) { return a.cross(b); }
inline double norm(const V& a) { return a.norm(); }
inline V lerp(const V& a, const V& b, double u) { return a + (b - a) * u; }
inline double x_of(const V& a) { return a.x(); }
inline double y_of(const V& a) { return a.y(); }
inline double z_of(const V& a) { return a.z(); }
}  // namespace ops_eigen

// in: n records of 12 doubles (4 control points); out: n records of 10 doubles.
#define VEC3_EIGEN_KERNEL(NS)                                                                      \
  void kernel_##NS(const double* in, size_t n, double* out) {                                      \
    using namespace NS;                                                                            \
    for (size_t r = 0; r < n; ++r, in += 12, out += 10) {                                          \
      const auto p0 = make(in[0], in[1], in[2]), p1 = make(in[3], in[4], in[5]);                   \
      const auto p2 = make(in[6], in[7], in[8]), p3 = make(in[9], in[10], in[11]);                 \
      const double t = 0.37;                                                                       \
      const double u = 1.0 - t;                                                                    \
      const auto a0 = lerp(p0, p1, t), a1 = lerp(p1, p2, t), a2 = lerp(p2, p3, t);                 \
      const auto pt = lerp(lerp(a0, a1, t), lerp(a1, a2, t), t);                                   \
      const auto d1 = mul(add(add(mul(sub(p1, p0), u * u), mul(sub(p2, p1), 2.0 * u * t)),         \
                              mul(sub(p3, p2), t * t)),                                            \
                          3.0);                                                                    \
      const auto d2 =                                                                              \
          mul(add(mul(add(sub(p2, mul(p1, 2.0)), p0), u), mul(add(sub(p3, mul(p2, 2.0)), p1), t)), \
              6.0);                                                                                \
      const double sp = norm(d1);                                                                  \
      const auto tan = mul(d1, 1.0 / sp);                                                          \
      const auto kn = mul(sub(d2, mul(tan, dot(d2, tan))), 1.0 / (sp * sp));                       \
      const double kappa = norm(cross(d1, d2)) / (sp * sp * sp);                                   \
      const auto ab = sub(p3, p0);                                                                 \
      const double l2 = dot(ab, ab);                                                               \
      double s = l2 > 0.0 ? dot(sub(p1, p0), ab) / l2 : 0.0;                                       \
      s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);                                                     \
      const double seg_d = norm(sub(p1, add(p0, mul(ab, s))));                                     \
      const auto w = sub(p2, mul(tan, dot(p2, tan)));                                              \
      const auto arc = add(p0, add(mul(tan, cos(t)), mul(w, sin(t))));                             \
      out[0] = x_of(pt) + y_of(pt) + z_of(pt);                                                     \
      out[1] = x_of(kn);                                                                           \
      out[2] = y_of(kn);                                                                           \
      out[3] = z_of(kn);                                                                           \
      out[4] = kappa;                                                                              \
      out[5] = seg_d;                                                                              \
      out[6] = x_of(arc);                                                                          \
      out[7] = y_of(arc);                                                                          \
      out[8] = z_of(arc);                                                                          \
      out[9] = sp;                                                                                 \
    }                                                                                              \
  }

}  // namespace

extern "C" {
VEC3_EIGEN_KERNEL(ops_plain)
VEC3_EIGEN_KERNEL(ops_eigen)
}

#ifndef VEC3_EIGEN_KERNELS_ONLY
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <vector>

int main() {
  constexpr size_t kRecords = 200000;
  std::vector<double> in(kRecords * 12), out_plain(kRecords * 10), out_eigen(kRecords * 10);
  uint64_t x = 88172645463325252ull;  // xorshift64: fixed inputs in [-10, 10) m
  for (double& v : in) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    v = static_cast<double>(x >> 11) * (20.0 / 9007199254740992.0) - 10.0;
  }
  double t_plain = 1e300, t_eigen = 1e300;
  auto time_ms = [&](void (*k)(const double*, size_t, double*), double* out) {
    // CPU time of this process: the machine is shared, so wall time measures the neighbours too.
    timespec t0{}, t1{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
    k(in.data(), kRecords, out);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
    return static_cast<double>(t1.tv_sec - t0.tv_sec) * 1e3 +
           static_cast<double>(t1.tv_nsec - t0.tv_nsec) * 1e-6;
  };
  for (int rep = 0; rep < 21; ++rep) {  // interleaved: both see the same machine load
    t_plain = std::min(t_plain, time_ms(kernel_ops_plain, out_plain.data()));
    t_eigen = std::min(t_eigen, time_ms(kernel_ops_eigen, out_eigen.data()));
  }
  size_t differ = 0;
  for (size_t i = 0; i < out_plain.size(); ++i)
    if (std::memcmp(&out_plain[i], &out_eigen[i], sizeof(double)) != 0) ++differ;
  std::printf("vec3-eigen: %zu records, vec3.h %.3f ms, Eigen::Vector3d %.3f ms, ratio %.3f\n",
              kRecords, t_plain, t_eigen, t_eigen / t_plain);
  std::printf("vec3-eigen: results differing bit for bit: %zu of %zu\n", differ, out_plain.size());
  return differ == 0 ? 0 : 1;
}
#endif
