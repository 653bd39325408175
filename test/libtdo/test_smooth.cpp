// Stage 3 smoothing (smooth.h, docs/design.md s.3, paper eq. 8-9): G1 everywhere, G2 in g2 mode,
// peak curvature 1/r, exact start and goal, corners in the plane of their segments and tangent to
// them, fitting and shrinking with lowered speed, stop points, arc mode's curvature jump, clearance
// with obstacles, named statuses, and a seeded random-polyline property test.
//
// The checker below is independent of libtdo: it evaluates Beziers in Bernstein form, fits circles
// through positions for curvature, measures clearance by exact point-to-box distances of dense
// samples, and re-derives tangency and planarity from the control points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "rng.h"
#include "tdo/path.h"
#include "tdo/smooth.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;

const double kPi = std::acos(-1.0);
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
double deg(double d) { return d * kPi / 180.0; }

// ---------------------------------------------------------------------------------------------
// Small vector kit.

struct P {
  double x, y, z;
};
P of(const tdo_vec3& v) { return P{v.x, v.y, v.z}; }
tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }
tdo_vec3 v3(const P& p) { return tdo_vec3{p.x, p.y, p.z}; }
P operator+(P a, P b) { return P{a.x + b.x, a.y + b.y, a.z + b.z}; }
P operator-(P a, P b) { return P{a.x - b.x, a.y - b.y, a.z - b.z}; }
P operator*(P a, double k) { return P{a.x * k, a.y * k, a.z * k}; }
double dot(P a, P b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
P cross(P a, P b) { return P{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(P a) { return std::sqrt(dot(a, a)); }
P unit(P a) { return a * (1.0 / norm(a)); }
bool same(const tdo_vec3& a, const tdo_vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
std::string str(const P& p) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << p.x << "," << p.y << "," << p.z << ")";
  return os.str();
}
double angle(P a, P b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

/** Distance from x to the segment [a, b]. */
double dist_segment(P x, P a, P b) {
  const P d = b - a;
  double t = dot(x - a, d) / dot(d, d);
  t = std::min(1.0, std::max(0.0, t));
  return norm(x - (a + d * t));
}
/** Distance from x to the infinite line through a and b. */
double dist_line(P x, P a, P b) {
  const P d = unit(b - a);
  const P r = x - a;
  return norm(r - d * dot(r, d));
}

// ---------------------------------------------------------------------------------------------
// Independent segment geometry.

P bez(const tdo_path_segment& s, double t) {
  const double u = 1.0 - t;
  return of(s.p[0]) * (u * u * u) + of(s.p[1]) * (3.0 * u * u * t) +
         of(s.p[2]) * (3.0 * u * t * t) + of(s.p[3]) * (t * t * t);
}
P bez_d1(const tdo_path_segment& s, double t) {
  const double u = 1.0 - t;
  return ((of(s.p[1]) - of(s.p[0])) * (u * u) + (of(s.p[2]) - of(s.p[1])) * (2.0 * u * t) +
          (of(s.p[3]) - of(s.p[2])) * (t * t)) *
         3.0;
}
P bez_d2(const tdo_path_segment& s, double t) {
  return ((of(s.p[2]) - of(s.p[1]) * 2.0 + of(s.p[0])) * (1.0 - t) +
          (of(s.p[3]) - of(s.p[2]) * 2.0 + of(s.p[1])) * t) *
         6.0;
}
double bez_kappa(const tdo_path_segment& s, double t) {
  const P d1 = bez_d1(s, t);
  const double sp = norm(d1);
  return norm(cross(d1, bez_d2(s, t))) / (sp * sp * sp);
}

P seg_start(const tdo_path_segment& s) { return of(s.p[0]); }
P seg_end(const tdo_path_segment& s) {
  return s.kind == TDO_SEGMENT_BEZIER ? of(s.p[3]) : of(s.p[1]);
}
const tdo_vec3& seg_end_raw(const tdo_path_segment& s) {
  return s.kind == TDO_SEGMENT_BEZIER ? s.p[3] : s.p[1];
}

/** Direction of travel at the start (end = false) or end of a segment, from its defining points. */
P seg_dir(const tdo_path_segment& s, bool end) {
  switch (s.kind) {
    case TDO_SEGMENT_LINE:
      return unit(of(s.p[1]) - of(s.p[0]));
    case TDO_SEGMENT_BEZIER:
      return end ? unit(of(s.p[3]) - of(s.p[2])) : unit(of(s.p[1]) - of(s.p[0]));
    case TDO_SEGMENT_ARC: {
      const P rad = (end ? of(s.p[1]) : of(s.p[0])) - of(s.p[2]);
      const P chord = of(s.p[1]) - of(s.p[0]);
      return unit(chord - rad * (dot(chord, rad) / dot(rad, rad)));  // chord minus radial part
    }
  }
  return P{0, 0, 0};
}

/** Independent length: exact for lines and arcs, Richardson-extrapolated chords for Beziers. */
double seg_length_ref(const tdo_path_segment& s) {
  switch (s.kind) {
    case TDO_SEGMENT_LINE:
      return norm(of(s.p[1]) - of(s.p[0]));
    case TDO_SEGMENT_ARC: {
      const P a = of(s.p[0]) - of(s.p[2]), b = of(s.p[1]) - of(s.p[2]);
      return norm(a) * angle(a, b);
    }
    case TDO_SEGMENT_BEZIER: {
      auto chords = [&](int n) {
        double sum = 0.0;
        P prev = bez(s, 0.0);
        for (int i = 1; i <= n; ++i) {
          const P q = bez(s, static_cast<double>(i) / n);
          sum += norm(q - prev);
          prev = q;
        }
        return sum;
      };
      const double a = chords(2000), b = chords(4000);
      return (4.0 * b - a) / 3.0;
    }
  }
  return 0.0;
}

/** Curvature of the circle through three points. */
double circle_kappa(P a, P b, P c) {
  const double ab = norm(b - a), bc = norm(c - b), ca = norm(a - c);
  return 2.0 * norm(cross(b - a, c - a)) / (ab * bc * ca);
}

/** Curvature estimate near one end of a segment and its estimated error (1/m). */
struct EndKappa {
  double kappa;
  double error;
};

/**
 * Curvature at the start or end of a segment, from positions only: circles through three points
 * spaced h apart, centred h, 2h and 3h from the end, quadratically extrapolated to the end. The
 * spacing is halved from min(1e-3 m, L/32) a bounded number of times; the estimate with the
 * smallest error bound is returned: truncation (the change from the previous spacing) plus position
 * rounding (~1e-15 |p| per coordinate, amplified ~28 / h^2 by the fits and the extrapolation).
 */
EndKappa kappa_end(const tdo_path_segment& s, bool end) {
  const double len = s.length;
  auto at = [&](double d) { return of(tdo_segment_point(&s, end ? len - d : d)); };
  auto estimate = [&](double h) {
    const double k1 = circle_kappa(at(0.0), at(h), at(2.0 * h));
    const double k2 = circle_kappa(at(h), at(2.0 * h), at(3.0 * h));
    const double k3 = circle_kappa(at(2.0 * h), at(3.0 * h), at(4.0 * h));
    return 3.0 * k1 - 3.0 * k2 + k3;
  };
  const double eps = 1e-15 * (1.0 + norm(at(0.0)));
  double h = std::min(1e-3, len / 32.0);
  double prev2 = estimate(h);
  h *= 0.5;
  double prev = estimate(h);
  EndKappa best{prev, kInf};
  for (int i = 0; i < 24; ++i) {
    h *= 0.5;
    const double k = estimate(h);
    // truncation: the last two changes (one alone can vanish by coincidence)
    const double err = std::fabs(k - prev) + std::fabs(prev - prev2) + 28.0 * eps / (h * h);
    if (err < best.error) best = EndKappa{k, err};
    prev2 = prev;
    prev = k;
  }
  return best;
}
double kappa_end_from_positions(const tdo_path_segment& s, bool end) {
  return kappa_end(s, end).kappa;
}

// ---------------------------------------------------------------------------------------------
// The checker.

struct CornerSeen {
  uint32_t waypoint;  // interior waypoint index
  bool arc;
  double peak_kappa;      // 1/m, max curvature over the corner (dense Bernstein samples + junction)
  double junction_kappa;  // 1/m, G2: curvature at the junction of the two halves
  double max_rate;        // 1/m^2, max |dkappa/ds| over the corner (finite differences in t)
  double v_limit;         // m/s
  double tangent_len;     // m, distance from the waypoint to where the curve leaves the line
};

struct Seen {
  std::vector<CornerSeen> corners;
  std::vector<uint32_t> stops;    // interior waypoint indices where the path stops
  double max_g1_error = 0.0;      // rad, largest direction change at a non-stop junction
  double max_g2_error = 0.0;      // largest curvature jump at a non-stop junction / (1 + kappa)
  double max_g2_est_error = 0.0;  // largest error estimate of those measurements / (1 + kappa)
};

/** Deflection of the polyline at interior waypoint i. */
double deflection(const std::vector<tdo_vec3>& w, size_t i) {
  return angle(of(w[i]) - of(w[i - 1]), of(w[i + 1]) - of(w[i]));
}

/** Which input segment j (w[j] -> w[j+1]) holds point x; -1 if none. Prefers the first. */
int holding_segment(const std::vector<tdo_vec3>& w, P x, double tol, int from = 0) {
  for (size_t j = static_cast<size_t>(from); j + 1 < w.size(); ++j)
    if (dist_segment(x, of(w[j]), of(w[j + 1])) <= tol) return static_cast<int>(j);
  return -1;
}

/** Max |dkappa/ds| of a Bezier from curvature differences over a dense t grid. */
double bezier_max_rate(const tdo_path_segment& s) {
  const int n = 4000;
  double best = 0.0;
  double k_prev = bez_kappa(s, 0.0);
  P p_prev = bez(s, 0.0);
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double k = bez_kappa(s, t);
    const P p = bez(s, t);
    best = std::max(best, std::fabs(k - k_prev) / norm(p - p_prev));
    k_prev = k;
    p_prev = p;
  }
  return best;
}

/**
 * Checks everything that must hold for any smoothing output of polyline `w` (duplicates already
 * removed by the caller) and describes what it saw. `g2` adds curvature continuity.
 */
::testing::AssertionResult check_path(const std::vector<tdo_vec3>& w, const tdo_smooth_output& out,
                                      const tdo_smooth_input& in, Seen* seen) {
  const tdo_path& path = out.path;
  const bool g2 = in.mode == TDO_SMOOTHING_G2;
  *seen = Seen{};
  if (path.n == 0 || path.seg == nullptr) return ::testing::AssertionFailure() << "empty path";
  // Exact start and goal.
  if (!same(path.seg[0].p[0], w.front()))
    return ::testing::AssertionFailure() << "starts at " << str(of(path.seg[0].p[0]));
  if (!same(seg_end_raw(path.seg[path.n - 1]), w.back()))
    return ::testing::AssertionFailure() << "ends at " << str(seg_end(path.seg[path.n - 1]));
  // Scale for tolerances.
  double scale = 1.0;
  for (const tdo_vec3& p : w) scale = std::max(scale, norm(of(p)));
  const double tol = 1e-9 * scale;
  double total = 0.0;
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& s = path.seg[i];
    const double ref = seg_length_ref(s);
    if (!(s.length > 0.0) || std::fabs(s.length - ref) > 1e-7 * std::max(1.0, ref))
      return ::testing::AssertionFailure()
             << "segment " << i << " length " << s.length << " vs reference " << ref;
    total += s.length;
    if (!(s.v_limit > 0.0) || s.v_limit > in.v_max * (1.0 + 1e-12))
      return ::testing::AssertionFailure() << "segment " << i << " v_limit " << s.v_limit;
    if (i + 1 == path.n) break;
    const tdo_path_segment& nx = path.seg[i + 1];
    // Positions join.
    if (norm(seg_end(s) - seg_start(nx)) > tol)
      return ::testing::AssertionFailure() << "gap after segment " << i << ": " << str(seg_end(s))
                                           << " vs " << str(seg_start(nx));
    if (s.stop_at_end) continue;  // the vehicle is at rest there: direction may change
    const double g1 = angle(seg_dir(s, true), seg_dir(nx, false));
    seen->max_g1_error = std::max(seen->max_g1_error, g1);
    if (g1 > 1e-6)
      return ::testing::AssertionFailure() << "tangent jumps by " << g1 << " rad after segment "
                                           << i << " (kinds " << s.kind << " -> " << nx.kind << ")";
    if (g2) {
      // The estimates must be good to a few percent of the curvature (so a jump as in arc mode
      // could not hide), and agree within their error estimates.
      const EndKappa ka = kappa_end(s, true);
      const EndKappa kb = kappa_end(nx, false);
      const double ks = 1.0 + std::max(ka.kappa, kb.kappa);
      const double jump = std::fabs(ka.kappa - kb.kappa);
      seen->max_g2_error = std::max(seen->max_g2_error, jump / ks);
      seen->max_g2_est_error = std::max(seen->max_g2_est_error, (ka.error + kb.error) / ks);
      if (ka.error + kb.error > 0.02 * ks || jump > 1e-5 * ks + 4.0 * (ka.error + kb.error))
        return ::testing::AssertionFailure()
               << "curvature jumps " << ka.kappa << " (+-" << ka.error << ") -> " << kb.kappa
               << " (+-" << kb.error << ") after segment " << i << " (kinds " << s.kind << " -> "
               << nx.kind << ")";
    }
  }
  if (std::fabs(total - path.length) > 1e-9 * std::max(1.0, total))
    return ::testing::AssertionFailure() << "path length " << path.length << " != sum " << total;

  // Segment by segment against the polyline: lines lie on input segments, corners sit in the
  // plane of their two segments, tangent to both, and stops are at waypoints.
  for (uint32_t i = 0; i < path.n; ++i) {
    if (!path.seg[i].stop_at_end) continue;
    const tdo_vec3& e = seg_end_raw(path.seg[i]);
    uint32_t found = 0;
    for (size_t k = 1; k + 1 < w.size(); ++k)
      if (same(e, w[k])) found = static_cast<uint32_t>(k);
    if (found == 0)
      return ::testing::AssertionFailure() << "stop at " << str(of(e)) << " is no waypoint";
    seen->stops.push_back(found);
  }
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& s = path.seg[i];
    if (s.kind == TDO_SEGMENT_LINE) {
      const int j = holding_segment(w, seg_start(s), tol);
      if (j < 0 || dist_segment(seg_end(s), of(w[j]), of(w[j + 1])) > tol) {
        // a line may start exactly at a waypoint and run along the next segment
        const int j2 = holding_segment(w, seg_start(s), tol, j + 1);
        if (j2 < 0 || dist_segment(seg_end(s), of(w[j2]), of(w[j2 + 1])) > tol)
          return ::testing::AssertionFailure() << "line " << i << " leaves the polyline";
      }
      continue;
    }
    if (in.mode == TDO_SMOOTHING_NONE) return ::testing::AssertionFailure() << "curve in mode none";
    // A corner: one arc, or two Beziers (this one and the next).
    const bool arc = s.kind == TDO_SEGMENT_ARC;
    if (arc != (in.mode == TDO_SMOOTHING_ARC))
      return ::testing::AssertionFailure()
             << "segment " << i << " kind " << s.kind << " in mode " << in.mode;
    if (!arc && (i + 1 >= path.n || path.seg[i + 1].kind != TDO_SEGMENT_BEZIER))
      return ::testing::AssertionFailure() << "Bezier " << i << " without its second half";
    const tdo_path_segment& last = arc ? s : path.seg[i + 1];
    int c = -1;
    for (int j = 0; j + 2 < static_cast<int>(w.size()); ++j)
      if (dist_segment(seg_start(s), of(w[j]), of(w[j + 1])) <= tol &&
          dist_segment(seg_end(last), of(w[j + 1]), of(w[j + 2])) <= tol) {
        c = j + 1;
        break;
      }
    if (c < 0) return ::testing::AssertionFailure() << "corner at segment " << i << " has no home";
    const P a = of(w[c - 1]), b = of(w[c]), d = of(w[c + 1]);
    const P nrm = unit(cross(b - a, d - b));
    CornerSeen cs{};
    cs.waypoint = static_cast<uint32_t>(c);
    cs.arc = arc;
    cs.v_limit = s.v_limit;
    cs.tangent_len = norm(seg_start(s) - b);
    if (arc) {
      const P ctr = of(s.p[2]);
      const double r0 = norm(of(s.p[0]) - ctr), r1 = norm(of(s.p[1]) - ctr);
      if (std::fabs(r0 - r1) > tol || std::fabs(dot(of(s.p[0]) - ctr, unit(b - a))) > tol ||
          std::fabs(dot(of(s.p[1]) - ctr, unit(d - b))) > tol)
        return ::testing::AssertionFailure() << "arc " << i << " not tangent to its segments";
      for (int q = 0; q < 3; ++q)
        if (std::fabs(dot(of(s.p[q]) - b, nrm)) > tol)
          return ::testing::AssertionFailure() << "arc " << i << " out of the corner plane";
      cs.peak_kappa = 1.0 / r0;
      cs.junction_kappa = 1.0 / r0;
      cs.max_rate = 0.0;
    } else {
      const tdo_path_segment& s2 = path.seg[i + 1];
      for (int q = 0; q < 4; ++q)
        if (std::fabs(dot(of(s.p[q]) - b, nrm)) > tol || std::fabs(dot(of(s2.p[q]) - b, nrm)) > tol)
          return ::testing::AssertionFailure() << "Bezier pair " << i << " out of the corner plane";
      // Tangent to the lines with zero end curvature: three collinear control points per end.
      for (int q = 0; q < 3; ++q)
        if (dist_line(of(s.p[q]), a, b) > tol || dist_line(of(s2.p[3 - q]), b, d) > tol)
          return ::testing::AssertionFailure() << "Bezier pair " << i << " not tangent to lines";
      cs.junction_kappa = bez_kappa(s, 1.0);
      double peak = std::max(cs.junction_kappa, bez_kappa(s2, 0.0));
      for (int q = 0; q <= 2000; ++q) {
        const double t = q / 2000.0;
        peak = std::max(peak, std::max(bez_kappa(s, t), bez_kappa(s2, t)));
      }
      cs.peak_kappa = peak;
      cs.max_rate = std::max(bezier_max_rate(s), bezier_max_rate(s2));
      if (std::fabs(s2.v_limit - s.v_limit) > 0.0)
        return ::testing::AssertionFailure() << "halves of corner " << c << " differ in speed";
      ++i;  // second half done
    }
    // Lateral acceleration and jerk at the speed cap.
    if (cs.v_limit * cs.v_limit * cs.peak_kappa > in.a_lat_max * (1.0 + 1e-6))
      return ::testing::AssertionFailure() << "corner " << c << " lateral acceleration "
                                           << cs.v_limit * cs.v_limit * cs.peak_kappa;
    if (cs.v_limit * cs.v_limit * cs.v_limit * cs.max_rate > in.j_max * (1.0 + 2e-3))
      return ::testing::AssertionFailure()
             << "corner " << c << " lateral jerk " << std::pow(cs.v_limit, 3.0) * cs.max_rate;
    seen->corners.push_back(cs);
  }
  if (seen->corners.size() != out.n_corners || seen->stops.size() != out.n_stops)
    return ::testing::AssertionFailure()
           << "counts: corners " << seen->corners.size() << " vs " << out.n_corners << ", stops "
           << seen->stops.size() << " vs " << out.n_stops;
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// A smoothing context in an exactly footprint-sized heap block.

class Smoother {
 public:
  explicit Smoother(uint32_t max_waypoints = 64, uint32_t max_segments = 0,
                    uint32_t max_shrinks = 8) {
    cfg_.max_waypoints = max_waypoints;
    cfg_.max_segments = max_segments != 0 ? max_segments : 3u * max_waypoints;
    cfg_.max_shrinks = max_shrinks;
    const size_t bytes = tdo_smooth_footprint(&cfg_);
    mem_.assign(bytes, 0u);
    tdo_arena_init(&arena_, mem_.data(), mem_.size());
    status_ = tdo_smooth_init(&ctx_, &arena_, &cfg_);
  }
  tdo_status status() const { return status_; }
  tdo_smooth* ctx() { return ctx_; }
  tdo_status run(const tdo_smooth_input& in, tdo_smooth_output* out) {
    return tdo_smooth_run(ctx_, &in, out);
  }

 private:
  tdo_smooth_config cfg_{};
  std::vector<unsigned char> mem_;
  tdo_arena arena_{};
  tdo_smooth* ctx_ = nullptr;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

/** The pipeline defaults (v = a = 3, j = 10, stop at 150 degrees), no grid. */
tdo_smooth_input default_input(const std::vector<tdo_vec3>& w,
                               tdo_smoothing mode = TDO_SMOOTHING_G2) {
  tdo_smooth_input in{};
  in.grid = nullptr;
  in.waypoints = w.data();
  in.n_waypoints = static_cast<uint32_t>(w.size());
  in.mode = mode;
  in.clearance = 0.5;
  in.k = 1.0;
  in.v_cruise = 3.0;
  in.v_max = 3.0;
  in.a_lat_max = 3.0;
  in.j_max = 10.0;
  in.stop_angle = deg(150.0);
  in.min_radius = 0.0;
  return in;
}

/** Paper eq. 8. */
double eq8_radius(const tdo_smooth_input& in, double theta) {
  return in.k * theta / (2.0 * std::sin(theta / 2.0)) * in.v_cruise * in.v_cruise / in.a_lat_max;
}

/** A planar corner at (1,-2,3): legs of `len` along e1, then turning by theta (plane may tilt). */
std::vector<tdo_vec3> corner_polyline(double theta, double len, bool tilted = false) {
  P e1{1, 0, 0}, e2{0, 1, 0};
  if (tilted) {
    e1 = unit(P{1, 2, 2});
    e2 = unit(cross(P{0.3, -1, 0.7}, e1));
  }
  const P w1{1, -2, 3};  // the corner near the origin: fine position resolution around it
  const P w0 = w1 - e1 * len;
  const P w2 = w1 + (e1 * std::cos(theta) + e2 * std::sin(theta)) * len;
  return {v3(w0), v3(w1), v3(w2)};
}

// ---------------------------------------------------------------------------------------------
// Known answers.

TEST(SmoothG2, GivenRightAngleCorner_WhenSmoothed_ThenSpiralPairWithPeakCurvatureOneOverR) {
  // GIVEN a 90 degree corner with long legs and a j_max so large that eq. 8 alone sets r
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(20, 0, 0), v3(20, 20, 0)};
  tdo_smooth_input in = default_input(w);
  in.j_max = 1e9;
  Smoother sm;
  ASSERT_EQ(sm.status(), TDO_OK);
  // WHEN smoothed
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  // THEN line, Bezier, Bezier, line, G1 and G2, exact ends
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  ASSERT_EQ(out.path.n, 4u);
  EXPECT_EQ(out.path.seg[0].kind, TDO_SEGMENT_LINE);
  EXPECT_EQ(out.path.seg[1].kind, TDO_SEGMENT_BEZIER);
  EXPECT_EQ(out.path.seg[2].kind, TDO_SEGMENT_BEZIER);
  EXPECT_EQ(out.path.seg[3].kind, TDO_SEGMENT_LINE);
  ASSERT_EQ(seen.corners.size(), 1u);
  EXPECT_EQ(out.n_shrunk, 0u);
  EXPECT_EQ(out.n_stops, 0u);
  // AND the peak curvature is 1/r (eq. 8), reached at the junction of the halves
  const double r = eq8_radius(in, kPi / 2.0);
  EXPECT_NEAR(seen.corners[0].peak_kappa * r, 1.0, 1e-6);
  EXPECT_NEAR(seen.corners[0].junction_kappa * r, 1.0, 1e-6);
  // AND curvature is zero where the spirals meet the lines
  EXPECT_LT(bez_kappa(out.path.seg[1], 0.0), 1e-9);
  EXPECT_LT(bez_kappa(out.path.seg[2], 1.0), 1e-9);
  EXPECT_LT(kappa_end_from_positions(out.path.seg[1], false), 1e-4);
  // AND the junction sits on the bisector, symmetric
  const P j = seg_end(out.path.seg[1]);
  EXPECT_NEAR(j.x - 20.0, -(j.y - 0.0), 1e-12);
  // AND the corner flies at v_max: sqrt(a_lat r) = sqrt(3 * 3.33) > 3
  EXPECT_DOUBLE_EQ(out.path.seg[1].v_limit, 3.0);
  EXPECT_DOUBLE_EQ(out.path.seg[0].v_limit, 3.0);
}

TEST(SmoothG2, GivenDeflectionsFromTinyToSharp_WhenSmoothed_ThenPeakIsOneOverRAndMonotone) {
  Smoother sm;
  for (double d : {0.1, 1.0, 5.0, 20.0, 45.0, 60.0, 90.0, 120.0, 135.0, 149.0}) {
    SCOPED_TRACE(d);
    // GIVEN a corner of d degrees in a tilted plane, legs long enough for any radius
    const std::vector<tdo_vec3> w = corner_polyline(deg(d), 400.0, true);
    tdo_smooth_input in = default_input(w);
    in.j_max = 1e12;  // eq. 8 alone
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    ASSERT_EQ(seen.corners.size(), 1u);
    const double theta = deflection(w, 1);
    const double r = eq8_radius(in, theta);
    // THEN the maximum curvature is 1/r within 1e-6 relative, attained at the junction
    EXPECT_NEAR(seen.corners[0].peak_kappa * r, 1.0, 1e-6);
    EXPECT_NEAR(seen.corners[0].junction_kappa * r, 1.0, 1e-6);
    // AND it rises monotonically along the first half (no overshoot) and is flat at the junction
    const tdo_path_segment& b = out.path.seg[1];
    const double dt = 1e-5;
    const double slope = (bez_kappa(b, 1.0) - bez_kappa(b, 1.0 - dt)) / (dt * norm(bez_d1(b, 1.0)));
    EXPECT_LT(std::fabs(slope), 1e-3 * seen.corners[0].max_rate);
    double prev = -1.0;
    for (int q = 0; q <= 1000; ++q) {
      const double k = bez_kappa(b, q / 1000.0);
      ASSERT_GE(k, prev - 1e-9 / r) << "t " << q / 1000.0;
      prev = k;
    }
  }
}

TEST(SmoothG2, GivenDefaultJerkLimit_WhenSmoothed_ThenRadiusGrowsSoLateralJerkFitsAtCruise) {
  Smoother sm;
  for (double d : {2.0, 10.0, 30.0, 60.0, 100.0, 140.0}) {
    SCOPED_TRACE(d);
    // GIVEN a corner with room to spare and the default j_max = 10 m/s^3
    const std::vector<tdo_vec3> w = corner_polyline(deg(d), 300.0);
    const tdo_smooth_input in = default_input(w);
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));  // includes v^3 max|dkappa/ds| <= j_max
    ASSERT_EQ(seen.corners.size(), 1u);
    const CornerSeen& c = seen.corners[0];
    // THEN the corner is never tighter than eq. 8 and is flown at cruise speed
    EXPECT_LE(c.peak_kappa, (1.0 + 1e-6) / eq8_radius(in, deflection(w, 1)));
    EXPECT_NEAR(c.v_limit, in.v_cruise, 1e-9);
    // AND at cruise speed lateral jerk stays within j_max (measured by finite differences)
    EXPECT_LE(std::pow(in.v_cruise, 3.0) * c.max_rate, in.j_max * (1.0 + 2e-3));
    EXPECT_EQ(out.n_shrunk, 0u);
  }
}

