// Property tests of the whole TDO-MSF pipeline (tdo_planner_plan, issue 3) on 200+ seeded random
// maps from tdo-mapgen's generator, the paper's Map1-Map5, the OctoMap building floor geb079 and
// the three OctoMap forests with their published start/goal pairs.
//
// Every plan is judged by an independent checker written here from docs/design.md and path.h; it
// calls no libtdo geometry (no tdo_segment_*, tdo_collision_*, tdo_grid distance queries):
//   1. ends: the path and the trajectory begin exactly at the start and end exactly at the goal
//      (bit-identical doubles);
//   2. clearance: every point of every path piece is at least `clearance` from the obstacle
//      geometry (boxes of the map file, or the occupied voxel cubes of an OcTree):
//      - lines: exact segment-to-box distance (the squared distance is piecewise quadratic in the
//        segment parameter, with breakpoints where a coordinate crosses a slab; each piece is
//        minimised in closed form);
//      - cubic Beziers: certified by subdivision. A piece with control points Q0..Q3 lies in their
//        convex hull, and every hull point is within dev = max(d(Q1, Q0Q3), d(Q2, Q0Q3)) of the
//        chord Q0Q3 (distance to a segment is convex, so its maximum over the hull is at a
//        vertex). Hence distance(curve, obstacles) >= distance(chord, obstacles) - dev, with the
//        chord distance exact. A piece that this bound does not certify is split at t = 1/2 (de
//        Casteljau) down to depth 40; a piece end point (on the curve) closer than the clearance,
//        or an uncertified piece at depth 40, is a violation;
//      - circular arcs: the same with sub-arcs, dev = the sagitta r (1 - cos(phi/2));
//      - and every trajectory sample (exact point-to-box distance);
//      tolerance 1e-9 m, the same as the library's own report (trajectory.h);
//   3. dynamics: v, a, j by finite differences of the sampled positions at dt = 0.01 s, each
//      within 1.01 x its limit (docs/design.md s.5, 1 % for discretisation);
//   4. g2 mode: the path's pieces meet end to start (1e-9 m), with continuous unit tangents
//      (except at stop points, where the vehicle is at rest) and continuous curvature vectors
//      (closed-form line/arc/Bezier end curvatures; 1e-6 1/m + 1e-6 relative) at every junction;
//   5. completeness: plain A* (lambda = mu = 0, no direction constraint) on the same planner and
//      clearance; whenever it finds a path, the full pipeline must return TDO_OK.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "arena_contexts.h"
#include "mapgen.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace fs = std::filesystem;

