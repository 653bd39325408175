// Geometric metrics of a polyline. See path_metrics.h.
#include "path_metrics.h"

#include <algorithm>
#include <cmath>

namespace tdo_tools {
namespace {

constexpr double kPi = 3.14159265358979323846;

tdo_vec3 sub(const tdo_vec3& a, const tdo_vec3& b) {
  return tdo_vec3{a.x - b.x, a.y - b.y, a.z - b.z};
}

double norm(const tdo_vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

}  // namespace

double polyline_length(const std::vector<tdo_vec3>& pts) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += norm(sub(pts[i], pts[i - 1]));
  return len;
}

double deflection_deg(const tdo_vec3& prev, const tdo_vec3& at, const tdo_vec3& next) {
  const tdo_vec3 a = sub(at, prev);
  const tdo_vec3 b = sub(next, at);
  const double na = norm(a);
  const double nb = norm(b);
  if (!(na > 0.0) || !(nb > 0.0)) return 0.0;
  // atan2 of |a x b| and a.b is accurate for small and large angles alike.
  const tdo_vec3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  const double dot = a.x * b.x + a.y * b.y + a.z * b.z;
  return std::atan2(norm(c), dot) * 180.0 / kPi;
}

TurnStats turn_stats(const std::vector<tdo_vec3>& pts, double threshold_deg) {
  std::vector<tdo_vec3> q;
  q.reserve(pts.size());
  for (const tdo_vec3& p : pts) {
    if (q.empty() || norm(sub(p, q.back())) > 0.0) q.push_back(p);
  }
  TurnStats s;
  for (std::size_t i = 1; i + 1 < q.size(); ++i) {
    const double d = deflection_deg(q[i - 1], q[i], q[i + 1]);
    if (d > threshold_deg) {
      ++s.turns;
      s.total_turn_deg += d;
    }
  }
  return s;
}

}  // namespace tdo_tools