TEST(SmoothArc, GivenRightAngleCorner_WhenArcMode_ThenTangentArcWithCurvatureJump) {
  // GIVEN a 90 degree corner
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(20, 0, 0), v3(20, 20, 0)};
  const tdo_smooth_input in = default_input(w, TDO_SMOOTHING_ARC);
  Smoother sm;
  tdo_smooth_output out{};
  // WHEN smoothed with arcs
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  ASSERT_EQ(out.path.n, 3u);
  ASSERT_EQ(out.path.seg[1].kind, TDO_SEGMENT_ARC);
  const double r = eq8_radius(in, kPi / 2.0);
  // THEN the arc has radius r and tangent length r tan(theta/2) = r
  EXPECT_NEAR(1.0 / seen.corners[0].peak_kappa, r, 1e-9);
  EXPECT_NEAR(seen.corners[0].tangent_len, r, 1e-9);
  EXPECT_NEAR(out.path.seg[1].length, r * kPi / 2.0, 1e-9);
  // AND curvature jumps from 0 to 1/r where the arc meets the lines (measured from positions)
  EXPECT_NEAR(kappa_end_from_positions(out.path.seg[0], true), 0.0, 1e-6);
  EXPECT_NEAR(kappa_end_from_positions(out.path.seg[1], false), 1.0 / r, 1e-4);
  EXPECT_NEAR(kappa_end_from_positions(out.path.seg[1], true), 1.0 / r, 1e-4);
  EXPECT_NEAR(kappa_end_from_positions(out.path.seg[2], false), 0.0, 1e-6);
  // AND speed through it is min(v_max, sqrt(a_lat r))
  EXPECT_NEAR(out.path.seg[1].v_limit, std::min(in.v_max, std::sqrt(in.a_lat_max * r)), 1e-12);
}

