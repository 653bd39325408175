// Stage 6: trajectory quality metrics (docs/design.md s.6), identical for every planner.
//
// Curvature integrals use composite 8-point Gauss-Legendre per curved segment (lines contribute
// nothing; Beziers over their parameter, arcs over arclength). Without a geometric path the
// waypoint polyline is measured with its discrete curvature: the turn angle theta_i concentrated at
// vertex i, so integral |kappa| ds = sum theta_i (exact for the polyline as a limit of ever tighter
// fillets) and integral kappa^2 ds = sum theta_i^2 / l_i with l_i the mean length of the two
// segments at the vertex (the usual discrete bending energy; the exact value is infinite for a
// sharp corner).
//
// The clearance of curves is a proven lower bound: each curve is cut into chords, the exact
// segment-to-obstacle distance of a chord is computed by the collision module, and the largest
// distance from the curve piece to its chord (sagitta bound) is subtracted. For a Bezier piece the
// bound is the distance of its inner control points to the chord (convex hull property); for an
// arc piece it is the circular sagitta.
#include "tdo/metrics.h"

#include <math.h>
#include <string.h>

#include "path_clearance.h"
#include "path_segment.h"
#include "sample_energy.h"
#include "scalar.h"
#include "tdo/collision.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTurnThresholdDeg = 1.0;   // deg, interior waypoints turning more are "turns"
constexpr double kAngleTol = 1e-6;          // rad, tangent continuity at segment junctions
constexpr double kCurvatureJumpTol = 1e-4;  // 1/m, curvature continuity at segment junctions
constexpr uint32_t kPanels = 4;             // Gauss-Legendre panels per curved segment
constexpr double kSagittaTarget = 1e-4;     // m, aimed chord sagitta for the clearance bound
constexpr uint32_t kMaxChords = 256;        // chords per curved segment, at most
constexpr double kSagittaSlack = 1e-12;     // m, rounding of chord end points on an arc
// m, allowance of bezier_above for the rounding of the pieces' end points, control points and
// distances (all far below it)
constexpr double kWholeMargin = 1e-7;
constexpr uint32_t kLeafPieces = 2;  // chord pieces queried one by one below this many
constexpr uint32_t kPartDepth = 9;   // halvings of kMaxChords pieces down to one: log2(256) + 1

// 8-point Gauss-Legendre on [-1, 1] (nodes and weights of the positive half).
constexpr double kGlX[4] = {0.1834346424956498049394761, 0.5255324099163289858177390,
                            0.7966664774136267395915539, 0.9602898564975362316835609};
constexpr double kGlW[4] = {0.3626837833783619829651504, 0.3137066458778872873379622,
                            0.2223810344533744705443560, 0.1012285362903762591525314};

/** rad, angle between two vectors (0 when either is zero). */
double angle(const tdo_vec3& a, const tdo_vec3& b) {
  if (!(norm(a) > 0.0) || !(norm(b) > 0.0)) return 0.0;
  return atan2(norm(cross(a, b)), dot(a, b));
}

/** m, distance from q to the segment [a, b]. */
double point_segment(const tdo_vec3& q, const tdo_vec3& a, const tdo_vec3& b) {
  const tdo_vec3 d = sub(b, a);
  const double dd = dot(d, d);
  double t = dd > 0.0 ? dot(sub(q, a), d) / dd : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return norm(sub(q, add(a, mul(d, t))));
}

// ---------------------------------------------------------------------------------------------
// Turns on the waypoints (repeated points merged).

struct Turns {
  uint32_t turns;
  double total_deg;  // deg, deflections above the threshold
  double sum_abs;    // rad, every deflection (discrete integral |kappa| ds)
  double sum_sq;     // 1/m, sum theta^2 / mean adjacent length (discrete integral kappa^2 ds)
  double length;     // m, polyline length
  double max_theta;  // rad
};