namespace {

const std::string kMaps = std::string(TDO_SOURCE_DIR) + "/maps";

#ifdef TDO_PROPERTY_RANDOM_MAPS
constexpr int kRandomMaps = TDO_PROPERTY_RANDOM_MAPS;
#else
constexpr int kRandomMaps = 240;
#endif

constexpr double kClearTol = 1e-9;    // m, as the library's feasibility report
constexpr double kLimitTol = 1.01;    // docs/design.md s.5: 1 % for discretisation
constexpr double kJoinTol = 1e-9;     // m, junction gap
constexpr double kTangentTol = 1e-6;  // rad-ish, |T1 - T2|
constexpr double kCurvTol = 1e-6;     // 1/m, plus the same relative
constexpr int kMaxDepth = 40;         // subdivision depth of the curve certification
constexpr double kCap = 0.05;         // m, distances are computed exactly up to clearance + kCap

// ---------------------------------------------------------------------------------------------
// Small vector algebra (own, not libtdo's).

struct V {
  double x, y, z;
};
V vec(const tdo_vec3& p) { return V{p.x, p.y, p.z}; }
V operator+(V a, V b) { return V{a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return V{a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return V{s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(V a) { return std::sqrt(dot(a, a)); }
V lerp(V a, V b, double t) { return a + t * (b - a); }
std::string str(V a) {
  std::ostringstream o;
  o.precision(17);
  o << "(" << a.x << ", " << a.y << ", " << a.z << ")";
  return o.str();
}
/** Bit-identical points. */
bool same(const tdo_vec3& a, const tdo_vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/** Distance from point p to segment [a, b]. */
double point_segment(V p, V a, V b) {
  const V d = b - a;
  const double dd = dot(d, d);
  double t = dd > 0.0 ? dot(p - a, d) / dd : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return norm(p - (a + t * d));
}

struct Box {
  V lo, hi;
};

double axis_gap(double p, double lo, double hi) {
  return p < lo ? lo - p : (p > hi ? p - hi : 0.0);
}

double point_box(V p, const Box& b) {
  const double gx = axis_gap(p.x, b.lo.x, b.hi.x);
  const double gy = axis_gap(p.y, b.lo.y, b.hi.y);
  const double gz = axis_gap(p.z, b.lo.z, b.hi.z);
  return std::sqrt(gx * gx + gy * gy + gz * gz);
}

/**
 * Exact distance from segment [a, b] to the closed box: between consecutive slab crossings each
 * axis gap is one linear function of t (or zero), so the squared distance is a quadratic whose
 * minimum on the piece is found in closed form; the answer is the smallest piece minimum.
 */
double segment_box(V a, V b, const Box& box) {
  const V d = b - a;
  const double pa[3] = {a.x, a.y, a.z};
  const double pd[3] = {d.x, d.y, d.z};
  const double lo[3] = {box.lo.x, box.lo.y, box.lo.z};
  const double hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  double ts[8];
  int n = 0;
  ts[n++] = 0.0;
  ts[n++] = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (!(std::fabs(pd[k]) > 0.0)) continue;
    for (double s : {lo[k], hi[k]}) {
      const double t = (s - pa[k]) / pd[k];
      if (t > 0.0 && t < 1.0) ts[n++] = t;
    }
  }
  for (int i = 1; i < n; ++i)  // insertion sort of at most 8 values
    for (int j = i; j > 0 && ts[j] < ts[j - 1]; --j) std::swap(ts[j], ts[j - 1]);
  const auto at = [&](double t) { return point_box(a + t * d, box); };
  double best = std::min(at(0.0), at(1.0));
  for (int i = 0; i + 1 < n; ++i) {
    const double t0 = ts[i], t1 = ts[i + 1];
    if (!(t1 > t0)) continue;
    const double tm = 0.5 * (t0 + t1);
    double qa = 0.0, qb = 0.0;  // gap_k(t) = c_k + e_k t on this piece; f = sum (c + e t)^2
    for (int k = 0; k < 3; ++k) {
      const double p = pa[k] + tm * pd[k];
      double c = 0.0, e = 0.0;
      if (p < lo[k]) {
        c = lo[k] - pa[k];
        e = -pd[k];
      } else if (p > hi[k]) {
        c = pa[k] - hi[k];
        e = pd[k];
      }
      qa += e * e;
      qb += c * e;
    }
    best = std::min(best, at(t0));
    best = std::min(best, at(t1));
    if (qa > 0.0) {
      const double t = std::min(t1, std::max(t0, -qb / qa));
      best = std::min(best, at(t));
    }
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Obstacle model: the map file's boxes, or its occupied voxel cubes in a hash-free bitmap.

class World {
 public:
  explicit World(const tdo_io::Map& m) : desc_(m.desc) {
    for (const tdo_box& b : m.boxes) boxes_.push_back(Box{vec(b.min), vec(b.max)});
    if (!m.voxels.empty()) {
      occ_.assign(static_cast<size_t>(desc_.nx) * desc_.ny * desc_.nz, 0u);
      for (const tdo_voxel& v : m.voxels) occ_[index(v.i, v.j, v.k)] = 1u;
    }
  }

  /** Exact distance of segment [a, b] to the obstacles, capped at `cap` (m). */
  double segment(V a, V b, double cap) const {
    double best = cap;
    for (const Box& box : boxes_) best = std::min(best, segment_box(a, b, box));
    if (occ_.empty()) return best;
    // Long segments are cut into pieces of at most 2 voxels so the cube scan stays local; the
    // minimum over the pieces is still the exact distance.
    const double len = norm(b - a);
    const int pieces = std::max(1, static_cast<int>(std::ceil(len / (2.0 * desc_.res))));
    for (int p = 0; p < pieces; ++p) {
      const V pa = lerp(a, b, static_cast<double>(p) / pieces);
      const V pb = p + 1 == pieces ? b : lerp(a, b, static_cast<double>(p + 1) / pieces);
      best = std::min(best, cubes_near(pa, pb, best));
    }
    return best;
  }

  double point(V p, double cap) const { return segment(p, p, cap); }

 private:
  size_t index(int64_t i, int64_t j, int64_t k) const {
    return static_cast<size_t>(i + desc_.nx * (j + static_cast<int64_t>(desc_.ny) * k));
  }
  int32_t cell(double w, double o, int32_t n) const {
    const double c = std::floor((w - o) / desc_.res);
    return static_cast<int32_t>(std::min<double>(n - 1, std::max<double>(0.0, c)));
  }
  double cubes_near(V a, V b, double cap) const {
    const double r = cap;  // cubes farther than cap cannot lower the answer
    const tdo_vec3& o = desc_.origin;
    const int32_t i0 = cell(std::min(a.x, b.x) - r, o.x, desc_.nx);
    const int32_t i1 = cell(std::max(a.x, b.x) + r, o.x, desc_.nx);
    const int32_t j0 = cell(std::min(a.y, b.y) - r, o.y, desc_.ny);
    const int32_t j1 = cell(std::max(a.y, b.y) + r, o.y, desc_.ny);
    const int32_t k0 = cell(std::min(a.z, b.z) - r, o.z, desc_.nz);
    const int32_t k1 = cell(std::max(a.z, b.z) + r, o.z, desc_.nz);
    double best = cap;
    for (int32_t k = k0; k <= k1; ++k)
      for (int32_t j = j0; j <= j1; ++j)
        for (int32_t i = i0; i <= i1; ++i) {
          if (!occ_[index(i, j, k)]) continue;
          const Box c{
              V{o.x + i * desc_.res, o.y + j * desc_.res, o.z + k * desc_.res},
              V{o.x + (i + 1) * desc_.res, o.y + (j + 1) * desc_.res, o.z + (k + 1) * desc_.res}};
          best = std::min(best, segment_box(a, b, c));
        }
    return best;
  }

  tdo_grid_desc desc_;
  std::vector<Box> boxes_;
  std::vector<uint8_t> occ_;
};

// ---------------------------------------------------------------------------------------------
// Curve certification.

struct Certify {
  const World* world;
  double clearance;
  double worst = HUGE_VAL;  // smallest distance of a point found on the curve
  V worst_at{0.0, 0.0, 0.0};
  bool uncertified = false;
  long pieces = 0;  // budget: a violation stops the subdivision, so this is never reached on
                    // valid curves (only pieces near a touching point are split further)

  bool done() const { return worst < clearance - kClearTol || uncertified; }

  void on_curve(V p) {
    const double d = world->point(p, clearance + kCap);
    if (d < worst) {
      worst = d;
      worst_at = p;
    }
  }

  void bezier(const std::array<V, 4>& q, int depth) {
    if (done()) return;
    if (++pieces > 200000) {
      uncertified = true;
      return;
    }
    on_curve(q[0]);
    on_curve(q[3]);
    const double dev = std::max(point_segment(q[1], q[0], q[3]), point_segment(q[2], q[0], q[3]));
    const double chord = world->segment(q[0], q[3], clearance + dev + kCap);
    if (chord - dev >= clearance - kClearTol || done()) return;
    if (depth >= kMaxDepth) {
      uncertified = true;
      return;
    }
    const V a = lerp(q[0], q[1], 0.5), b = lerp(q[1], q[2], 0.5), c = lerp(q[2], q[3], 0.5);
    const V ab = lerp(a, b, 0.5), bc = lerp(b, c, 0.5), m = lerp(ab, bc, 0.5);
    bezier({q[0], a, ab, m}, depth + 1);
    bezier({m, bc, c, q[3]}, depth + 1);
  }

  // Arc about centre c in the plane of unit vectors u, w: c + r (cos(al) u + sin(al) w).
  void arc(V c, V u, V w, double r, double a0, double a1, int depth) {
    if (done()) return;
    if (++pieces > 200000) {
      uncertified = true;
      return;
    }
    const V p0 = c + r * (std::cos(a0) * u + std::sin(a0) * w);
    const V p1 = c + r * (std::cos(a1) * u + std::sin(a1) * w);
    on_curve(p0);
    on_curve(p1);
    const double dev = r * (1.0 - std::cos(0.5 * (a1 - a0))) + 1e-12 * r;
    const double chord = world->segment(p0, p1, clearance + dev + kCap);
    if (chord - dev >= clearance - kClearTol || done()) return;
    if (depth >= kMaxDepth) {
      uncertified = true;
      return;
    }
    const double am = 0.5 * (a0 + a1);
    arc(c, u, w, r, a0, am, depth + 1);
    arc(c, u, w, r, am, a1, depth + 1);
  }
};

/** Unit tangent and curvature vector at one end of a segment (closed forms, own). */
struct EndGeometry {
  V t{0, 0, 0};
  V kn{0, 0, 0};
};

EndGeometry end_geometry(const tdo_path_segment& s, bool at_end) {
  EndGeometry g;
  const V p0 = vec(s.p[0]), p1 = vec(s.p[1]), p2 = vec(s.p[2]), p3 = vec(s.p[3]);
  if (s.kind == TDO_SEGMENT_LINE) {
    g.t = (1.0 / norm(p1 - p0)) * (p1 - p0);
  } else if (s.kind == TDO_SEGMENT_BEZIER) {
    const V d1 = at_end ? 3.0 * (p3 - p2) : 3.0 * (p1 - p0);
    const V d2 = at_end ? 6.0 * (p1 - 2.0 * p2 + p3) : 6.0 * (p0 - 2.0 * p1 + p2);
    const double l = norm(d1);
    g.t = (1.0 / l) * d1;
    g.kn = (1.0 / (l * l)) * (d2 - dot(d2, g.t) * g.t);
  } else {  // arc about p2 from p0 to p1
    const V c = p2;
    const V p = at_end ? p1 : p0;
    const V rad = p - c;
    const double r = norm(rad);
    // Tangent: the part of the chord p0 -> p1 orthogonal to the radius points onward at both
    // ends (sweep < pi).
    V dir = p1 - p0;
    dir = dir - (dot(dir, rad) / (r * r)) * rad;
    g.t = (1.0 / norm(dir)) * dir;
    g.kn = (-1.0 / (r * r)) * rad;
  }
  return g;
}

V segment_start(const tdo_path_segment& s) { return vec(s.p[0]); }
V segment_end(const tdo_path_segment& s) {
  return s.kind == TDO_SEGMENT_BEZIER ? vec(s.p[3]) : vec(s.p[1]);
}

struct Limits {
  double v_max, a_max, j_max, dt;
};

/** Pieces the checker saw, by kind, and the junctions it checked. */
struct Seen {
  long lines = 0, beziers = 0, arcs = 0, junctions = 0, samples = 0;
};

/** Check 3: v, a, j by finite differences of the sampled positions, each within kLimitTol x its
 *  limit, and the samples every dt. */
::testing::AssertionResult check_dynamics(const tdo_plan_result& r, const Limits& lim) {
  auto fail = [](const std::string& what) { return ::testing::AssertionFailure() << what; };
  const double dt = lim.dt;
  std::vector<V> v, a;
  for (uint32_t i = 0; i < r.n_samples; ++i) {
    if (std::fabs(r.samples[i].t - i * dt) > 1e-9 * std::max(1.0, i * dt))
      return fail("sample " + std::to_string(i) + " at t = " + std::to_string(r.samples[i].t) +
                  ", expected i * dt");
    if (i + 1 < r.n_samples)
      v.push_back((1.0 / dt) * (vec(r.samples[i + 1].p) - vec(r.samples[i].p)));
  }
  for (size_t i = 0; i < v.size(); ++i) {
    if (norm(v[i]) > kLimitTol * lim.v_max)
      return fail("speed " + std::to_string(norm(v[i])) + " m/s at sample " + std::to_string(i) +
                  " exceeds v_max " + std::to_string(lim.v_max));
    if (i + 1 < v.size()) a.push_back((1.0 / dt) * (v[i + 1] - v[i]));
  }
  for (size_t i = 0; i < a.size(); ++i) {
    if (norm(a[i]) > kLimitTol * lim.a_max)
      return fail("acceleration " + std::to_string(norm(a[i])) + " m/s^2 at sample " +
                  std::to_string(i) + " exceeds a_max " + std::to_string(lim.a_max));
    if (i + 1 < a.size()) {
      const double j = norm((1.0 / dt) * (a[i + 1] - a[i]));
      if (j > kLimitTol * lim.j_max)
        return fail("jerk " + std::to_string(j) + " m/s^3 at sample " + std::to_string(i) +
                    " exceeds j_max " + std::to_string(lim.j_max));
    }
  }
  return ::testing::AssertionSuccess();
}

/**
 * Checks 1-4 on one successful plan. `trajectory`: the plan reached stage 5 (else only the
 * geometric path is checked: ends, clearance, junctions). Tangents are continuous at every
 * junction but a stop point in g2 and arc mode; curvature vectors only in g2 mode.
 */
::testing::AssertionResult check_plan(const World& world, double clearance, const tdo_vec3& start,
                                      const tdo_vec3& goal, const tdo_plan_result& r,
                                      const Limits& lim, tdo_smoothing mode, bool trajectory,
                                      Seen* seen) {
  auto fail = [](const std::string& what) { return ::testing::AssertionFailure() << what; };
  const bool g2 = mode == TDO_SMOOTHING_G2;
  const tdo_path& path = r.path;
  if (path.n == 0 || path.seg == nullptr) return fail("empty path");
  if (!trajectory && r.n_samples != 0) return fail("samples without the trajectory stage");
  if (trajectory && (r.n_samples < 2 || r.samples == nullptr)) return fail("fewer than 2 samples");
  for (uint32_t i = 0; i < path.n; ++i) {
    seen->lines += path.seg[i].kind == TDO_SEGMENT_LINE;
    seen->beziers += path.seg[i].kind == TDO_SEGMENT_BEZIER;
    seen->arcs += path.seg[i].kind == TDO_SEGMENT_ARC;
  }
  seen->junctions += path.n - 1;
  seen->samples += r.n_samples;
  // 1. ends, bit-exact.
  if (!same(path.seg[0].p[0], start))
    return fail("path starts at " + str(vec(path.seg[0].p[0])) + ", not the start");
  const tdo_path_segment& last = path.seg[path.n - 1];
  const tdo_vec3 end = last.kind == TDO_SEGMENT_BEZIER ? last.p[3] : last.p[1];
  if (!same(end, goal)) return fail("path ends at " + str(vec(end)) + ", not the goal");
  if (trajectory && !same(r.samples[0].p, start))
    return fail("trajectory starts at " + str(vec(r.samples[0].p)) + ", not the start " +
                str(vec(start)));
  if (trajectory && !same(r.samples[r.n_samples - 1].p, goal))
    return fail("trajectory ends at " + str(vec(r.samples[r.n_samples - 1].p)) + ", not the goal " +
                str(vec(goal)));

  // 2. clearance of every piece.
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& s = path.seg[i];
    std::ostringstream where;
    where << "segment " << i << " of " << path.n << " (kind " << s.kind << ")";
    if (s.kind == TDO_SEGMENT_LINE) {
      const double d = world.segment(vec(s.p[0]), vec(s.p[1]), clearance + kCap);
      if (d < clearance - kClearTol)
        return fail(where.str() + " line " + str(vec(s.p[0])) + " -> " + str(vec(s.p[1])) +
                    " comes within " + std::to_string(d) + " m of an obstacle");
      continue;
    }
    Certify c{&world, clearance};
    if (s.kind == TDO_SEGMENT_BEZIER) {
      c.bezier({vec(s.p[0]), vec(s.p[1]), vec(s.p[2]), vec(s.p[3])}, 0);
    } else if (s.kind == TDO_SEGMENT_ARC) {
      const V cen = vec(s.p[2]);
      const V r0 = vec(s.p[0]) - cen, r1 = vec(s.p[1]) - cen;
      const double rad = norm(r0);
      const V u = (1.0 / rad) * r0;
      V w = r1 - dot(r1, u) * u;
      w = (1.0 / norm(w)) * w;
      const double sweep = std::atan2(dot(r1, w), dot(r1, u));
      c.arc(cen, u, w, rad, 0.0, sweep, 0);
    } else {
      return fail(where.str() + ": unknown kind");
    }
    if (c.worst < clearance - kClearTol)
      return fail(where.str() + " passes " + str(c.worst_at) + " at " + std::to_string(c.worst) +
                  " m from an obstacle (clearance " + std::to_string(clearance) + ")");
    if (c.uncertified)
      return fail(where.str() + ": clearance not certified at subdivision depth " +
                  std::to_string(kMaxDepth));
  }
  for (uint32_t i = 0; i < r.n_samples; ++i) {
    const double d = world.point(vec(r.samples[i].p), clearance + kCap);
    if (d < clearance - kClearTol)
      return fail("sample " + std::to_string(i) + " at " + str(vec(r.samples[i].p)) + " is " +
                  std::to_string(d) + " m from an obstacle");
  }

  // 3. dynamics by finite differences of the positions.
  const ::testing::AssertionResult dynamics = check_dynamics(r, lim);
  if (!dynamics) return dynamics;

  // 4. junctions: positions always; tangents (not at stop points) and curvature vectors (g2).
  for (uint32_t i = 0; i + 1 < path.n; ++i) {
    const tdo_path_segment& s0 = path.seg[i];
    const tdo_path_segment& s1 = path.seg[i + 1];
    const double gap = norm(segment_start(s1) - segment_end(s0));
    if (gap > kJoinTol)
      return fail("gap of " + std::to_string(gap) + " m between segments " + std::to_string(i) +
                  " and " + std::to_string(i + 1));
    if (mode == TDO_SMOOTHING_NONE) continue;
    if (g2 && (s0.kind == TDO_SEGMENT_ARC || s1.kind == TDO_SEGMENT_ARC))
      return fail("an arc in g2 mode at junction " + std::to_string(i));
    const EndGeometry e0 = end_geometry(s0, true);
    const EndGeometry e1 = end_geometry(s1, false);
    if (!s0.stop_at_end && norm(e0.t - e1.t) > kTangentTol)
      return fail("tangent kink of " + std::to_string(norm(e0.t - e1.t)) + " at junction " +
                  std::to_string(i) + " (no stop point)");
    if (!g2) continue;
    const double jump = norm(e0.kn - e1.kn);
    const double scale = std::max(norm(e0.kn), norm(e1.kn));
    if (jump > kCurvTol * (1.0 + scale))
      return fail("curvature jump of " + std::to_string(jump) + " 1/m at junction " +
                  std::to_string(i) + " (kinds " + std::to_string(s0.kind) + " -> " +
                  std::to_string(s1.kind) + ", |k| " + std::to_string(norm(e0.kn)) + " -> " +
                  std::to_string(norm(e1.kn)) + ")");
  }
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// Planner on a heap arena, the A* reference run and one property case.

using tdo_test::TestPlanner;

/** `map` at `clearance` in a planner of tdo_io::capacity_for's sizes with the obstacle-aware retry
 *  (geb079 G4 and G5 need it). */
TestPlanner map_planner(const tdo_io::Map& map, double clearance, uint32_t node_cap,
                        uint32_t stream = 0u) {
  tdo_capacity cap = tdo_io::capacity_for(map, clearance, 27u, node_cap);
  cap.exact_heuristic = 1u;
  cap.stream_samples = stream;
  return TestPlanner(cap, [&](tdo_grid* g) { return tdo_io::load_into(map, g, clearance); });
}

tdo_plan_params astar_params() {
  tdo_plan_params p;
  tdo_plan_params_default(&p);
  p.depth = TDO_PLAN_SEARCH;
  p.search = TDO_SEARCH_ASTAR;
  p.lambda = 0.0;
  p.mu = 0.0;
  p.theta_max = 0.0;
  p.first_meet = 0;
  return p;
}

struct Tally {
  int queries = 0;
  int astar_ok = 0;
  int tdo_ok = 0;
  Seen seen;
};

/**
 * Plan start -> goal with plain A* and with the pipeline (`params`), and check the properties.
 * @return the pipeline's status.
 */
tdo_status run_case(const std::string& label, const World& world, TestPlanner& pl, double clearance,
                    const tdo_vec3& start, const tdo_vec3& goal, const tdo_plan_params& params,
                    Tally* tally) {
  SCOPED_TRACE(label + ": " + str(vec(start)) + " -> " + str(vec(goal)));
  ++tally->queries;
  tdo_plan_request req{};
  req.start = start;
  req.goal = goal;
  req.params = astar_params();
  tdo_plan_result res{};
  const tdo_status astar = tdo_planner_plan(pl.planner(), &req, &res);
  req.params = params;
  const tdo_status st = tdo_planner_plan(pl.planner(), &req, &res);
  if (astar == TDO_OK) {
    ++tally->astar_ok;
    EXPECT_EQ(st, TDO_OK) << "A* found a path, the pipeline returned " << tdo_status_str(st)
                          << " (feasibility ok " << res.feasibility.ok << ", "
                          << res.feasibility.n_violations_total << " violations, max speed "
                          << res.feasibility.max_speed << ", acc " << res.feasibility.max_acc
                          << ", jerk " << res.feasibility.max_jerk << ", min clearance "
                          << res.feasibility.min_clearance << ")";
  } else {
    // Nothing to plan: the pipeline names the same reason (blocked end, no path ...).
    EXPECT_EQ(st, astar) << "A* said " << tdo_status_str(astar);
  }
  if (st != TDO_OK) return st;
  ++tally->tdo_ok;
  const Limits lim{params.v_max, params.a_max, params.j_max, params.dt};
  EXPECT_TRUE(check_plan(world, clearance, start, goal, res, lim, params.smoothing,
                         params.depth == TDO_PLAN_TRAJECTORY, &tally->seen));
  return st;
}

tdo_io::Map load(const std::string& path, double resolution = 0.0) {
  tdo_io::Map m;
  std::string err;
  tdo_io::LoadOptions opt;
  opt.resolution = resolution;
  EXPECT_TRUE(tdo_io::load_map(path, opt, &m, &err)) << err;
  return m;
}

/** Deterministic random numbers of the test (splitmix64). */
class TestRng {
 public:
  explicit TestRng(uint64_t s) : s_(s) {}
  uint64_t next() { return tdo_mapgen::splitmix64(&s_); }
  double uniform(double a, double b) {
    return a + (b - a) * static_cast<double>(next() >> 11) * 0x1.0p-53;
  }
  int64_t range(int64_t lo, int64_t hi) {
    return lo + static_cast<int64_t>(next() % static_cast<uint64_t>(hi - lo + 1));
  }

 private:
  uint64_t s_;
};

tdo_vec3 random_point(TestRng& rng, const tdo_grid_desc& d) {
  return tdo_vec3{rng.uniform(d.origin.x, d.origin.x + d.nx * d.res),
                  rng.uniform(d.origin.y, d.origin.y + d.ny * d.res),
                  rng.uniform(d.origin.z, d.origin.z + d.nz * d.res)};
}

// ---------------------------------------------------------------------------------------------

class PipelineProperty : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tdo_pipeline_property_" + std::to_string(static_cast<long>(::getpid())));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// 200 seeded random column maps (tdo-mapgen --random), a few hundred voxels to ~16k voxels, at
// random clearance, resolution and dynamic limits; the map's own query plus one random query.
TEST_F(PipelineProperty, GivenSeededRandomMapsWhenPlannedThenEveryPropertyHolds) {
  Tally tally;
  int generated = 0;
  // Draw until kRandomMaps maps were generated (a draw too dense for 16 streams is skipped).
  for (int m = 0; generated < kRandomMaps && m < 2 * kRandomMaps; ++m) {
    TestRng rng(0x5EED0000u + static_cast<uint64_t>(m));
    tdo_mapgen::Params p;
    p.layout = tdo_mapgen::Layout::Columns;
    p.seed = static_cast<uint64_t>(m) + 1u;
    p.size[0] = static_cast<int32_t>(rng.range(6, 14));
    p.size[1] = static_cast<int32_t>(rng.range(6, 14));
    p.size[2] = static_cast<int32_t>(rng.range(3, 7));
    p.resolution_mm = rng.range(0, 3) == 0 ? 500 : 1000;
    p.clearance_mm = static_cast<int32_t>(rng.range(2, 7) * 100);
    p.margin_mm = p.clearance_mm + 700;
    if (rng.range(0, 1) == 0) {  // whole metres, aligned to a 1 m grid
      p.footprint_dm[0] = 10;
      p.footprint_dm[1] = static_cast<int32_t>(rng.range(1, 3) * 10);
    } else {  // decimetres: boxes off the voxel grid
      p.footprint_dm[0] = static_cast<int32_t>(rng.range(3, 10));
      p.footprint_dm[1] = static_cast<int32_t>(rng.range(p.footprint_dm[0], 25));
    }
    p.columns = static_cast<uint32_t>(p.size[0] * p.size[1] / rng.range(4, 10));
    for (int a = 0; a < 3; ++a) {
      const int64_t hi = static_cast<int64_t>(p.size[a]) * 10000;
      const int64_t edge = a == 2 ? 8000 : 12000;
      p.start[a] = rng.range(5000, std::min<int64_t>(edge, hi - 5000));
      p.goal[a] = rng.range(std::max<int64_t>(hi - edge, 5000), hi - 5000);
    }
    p.max_streams = 16;
    const std::string label = "random map " + std::to_string(m);
    tdo_mapgen::Result gen;
    std::string err;
    if (!tdo_mapgen::generate(p, (dir_ / "scratch").string(), &gen, &err)) continue;  // too dense
    ++generated;
    const std::string file = (dir_ / ("map" + std::to_string(m) + ".tdomap")).string();
    std::ofstream(file) << gen.text;
    const tdo_io::Map map = load(file);
    const double clearance = p.clearance_mm / 1000.0;
    TestPlanner pl = map_planner(map, clearance, 0u);
    ASSERT_EQ(pl.status(), TDO_OK) << label;
    const World world(map);

    tdo_plan_params params;
    tdo_plan_params_default(&params);
    if (m % 2 == 1) {  // other dynamic limits on every second map
      params.v_max = rng.uniform(1.0, 5.0);
      params.a_max = rng.uniform(1.5, 6.0);
      params.j_max = rng.uniform(4.0, 25.0);
      params.a_lat_max = params.a_max;
      params.v_cruise = params.v_max;
      params.k = rng.uniform(0.5, 2.0);
    }
    run_case(label + " (own query)", world, pl, clearance, map.start, map.goal, params, &tally);
    run_case(label + " (random query)", world, pl, clearance, random_point(rng, map.desc),
             random_point(rng, map.desc), params, &tally);
    // The paper's arcs (the ablation), geometric path only: clearance, ends, tangents.
    tdo_plan_params arcs = params;
    arcs.smoothing = TDO_SMOOTHING_ARC;
    arcs.depth = TDO_PLAN_SMOOTH;
    run_case(label + " (own query, arcs)", world, pl, clearance, map.start, map.goal, arcs, &tally);
    // The options that start with grid distances (tdo_plan_params.grid_first).
    tdo_plan_params grid = params;
    grid.grid_first = TDO_GRID_FIRST_PLAIN;
    run_case(label + " (own query, grid_first)", world, pl, clearance, map.start, map.goal, grid,
             &tally);
    grid.grid_first = TDO_GRID_FIRST_TERMS;
    run_case(label + " (own query, grid_first terms)", world, pl, clearance, map.start, map.goal,
             grid, &tally);
    if (HasFailure()) {
      ADD_FAILURE() << label << " failed; its map:\n" << gen.text;
      break;
    }
  }
  const Seen& seen = tally.seen;
  std::printf(
      "random maps: %d generated; %d queries, A* ok %d, tdo ok %d; checked %ld lines, "
      "%ld Beziers, %ld arcs, %ld junctions, %ld samples\n",
      generated, tally.queries, tally.astar_ok, tally.tdo_ok, seen.lines, seen.beziers, seen.arcs,
      seen.junctions, seen.samples);
  EXPECT_GT(seen.beziers, 500);  // the checker had curves to judge
  EXPECT_GT(seen.arcs, 200);
  EXPECT_EQ(generated, kRandomMaps);
  EXPECT_GE(tally.tdo_ok, 4 * generated);  // every own query is solvable (generate checked it)
}

// The paper's maps at the default clearance 0.5 m: the map's query and 4 random ones each.
TEST(PipelinePropertyMaps, GivenMap1ToMap5WhenPlannedThenEveryPropertyHolds) {
  Tally tally;
  for (int n = 1; n <= 5; ++n) {
    const std::string name = "map" + std::to_string(n);
    const tdo_io::Map map = load(kMaps + "/" + name + ".tdomap");
    const double clearance = 0.5;
    TestPlanner pl = map_planner(map, clearance, 0u);
    ASSERT_EQ(pl.status(), TDO_OK) << name;
    const World world(map);
    tdo_plan_params params;
    tdo_plan_params_default(&params);
    EXPECT_EQ(run_case(name, world, pl, clearance, map.start, map.goal, params, &tally), TDO_OK);
    tdo_plan_params grid = params;
    grid.grid_first = TDO_GRID_FIRST_PLAIN;
    EXPECT_EQ(
        run_case(name + " grid_first", world, pl, clearance, map.start, map.goal, grid, &tally),
        TDO_OK);
    grid.grid_first = TDO_GRID_FIRST_TERMS;
    for (double w : {1.0, 2.0}) {
      grid.h_weight = w;
      EXPECT_EQ(run_case(name + " grid_first terms, h_weight " + std::to_string(w), world, pl,
                         clearance, map.start, map.goal, grid, &tally),
                TDO_OK);
    }
    TestRng rng(100u + static_cast<uint64_t>(n));
    for (int q = 0; q < 4; ++q)
      run_case(name + " random", world, pl, clearance, random_point(rng, map.desc),
               random_point(rng, map.desc), params, &tally);
  }
  std::printf("maps 1-5: %d queries, A* ok %d, tdo ok %d\n", tally.queries, tally.astar_ok,
              tally.tdo_ok);
  EXPECT_GE(tally.tdo_ok, 20);  // the own queries: default, grid_first plain and terms (w 1, 2)
}

/** A moving start's plan: its first sample is exactly the state, its samples keep v, a, j (check
 *  3) and the clearance, and it ends exactly at the goal. */
::testing::AssertionResult check_moving_plan(const World& world, double clearance,
                                             const tdo_sample& state, const tdo_vec3& goal,
                                             const tdo_plan_result& r, const Limits& lim) {
  if (r.n_samples < 3 || r.samples == nullptr) return ::testing::AssertionFailure() << "samples";
  const tdo_sample& s0 = r.samples[0];
  if (!same(s0.p, state.p) || !same(s0.v, state.v) || !same(s0.a, state.a))
    return ::testing::AssertionFailure() << "sample 0 is not the start state";
  if (!same(r.samples[r.n_samples - 1].p, goal))
    return ::testing::AssertionFailure() << "the trajectory does not end at the goal";
  for (uint32_t i = 0; i < r.n_samples; ++i) {
    const double d = world.point(vec(r.samples[i].p), clearance + kCap);
    if (d < clearance - kClearTol)
      return ::testing::AssertionFailure()
             << "sample " << i << " is " << d << " m from an obstacle";
  }
  return check_dynamics(r, lim);
}

// Replanning from the library's own motion (docs/design.md s.5, "Moving start"): states of the
// plans of Map2 and Map5 (every second, and 40 random samples each) as start states. None is
// refused as over the limits or too fast; the plans keep every limit from their first sample.
TEST(PipelineMovingStart,
     GivenStatesOfItsOwnPlansOnMap2AndMap5_WhenReplannedFromThem_ThenNoneIsRefusedAsOverLimits) {
  int tried = 0, planned = 0, cannot_stop = 0, two_piece = 0;
  for (int n : {2, 5}) {
    const std::string name = "map" + std::to_string(n);
    const tdo_io::Map map = load(kMaps + "/" + name + ".tdomap");
    const double clearance = 0.5;
    TestPlanner pl = map_planner(map, clearance, 0u);
    ASSERT_EQ(pl.status(), TDO_OK) << name;
    const World world(map);
    tdo_plan_request req{};
    req.start = map.start;
    req.goal = map.goal;
    tdo_plan_params_default(&req.params);
    const Limits lim{req.params.v_max, req.params.a_max, req.params.j_max, req.params.dt};
    tdo_plan_result res{};
    ASSERT_EQ(tdo_planner_plan(pl.planner(), &req, &res), TDO_OK) << name;
    const std::vector<tdo_sample> plan(res.samples, res.samples + res.n_samples);
    std::vector<uint32_t> picks;
    for (uint32_t i = 100; i + 1 < plan.size(); i += 100) picks.push_back(i);  // every second
    TestRng rng(500u + static_cast<uint64_t>(n));
    for (int q = 0; q < 40; ++q)
      picks.push_back(static_cast<uint32_t>(rng.range(1, static_cast<int64_t>(plan.size()) - 2)));
    for (uint32_t i : picks) {
      const tdo_sample& x = plan[i];
      SCOPED_TRACE(name + " sample " + std::to_string(i) + " at " + str(vec(x.p)) + ", v " +
                   str(vec(x.v)) + ", a " + str(vec(x.a)));
      // GIVEN the plan's state at sample i as a start state
      tdo_plan_request r = req;
      r.start = x.p;
      r.state.v = x.v;
      r.state.a = x.a;
      // (a state whose entry needs the two-piece ramp: a one-piece one would exceed v_max)
      tdo_traj_entry e{};
      if (tdo_traj_entry_plan(x.p, &r.state, lim.v_max, lim.a_max, lim.j_max, &e) == TDO_OK &&
          e.knot < e.ramp)
        ++two_piece;
      // WHEN planned from it
      const tdo_status st = tdo_planner_plan(pl.planner(), &r, &res);
      ++tried;
      // THEN it is not refused for its motion; a stop along the velocity that would come too
      // close to a column (state_cannot_stop) is the only refusal
      EXPECT_TRUE(st == TDO_OK || st == TDO_ERR_STATE_CANNOT_STOP) << tdo_status_str(st);
      cannot_stop += st == TDO_ERR_STATE_CANNOT_STOP;
      if (st != TDO_OK) continue;
      ++planned;
      // AND the plan starts in exactly that state and keeps every limit and the clearance
      EXPECT_TRUE(check_moving_plan(world, clearance, x, map.goal, res, lim));
    }
  }
  std::printf(
      "moving starts from Map2/Map5 plans: %d tried (%d with a two-piece entry), %d planned, %d "
      "state_cannot_stop\n",
      tried, two_piece, planned, cannot_stop);
  EXPECT_GE(planned, tried * 9 / 10);
  EXPECT_GT(two_piece, 0);  // the states turning near v_max were among them
}

// tdo_capacity.stream_samples: the same plans, feasibility reports, metrics and samples (bit for
// bit) as with stored samples, on the paper's maps (Map4 left out: 150 MB per planner) and a few
// random queries each, which include infeasible and failed ones.
std::vector<tdo_sample> collect_samples(const tdo_planner* pl) {
  std::vector<tdo_sample> out;
  const tdo_status st = tdo_planner_each_sample(
      pl,
      [](void* user, uint32_t index, const tdo_sample* s) {
        auto* v = static_cast<std::vector<tdo_sample>*>(user);
        EXPECT_EQ(index, v->size());
        v->push_back(*s);
      },
      &out);
  if (st != TDO_OK) out.clear();
  return out;
}

// Every metric of `a` and `b` bit for bit; the energy only `with_energy`, the minimum clearance
// only `with_clearance`.
void expect_same_metrics(const tdo_metrics& a, const tdo_metrics& b, bool with_energy,
                         const std::string& what, bool with_clearance = true) {
  EXPECT_EQ(a.turns, b.turns) << what;
  EXPECT_EQ(a.curvature_continuous, b.curvature_continuous) << what;
  for (const auto field :
       {&tdo_metrics::length_m, &tdo_metrics::total_turn_deg, &tdo_metrics::avg_curvature,
        &tdo_metrics::smoothness, &tdo_metrics::flight_time_s})
    EXPECT_EQ(std::memcmp(&(a.*field), &(b.*field), sizeof(double)), 0) << what;
  if (with_clearance) {
    EXPECT_EQ(std::memcmp(&a.min_clearance_m, &b.min_clearance_m, sizeof(double)), 0) << what;
  }
  if (with_energy) {
    EXPECT_EQ(std::memcmp(&a.energy, &b.energy, sizeof(double)), 0) << what;
  }
}

// Plans each of Map1, 2, 3 and 5 (Map4 left out: 150 MB per planner) at clearance 0.5 m with
// stored samples and with stream_samples `mode`: the map's own query and three seeded random ones,
// which include infeasible and failed ones. check(a, b, sa, sb, what, stored, other) gets both
// results, their statuses, a label and both planners.
template <typename Check>
void for_each_mode_pair(uint32_t mode, Check check) {
  for (int n : {1, 2, 3, 5}) {
    const std::string name = "map" + std::to_string(n);
    const tdo_io::Map map = load(kMaps + "/" + name + ".tdomap");
    TestPlanner stored = map_planner(map, 0.5, 0u);
    TestPlanner other = map_planner(map, 0.5, 0u, mode);
    ASSERT_EQ(stored.status(), TDO_OK) << name;
    ASSERT_EQ(other.status(), TDO_OK) << name;
    TestRng rng(300u + static_cast<uint64_t>(n));
    for (int q = 0; q < 4; ++q) {
      tdo_plan_request req{};
      req.start = q == 0 ? map.start : random_point(rng, map.desc);
      req.goal = q == 0 ? map.goal : random_point(rng, map.desc);
      tdo_plan_params_default(&req.params);
      tdo_plan_result a{}, b{};
      const tdo_status sa = tdo_planner_plan(stored.planner(), &req, &a);
      const tdo_status sb = tdo_planner_plan(other.planner(), &req, &b);
      check(a, b, sa, sb, name + " query " + std::to_string(q), stored.planner(), other.planner());
    }
  }
}

TEST(PipelineStreaming,
     GivenStreamedSamplesWhenPlannedThenReportMetricsAndSamplesAreTheStoredOnes) {
  int compared = 0;
  for_each_mode_pair(1u, [&](const tdo_plan_result& a, const tdo_plan_result& b, tdo_status sa,
                             tdo_status sb, const std::string& what, const tdo_planner* stored,
                             const tdo_planner* streamed) {
    ASSERT_EQ(sa, sb) << what;
    EXPECT_EQ(b.samples, nullptr) << what;
    EXPECT_EQ(a.n_samples, b.n_samples) << what;
    EXPECT_EQ(a.refinements, b.refinements) << what;
    // The reports field by field (the violation lists by value), the metrics bit for bit.
    const tdo_feasibility& fa = a.feasibility;
    const tdo_feasibility& fb = b.feasibility;
    EXPECT_EQ(fa.ok, fb.ok) << what;
    EXPECT_EQ(std::memcmp(&fa.max_speed, &fb.max_speed, sizeof(double)), 0) << what;
    EXPECT_EQ(std::memcmp(&fa.max_acc, &fb.max_acc, sizeof(double)), 0) << what;
    EXPECT_EQ(std::memcmp(&fa.max_jerk, &fb.max_jerk, sizeof(double)), 0) << what;
    EXPECT_EQ(std::memcmp(&fa.min_turn_radius, &fb.min_turn_radius, sizeof(double)), 0) << what;
    EXPECT_EQ(std::memcmp(&fa.min_clearance, &fb.min_clearance, sizeof(double)), 0) << what;
    EXPECT_EQ(fa.n_violations_total, fb.n_violations_total) << what;
    ASSERT_EQ(fa.n_violations, fb.n_violations) << what;
    for (uint32_t i = 0; i < fa.n_violations; ++i) {  // field by field (padding differs)
      const tdo_violation& va = fa.violations[i];
      const tdo_violation& vb = fb.violations[i];
      EXPECT_EQ(va.what, vb.what) << what;
      for (const auto field : {&tdo_violation::t, &tdo_violation::value, &tdo_violation::limit})
        EXPECT_EQ(std::memcmp(&(va.*field), &(vb.*field), sizeof(double)), 0) << what;
    }
    expect_same_metrics(a.metrics, b.metrics, true, what);
    if (sa != TDO_OK || a.n_samples == 0u) return;
    ++compared;
    EXPECT_GT(b.metrics.energy, 0.0) << what;  // the streamed energy is there, not left at 0
    const std::vector<tdo_sample> via_a = collect_samples(stored);
    const std::vector<tdo_sample> via_b = collect_samples(streamed);
    ASSERT_EQ(via_a.size(), a.n_samples) << what;
    ASSERT_EQ(via_b.size(), a.n_samples) << what;
    EXPECT_EQ(std::memcmp(via_a.data(), a.samples, a.n_samples * sizeof(tdo_sample)), 0) << what;
    EXPECT_EQ(std::memcmp(via_b.data(), a.samples, a.n_samples * sizeof(tdo_sample)), 0) << what;
  });
  EXPECT_GE(compared, 4);  // at least the four maps' own queries
}

// tdo_capacity.stream_samples TDO_TRAJ_SAMPLES_PIECES: the same plans (waypoints, path, samples bit
// for bit) and metrics as with stored samples, but for the energy, which is the integral of |a|^2
// instead of the trapezoid over the samples: relative 1e-3 (the trapezoid's error at dt = 0.01 s,
// dt^2 / 12 |f''| with |f''| / f up to ~(j_max / a_max)^2 ~ 11 1/s^2, plus its kinks at the jerk
// switches: well below 1e-3 of the integral on these flights of tens of seconds), and the minimum
// clearance of a plan the closed form accepted: the bound the stages proved (0.5 m less 1e-9 m),
// at most the stored plan's measured one.
TEST(PipelineStreaming, GivenPiecesWhenPlannedThenPlanSamplesAndMetricsAreTheStoredOnes) {
  int compared = 0, closed = 0;
  for_each_mode_pair(TDO_TRAJ_SAMPLES_PIECES, [&](const tdo_plan_result& a,
                                                  const tdo_plan_result& b, tdo_status sa,
                                                  tdo_status sb, const std::string& what,
                                                  const tdo_planner*, const tdo_planner* pieces) {
    ASSERT_EQ(sa, sb) << what;
    EXPECT_EQ(b.samples, nullptr) << what;
    EXPECT_EQ(a.n_samples, b.n_samples) << what;
    EXPECT_EQ(a.refinements, b.refinements) << what;
    EXPECT_EQ(a.feasibility.ok, b.feasibility.ok) << what;
    ASSERT_EQ(a.n_waypoints, b.n_waypoints) << what;
    if (a.n_waypoints > 0u) {  // no waypoints (a failed search): nothing to compare
      EXPECT_EQ(std::memcmp(a.waypoints, b.waypoints, a.n_waypoints * sizeof(tdo_vec3)), 0) << what;
    }
    ASSERT_EQ(a.path.n, b.path.n) << what;
    for (uint32_t i = 0; i < a.path.n; ++i) {
      const tdo_path_segment& x = a.path.seg[i];
      const tdo_path_segment& y = b.path.seg[i];
      EXPECT_EQ(x.kind, y.kind) << what;
      EXPECT_EQ(std::memcmp(x.p, y.p, sizeof(x.p)), 0) << what;
      EXPECT_EQ(std::memcmp(&x.length, &y.length, sizeof(double)), 0) << what;
    }
    const tdo_metrics& ma = a.metrics;
    const tdo_metrics& mb = b.metrics;
    const bool proven = sb == TDO_OK && b.sample_passes == 0u;  // the closed form took the proof
    expect_same_metrics(ma, mb, false, what, !proven);
    if (proven) {
      EXPECT_EQ(mb.min_clearance_m, 0.5 - 1e-9) << what;
      EXPECT_EQ(b.feasibility.min_clearance, 0.5 - 1e-9) << what;
      EXPECT_LE(mb.min_clearance_m, ma.min_clearance_m) << what;
    }
    if (sa != TDO_OK || a.n_samples == 0u) return;
    ++compared;
    if (b.sample_passes == 0u) ++closed;
    EXPECT_NEAR(mb.energy, ma.energy, 1e-3 * ma.energy) << what;
    const std::vector<tdo_sample> via_b = collect_samples(pieces);
    ASSERT_EQ(via_b.size(), a.n_samples) << what;
    EXPECT_EQ(std::memcmp(via_b.data(), a.samples, a.n_samples * sizeof(tdo_sample)), 0) << what;
  });
  EXPECT_GE(compared, 4);  // at least the four maps' own queries
  EXPECT_GE(closed, 1);    // and the closed form accepted some of them
}

// geb079 voxelized at 0.2 m, clearance 0.3 m: the checked pairs G1-G5 of maps/octomap/README.md
// (the corridor, a room off it, and north room to south room). The octile-guided turn-penalised
// search floods the building on G4 and G5 (2.3-2.7 million expansions); they are here for its
// retry with the obstacle-aware heuristic (search.h, tdo_search_output.fallback).
TEST(PipelinePropertyMaps, GivenGeb079WhenPlannedThenEveryPropertyHolds) {
  const tdo_io::Map map = load(kMaps + "/octomap/geb079.bt", 0.2);
  const double clearance = 0.3;
  TestPlanner pl = map_planner(map, clearance, 2000000u);
  ASSERT_EQ(pl.status(), TDO_OK);
  const World world(map);
  tdo_plan_params params;
  tdo_plan_params_default(&params);
  const double q[5][6] = {{-5, 0, 1.2, 27, 0, 1.2},
                          {-5, 0, 1.2, 10, 0, 1.2},
                          {13, 0, 1.2, 27, 0, 1.2},
                          {-5, 0, 1.2, 24, -5, 1.2},
                          {6, 5, 1.2, 11, -5, 1.2}};
  Tally tally;
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(run_case("geb079 G" + std::to_string(i + 1), world, pl, clearance,
                       tdo_vec3{q[i][0], q[i][1], q[i][2]}, tdo_vec3{q[i][3], q[i][4], q[i][5]},
                       params, &tally),
              TDO_OK);
  }
}

// The forests at their own resolution, clearance 0.3 m: the first 6 published pairs of each.
TEST(PipelinePropertyMaps, GivenForestsWithPublishedPairsWhenPlannedThenEveryPropertyHolds) {
  std::ifstream csv(kMaps + "/forest_gen/start_and_end.csv");
  ASSERT_TRUE(csv.good());
  std::vector<std::array<double, 7>> rows;  // map id, start, goal
  std::string line;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::array<double, 8> f{};
    char c = 0;
    std::istringstream s(line);
    s >> f[0] >> c >> f[1] >> c >> f[2] >> c >> f[3] >> c >> f[4] >> c >> f[5] >> c >> f[6] >> c >>
        f[7];
    ASSERT_FALSE(s.fail()) << line;
    rows.push_back({f[1], f[2], f[3], f[4], f[5], f[6], f[7]});
  }
  Tally tally;
  for (int id = 0; id < 3; ++id) {
    const std::string name = "forest" + std::to_string(id);
    const tdo_io::Map map = load(kMaps + "/forest_gen/" + name + ".bt");
    const double clearance = 0.3;
    TestPlanner pl = map_planner(map, clearance, 0u);
    ASSERT_EQ(pl.status(), TDO_OK) << name;
    const World world(map);
    tdo_plan_params params;
    tdo_plan_params_default(&params);
    int used = 0;
    for (const auto& r : rows) {
      if (static_cast<int>(r[0]) != id || used == 6) continue;
      ++used;
      run_case(name, world, pl, clearance, tdo_vec3{r[1], r[2], r[3]}, tdo_vec3{r[4], r[5], r[6]},
               params, &tally);
    }
    EXPECT_EQ(used, 6) << name;
  }
  std::printf("forests: %d queries, A* ok %d, tdo ok %d\n", tally.queries, tally.astar_ok,
              tally.tdo_ok);
  EXPECT_GE(tally.tdo_ok, 9);
}

// The checker itself must be able to fail: a line through a box, a Bezier bulging into one, an
// arc cutting a corner, and a curvature jump between a line and an arc.
TEST(PipelinePropertyChecker, GivenViolatingGeometryThenTheCheckerSeesIt) {
  tdo_io::Map map;
  map.desc = tdo_grid_desc{10, 10, 10, 1.0, tdo_vec3{0, 0, 0}};
  map.boxes.push_back(tdo_box{tdo_vec3{4, 4, 0}, tdo_vec3{6, 6, 10}});
  const World world(map);
  EXPECT_DOUBLE_EQ(world.segment(V{0, 5, 5}, V{10, 5, 5}, 9.0), 0.0);
  EXPECT_DOUBLE_EQ(world.segment(V{0, 3, 5}, V{10, 3, 5}, 9.0), 1.0);
  EXPECT_NEAR(world.segment(V{0, 0, 5}, V{3, 3, 5}, 9.0), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(world.segment(V{0, 3, 5}, V{3, 0, 5}, 9.0), 5.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(world.segment(V{2, 8, 12}, V{8, 8, 12}, 9.0), std::sqrt(4.0 + 4.0), 1e-12);

  // A Bezier from (3, 3.5) to (7, 3.5) bulging to y ~ 3.95 (control points at y = 4.1): its
  // chord keeps 0.5 m, the curve does not.
  Certify c{&world, 0.3};
  c.bezier({V{3, 3.5, 5}, V{4, 4.1, 5}, V{6, 4.1, 5}, V{7, 3.5, 5}}, 0);
  EXPECT_LT(c.worst, 0.3);
  Certify ok{&world, 0.3};
  ok.bezier({V{3, 3.5, 5}, V{4, 3.6, 5}, V{6, 3.6, 5}, V{7, 3.5, 5}}, 0);
  EXPECT_GE(ok.worst, 0.3);
  EXPECT_FALSE(ok.uncertified);

  // Voxel cubes: the same box as occupied voxels.
  tdo_io::Map vox;
  vox.desc = map.desc;
  for (int32_t k = 0; k < 10; ++k)
    for (int32_t j = 4; j < 6; ++j)
      for (int32_t i = 4; i < 6; ++i) vox.voxels.push_back(tdo_voxel{i, j, k});
  const World cubes(vox);
  EXPECT_DOUBLE_EQ(cubes.segment(V{0, 3, 5}, V{10, 3, 5}, 9.0), 1.0);
  EXPECT_DOUBLE_EQ(cubes.segment(V{0, 5, 5}, V{10, 5, 5}, 9.0), 0.0);
  Certify arc{&cubes, 0.5};
  // Quarter-ish arc about (3, 3) of radius 2.5 from (5.5, 3) to (3, 5.5): passes near (4.77, 4.77).
  arc.arc(V{3, 3, 5}, V{1, 0, 0}, V{0, 1, 0}, 2.5, 0.0, 1.5707963267948966, 0);
  EXPECT_LT(arc.worst, 0.5);

  // End geometry: a line into an arc has a curvature jump of 1/r.
  tdo_path_segment line{};
  line.kind = TDO_SEGMENT_LINE;
  line.p[0] = tdo_vec3{0, 0, 0};
  line.p[1] = tdo_vec3{1, 0, 0};
  tdo_path_segment a{};
  a.kind = TDO_SEGMENT_ARC;
  a.p[0] = tdo_vec3{1, 0, 0};
  a.p[1] = tdo_vec3{3, 2, 0};
  a.p[2] = tdo_vec3{1, 2, 0};
  const EndGeometry e0 = end_geometry(line, true);
  const EndGeometry e1 = end_geometry(a, false);
  EXPECT_NEAR(norm(e0.t - e1.t), 0.0, 1e-15);
  EXPECT_NEAR(norm(e1.kn - e0.kn), 0.5, 1e-15);
  EXPECT_NEAR(e1.kn.y, 0.5, 1e-15);
  // A Bezier with a straight start (P0, P1, P2 collinear) has zero curvature there.
  tdo_path_segment b{};
  b.kind = TDO_SEGMENT_BEZIER;
  b.p[0] = tdo_vec3{0, 0, 0};
  b.p[1] = tdo_vec3{1, 0, 0};
  b.p[2] = tdo_vec3{2, 0, 0};
  b.p[3] = tdo_vec3{3, 1, 0};
  EXPECT_NEAR(norm(end_geometry(b, false).kn), 0.0, 1e-15);
  // At its end: B'(1) = 3 (1, 1, 0), B''(1) = 6 (0, 1, 0) -> kappa = |B' x B''| / |B'|^3.
  const double kappa = 18.0 / std::pow(std::sqrt(18.0), 3);
  EXPECT_NEAR(norm(end_geometry(b, true).kn), kappa, 1e-12);
}

}  // namespace