TEST(SmoothFit, GivenShortSegments_WhenSmoothed_ThenCornersShrinkToFitAndSlowDown) {
  // GIVEN two 90 degree corners 2 m apart (each would like a ~5 m tangent length)
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(10, 0, 0), v3(10, 2, 0), v3(20, 2, 0)};
  for (tdo_smoothing mode : {TDO_SMOOTHING_G2, TDO_SMOOTHING_ARC}) {
    SCOPED_TRACE(mode);
    const tdo_smooth_input in = default_input(w, mode);
    Smoother sm;
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    // THEN both corners are shrunk, they share the middle segment fairly (1 m each)
    EXPECT_EQ(out.n_shrunk, 2u);
    ASSERT_EQ(seen.corners.size(), 2u);
    for (const CornerSeen& c : seen.corners) {
      EXPECT_LE(c.tangent_len, 1.0 + 1e-9);
      EXPECT_GT(c.peak_kappa, 1.0 / eq8_radius(in, kPi / 2.0));
      // AND the speed drops below v_max and respects a_lat at the smaller radius
      EXPECT_LT(c.v_limit, in.v_max);
      EXPECT_LE(c.v_limit * c.v_limit * c.peak_kappa, in.a_lat_max * (1.0 + 1e-6));
    }
    // AND they do not overlap: the middle line has non-negative length (checked: joins exact)
    EXPECT_EQ(out.n_stops, 0u);
  }
}