Turns turn_stats(const tdo_vec3* w, uint32_t n) {
  Turns r{0u, 0.0, 0.0, 0.0, 0.0, 0.0};
  // prev = last distinct point before `at`; a vertex is evaluated once its successor is known.
  uint32_t prev = 0, at = 0;
  bool have_at = false;
  for (uint32_t i = 1; i < n; ++i) {
    const tdo_vec3 p = w[i];
    const tdo_vec3 last = w[have_at ? at : prev];
    const double seg = norm(sub(p, last));
    if (!(seg > 0.0)) continue;  // repeated point
    r.length += seg;
    if (have_at) {
      const tdo_vec3 a = sub(w[at], w[prev]);
      const tdo_vec3 b = sub(p, w[at]);
      const double theta = angle(a, b);
      const double deg = theta * 180.0 / kPi;
      if (deg > kTurnThresholdDeg) {
        ++r.turns;
        r.total_deg += deg;
      }
      r.sum_abs += theta;
      r.sum_sq += theta * theta / (0.5 * (norm(a) + norm(b)));
      r.max_theta = dmax(r.max_theta, theta);
      prev = at;
    }
    at = i;
    have_at = true;
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Curvature integrals of a path.

/**
 * Adds integral |kappa| ds and integral kappa^2 ds of a cubic Bezier, integrated over its
 * parameter u (ds = |B'| du, kappa = |B' x B''| / |B'|^3), so no arclength is inverted: the
 * integrands |B' x B''| / |B'|^2 and |B' x B''|^2 / |B'|^5, kPanels panels of the 8-point rule.
 */
void bezier_curvature_integrals(const tdo_path_segment& seg, double* abs_int, double* sq_int) {
  const tdo_vec3 d0 = sub(seg.p[1], seg.p[0]), d1 = sub(seg.p[2], seg.p[1]),
                 d2 = sub(seg.p[3], seg.p[2]);
  const tdo_vec3 e0 = sub(d1, d0), e1 = sub(d2, d1);
  const auto add_at = [&](double u, double w, double* a, double* q) {
    const double v = 1.0 - u;
    const tdo_vec3 b1 = mul(add(add(mul(d0, v * v), mul(d1, 2.0 * v * u)), mul(d2, u * u)), 3.0);
    const tdo_vec3 b2 = mul(add(mul(e0, v), mul(e1, u)), 6.0);
    const double sp2 = dot(b1, b1);
    if (!(sp2 > 0.0)) return;  // a cusp of a degenerate curve: no curvature counted
    const double c = norm(cross(b1, b2));
    *a += w * c / sp2;
    *q += w * c * c / (sp2 * sp2 * sqrt(sp2));
  };
  const double h = 1.0 / kPanels;
  for (uint32_t p = 0; p < kPanels; ++p) {
    const double mid = h * (p + 0.5);
    double a = 0.0, q = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double dx = 0.5 * h * kGlX[i];
      add_at(mid - dx, kGlW[i], &a, &q);
      add_at(mid + dx, kGlW[i], &a, &q);
    }
    *abs_int += 0.5 * h * a;
    *sq_int += 0.5 * h * q;
  }
}

/** Adds integral |kappa| ds and integral kappa^2 ds of one segment. */
void curvature_integrals(const tdo_path_segment& seg, double* abs_int, double* sq_int) {
  if (seg.kind == TDO_SEGMENT_LINE || !(seg.length > 0.0)) return;
  if (seg.kind == TDO_SEGMENT_BEZIER) {
    bezier_curvature_integrals(seg, abs_int, sq_int);
    return;
  }
  const double h = seg.length / kPanels;
  for (uint32_t p = 0; p < kPanels; ++p) {
    const double mid = h * (p + 0.5);
    double a = 0.0, q = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double dx = 0.5 * h * kGlX[i];
      const double k0 = tdo_segment_curvature(&seg, mid - dx);
      const double k1 = tdo_segment_curvature(&seg, mid + dx);
      a += kGlW[i] * (k0 + k1);
      q += kGlW[i] * (k0 * k0 + k1 * k1);
    }
    *abs_int += 0.5 * h * a;
    *sq_int += 0.5 * h * q;
  }
}

/** 1 when tangent and curvature vector agree at every junction of positive-length segments. */
int curvature_continuous(const tdo_path& path) {
  int have = 0;
  tdo_segment_state end;
  memset(&end, 0, sizeof(end));
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& seg = path.seg[i];
    if (!(seg.length > 0.0)) continue;
    if (have) {
      tdo_segment_state start;
      tdo_segment_eval(&seg, 0.0, &start);
      if (angle(end.t, start.t) > kAngleTol) return 0;
      if (norm(sub(end.kn, start.kn)) > kCurvatureJumpTol) return 0;
    }
    tdo_segment_eval(&seg, seg.length, &end);
    have = 1;
  }
  return 1;
}

// ---------------------------------------------------------------------------------------------
// Clearance lower bounds.

/**
 * min(best, the lower bound (m) of the distance of a chord-approximated piece: chord distance,
 * capped at cap + sagitta, minus the sagitta). The chord is queried with a cap just above
 * min(best, cap) + sagitta, so the distance queries stop early (the obstacle index is searched
 * only that far): when the distance reaches that cap, the uncapped bound would exceed best by far
 * more than a rounding error and best stays; below it the distance is the same exact value. So the
 * result is bit for bit that of querying every chord at cap + sagitta.
 */
double piece_bound(const tdo_grid* grid, const tdo_vec3& a, const tdo_vec3& b, double sagitta,
                   double cap, double best) {
  const double full = cap + sagitta;
  double q = full;
  if (best < cap) {
    const double tight = (best + sagitta) * (1.0 + 1e-9) + 1e-12;
    if (tight < full) q = tight;
  }
  const double d = tdo_collision_segment_distance(grid, a, b, q);
  if (q < full && !(d < q)) return best;  // reached the tight cap: no lower bound below best
  return dmin(best, d - sagitta);
}

uint32_t chords_for(double flatness) {
  if (!(flatness > 0.0)) return 1u;
  const double k = ceil(sqrt(flatness / kSagittaTarget));
  if (!(k < static_cast<double>(kMaxChords))) return kMaxChords;
  return k < 1.0 ? 1u : static_cast<uint32_t>(k);
}

struct Bezier {
  tdo_vec3 p[4];
};

tdo_vec3 bez_point(const Bezier& b, double u) {
  if (u <= 0.0) return b.p[0];
  if (u >= 1.0) return b.p[3];
  const tdo_vec3 a0 = lerp(b.p[0], b.p[1], u), a1 = lerp(b.p[1], b.p[2], u),
                 a2 = lerp(b.p[2], b.p[3], u);
  return lerp(lerp(a0, a1, u), lerp(a1, a2, u), u);
}

tdo_vec3 bez_d1(const Bezier& b, double u) {
  const double w = 1.0 - u;
  const tdo_vec3 d0 = sub(b.p[1], b.p[0]), d1 = sub(b.p[2], b.p[1]), d2 = sub(b.p[3], b.p[2]);
  return mul(add(add(mul(d0, w * w), mul(d1, 2.0 * w * u)), mul(d2, u * u)), 3.0);
}

/** Parameter at which chord piece i of k of a Bezier starts (i = k: the end, exactly 1). */
inline double piece_u(uint32_t i, uint32_t k) { return i == k ? 1.0 : static_cast<double>(i) / k; }

/** The bound of the chord pieces [i0, i1) of the k of b, into best (piece_bound, in order). */
double bezier_pieces(const tdo_grid* grid, const Bezier& b, uint32_t k, uint32_t i0, uint32_t i1,
                     double cap, double best) {
  tdo_vec3 q0 = bez_point(b, piece_u(i0, k)), d0 = bez_d1(b, piece_u(i0, k));
  for (uint32_t i = i0; i < i1; ++i) {
    const double u1 = piece_u(i + 1u, k);
    const double u0 = static_cast<double>(i) / k;
    const double du = u1 - u0;
    const tdo_vec3 q3 = bez_point(b, u1), d1 = bez_d1(b, u1);
    // Control points of the piece [u0, u1] (exact for a cubic: Hermite data at both ends).
    const tdo_vec3 q1 = add(q0, mul(d0, du / 3.0));
    const tdo_vec3 q2 = sub(q3, mul(d1, du / 3.0));
    const double sag = dmax(point_segment(q1, q0, q3), point_segment(q2, q0, q3));
    best = piece_bound(grid, q0, q3, sag, cap, best);
    q0 = q3;
    d0 = d1;
  }
  return best;
}

/**
 * True when none of the chord pieces [i0, i1) of the k of b can lower best: one capped query of
 * the chord of that part of the curve. The part lies in the hull of its control points, within
 * `flat` of its chord, and so does every piece chord: its distance is at least the part chord's
 * minus flat. A piece's sagitta is at most its end tangent times du / 3 <= `sag` (the longest
 * control polygon edge / k). So a part chord at least best + flat + sag + kWholeMargin away keeps
 * every piece's bound (distance - sagitta) above best, where piece_bound leaves best as it is.
 */