TEST(SmoothFit, GivenCornerNextToStart_WhenSmoothed_ThenItMayUseTheWholeFirstSegment) {
  // GIVEN a 90 degree corner 3 m after the start (needs ~5.3 m) and a long outgoing leg
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(3, 0, 0), v3(3, 30, 0)};
  tdo_smooth_input in = default_input(w);
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  // THEN the corner starts exactly at the start point: the first segment is a Bezier
  ASSERT_EQ(seen.corners.size(), 1u);
  EXPECT_EQ(out.path.seg[0].kind, TDO_SEGMENT_BEZIER);
  EXPECT_NEAR(seen.corners[0].tangent_len, 3.0, 1e-12);
  EXPECT_EQ(out.n_shrunk, 1u);
}

TEST(SmoothStop, GivenNearUTurn_WhenSmoothed_ThenStopPointAtTheWaypoint) {
  // GIVEN a 170 degree deflection (beyond stop_angle = 150 degrees)
  const std::vector<tdo_vec3> w = corner_polyline(deg(170.0), 10.0);
  for (tdo_smoothing mode : {TDO_SMOOTHING_G2, TDO_SMOOTHING_ARC}) {
    const tdo_smooth_input in = default_input(w, mode);
    Smoother sm;
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    // THEN the path is the polyline, stopping exactly at the waypoint
    ASSERT_EQ(out.path.n, 2u);
    EXPECT_EQ(out.n_stops, 1u);
    EXPECT_EQ(out.n_corners, 0u);
    EXPECT_EQ(out.path.seg[0].stop_at_end, 1);
    EXPECT_EQ(out.path.seg[1].stop_at_end, 0);
    EXPECT_TRUE(same(out.path.seg[0].p[1], w[1]));
    ASSERT_EQ(seen.stops.size(), 1u);
    EXPECT_EQ(seen.stops[0], 1u);
  }
}