bool part_above(const tdo_grid* grid, const Bezier& b, uint32_t k, uint32_t i0, uint32_t i1,
                double sag, double best) {
  const double u0 = piece_u(i0, k), u1 = piece_u(i1, k), du = u1 - u0;
  const tdo_vec3 c0 = bez_point(b, u0), c3 = bez_point(b, u1);
  const tdo_vec3 c1 = add(c0, mul(bez_d1(b, u0), du / 3.0));
  const tdo_vec3 c2 = sub(c3, mul(bez_d1(b, u1), du / 3.0));
  const double flat = dmax(point_segment(c1, c0, c3), point_segment(c2, c0, c3));
  const double q = best + flat + sag + kWholeMargin;
  return tdo_collision_segment_distance(grid, c0, c3, q) >= q;
}

/**
 * min(best, the chord pieces' bounds of the Bezier `seg`). Below the cap, parts of the curve that
 * cannot lower best (part_above) are skipped whole, halving the rest down to kLeafPieces: the
 * minimum is that of all the pieces, bit for bit, with fewer queries where the curve is far.
 */
double bezier_clearance(const tdo_grid* grid, const tdo_path_segment& seg, double cap,
                        double best) {
  const Bezier b{{seg.p[0], seg.p[1], seg.p[2], seg.p[3]}};
  const double flat =
      dmax(point_segment(b.p[1], b.p[0], b.p[3]), point_segment(b.p[2], b.p[0], b.p[3]));
  const uint32_t k = chords_for(flat);
  if (!(best < cap)) return bezier_pieces(grid, b, k, 0u, k, cap, best);
  const double sag =
      dmax(norm(sub(b.p[1], b.p[0])), dmax(norm(sub(b.p[2], b.p[1])), norm(sub(b.p[3], b.p[2])))) /
      k;
  uint32_t stack[2u * kPartDepth][2];  // ranges [i0, i1), the left one on top
  uint32_t top = 0;
  stack[top][0] = 0u;
  stack[top++][1] = k;
  while (top > 0u) {  // every range is split or consumed: at most 2 k ranges
    const uint32_t i0 = stack[top - 1u][0], i1 = stack[top - 1u][1];
    --top;
    if (i1 - i0 <= kLeafPieces) {
      best = bezier_pieces(grid, b, k, i0, i1, cap, best);
      continue;
    }
    if (part_above(grid, b, k, i0, i1, sag, best)) continue;
    const uint32_t mid = i0 + (i1 - i0) / 2u;
    stack[top][0] = mid;
    stack[top++][1] = i1;
    stack[top][0] = i0;
    stack[top++][1] = mid;
  }
  return best;
}

double arc_clearance(const tdo_grid* grid, const tdo_path_segment& seg, double cap, double best) {
  const double r = norm(sub(seg.p[0], seg.p[2]));
  const double whole = norm(sub(seg.p[1], seg.p[0]));
  // Sagitta of a chord c on a circle of radius r: (c^2/4) / (r + sqrt(r^2 - c^2/4)).
  const auto sagitta = [r](double c) {
    const double q = 0.25 * c * c;
    const double root = r * r - q;
    return q / (r + sqrt(root > 0.0 ? root : 0.0)) + kSagittaSlack;
  };
  const uint32_t k = chords_for(sagitta(whole));
  tdo_vec3 a = seg.p[0];
  for (uint32_t i = 0; i < k; ++i) {
    const tdo_vec3 b = i + 1u == k ? seg.p[1] : tdo_segment_point(&seg, seg.length * (i + 1u) / k);
    best = piece_bound(grid, a, b, sagitta(norm(sub(b, a))), cap, best);
    a = b;
  }
  return best;
}

// The running minimum goes into every query (piece_bound): same result, shorter queries.
double path_clearance(const tdo_grid* grid, const tdo_path& path, double cap, double best) {
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& seg = path.seg[i];
    if (seg.kind == TDO_SEGMENT_LINE || !(seg.length > 0.0))
      best = piece_bound(grid, seg.p[0], tdo_segment_point(&seg, seg.length), 0.0, cap, best);
    else if (seg.kind == TDO_SEGMENT_ARC)
      best = arc_clearance(grid, seg, cap, best);
    else
      best = bezier_clearance(grid, seg, cap, best);
  }
  return best;
}