TEST(SmoothStop, GivenCornerThatFitsOnlyBelowMinRadius_WhenSmoothed_ThenStopPoint) {
  // GIVEN the 2 m zig-zag (fits only with r ~ 0.63 m) and a minimum radius of 1 m
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(10, 0, 0), v3(10, 2, 0), v3(20, 2, 0)};
  tdo_smooth_input in = default_input(w);
  in.min_radius = 1.0;
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  // THEN both corners are stop points and the path is the polyline
  EXPECT_EQ(out.n_stops, 2u);
  EXPECT_EQ(out.n_corners, 0u);
  EXPECT_EQ(out.path.n, 3u);
}

TEST(SmoothNone, GivenPolyline_WhenModeNone_ThenPolylineWithStopAtEveryCorner) {
  // GIVEN corners and one collinear waypoint
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(5, 0, 0), v3(10, 0, 0), v3(10, 5, 1),
                                   v3(4, 7, 2)};
  const tdo_smooth_input in = default_input(w, TDO_SMOOTHING_NONE);
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  // THEN 4 lines, stops at the two real corners, none at the collinear point
  ASSERT_EQ(out.path.n, 4u);
  EXPECT_EQ(out.n_stops, 2u);
  EXPECT_EQ(out.path.seg[0].stop_at_end, 0);
  EXPECT_EQ(out.path.seg[1].stop_at_end, 1);
  EXPECT_EQ(out.path.seg[2].stop_at_end, 1);
  EXPECT_NEAR(out.path.length, 5.0 + 5.0 + std::sqrt(26.0) + std::sqrt(41.0), 1e-12);
}

TEST(SmoothG2, GivenCollinearAndDuplicateWaypoints_WhenSmoothed_ThenStraightThroughExactEnds) {
  // GIVEN a straight polyline with a repeated point and a repeated goal
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(1, 1, 1),       v3(1, 1, 1),
                                   v3(3, 3, 3), v3(3.5, 3.5, 3.5), v3(3.5, 3.5, 3.5)};
  const tdo_smooth_input in = default_input(w);
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  const std::vector<tdo_vec3> distinct = {w[0], w[1], w[3], w[4]};
  Seen seen;
  ASSERT_TRUE(check_path(distinct, out, in, &seen));
  // THEN only lines, no corners, no stops
  EXPECT_EQ(out.n_corners, 0u);
  EXPECT_EQ(out.n_stops, 0u);
  for (uint32_t i = 0; i < out.path.n; ++i) EXPECT_EQ(out.path.seg[i].kind, TDO_SEGMENT_LINE);
  EXPECT_NEAR(out.path.length, 3.5 * std::sqrt(3.0), 1e-12);
}

TEST(SmoothG2, GivenTwoWaypoints_WhenSmoothed_ThenOneExactLine) {
  const std::vector<tdo_vec3> w = {v3(0.1, 0.2, 0.3), v3(4, 5, 6)};
  const tdo_smooth_input in = default_input(w);
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  ASSERT_EQ(out.path.n, 1u);
  EXPECT_TRUE(same(out.path.seg[0].p[0], w[0]));
  EXPECT_TRUE(same(out.path.seg[0].p[1], w[1]));
}

TEST(SmoothChecker, GivenArcOutput_WhenCheckedForG2_ThenTheCheckerSeesTheCurvatureJump) {
  // GIVEN an arc-mode path (curvature jumps 0 -> 1/r at the lines)
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(20, 0, 0), v3(20, 20, 0)};
  const tdo_smooth_input in = default_input(w, TDO_SMOOTHING_ARC);
  Smoother sm;
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  // WHEN the checker is asked for curvature continuity THEN it rejects the path
  tdo_smooth_input as_g2 = in;
  as_g2.mode = TDO_SMOOTHING_G2;
  Seen seen;
  const ::testing::AssertionResult r = check_path(w, out, as_g2, &seen);
  EXPECT_FALSE(r);
  EXPECT_NE(std::string(r.message()).find("curvature jumps"), std::string::npos) << r.message();
}

// ---------------------------------------------------------------------------------------------
// Clearance against obstacle boxes (real grid, real collision queries; checked by exact point-box
// distances of samples every 2 mm).

constexpr double kClearance = 0.5;

/** A 30 x 30 x 10 m grid at 1 m resolution holding `boxes`. */
class World {
 public:
  explicit World(const std::vector<tdo_box>& boxes)
      : tp_(tdo_test::make_cap(30u * 30u * 10u, 1000u, 100u, 64u)), boxes_(boxes) {
    tdo_grid_desc d{};
    d.nx = 30;
    d.ny = 30;
    d.nz = 10;
    d.res = 1.0;
    d.origin = v3(0, 0, 0);
    status_ = tp_.status();
    if (status_ == TDO_OK) status_ = tdo_grid_reset(tp_.grid(), &d);
    for (const tdo_box& b : boxes_)
      if (status_ == TDO_OK) status_ = tdo_grid_add_box(tp_.grid(), &b);
    if (status_ == TDO_OK) status_ = tdo_grid_finish(tp_.grid(), kClearance);
  }
  tdo_status status() const { return status_; }
  const tdo_grid* grid() { return tp_.grid(); }
  /** Exact distance from p to the nearest box. */
  double distance(const P& p) const {
    double d = kInf;
    for (const tdo_box& b : boxes_) d = std::min(d, tdo_test::distance_to_box(v3(p), b));
    return d;
  }
  /** Smallest distance over samples every `step` m along the path. */
  double min_distance(const tdo_path& path, double step = 0.002) const {
    double d = kInf;
    for (uint32_t i = 0; i < path.n; ++i) {
      const tdo_path_segment& s = path.seg[i];
      const int n = 1 + static_cast<int>(s.length / step);
      for (int q = 0; q <= n; ++q)
        d = std::min(d, distance(of(tdo_segment_point(&s, s.length * q / n))));
    }
    return d;
  }