double polyline_clearance(const tdo_grid* grid, const tdo_vec3* w, uint32_t n, double cap,
                          double best) {
  for (uint32_t i = 1; i < n; ++i) best = piece_bound(grid, w[i - 1], w[i], 0.0, cap, best);
  return best;
}

tdo_status validate(const tdo_metrics_input* in) {
  if (in->waypoints == nullptr || in->n_waypoints < 2u) return TDO_ERR_INVALID_ARGUMENT;
  for (uint32_t i = 0; i < in->n_waypoints; ++i)
    if (!finite3(in->waypoints[i])) return TDO_ERR_INVALID_ARGUMENT;
  if (in->path != nullptr) {
    const tdo_path& p = *in->path;
    if (p.seg == nullptr || p.n == 0u) return TDO_ERR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < p.n; ++i) {
      if (!segment_shape_ok(p.seg[i])) return TDO_ERR_INVALID_ARGUMENT;
    }
  }
  if (in->samples != nullptr && in->n_samples > 0u &&
      !samples_accepted(in->samples, in->n_samples, in->dt))
    return TDO_ERR_INVALID_ARGUMENT;
  if (in->grid != nullptr) {
    if (isnan(in->clearance_cap) || !(in->clearance_cap > 0.0)) return TDO_ERR_INVALID_ARGUMENT;
    if (tdo_grid_clearance(in->grid) < 0.0) return TDO_ERR_MAP_NOT_READY;
  }
  return TDO_OK;
}

}  // namespace

// A hint starts the running minimum just above the expected result, so the queries are capped
// tightly from the first one; the result is the same as long as the path comes below the hint
// (every piece at or above it changes nothing), else it is measured again without.
double path_min_clearance(const tdo_grid* grid, const tdo_path* path, const tdo_vec3* w, uint32_t n,
                          double cap, double hint) {
  const bool hinted = hint > 0.0 && hint < cap;
  const auto measure = [=](double start) {
    return path != nullptr ? path_clearance(grid, *path, cap, start)
                           : polyline_clearance(grid, w, n, cap, start);
  };
  double d = measure(hinted ? hint : HUGE_VAL);
  if (hinted && !(d < hint)) d = measure(HUGE_VAL);
  if (d < 0.0) d = 0.0;  // a lower bound below zero means touching
  return d < cap ? d : cap;
}

}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" tdo_status tdo_metrics_compute(const tdo_metrics_input* in, tdo_metrics* out) {
  if (in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  out->min_clearance_m = HUGE_VAL;
  const tdo_status st = validate(in);
  if (st != TDO_OK) return st;

  const Turns tw = turn_stats(in->waypoints, in->n_waypoints);
  out->turns = tw.turns;
  out->total_turn_deg = tw.total_deg;

  double length = 0.0, abs_int = 0.0, sq_int = 0.0;
  if (in->path != nullptr) {
    for (uint32_t i = 0; i < in->path->n; ++i) {
      length += in->path->seg[i].length;
      curvature_integrals(in->path->seg[i], &abs_int, &sq_int);
    }
    out->curvature_continuous = curvature_continuous(*in->path);
  } else {
    length = tw.length;
    abs_int = tw.sum_abs;
    sq_int = tw.sum_sq;
    out->curvature_continuous = tw.max_theta > kAngleTol ? 0 : 1;
  }
  out->length_m = length;
  out->avg_curvature = length > 0.0 ? abs_int / length : 0.0;
  out->smoothness = 1.0 / (1.0 + sq_int * 1.0);  // integral kappa^2 ds (1/m) times 1 m

  if (in->grid != nullptr)
    out->min_clearance_m = path_min_clearance(in->grid, in->path, in->waypoints, in->n_waypoints,
                                              in->clearance_cap, in->clearance_hint);

  if (in->samples != nullptr && in->n_samples >= 2u) {
    double energy = 0.0;
    for (uint32_t i = 1; i < in->n_samples; ++i)
      energy += tdo_internal::energy_step(in->samples[i - 1u], in->samples[i]);
    out->energy = energy;
    out->flight_time_s = in->samples[in->n_samples - 1u].t - in->samples[0].t;
  }
  return TDO_OK;
}