 private:
  tdo_test::TestPlanner tp_;
  std::vector<tdo_box> boxes_;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

tdo_box box(double x0, double y0, double z0, double x1, double y1, double z1) {
  tdo_box b{};
  b.min = v3(x0, y0, z0);
  b.max = v3(x1, y1, z1);
  return b;
}

TEST(SmoothClearance, GivenBoxInsideTheCorner_WhenSmoothed_ThenCornerShrinksAndKeepsClearance) {
  // GIVEN an L-shaped polyline 0.6 m from a box in the inside of its corner (clear at 0.5 m)
  const std::vector<tdo_vec3> w = {v3(2, 3, 5), v3(20, 3, 5), v3(20, 25, 5)};
  World world({box(16.5, 3.6, 0.0, 19.4, 7.0, 10.0)});
  ASSERT_EQ(world.status(), TDO_OK);
  for (tdo_smoothing mode : {TDO_SMOOTHING_G2, TDO_SMOOTHING_ARC}) {
    SCOPED_TRACE(mode);
    tdo_smooth_input in = default_input(w, mode);
    in.clearance = kClearance;
    Smoother sm;
    tdo_smooth_output free_out{};
    ASSERT_EQ(sm.run(in, &free_out), TDO_OK);
    // (without the clearance check the corner would cut into the margin)
    ASSERT_LT(world.min_distance(free_out.path), kClearance);
    // WHEN smoothed against the grid
    in.grid = world.grid();
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    // THEN the corner is still a curve, shrunk, slower, and every point keeps the clearance
    EXPECT_EQ(out.n_corners, 1u);
    EXPECT_EQ(out.n_shrunk, 1u);
    EXPECT_EQ(out.n_stops, 0u);
    EXPECT_GE(out.n_clear_checks, 2u);
    EXPECT_GE(world.min_distance(out.path), kClearance - 1e-9);
    EXPECT_LT(out.path.seg[1].v_limit, free_out.path.seg[1].v_limit + 1e-12);
  }
}

TEST(SmoothClearance, GivenNoShrinksAllowed_WhenCornerHitsTheMargin_ThenStopPoint) {
  // GIVEN the same corner and box, and max_shrinks = 0
  const std::vector<tdo_vec3> w = {v3(2, 3, 5), v3(20, 3, 5), v3(20, 25, 5)};
  World world({box(16.5, 3.6, 0.0, 19.4, 7.0, 10.0)});
  ASSERT_EQ(world.status(), TDO_OK);
  tdo_smooth_input in = default_input(w);
  in.grid = world.grid();
  in.clearance = kClearance;
  Smoother sm(16, 0, 0);
  tdo_smooth_output out{};
  ASSERT_EQ(sm.run(in, &out), TDO_OK);
  Seen seen;
  ASSERT_TRUE(check_path(w, out, in, &seen));
  // THEN the corner becomes a stop point: the verified polyline itself
  EXPECT_EQ(out.n_stops, 1u);
  EXPECT_EQ(out.n_corners, 0u);
  EXPECT_GE(world.min_distance(out.path), kClearance - 1e-9);
}

TEST(SmoothClearance, GivenSeededRandomPolylinesAmongBoxes_WhenSmoothed_ThenClearanceHolds) {
  Rng rng(4242u);
  Smoother sm(16);
  int shrunk = 0, corners = 0;
  for (int n = 0; n < 120; ++n) {
    SCOPED_TRACE(n);
    // GIVEN a random polyline inside the grid and boxes at least clearance + 1 cm away from it
    std::vector<tdo_vec3> w;
    const uint32_t nw = 3u + rng.below(6u);
    for (uint32_t i = 0; i < nw; ++i)
      w.push_back(v3(rng.uniform(2, 28), rng.uniform(2, 28), rng.uniform(1.5, 8.5)));
    std::vector<tdo_box> boxes;
    for (int tries = 0; tries < 200 && boxes.size() < 12; ++tries) {
      const P c{rng.uniform(0, 30), rng.uniform(0, 30), rng.uniform(0, 10)};
      const P h{rng.uniform(0.2, 2.5), rng.uniform(0.2, 2.5), rng.uniform(0.2, 2.5)};
      const tdo_box b = box(c.x - h.x, c.y - h.y, c.z - h.z, c.x + h.x, c.y + h.y, c.z + h.z);
      bool ok = true;
      for (size_t j = 0; ok && j + 1 < w.size(); ++j) {
        const P a = of(w[j]), e = of(w[j + 1]);
        const int steps = 1 + static_cast<int>(norm(e - a) / 0.005);
        for (int q = 0; ok && q <= steps; ++q)
          ok = tdo_test::distance_to_box(v3(a + (e - a) * (static_cast<double>(q) / steps)), b) >=
               kClearance + 0.01;
      }
      if (ok) boxes.push_back(b);
    }
    World world(boxes);
    ASSERT_EQ(world.status(), TDO_OK);
    tdo_smooth_input in =
        default_input(w, rng.below(3u) == 0 ? TDO_SMOOTHING_ARC : TDO_SMOOTHING_G2);
    in.grid = world.grid();
    in.clearance = kClearance;
    in.k = rng.uniform(0.5, 3.0);
    // WHEN smoothed
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    // THEN the path is valid and keeps the clearance everywhere
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    ASSERT_GE(world.min_distance(out.path), kClearance - 1e-9);
    shrunk += static_cast<int>(out.n_shrunk);
    corners += static_cast<int>(out.n_corners);
  }
  EXPECT_GT(corners, 200);
  EXPECT_GT(shrunk, 20);
}

// ---------------------------------------------------------------------------------------------
// Named statuses.

TEST(SmoothStatus, GivenInvalidParameters_WhenRun_ThenInvalidArgument) {
  const std::vector<tdo_vec3> w = {v3(0, 0, 0), v3(10, 0, 0), v3(10, 10, 0)};
  Smoother sm;
  tdo_smooth_output out{};
  auto expect_invalid = [&](const tdo_smooth_input& in, const char* what) {
    EXPECT_EQ(sm.run(in, &out), TDO_ERR_INVALID_ARGUMENT) << what;
    EXPECT_EQ(out.path.n, 0u) << what;
  };
  const tdo_smooth_input base = default_input(w);
  ASSERT_EQ(sm.run(base, &out), TDO_OK);
  const double bad[] = {0.0, -1.0, kNan, kInf, -kInf};
  for (double b : bad) {
    tdo_smooth_input in = base;
    in.k = b;
    expect_invalid(in, "k");
    in = base;
    in.v_cruise = b;
    expect_invalid(in, "v_cruise");
    in = base;
    in.v_max = b;
    expect_invalid(in, "v_max");
    in = base;
    in.a_lat_max = b;
    expect_invalid(in, "a_lat_max");
    in = base;
    in.j_max = b;
    expect_invalid(in, "j_max");
    in = base;
    in.stop_angle = b;
    expect_invalid(in, "stop_angle");
  }
  for (double b : {-0.1, kNan, kInf}) {
    tdo_smooth_input in = base;
    in.clearance = b;
    expect_invalid(in, "clearance");
    in = base;
    in.min_radius = b;
    expect_invalid(in, "min_radius");
  }
  tdo_smooth_input in = base;
  in.mode = static_cast<tdo_smoothing>(3);
  expect_invalid(in, "mode");
  in = base;
  in.waypoints = nullptr;
  expect_invalid(in, "null waypoints");
  in = base;
  in.n_waypoints = 1;
  expect_invalid(in, "one waypoint");
  const std::vector<tdo_vec3> nan_w = {v3(0, 0, 0), v3(kNan, 0, 0), v3(10, 10, 0)};
  expect_invalid(default_input(nan_w), "NaN waypoint");
  const std::vector<tdo_vec3> inf_w = {v3(0, 0, 0), v3(10, 0, kInf)};
  expect_invalid(default_input(inf_w), "inf waypoint");
  const std::vector<tdo_vec3> same_w = {v3(1, 2, 3), v3(1, 2, 3), v3(1, 2, 3)};
  expect_invalid(default_input(same_w), "start equals goal");
  EXPECT_EQ(tdo_smooth_run(nullptr, &base, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_smooth_run(sm.ctx(), nullptr, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_smooth_run(sm.ctx(), &base, nullptr), TDO_ERR_INVALID_ARGUMENT);
}

TEST(SmoothStatus, GivenTooManyWaypointsOrSegments_WhenRun_ThenPathCapacityAndNoPath) {
  // GIVEN a zig-zag of 10 waypoints (8 corners: 9 lines + 16 Beziers in g2)
  std::vector<tdo_vec3> w;
  for (int i = 0; i < 10; ++i) w.push_back(v3(10.0 * i, (i % 2) * 10.0, 0.0));
  const tdo_smooth_input in = default_input(w);
  tdo_smooth_output out{};
  // WHEN the context holds fewer waypoints THEN path capacity
  Smoother small_w(9);
  ASSERT_EQ(small_w.status(), TDO_OK);
  EXPECT_EQ(small_w.run(in, &out), TDO_ERR_PATH_CAPACITY);
  EXPECT_EQ(out.path.n, 0u);
  // WHEN it holds the waypoints but one segment too few THEN path capacity, no partial path
  Smoother exact(10, 25);
  ASSERT_EQ(exact.run(in, &out), TDO_OK);
  ASSERT_EQ(out.path.n, 25u);
  Smoother short_s(10, 24);
  EXPECT_EQ(short_s.run(in, &out), TDO_ERR_PATH_CAPACITY);
  EXPECT_EQ(out.path.n, 0u);
  EXPECT_EQ(out.path.seg, nullptr);
}

TEST(SmoothStatus, GivenBadConfigOrSmallArena_WhenInit_ThenNamedStatus) {
  tdo_smooth_config cfg{0u, 10u, 4u};
  EXPECT_EQ(tdo_smooth_footprint(&cfg), 0u);
  unsigned char mem[64];
  tdo_arena arena;
  tdo_arena_init(&arena, mem, sizeof mem);
  tdo_smooth* ctx = nullptr;
  EXPECT_EQ(tdo_smooth_init(&ctx, &arena, &cfg), TDO_ERR_INVALID_ARGUMENT);
  cfg = tdo_smooth_config{10u, 30u, 4u};
  EXPECT_GT(tdo_smooth_footprint(&cfg), sizeof mem);
  EXPECT_EQ(tdo_smooth_init(&ctx, &arena, &cfg), TDO_ERR_ARENA_TOO_SMALL);
  EXPECT_EQ(tdo_smooth_init(nullptr, &arena, &cfg), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_smooth_init(&ctx, nullptr, &cfg), TDO_ERR_INVALID_ARGUMENT);
}

// ---------------------------------------------------------------------------------------------
// Seeded random polylines.

/** A random polyline: segment lengths 0.2..40 m, deflections from exactly 0 to nearly 180 deg. */
std::vector<tdo_vec3> random_polyline(Rng& rng) {
  const uint32_t n = 2u + rng.below(11u);
  std::vector<tdo_vec3> w;
  P p{rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50)};
  P dir = unit(P{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1) + 1e-3});
  w.push_back(v3(p));
  for (uint32_t i = 1; i < n; ++i) {
    const double len = std::exp(rng.uniform(std::log(0.2), std::log(40.0)));
    p = p + dir * len;
    w.push_back(v3(p));
    // next direction: straight, small, moderate or sharp turn about a random axis
    const uint32_t kind = rng.below(8u);
    double turn;
    if (kind == 0)
      turn = 0.0;
    else if (kind == 1)
      turn = rng.uniform(1e-5, deg(2.0));
    else if (kind == 2)
      turn = rng.uniform(deg(160.0), deg(179.9));
    else
      turn = rng.uniform(deg(2.0), deg(160.0));
    P axis = cross(dir, P{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    if (norm(axis) < 1e-3) axis = cross(dir, P{0.3, 0.5, 0.9});
    const P e2 = unit(axis - dir * dot(axis, dir));
    dir = unit(dir * std::cos(turn) + cross(dir, e2) * std::sin(turn));
  }
  return w;
}

TEST(SmoothProperty, GivenSeededRandomPolylines_WhenSmoothed_ThenEveryInvariantHolds) {
  Rng rng(0x5300u);
  Smoother sm(16);
  int g2_cases = 0, arc_cases = 0, corners = 0, stops = 0, shrunk = 0;
  double worst_g1 = 0.0, worst_g2 = 0.0, worst_est = 0.0;
  for (int n = 0; n < 400; ++n) {
    SCOPED_TRACE(n);
    // GIVEN a random polyline and random limits
    const std::vector<tdo_vec3> w = random_polyline(rng);
    const uint32_t m = rng.below(10u);
    const tdo_smoothing mode =
        m < 6 ? TDO_SMOOTHING_G2 : (m < 9 ? TDO_SMOOTHING_ARC : TDO_SMOOTHING_NONE);
    tdo_smooth_input in = default_input(w, mode);
    in.k = rng.uniform(0.3, 3.0);
    in.v_max = rng.uniform(0.5, 8.0);
    in.v_cruise = rng.uniform(0.5, 1.2) * in.v_max;
    in.a_lat_max = rng.uniform(0.5, 8.0);
    in.j_max = rng.uniform(1.0, 40.0);
    in.stop_angle = rng.uniform(deg(100.0), deg(179.0));
    // WHEN smoothed
    tdo_smooth_output out{};
    ASSERT_EQ(sm.run(in, &out), TDO_OK);
    // THEN the checker accepts it
    Seen seen;
    ASSERT_TRUE(check_path(w, out, in, &seen));
    worst_g1 = std::max(worst_g1, seen.max_g1_error);
    worst_g2 = std::max(worst_g2, seen.max_g2_error);
    worst_est = std::max(worst_est, seen.max_g2_est_error);
    // AND every corner sharper than stop_angle is a stop; every real corner is a curve or a stop
    std::vector<int> state(w.size(), 0);  // 1 curve, 2 stop
    for (const CornerSeen& c : seen.corners) state[c.waypoint] = 1;
    for (uint32_t s : seen.stops) state[s] = 2;
    for (size_t i = 1; i + 1 < w.size(); ++i) {
      const double th = deflection(w, i);
      if (th > in.stop_angle) {
        EXPECT_EQ(state[i], 2) << "waypoint " << i << " theta " << th;
      }
      if (th > 1e-6) {
        EXPECT_NE(state[i], 0) << "waypoint " << i << " theta " << th;
      }
      if (mode == TDO_SMOOTHING_NONE && th > 1e-6) {
        EXPECT_EQ(state[i], 2);
      }
    }
    // AND corner radii are never below eq. 8 unless the corner was shrunk
    for (const CornerSeen& c : seen.corners) {
      const double r8 = eq8_radius(in, deflection(w, c.waypoint));
      if (out.n_shrunk == 0) {
        EXPECT_LE(c.peak_kappa * r8, 1.0 + 1e-6);
      }
    }
    g2_cases += mode == TDO_SMOOTHING_G2;
    arc_cases += mode == TDO_SMOOTHING_ARC;
    corners += static_cast<int>(out.n_corners);
    stops += static_cast<int>(out.n_stops);
    shrunk += static_cast<int>(out.n_shrunk);
  }
  // The generator exercises every branch.
  EXPECT_GT(g2_cases, 150);
  EXPECT_GT(arc_cases, 60);
  EXPECT_GT(corners, 500);
  EXPECT_GT(stops, 100);
  EXPECT_GT(shrunk, 100);
  EXPECT_LT(worst_g1, 1e-6);
  EXPECT_LT(worst_g2, 1e-3);
  EXPECT_LT(worst_est, 2e-2);
  RecordProperty("worst_g1_rad", std::to_string(worst_g1));
  RecordProperty("worst_g2_relative_jump", std::to_string(worst_g2));
}

TEST(SmoothProperty, GivenSameInput_WhenRunTwice_ThenBitIdentical) {
  Rng rng(99u);
  Smoother a(16), b(16);
  for (int n = 0; n < 50; ++n) {
    const std::vector<tdo_vec3> w = random_polyline(rng);
    const tdo_smooth_input in = default_input(w, n % 2 ? TDO_SMOOTHING_ARC : TDO_SMOOTHING_G2);
    tdo_smooth_output oa{}, ob{};
    ASSERT_EQ(a.run(in, &oa), TDO_OK);
    ASSERT_EQ(b.run(in, &ob), TDO_OK);
    ASSERT_EQ(oa.path.n, ob.path.n);
    for (uint32_t i = 0; i < oa.path.n; ++i) {
      const tdo_path_segment& x = oa.path.seg[i];
      const tdo_path_segment& y = ob.path.seg[i];
      EXPECT_EQ(x.kind, y.kind);
      EXPECT_EQ(0, std::memcmp(x.p, y.p, sizeof x.p));
      EXPECT_EQ(0, std::memcmp(&x.length, &y.length, sizeof x.length));
      EXPECT_EQ(0, std::memcmp(&x.v_limit, &y.v_limit, sizeof x.v_limit));
      EXPECT_EQ(x.stop_at_end, y.stop_at_end);
    }
    EXPECT_EQ(0, std::memcmp(&oa.path.length, &ob.path.length, sizeof(double)));
  }
}

}  // namespace
