// Exact continuous clearance queries against the grid's obstacle geometry (collision.h).
//
// Geometry = the boxes (exact, also their parts outside the grid bounds) + the occupied voxel
// cubes of voxel maps. Two independent parts answer every query:
// - Boxes: the segment is cut at the coarse bucket cells it crosses (a 3D DDA); every box listed
//   in a cell is tested exactly against the piece of the segment inside that cell. A box is listed
//   in every cell its box grown by bucket_reach touches, so every box closer than bucket_reach to
//   a point of the piece is tested. Queries that reach further scan every box.
// - Cubes: the segment is split recursively (explicit fixed-size stack). A piece with midpoint m
//   and half-length L is clear when df(voxel of m) - |m - centre| - res*sqrt(3)/2 - L >= clearance:
//   the distance field bounds the distance to every occupied voxel from below. Pieces at voxel
//   scale test the nearby surface cubes exactly, found through the brick index
//   (surface_index.h): nearest brick first, up to the first that cannot hold anything nearer.
// Segment-to-box distances are exact: the squared distance is a convex piecewise quadratic in the
// segment parameter; it is minimised in closed form on each piece between slab crossings.
#include "tdo/collision.h"

#include <math.h>

#include "collision_internal.h"
#include "grid_internal.h"
#include "surface_index.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

constexpr double kHalfDiag = 0.86602540378443864676;  // sqrt(3) / 2
constexpr int kStackCap = 64;              // subdivision stack entries (depth 63: pieces of 2^-63)
constexpr uint32_t kMaxPieces = 1u << 20;  // pieces of one cube query; beyond: "not clear"
constexpr int kBezierStackCap = 40;        // Bezier subdivision stack entries
constexpr uint32_t kMaxBezierPieces = 1u << 14;  // Bezier pieces of one query; beyond: "not clear"
constexpr double kMinTolerance = 1e-9;           // m, smallest Bezier tolerance honoured

inline void load(const tdo_vec3& v, double p[3]) {
  p[0] = v.x;
  p[1] = v.y;
  p[2] = v.z;
}

inline tdo_vec3 vec(const double p[3]) { return tdo_vec3{p[0], p[1], p[2]}; }

inline double dmin(double a, double b) { return b < a ? b : a; }
inline double dmax(double a, double b) { return b > a ? b : a; }

// Point of the segment a + t (b - a); the end points are returned exactly.
inline void seg_point(const double a[3], const double b[3], double t, double p[3]) {
  if (!(t > 0.0)) {
    for (int i = 0; i < 3; ++i) p[i] = a[i];
  } else if (!(t < 1.0)) {
    for (int i = 0; i < 3; ++i) p[i] = b[i];
  } else {
    for (int i = 0; i < 3; ++i) p[i] = a[i] + t * (b[i] - a[i]);
  }
}

// Squared distance (m^2) from point p to the closed box [lo, hi].
inline double point_box_d2(const double p[3], const double lo[3], const double hi[3]) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i) {
    // Branch-free (max instructions): at most one of the two gaps is positive.
    const double g = dmax(lo[i] - p[i], 0.0) + dmax(p[i] - hi[i], 0.0);
    s += g * g;
  }
  return s;
}

// Exact minimum squared distance (m^2) from the segment [a, b] to the closed box [lo, hi].
// F(t) = sum_i gap_i(a + t d)^2 is convex and quadratic between the breakpoints where a coordinate
// crosses a slab face. Candidates: both ends, every breakpoint and the vertex of each piece's
// quadratic when it lies inside the piece; every candidate is evaluated as the distance of an
// actual point, so rounding can only make the result larger by rounding of that evaluation.
// With stop2 > 0 it returns as soon as the running minimum falls below stop2 (or to 0): a value
// below stop2 then, the exact minimum otherwise (the minimum only falls).
double segment_box_d2(const double a[3], const double b[3], const double lo[3], const double hi[3],
                      double stop2 = -1.0) {
  double best = point_box_d2(a, lo, hi);
  if (!(best > 0.0)) return 0.0;
  if (best < stop2) return best;
  double d[3];
  for (int i = 0; i < 3; ++i) d[i] = b[i] - a[i];
  double bp[8];
  int n = 0;
  bp[n++] = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (!(d[i] < 0.0 || d[i] > 0.0)) continue;
    const double t1 = (lo[i] - a[i]) / d[i];
    const double t2 = (hi[i] - a[i]) / d[i];
    if (t1 > 0.0 && t1 < 1.0) bp[n++] = t1;
    if (t2 > 0.0 && t2 < 1.0) bp[n++] = t2;
  }
  bp[n++] = 1.0;
  for (int i = 2; i < n - 1; ++i) {  // insertion sort of the interior breakpoints
    const double x = bp[i];
    int j = i - 1;
    while (j >= 1 && bp[j] > x) {
      bp[j + 1] = bp[j];
      --j;
    }
    bp[j + 1] = x;
  }
  double p[3];
  for (int k = 1; k < n; ++k) {
    seg_point(a, b, bp[k], p);
    best = dmin(best, point_box_d2(p, lo, hi));
    if (!(best > 0.0) || best < stop2) return best;
    const double t0 = bp[k - 1], t1 = bp[k];
    if (!(t1 > t0)) continue;
    // The active slab faces on (t0, t1) are those of its midpoint.
    const double tm = 0.5 * (t0 + t1);
    double qa = 0.0, qb = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double x = a[i] + tm * d[i];
      const double face = x < lo[i] ? lo[i] : (x > hi[i] ? hi[i] : x);
      if (!(x < face || x > face)) continue;  // inside the slab: no term
      qa += d[i] * d[i];
      qb += (a[i] - face) * d[i];
    }
    if (!(qa > 0.0)) continue;
    const double tv = -qb / qa;
    if (tv > t0 && tv < t1) {
      seg_point(a, b, tv, p);
      best = dmin(best, point_box_d2(p, lo, hi));
      if (!(best > 0.0) || best < stop2) return best;
    }
  }
  return best;
}

inline void box_bounds(const tdo_box& b, double lo[3], double hi[3]) {
  load(b.min, lo);
  load(b.max, hi);
}

// The segment's bounding box grown by r misses [lo, hi]: no point of it is within r.
inline bool far_apart(const double a[3], const double b[3], const double lo[3], const double hi[3],
                      double r) {
  for (int i = 0; i < 3; ++i) {
    if (lo[i] - r > dmax(a[i], b[i]) || hi[i] + r < dmin(a[i], b[i])) return true;
  }
  return false;
}

// A distance d (as d^2) violates clearance c: closer than c, or touching at all.
inline bool violates(double d2, double c) { return !(d2 >= c * c) || !(d2 > 0.0); }

bool inside_bounds(const tdo_grid* g, const double p[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  for (int i = 0; i < 3; ++i)
    if (!(p[i] >= o[i]) || !(p[i] <= o[i] + static_cast<double>(n[i]) * d.res)) return false;
  return true;
}

// Distance (m) from p to the closed grid bounds, 0 inside.
double bounds_distance(const tdo_grid* g, const double p[3]) {
  const tdo_grid_desc& d = g->desc;
  const double lo[3] = {d.origin.x, d.origin.y, d.origin.z};
  const double hi[3] = {d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res,
                        d.origin.z + d.nz * d.res};
  return sqrt(point_box_d2(p, lo, hi));
}

// ---------------------------------------------------------------------------------------------
// Boxes.

// floor(x) clamped to [0, n - 1], for finite x: truncation equals floor on [0, n), and below 0
// or from n on the clamp decides (no libm call).
inline int32_t clamped_floor(double x, int32_t n) {
  if (!(x >= 0.0)) return 0;
  if (!(x < static_cast<double>(n))) return n - 1;
  return static_cast<int32_t>(x);
}

// Cut [a, b] (inside the grid bounds) at the bucket cell faces and call f(p0, p1, cell) for every
// non-empty piece, in order; the cell is that of the piece's midpoint. Stops when f returns false.
// Bounded: every iteration crosses one cell face, at most ncx + ncy + ncz + 3 iterations.
template <class F>
bool for_each_cell_piece(const tdo_grid* g, const double a[3], const double b[3], F&& f) {
  const tdo_grid_desc& desc = g->desc;
  const double o[3] = {desc.origin.x, desc.origin.y, desc.origin.z};
  const int32_t nc[3] = {g->ncx, g->ncy, g->ncz};
  const double e = g->cell_edge;
  double d[3], next[3];
  int32_t face[3];
  for (int i = 0; i < 3; ++i) {
    d[i] = b[i] - a[i];
    const int32_t ci = clamped_floor((a[i] - o[i]) / e, nc[i]);
    next[i] = HUGE_VAL;
    face[i] = 0;
    if (d[i] > 0.0) {
      face[i] = ci + 1;
      if (face[i] < nc[i]) next[i] = (o[i] + face[i] * e - a[i]) / d[i];
    } else if (d[i] < 0.0) {
      face[i] = ci;
      if (face[i] > 0) next[i] = (o[i] + face[i] * e - a[i]) / d[i];
    }
  }
  const int64_t guard = static_cast<int64_t>(nc[0]) + nc[1] + nc[2] + 3;
  double t0 = 0.0;
  for (int64_t it = 0; it < guard; ++it) {
    const double t1 = dmin(1.0, dmin(next[0], dmin(next[1], next[2])));
    if (t1 > t0 || it == 0) {
      double p0[3], p1[3];
      seg_point(a, b, t0, p0);
      seg_point(a, b, t1 > t0 ? t1 : t0, p1);
      int32_t cell[3];
      for (int i = 0; i < 3; ++i) {
        cell[i] = clamped_floor((0.5 * (p0[i] + p1[i]) - o[i]) / e, nc[i]);
      }
      if (!f(p0, p1, static_cast<uint32_t>(cell[0] + nc[0] * (cell[1] + nc[1] * cell[2]))))
        return false;
    }
    if (!(t1 < 1.0)) return true;
    for (int i = 0; i < 3; ++i) {
      if (next[i] > t1) continue;
      next[i] = HUGE_VAL;
      if (d[i] > 0.0) {
        ++face[i];
        if (face[i] < nc[i]) next[i] = (o[i] + face[i] * e - a[i]) / d[i];
      } else {
        --face[i];
        if (face[i] > 0) next[i] = (o[i] + face[i] * e - a[i]) / d[i];
      }
    }
    t0 = dmax(t0, t1);
  }
  return true;
}

// Bounding box of a segment piece [p0, p1], as far_apart computes it for every box.
struct SpanBox {
  double mn[3], mx[3];
};
inline SpanBox span_box(const double p0[3], const double p1[3]) {
  SpanBox s;
  for (int i = 0; i < 3; ++i) {
    s.mn[i] = dmin(p0[i], p1[i]);
    s.mx[i] = dmax(p0[i], p1[i]);
  }
  return s;
}

// Squared gap (m^2) per axis and local coordinate between the span box and a brick's cubes
// (brick_faces): span_gap2's per-axis terms, which it sums in axis order.
inline void brick_gaps2(const double f[3][kBrickVoxels + 1], const SpanBox& sb,
                        double g2[3][kBrickVoxels]) {
  for (int a = 0; a < 3; ++a)
    for (int l = 0; l < kBrickVoxels; ++l) {
      const double gp = dmax(f[a][l] - sb.mx[a], 0.0) + dmax(sb.mn[a] - f[a][l + 1], 0.0);
      g2[a][l] = gp * gp;
    }
}

// far_apart of box b and the span box with distance r, read from the box itself (the same
// comparisons, without copying the bounds first: most boxes stop here).
inline bool span_far(const tdo_box& b, const SpanBox& sb, double r) {
  return b.min.x - r > sb.mx[0] || b.max.x + r < sb.mn[0] || b.min.y - r > sb.mx[1] ||
         b.max.y + r < sb.mn[1] || b.min.z - r > sb.mx[2] || b.max.z + r < sb.mn[2];
}

// Quick decisions before an exact segment-to-box distance. Every candidate point the exact
// computation evaluates lies within a few ulps of the coordinates (~1e-15 * scale) of the true
// segment, and every squared distance it sums is within a few ulps relative. So a lower bound
// (the distance between the segment's bounding box and the box) that exceeds the limit by `tol`,
// or a point of the segment closer than the limit by `tol`, gives the exact computation's
// decision; `tol` is kQuickRel * (1 + limit + scale) m, scale the largest coordinate magnitude
// in use, far above that rounding and far below any clearance that matters.
constexpr double kQuickRel = 1e-9;

// Largest coordinate magnitude (m) of the grid bounds: every segment of a box query lies inside.
inline double bounds_scale(const tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const double e[3] = {o[0] + d.nx * d.res, o[1] + d.ny * d.res, o[2] + d.nz * d.res};
  double s = 0.0;
  for (int i = 0; i < 3; ++i) s = dmax(s, dmax(fabs(o[i]), fabs(e[i])));
  return s;
}

inline double quick_tol(double limit, double scale) { return kQuickRel * (1.0 + limit + scale); }

// Squared distance (m^2) between the box [lo, hi] and the span box: at most the squared distance
// of every point of the piece.
inline double span_gap2(const SpanBox& sb, const double lo[3], const double hi[3]) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double g = dmax(lo[i] - sb.mx[i], 0.0) + dmax(sb.mn[i] - hi[i], 0.0);
    s += g * g;
  }
  return s;
}

// Squared distance (m^2) from [lo, hi] to the point of [a, b] nearest to the box's centre line
// projection (the centre projected onto the segment): an upper bound of the segment's distance.
inline double centre_point_d2(const double a[3], const double b[3], const double lo[3],
                              const double hi[3]) {
  double dd = 0.0, wd = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double d = b[i] - a[i];
    dd += d * d;
    wd += (0.5 * (lo[i] + hi[i]) - a[i]) * d;
  }
  double t = dd > 0.0 ? wd / dd : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  double p[3];
  seg_point(a, b, t, p);
  return point_box_d2(p, lo, hi);
}

// 1 when box `b` keeps clearance c from [p0, p1] (sb = span_box(p0, p1)): far_apart, the span
// box's distance (quick: clear), then the exact distance. `tol` = quick_tol(c, scale).
inline bool box_clear(const tdo_box& b, const double p0[3], const double p1[3], const SpanBox& sb,
                      double c, double tol) {
  if (span_far(b, sb, c)) return true;
  double lo[3], hi[3];
  box_bounds(b, lo, hi);
  const double ct = c + tol;
  if (span_gap2(sb, lo, hi) >= ct * ct) return true;
  return !violates(segment_box_d2(p0, p1, lo, hi, c * c), c);
}

// Lower *best (m) to the distance of [p0, p1] to box b when that is smaller.
// `scale` as for quick_tol: a span box farther than *best by the quick tolerance cannot lower it.
inline void box_min(const tdo_box& b, const double p0[3], const double p1[3], const SpanBox& sb,
                    double scale, double* best) {
  if (span_far(b, sb, *best)) return;
  double lo[3], hi[3];
  box_bounds(b, lo, hi);
  const double bt = *best + quick_tol(*best, scale);
  if (span_gap2(sb, lo, hi) >= bt * bt) return;
  const double d2 = segment_box_d2(p0, p1, lo, hi);
  if (d2 < *best * *best) *best = sqrt(d2);
}

// *hit = index of the box that failed (unchanged when every box keeps clearance).
bool boxes_clear(const tdo_grid* g, const double a[3], const double b[3], double c, uint32_t* hit) {
  if (g->n_boxes == 0) return true;
  const SpanBox whole = span_box(a, b);
  const double tol = quick_tol(c, bounds_scale(g));
  if (!(c <= g->bucket_reach)) {
    for (uint32_t k = 0; k < g->n_boxes; ++k) {
      if (!box_clear(g->boxes[k], a, b, whole, c, tol)) {
        *hit = k;
        return false;
      }
    }
    return true;
  }
  for (uint32_t k = 0; k < g->n_large; ++k) {
    if (!box_clear(g->boxes[g->large_boxes[k]], a, b, whole, c, tol)) {
      *hit = g->large_boxes[k];
      return false;
    }
  }
  return for_each_cell_piece(
      g, a, b, [g, c, tol, hit](const double* p0, const double* p1, uint32_t cell) {
        const SpanBox sb = span_box(p0, p1);
        for (uint32_t r = g->cell_start[cell]; r < g->cell_start[cell + 1]; ++r) {
          if (!box_clear(g->boxes[g->box_refs[r]], p0, p1, sb, c, tol)) {
            *hit = g->box_refs[r];
            return false;
          }
        }
        return true;
      });
}

// Margin (m) of the hinted test below: far above the rounding of piece end points (~1e-15 of the
// coordinates), far below any clearance that matters.
constexpr double kHintMargin = 1e-7;

// True when box k is certainly closer than c to [a, b] (both inside the bounds), so that
// boxes_clear finds a violation: the box is then within reach of the nearest point of the segment
// and listed in that point's cell (or scanned whole), and the piece holding that point is, up to
// rounding far below kHintMargin, at most as far from the box.
bool box_certainly_violates(const tdo_grid* g, uint32_t k, const double a[3], const double b[3],
                            double c) {
  if (k >= g->n_boxes || !(c > kHintMargin)) return false;
  double lo[3], hi[3];
  box_bounds(g->boxes[k], lo, hi);
  if (far_apart(a, b, lo, hi, c)) return false;
  const double m = c - kHintMargin;
  // Quick: a point of the segment closer than m (its rounding is far below the margin too).
  if (centre_point_d2(a, b, lo, hi) < m * m) return true;
  return segment_box_d2(a, b, lo, hi, m * m) < m * m;
}

// min(cap, distance from [a, b] to the boxes).
double boxes_min(const tdo_grid* g, const double a[3], const double b[3], double cap, bool inside) {
  double best = cap;
  if (g->n_boxes == 0) return best;
  const SpanBox whole = span_box(a, b);
  // Outside the bounds the segment's own coordinates count too.
  double scale = bounds_scale(g);
  for (int i = 0; i < 3; ++i) scale = dmax(scale, dmax(fabs(a[i]), fabs(b[i])));
  if (inside) {
    // Every box closer than bucket_reach to a point of the segment is listed in that point's cell:
    // a result below the reach (or a cap within it) is exact.
    const double reach = dmin(cap, g->bucket_reach);
    double near = reach;
    for (uint32_t k = 0; k < g->n_large; ++k)
      box_min(g->boxes[g->large_boxes[k]], a, b, whole, scale, &near);
    for_each_cell_piece(g, a, b,
                        [g, scale, &near](const double* p0, const double* p1, uint32_t cell) {
                          const SpanBox sb = span_box(p0, p1);
                          for (uint32_t r = g->cell_start[cell]; r < g->cell_start[cell + 1]; ++r)
                            box_min(g->boxes[g->box_refs[r]], p0, p1, sb, scale, &near);
                          return true;
                        });
    if (near < g->bucket_reach || !(cap > g->bucket_reach)) return near;
  }
  for (uint32_t k = 0; k < g->n_boxes; ++k) box_min(g->boxes[k], a, b, whole, scale, &best);
  return best;
}

// ---------------------------------------------------------------------------------------------
// Cubes.

struct Piece {
  double t0, t1;  // parameter interval of the segment
};

// Geometry of a piece relative to the distance field.
struct PieceInfo {
  double p0[3], p1[3];  // m, end points
  double lb;            // m, lower bound of the distance from the piece to every cube
  double ub;            // m, upper bound of the distance from the midpoint to obstacle geometry
  bool leaf;            // at voxel scale: test the cubes exactly
  bool in_cube;         // the midpoint lies in a cube: distance 0
};

}  // namespace

// Table of voxel_gap2_lower: built at compile time from the integer offsets of the first octant
// with sorted components up to kGapComponents (a larger component alone gives a gap^2 of at least
// kGapComponents^2 = 289 > 225, the gap^2 of offset (16, 0, 0), which qualifies for every n up
// to 256; the entries above kGapTableMax may miss offsets and are not used).
constexpr uint32_t kGapComponents = 17;
struct GapTable {
  uint16_t g[kGapTableMax + 1];
};
constexpr GapTable make_gap_table() {
  constexpr uint32_t kTop = 3 * kGapComponents * kGapComponents;
  uint16_t at[kTop + 1] = {};  // per exact squared offset: the smallest gap^2 (0xFFFF: none)
  for (uint32_t v = 0; v <= kTop; ++v) at[v] = 0xFFFFu;
  for (uint32_t a = 0; a <= kGapComponents; ++a)
    for (uint32_t b = a; b <= kGapComponents; ++b)
      for (uint32_t c = b; c <= kGapComponents; ++c) {
        const uint32_t v = a * a + b * b + c * c;
        const uint32_t e = (a > 0 ? (a - 1) * (a - 1) : 0) + (b > 0 ? (b - 1) * (b - 1) : 0) +
                           (c > 0 ? (c - 1) * (c - 1) : 0);
        if (e < at[v]) at[v] = static_cast<uint16_t>(e);
      }
  for (uint32_t v = kTop; v > 0; --v)  // suffix minimum: every offset with |d|^2 >= v
    if (at[v] < at[v - 1]) at[v - 1] = at[v];
  GapTable t{};
  for (uint32_t n = 0; n <= kGapTableMax; ++n) t.g[n] = at[n];
  return t;
}
constexpr GapTable kGapTable = make_gap_table();

uint32_t voxel_gap2_lower(uint32_t n) { return n <= kGapTableMax ? kGapTable.g[n] : 0xFFFFFFFFu; }

namespace {

// Lower bound (m) of the distance between the closed box of a voxel and every occupied voxel
// cube, from df_lb (m), a lower bound of the voxel's distance field entry. The squared centre
// offset in voxels is an integer of at least n = ceil((df_lb / res)^2 - 0.01) (df is rounded down
// by far less than 0.01 voxel^2 up to the table's end); beyond the table, |e| >= |d| - sqrt(3)
// for the per-axis gaps e_i = max(|d_i| - 1, 0).
inline double voxel_gap_lower(double df_lb, double res) {
  const double x = df_lb / res;
  if (!(x > 1.0)) return 0.0;  // also 0 and NaN: no claim beyond 0
  const double x2 = x * x;
  if (x2 > static_cast<double>(kGapTableMax)) return (x - 2.0 * kHalfDiag) * res;
  const double y = x2 - 0.01;  // > 0.99: ceil by truncation (no libm call)
  const uint32_t t = static_cast<uint32_t>(y);
  const uint32_t n = static_cast<double>(t) < y ? t + 1u : t;
  return sqrt(static_cast<double>(kGapTable.g[n])) * res;
}

// The voxel of the half-open grid holding p (finite), as tdo_grid_world_to_voxel finds it (the
// same span arithmetic), without its calls: false outside. Below -1 or from n + 1 on (in voxels)
// the point is outside whatever the corrections do (each moves the index by one at most); in
// between, truncation is floor for x >= 0 and [-1, 0) floors to -1. x may be one rounding step
// off the quotient (a multiplication by 1 / res); the corrections settle the index either way,
// and the outside tests hold with that slack (a point below -1 + 1e-15 voxels is outside too).
inline bool voxel_of(const tdo_grid* g, const double p[3], int64_t v[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  const double r = d.res;
  const double inv = 1.0 / r;  // the corrections below fix the one-off its rounding may cause
  for (int a = 0; a < 3; ++a) {
    const double x = (p[a] - o[a]) * inv;
    if (!(x >= -1.0) || !(x < static_cast<double>(n[a]) + 1.0)) return false;
    double i = x < 0.0 ? -1.0 : static_cast<double>(static_cast<int64_t>(x));
    if (o[a] + i * r > p[a]) i -= 1.0;
    if (!(o[a] + (i + 1.0) * r > p[a])) i += 1.0;
    if (i < 0.0 || i >= static_cast<double>(n[a])) return false;
    v[a] = static_cast<int64_t>(i);
  }
  return true;
}

PieceInfo piece_info(const tdo_grid* g, const double a[3], const double b[3], const Piece& pc) {
  PieceInfo pi;
  seg_point(a, b, pc.t0, pi.p0);
  seg_point(a, b, pc.t1, pi.p1);
  double m[3], half2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    m[i] = 0.5 * (pi.p0[i] + pi.p1[i]);
    const double h = 0.5 * (pi.p1[i] - pi.p0[i]);
    half2 += h * h;
  }
  const double half = sqrt(half2);
  const double res = g->desc.res;
  pi.leaf = !(2.0 * half > res);
  pi.in_cube = false;
  int64_t v[3];
  if (!voxel_of(g, m, v)) {
    // Outside the (half-open) grid: the cubes lie inside the bounds.
    pi.lb = bounds_distance(g, m) - half;
    pi.ub = HUGE_VAL;
    if (inside_bounds(g, m)) pi.lb = -1.0;  // on a max face: no bound used
    return pi;
  }
  const int64_t idx = v[0] + v[1] * g->stride_y + v[2] * g->stride_z;
  pi.in_cube = (g->flags[idx] & kFlagCube) != 0;
  const tdo_grid_desc& d = g->desc;
  // The voxel centre as tdo_grid_voxel_center computes it.
  const double dx = m[0] - (d.origin.x + (static_cast<double>(v[0]) + 0.5) * res);
  const double dy = m[1] - (d.origin.y + (static_cast<double>(v[1]) + 0.5) * res);
  const double dz = m[2] - (d.origin.z + (static_cast<double>(v[2]) + 0.5) * res);
  const double off = sqrt(dx * dx + dy * dy + dz * dz);
  df_ensure(g);  // built on the first query after a finish
  const double df = static_cast<double>(g->df[idx]);
  const double df_lb = g->df_cap > 0.0 && df > g->df_cap ? g->df_cap : df;  // map updates
  // Two lower bounds of the distance from the voxel's points to every occupied cube: through the
  // midpoint (its offset from the centre counted) and through the voxel's whole box (the integer
  // offsets of the voxels, docs/design.md s.0 "Distance to the cubes"); every piece point is
  // within `half` of the midpoint, which lies in the voxel's box.
  const double lb = dmax(df_lb - off - kHalfDiag * res, voxel_gap_lower(df_lb, res));
  pi.lb = lb - half - (1e-7 * res + 1e-12);
  pi.ub = g->df_valid ? df + off + kHalfDiag * res : HUGE_VAL;
  return pi;
}

// Call f(cube lo, cube hi) for every surface cube whose cube may lie within r of [p0, p1];
// stops when f returns false. Bounded by the voxels of the grown bounding box, clamped to the grid.
template <class F>
bool for_each_cube_near(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                        F&& f) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  int64_t lo[3], hi[3];  // one voxel of margin; far_apart filters the extra cubes
  if (!span_voxels(g, p0, p1, r, lo, hi)) return true;
  for (int64_t k = lo[2]; k <= hi[2]; ++k) {
    for (int64_t j = lo[1]; j <= hi[1]; ++j) {
      const uint8_t* row = g->flags + j * g->stride_y + k * g->stride_z;
      for (int64_t i = lo[0]; i <= hi[0]; ++i) {
        if ((row[i] & kFlagSurface) == 0) continue;
        const double clo[3] = {o[0] + static_cast<double>(i) * d.res,
                               o[1] + static_cast<double>(j) * d.res,
                               o[2] + static_cast<double>(k) * d.res};
        const double chi[3] = {o[0] + static_cast<double>(i + 1) * d.res,
                               o[1] + static_cast<double>(j + 1) * d.res,
                               o[2] + static_cast<double>(k + 1) * d.res};
        if (!f(clo, chi)) return false;
      }
    }
  }
  return true;
}

// Rounding allowance (m) of the brick gaps of a query on [p0, p1] at limit r: quick_tol with the
// query's own coordinates counted (a leaf may lie outside the bounds).
double brick_tol(const tdo_grid* g, const double p0[3], const double p1[3], double r) {
  double scale = bounds_scale(g);
  for (int i = 0; i < 3; ++i) scale = dmax(scale, dmax(fabs(p0[i]), fabs(p1[i])));
  return quick_tol(r, scale);
}

// Lower *bst (m) to the distance of [p0, p1] (span box sb) to the surface cubes of brick c.
// A cube whose gap to the span box reaches *bst + tol (tol: brick_tol at a limit >= *bst) cannot
// lower it (box_min's quick test).
// Only the cubes whose voxels lie within *bst of the span box, plus one voxel, are visited (in the
// same order): every other one is farther than *bst by a voxel on some axis, so far_apart skips
// it (*bst only falls during the brick).
inline void brick_min(const tdo_grid* g, const BrickCand& c, const double p0[3], const double p1[3],
                      const SpanBox& sb, double tol, bool point, double* bst) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  // The cube faces and squared span gaps per axis and local coordinate, once per brick; per cube
  // the same tests in the same order.
  int64_t base[3];
  double f[3][kBrickVoxels + 1], g2[3][kBrickVoxels];
  brick_faces(g, c.brick, base, f);
  if (!point) brick_gaps2(f, sb, g2);
  uint64_t m = g->brick_mask[c.brick];
  if (*bst < 64.0 * d.res) {
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<int64_t>(floor((sb.mn[a] - *bst - o[a]) / d.res)) - 1 - base[a];
      hi[a] = static_cast<int64_t>(floor((sb.mx[a] + *bst - o[a]) / d.res)) + 1 - base[a];
    }
    m &= brick_local_mask(lo, hi);
  }
  while (m != 0u) {
    const uint32_t b = static_cast<uint32_t>(__builtin_ctzll(m));
    m &= m - 1u;
    const uint32_t l[3] = {b & 3u, (b >> 2) & 3u, b >> 4};
    const double lo[3] = {f[0][l[0]], f[1][l[1]], f[2][l[2]]};
    const double hi[3] = {f[0][l[0] + 1], f[1][l[1] + 1], f[2][l[2] + 1]};
    if (far_apart(p0, p1, lo, hi, *bst)) continue;
    if (!point) {
      const double bt = *bst + tol;
      double s2 = 0.0;
      for (int a = 0; a < 3; ++a) s2 += g2[a][l[a]];
      if (s2 >= bt * bt) continue;
    }
    const double d2 = point ? point_box_d2(p0, lo, hi) : segment_box_d2(p0, p1, lo, hi);
    if (d2 < *bst * *bst) *bst = sqrt(d2);
    if (!(*bst > 0.0)) return;
  }
}

// min(*best, distance from [p0, p1] to the surface cubes within r of it) through the brick
// index: bricks in increasing gap, stopping at the first whose gap reaches the running minimum
// (more than kMaxBrickCands bricks: in index order, each skipped when its gap reaches it). The
// cubes visited get the scan's tests, and every cube the scan could lower the minimum with is
// visited, so the result is the scan's. false: no index (*best unchanged; the caller scans).
// Not inlined: its 2 KB candidate array stays off the stack of queries on maps without cubes.
__attribute__((noinline)) bool bricks_min(const tdo_grid* g, const double p0[3], const double p1[3],
                                          bool point, double r, double* best) {
  if (!g->bricks_valid) return false;
  BrickCand cand[kMaxBrickCands];
  const double tol = brick_tol(g, p0, p1, r);
  const SpanBox sb = span_box(p0, p1);
  double bst = *best;
  const uint32_t n = surface_bricks_sorted(g, p0, p1, r, r + tol, cand);
  if (n <= kMaxBrickCands) {
    for (uint32_t c = 0; c < n && bst > 0.0; ++c) {
      const double lim = bst + tol;
      if (cand[c].gap2 > 0.0 && cand[c].gap2 >= lim * lim) break;  // sorted: so are the rest
      brick_min(g, cand[c], p0, p1, sb, tol, point, &bst);
    }
  } else {
    for_each_brick_near(g, p0, p1, r, [&](const BrickCand& c) {
      const double lim = bst + tol;
      if (!(c.gap2 > 0.0 && c.gap2 >= lim * lim)) brick_min(g, c, p0, p1, sb, tol, point, &bst);
      return bst > 0.0;
    });
  }
  *best = bst;
  return true;
}

// Voxel index of the cube with lower corner lo (as the cube loops compute it).
inline uint32_t cube_index(const tdo_grid* g, const double lo[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  int64_t v[3];
  for (int i = 0; i < 3; ++i) v[i] = static_cast<int64_t>(floor((lo[i] - o[i]) / d.res + 0.5));
  return static_cast<uint32_t>(v[0] + v[1] * g->stride_y + v[2] * g->stride_z);
}

// Bits of a brick's mask whose local coordinate on axis a (x: bit & 3, y: (bit >> 2) & 3,
// z: bit >> 4) is in the 4-bit set m: kAxisBits[a][m].
struct AxisBits {
  uint64_t m[3][16];
};
constexpr AxisBits make_axis_bits() {
  AxisBits t{};
  const uint64_t one[3] = {0x1111111111111111u, 0x000F000F000F000Fu, 0xFFFFu};
  const int shift[3] = {1, 4, 16};
  for (int a = 0; a < 3; ++a)
    for (unsigned m = 0; m < 16u; ++m)
      for (int l = 0; l < 4; ++l)
        if ((m >> l) & 1u) t.m[a][m] |= one[a] << (shift[a] * l);
  return t;
}
constexpr AxisBits kAxisBits = make_axis_bits();

// The cube loop of bricks_clear_hit for brick `brick`: for each cube in bit order far_apart at c,
// then span_gap2 against lim^2, then the exact distance, by the same expressions, with the
// per-axis parts computed once per brick. A cube's bounds are f[a][l] and f[a][l + 1] (l its
// local coordinate: brick_faces); far_apart holds when
// one axis is far, so the cubes of far coordinates are left out of the mask (they pass); the
// squared axis gaps are summed in span_gap2's order (0 + x, + y, + z). 0 and *hit: the first
// cube closer than c.
bool brick_cubes_clear(const tdo_grid* g, uint32_t brick, const double p0[3], const double p1[3],
                       const SpanBox& sb, double c, double lim, uint32_t* hit) {
  int64_t base[3];
  double f[3][kBrickVoxels + 1], g2[3][kBrickVoxels];
  brick_faces(g, brick, base, f);
  brick_gaps2(f, sb, g2);
  uint64_t m = g->brick_mask[brick];
  for (int a = 0; a < 3; ++a) {
    unsigned near = 0u;
    for (int l = 0; l < kBrickVoxels; ++l)
      if (!(f[a][l] - c > sb.mx[a] || f[a][l + 1] + c < sb.mn[a])) near |= 1u << l;
    m &= kAxisBits.m[a][near];
  }
  while (m != 0u) {
    const uint32_t b = static_cast<uint32_t>(__builtin_ctzll(m));
    m &= m - 1u;
    const uint32_t l[3] = {b & 3u, (b >> 2) & 3u, b >> 4};
    double s = 0.0;
    for (int a = 0; a < 3; ++a) s += g2[a][l[a]];
    if (s >= lim * lim) continue;  // box_clear's quick test
    const double lo[3] = {f[0][l[0]], f[1][l[1]], f[2][l[2]]};
    const double hi[3] = {f[0][l[0] + 1], f[1][l[1] + 1], f[2][l[2] + 1]};
    if (!violates(segment_box_d2(p0, p1, lo, hi, c * c), c)) continue;
    *hit = cube_index(g, lo);
    return false;
  }
  return true;
}

// 1 when every surface cube keeps clearance c from [p0, p1], 0 when one does not (the cube that
// fails it goes to *hit), -1 without an index. Only bricks closer than c (or touching) are visited,
// in any order; for_each_brick_within leaves out only bricks this skips by their gap.
int bricks_clear_hit(const tdo_grid* g, const double p0[3], const double p1[3], double c,
                     uint32_t* hit) {
  if (!g->bricks_valid) return -1;
  const double lim = c + brick_tol(g, p0, p1, c);
  const SpanBox sb = span_box(p0, p1);
  const auto visit = [&](const BrickCand& k) {
    if (k.gap2 > 0.0 && k.gap2 >= lim * lim) return true;
    return brick_cubes_clear(g, k.brick, p0, p1, sb, c, lim, hit);
  };
  const bool ok = within_pays(g, c, lim) ? for_each_brick_within(g, p0, p1, c, lim, visit)
                                         : for_each_brick_near(g, p0, p1, c, visit);
  return ok ? 1 : 0;
}

// bricks_clear_hit without the failing cube.
int bricks_clear(const tdo_grid* g, const double p0[3], const double p1[3], double c) {
  uint32_t hit = 0;
  return bricks_clear_hit(g, p0, p1, c, &hit);
}

// What a piece walk's visitor decides for one piece.
enum class PieceStep { skip, split, stop };

// Walk the pieces of [a, b] depth first from piece `from` (the whole segment: {0, 1}), halving each
// piece for which visit(PieceInfo) returns split. @return 1 when every piece was done, 0 when visit
// stopped the walk, -1 when kMaxPieces or kStackCap was reached (the caller answers
// conservatively).
template <class F>
int walk_pieces(const tdo_grid* g, const double a[3], const double b[3], Piece from, F&& visit) {
  Piece stack[kStackCap];
  int top = 0;
  stack[top++] = from;
  for (uint32_t pieces = 0; top > 0; ++pieces) {
    if (pieces >= kMaxPieces) return -1;
    const Piece pc = stack[--top];
    const PieceStep step = visit(piece_info(g, a, b, pc));
    if (step == PieceStep::stop) return 0;
    if (step == PieceStep::skip) continue;
    if (top + 2 > kStackCap) return -1;
    const double tm = 0.5 * (pc.t0 + pc.t1);
    stack[top++] = Piece{tm, pc.t1};
    stack[top++] = Piece{pc.t0, tm};
  }
  return 1;
}

bool cubes_clear(const tdo_grid* g, const double a[3], const double b[3], double c) {
  if (g->n_cubes == 0) return true;
  const int walked = walk_pieces(g, a, b, Piece{0.0, 1.0}, [g, c](const PieceInfo& pi) {
    if (pi.lb >= c && pi.lb > 0.0) return PieceStep::skip;
    if (!pi.leaf) return PieceStep::split;
    if (pi.in_cube) return PieceStep::stop;
    const int fast = bricks_clear(g, pi.p0, pi.p1, c);
    if (fast == 0) return PieceStep::stop;
    if (fast == 1) return PieceStep::skip;
    const bool ok =
        for_each_cube_near(g, pi.p0, pi.p1, c, [&pi, c](const double* lo, const double* hi) {
          if (far_apart(pi.p0, pi.p1, lo, hi, c)) return true;
          return !violates(segment_box_d2(pi.p0, pi.p1, lo, hi, c * c), c);
        });
    return ok ? PieceStep::skip : PieceStep::stop;
  });
  return walked == 1;  // never "clear" on overflow
}

// The exact part of cubes_min for one leaf piece: lowers *best; false when it reached 0.
bool leaf_min(const tdo_grid* g, const PieceInfo& pi, bool point, double* best) {
  // The nearest geometry of this piece is within ub of its midpoint; a farther cube cannot
  // lower the result (the boxes' part of `best` is exact).
  const double r = dmin(*best, pi.ub);
  if (!bricks_min(g, pi.p0, pi.p1, point, r, best)) {
    for_each_cube_near(g, pi.p0, pi.p1, r, [&pi, best](const double* lo, const double* hi) {
      if (far_apart(pi.p0, pi.p1, lo, hi, *best)) return true;
      const double d2 = segment_box_d2(pi.p0, pi.p1, lo, hi);
      if (d2 < *best * *best) *best = sqrt(d2);
      return *best > 0.0;
    });
  }
  return *best > 0.0;
}

// Margin (of res) of cubes_min's block test of a leaf: far above the rounding of the block
// test's voxel ranges and of the leaf's end points.
constexpr double kLeafBlockRel = 4e-7;
bool block_free(const tdo_grid* g, const double p0[3], const double p1[3], double r, bool boxes);

// Pieces of the best-first walk of cubes_min waiting in its heap (smallest lb on top): the
// parameters and what piece_info found, 40 bytes (the end points are recomputed, bit for bit:
// seg_point), so the heap stays at 1.9 KB of stack (embedded targets: docs/embedded.md).
constexpr uint32_t kMinHeapCap = 48;
struct HeapPiece {
  Piece pc;
  double lb, ub;  // m, as PieceInfo
  uint8_t leaf, in_cube;
};

inline HeapPiece heap_piece(const Piece& pc, const PieceInfo& pi) {
  return HeapPiece{pc, pi.lb, pi.ub, pi.leaf ? uint8_t{1} : uint8_t{0},
                   pi.in_cube ? uint8_t{1} : uint8_t{0}};
}

// The PieceInfo piece_info gave for hp.pc on [a, b].
inline PieceInfo unpack(const HeapPiece& hp, const double a[3], const double b[3]) {
  PieceInfo pi;
  seg_point(a, b, hp.pc.t0, pi.p0);
  seg_point(a, b, hp.pc.t1, pi.p1);
  pi.lb = hp.lb;
  pi.ub = hp.ub;
  pi.leaf = hp.leaf != 0u;
  pi.in_cube = hp.in_cube != 0u;
  return pi;
}

inline void heap_push(HeapPiece* h, uint32_t* n, const HeapPiece& x) {
  uint32_t i = (*n)++;
  while (i > 0u && h[(i - 1u) / 2u].lb > x.lb) {  // bounded by the heap's depth
    h[i] = h[(i - 1u) / 2u];
    i = (i - 1u) / 2u;
  }
  h[i] = x;
}

inline HeapPiece heap_pop(HeapPiece* h, uint32_t* n) {
  const HeapPiece top = h[0];
  const HeapPiece last = h[--*n];
  uint32_t i = 0;
  for (;;) {  // bounded by the heap's depth
    uint32_t c = 2u * i + 1u;
    if (c >= *n) break;
    if (c + 1u < *n && h[c + 1u].lb < h[c].lb) ++c;
    if (!(h[c].lb < last.lb)) break;
    h[i] = h[c];
    i = c;
  }
  if (*n > 0u) h[i] = last;
  return top;
}

// min(best, distance from [a, b] to the cubes); `best` already holds the boxes' distance.
// The pieces are those of walk_pieces (halvings of the whole segment down to voxel scale), taken
// best first: smallest lower bound first, so the running minimum falls early and the walk ends
// when the smallest waiting bound reaches it. The result is the minimum over the leaves of their
// exact distances, whatever the order (a piece is dropped only when its bound shows that none of
// its leaves can lower the minimum), so it equals the depth-first walk's, bit for bit. A full
// heap sends the piece to the depth-first walk.
double cubes_min(const tdo_grid* g, const double a[3], const double b[3], double best) {
  if (g->n_cubes == 0) return best;
  const bool point = a == b;
  const double res = g->desc.res, margin = kLeafBlockRel * res;
  const auto visit = [g, point, res, margin, &best](const PieceInfo& pi) {
    if (pi.lb >= best) return PieceStep::skip;
    // A piece without an occupied voxel within the minimum (plus a margin far above the
    // rounding) has no cube that could lower it: none of its leaves would change anything.
    // Tried while the minimum is within a voxel (beyond, the block holds too many voxels).
    if (best <= res &&
        block_free(g, pi.p0, pi.p1, best + margin + brick_tol(g, pi.p0, pi.p1, best), false))
      return PieceStep::skip;
    if (!pi.leaf) return PieceStep::split;
    if (pi.in_cube) return PieceStep::stop;
    return leaf_min(g, pi, point, &best) ? PieceStep::skip : PieceStep::stop;
  };
  HeapPiece heap[kMinHeapCap];
  uint32_t n = 0;
  heap_push(heap, &n, heap_piece(Piece{0.0, 1.0}, piece_info(g, a, b, Piece{0.0, 1.0})));
  for (uint32_t pieces = 0; n > 0u; ++pieces) {
    if (pieces >= kMaxPieces) return 0.0;  // a bound reached (never on int32 grids): 0
    const HeapPiece hp = heap_pop(heap, &n);
    if (hp.lb >= best) break;  // every waiting piece: none can lower the minimum
    const PieceStep step = visit(unpack(hp, a, b));
    if (step == PieceStep::stop) return 0.0;
    if (step == PieceStep::skip) continue;
    if (n + 2u > kMinHeapCap) {
      if (walk_pieces(g, a, b, hp.pc, visit) != 1) return 0.0;
      continue;
    }
    const double tm = 0.5 * (hp.pc.t0 + hp.pc.t1);
    const Piece halves[2] = {Piece{hp.pc.t0, tm}, Piece{tm, hp.pc.t1}};
    for (const Piece& half : halves) {
      const PieceInfo pi = piece_info(g, a, b, half);
      if (pi.lb < best) heap_push(heap, &n, heap_piece(half, pi));
    }
  }
  return best;
}

bool ready(const tdo_grid* g) { return g != nullptr && g->ready && g->nvox > 0; }

// The checks of a segment clearance query (a ready grid, finite end points, a finite clearance
// >= 0) and its end points loaded into pa and pb; false: the query answers 0 (not clear).
bool load_segment_query(const tdo_grid* g, const tdo_vec3& a, const tdo_vec3& b, double clearance,
                        double pa[3], double pb[3]) {
  if (!ready(g) || !finite3(a) || !finite3(b) || !(clearance >= 0.0) || !isfinite(clearance))
    return false;
  load(a, pa);
  load(b, pb);
  return true;
}

// Lower *best (m) to the distance of point p to box b when that is smaller.
// The sum of squares is that of point_box_d2; it stops at the first axis whose gap alone reaches
// *best (rounding is monotone, so then d2 >= gap^2 >= best^2 and nothing changes).
inline void box_min_point(const tdo_box& b, const double p[3], double* best) {
  double lo[3], hi[3];
  box_bounds(b, lo, hi);
  double d2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double g = dmax(lo[i] - p[i], 0.0) + dmax(p[i] - hi[i], 0.0);
    if (g >= *best) return;
    d2 += g * g;
  }
  if (d2 < *best * *best) *best = sqrt(d2);
}

// Cell of the box bucket index holding point p (clamped to the index).
uint32_t point_cell(const tdo_grid* g, const double p[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t nc[3] = {g->ncx, g->ncy, g->ncz};
  int32_t cell[3];
  for (int i = 0; i < 3; ++i) {
    cell[i] = clamped_floor((p[i] - o[i]) / g->cell_edge, nc[i]);
  }
  return static_cast<uint32_t>(cell[0] + nc[0] * (cell[1] + nc[1] * cell[2]));
}

// boxes_min for a point: one cell of the index, point-to-box distances only.
double boxes_min_point(const tdo_grid* g, const double p[3], double cap, bool inside) {
  double best = cap;
  if (g->n_boxes == 0) return best;
  if (inside) {
    const uint32_t ci = point_cell(g, p);
    double near = dmin(cap, g->bucket_reach);
    for (uint32_t k = 0; k < g->n_large; ++k) box_min_point(g->boxes[g->large_boxes[k]], p, &near);
    for (uint32_t r = g->cell_start[ci]; r < g->cell_start[ci + 1]; ++r)
      box_min_point(g->boxes[g->box_refs[r]], p, &near);
    if (near < g->bucket_reach || !(cap > g->bucket_reach)) return near;
  }
  for (uint32_t k = 0; k < g->n_boxes; ++k) box_min_point(g->boxes[k], p, &best);
  return best;
}

double segment_distance(const tdo_grid* g, const double a[3], const double b[3], double cap) {
  const bool inside = inside_bounds(g, a) && inside_bounds(g, b);
  const double best = boxes_min(g, a, b, cap, inside);
  return cubes_min(g, a, b, best);
}

double point_distance(const tdo_grid* g, const double p[3], double cap) {
  const double best = boxes_min_point(g, p, cap, inside_bounds(g, p));
  return cubes_min(g, p, p, best);
}

bool segment_clear(const tdo_grid* g, const double a[3], const double b[3], double c) {
  if (!inside_bounds(g, a) || !inside_bounds(g, b)) return false;
  uint32_t hit = 0;
  return boxes_clear(g, a, b, c, &hit) && cubes_clear(g, a, b, c);
}

// segment_clear with a hint (see segment_clear_hinted): the same answer.
bool segment_clear_hint(const tdo_grid* g, const double a[3], const double b[3], double c,
                        uint32_t* hint) {
  if (!inside_bounds(g, a) || !inside_bounds(g, b)) return false;
  if (*hint != 0u && box_certainly_violates(g, *hint - 1u, a, b, c)) return false;
  uint32_t hit = 0xFFFFFFFFu;
  const bool ok = boxes_clear(g, a, b, c, &hit) && cubes_clear(g, a, b, c);
  if (hit != 0xFFFFFFFFu) *hint = hit + 1u;
  return ok;
}

// Distance (m) from p to the segment [a, b].
double point_segment_distance(const double p[3], const double a[3], const double b[3]) {
  double d[3], w[3], dd = 0.0, wd = 0.0;
  for (int i = 0; i < 3; ++i) {
    d[i] = b[i] - a[i];
    w[i] = p[i] - a[i];
    dd += d[i] * d[i];
    wd += w[i] * d[i];
  }
  double t = dd > 0.0 ? wd / dd : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  double s = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double e = w[i] - t * d[i];
    s += e * e;
  }
  return sqrt(s);
}

struct Bezier {
  double c[4][3];  // m, control points
};

}  // namespace
}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" double tdo_collision_point_distance(const tdo_grid* grid, tdo_vec3 p, double cap) {
  if (!ready(grid) || !finite3(p) || !(cap >= 0.0)) return -1.0;
  double q[3];
  load(p, q);
  return point_distance(grid, q, cap);
}

extern "C" double tdo_collision_segment_distance(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b,
                                                 double cap) {
  if (!ready(grid) || !finite3(a) || !finite3(b) || !(cap >= 0.0)) return -1.0;
  double pa[3], pb[3];
  load(a, pa);
  load(b, pb);
  return segment_distance(grid, pa, pb, cap);
}

namespace tdo_internal {

int segment_clear_hinted(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                         uint32_t* hint) {
  double pa[3], pb[3];
  if (!load_segment_query(grid, a, b, clearance, pa, pb)) return 0;
  return segment_clear_hint(grid, pa, pb, clearance, hint) ? 1 : 0;
}

int segment_blocked_by_hint(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                            uint32_t hint) {
  double pa[3], pb[3];
  if (hint == 0u || !load_segment_query(grid, a, b, clearance, pa, pb)) return 0;
  if (!inside_bounds(grid, pa) || !inside_bounds(grid, pb)) return 0;
  return box_certainly_violates(grid, hint - 1u, pa, pb, clearance) ? 1 : 0;
}

namespace {

// Margins of the hinted point distance: the nearest box's distance must stay below the bound of
// every other obstacle by more than this (relative and absolute), far above rounding.
constexpr double kPointHintRel = 1e-6;
constexpr double kPointHintAbs = 1e-9;  // m

}  // namespace

double point_distance_hinted(const tdo_grid* grid, tdo_vec3 pv, double cap, PointHint* h) {
  h->lower = -1.0;
  if (!ready(grid) || !finite3(pv) || !(cap >= 0.0)) return -1.0;
  double p[3];
  load(pv, p);
  // The hint covers box-only maps and points inside the bounds (the bucket index answers).
  if (grid->n_cubes != 0 || grid->n_boxes == 0 || !inside_bounds(grid, p)) {
    h->valid = 0;
    const double d = point_distance(grid, p, cap);
    h->lower = d;
    if (d >= cap && grid->n_boxes == 0) {
      // No box nearer than the cap: the distance field's bound of the cubes (no cube: none).
      h->lower =
          grid->n_cubes == 0 ? HUGE_VAL : dmax(d, piece_info(grid, p, p, Piece{0.0, 1.0}).lb);
    }
    return d;
  }
  const double reach = grid->bucket_reach;
  const double near0 = dmin(cap, reach);
  if (h->valid) {
    double m2 = 0.0;
    for (int i = 0; i < 3; ++i) m2 += (p[i] - h->q[i]) * (p[i] - h->q[i]);
    // Every other obstacle is at least others - |p - q| away (1-Lipschitz). Below the reach
    // the bucket pass of the full query ends with this box's value, beyond it the scan of every
    // box does; below the cap either way.
    const double lim = dmin(cap, h->others - sqrt(m2));
    double lo[3], hi[3];
    box_bounds(grid->boxes[h->box], lo, hi);
    const double d = sqrt(point_box_d2(p, lo, hi));
    // Then the full query's running minimum takes this box's value and keeps it: d^2 is below
    // the start value and every other box's d^2 by far more than rounding.
    if (d * (1.0 + kPointHintRel) + kPointHintAbs < lim) {
      h->lower = d;
      return d;
    }
  }
  // Full evaluation, as boxes_min_point does it (same running minimum, in the same order), also
  // keeping the nearest box and the second smallest distance of the listed boxes.
  const uint32_t ci = point_cell(grid, p);
  double near = near0, first = HUGE_VAL, second = HUGE_VAL;
  uint32_t nearest = 0xFFFFFFFFu;
  const auto visit = [&](uint32_t k) {
    double lo[3], hi[3];
    box_bounds(grid->boxes[k], lo, hi);
    // point_box_d2's sum; a partial sum already >= second changes neither the two smallest nor
    // the running minimum (near^2 is at most first up to rounding, so at most a tie repeats it).
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double g = dmax(lo[i] - p[i], 0.0) + dmax(p[i] - hi[i], 0.0);
      d2 += g * g;
      if (d2 >= second) return;
    }
    if (d2 < near * near) near = sqrt(d2);
    if (d2 < first) {
      second = first;
      first = d2;
      nearest = k;
    } else if (d2 < second) {
      second = d2;
    }
  };
  for (uint32_t k = 0; k < grid->n_large; ++k) visit(grid->large_boxes[k]);
  for (uint32_t r = grid->cell_start[ci]; r < grid->cell_start[ci + 1]; ++r)
    visit(grid->box_refs[r]);
  double others;
  if (near < reach || !(cap > reach)) {
    // Boxes not listed in the cell are farther than the reach from every point of it.
    others = dmin(sqrt(second), reach);
  } else {
    // Beyond the reach boxes_min_point scans every box from `cap`: the same, over all boxes.
    near = cap;
    first = HUGE_VAL;
    second = HUGE_VAL;
    nearest = 0xFFFFFFFFu;
    for (uint32_t k = 0; k < grid->n_boxes; ++k) visit(k);
    others = sqrt(second);
  }
  h->valid = nearest != 0xFFFFFFFFu ? 1 : 0;
  h->box = nearest;
  h->others = others;
  for (int i = 0; i < 3; ++i) h->q[i] = p[i];
  h->lower = near;
  return near;  // cubes_min adds nothing without cubes
}

}  // namespace tdo_internal

extern "C" int tdo_collision_segment_clear(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b,
                                           double clearance) {
  double pa[3], pb[3];
  if (!load_segment_query(grid, a, b, clearance, pa, pb)) return 0;
  return segment_clear(grid, pa, pb, clearance) ? 1 : 0;
}

extern "C" int tdo_collision_bezier_clear(const tdo_grid* grid, const tdo_vec3 c[4],
                                          double clearance, double tolerance) {
  uint32_t hint = 0, cube_hint = 0;
  return tdo_internal::bezier_clear_hinted(grid, c, clearance, tolerance, &hint, &cube_hint);
}

int tdo_internal::bezier_clear_hinted(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                                      double tolerance, uint32_t* hint, uint32_t* cube_hint) {
  if (!ready(grid) || c == nullptr || !(clearance >= 0.0) || !isfinite(clearance) ||
      !(tolerance >= 0.0) || !isfinite(tolerance))
    return 0;
  for (int i = 0; i < 4; ++i)
    if (!finite3(c[i])) return 0;
  const double tol = dmax(tolerance, kMinTolerance);
  Bezier stack[kBezierStackCap];
  int top = 0;
  for (int i = 0; i < 4; ++i) load(c[i], stack[0].c[i]);
  top = 1;
  for (uint32_t pieces = 0; top > 0; ++pieces) {
    if (pieces >= kMaxBezierPieces) return 0;
    const Bezier bz = stack[--top];
    // The curve lies in the hull of its control points, hence within `bound` of the chord; the
    // hull lies in the bounds when the control points do.
    const double bound = dmax(point_segment_distance(bz.c[1], bz.c[0], bz.c[3]),
                              point_segment_distance(bz.c[2], bz.c[0], bz.c[3]));
    bool in = true;
    for (int i = 0; i < 4; ++i) in = in && inside_bounds(grid, bz.c[i]);
    // The chord test: segment_clear_steered (the same answer as segment_clear, cheaper).
    if (in && segment_clear_steered(grid, vec(bz.c[0]), vec(bz.c[3]), clearance + bound, hint,
                                    cube_hint) != 0)
      continue;
    // Every chord point is within `bound` of the curve too, so a curve keeping clearance + tol
    // passes its chord test once bound <= tol / 2: stopping there keeps a 0 within tol.
    if (!(bound > 0.5 * tol)) return 0;
    if (top + 2 > kBezierStackCap) return 0;  // never "clear" on overflow
    // de Casteljau at 1/2.
    Bezier l, r;
    for (int i = 0; i < 3; ++i) {
      const double p01 = 0.5 * (bz.c[0][i] + bz.c[1][i]);
      const double p12 = 0.5 * (bz.c[1][i] + bz.c[2][i]);
      const double p23 = 0.5 * (bz.c[2][i] + bz.c[3][i]);
      const double p012 = 0.5 * (p01 + p12);
      const double p123 = 0.5 * (p12 + p23);
      const double mid = 0.5 * (p012 + p123);
      l.c[0][i] = bz.c[0][i];
      l.c[1][i] = p01;
      l.c[2][i] = p012;
      l.c[3][i] = mid;
      r.c[0][i] = mid;
      r.c[1][i] = p123;
      r.c[2][i] = p23;
      r.c[3][i] = bz.c[3][i];
    }
    stack[top++] = r;
    stack[top++] = l;
  }
  return 1;
}

// ---------------------------------------------------------------------------------------------
// Steered segment checks (the correction's queries, docs/design.md s.2): the same answers as
// segment_clear, with the cube part walked from the start of the segment towards its end.

namespace tdo_internal {
namespace {

constexpr double kSteerRel = 4e-7;       // of res: margin of the steering bounds (4x piece_info's)
constexpr double kSteerMinStep = 0.25;   // of res: a shorter steering step stops the steering
constexpr uint32_t kSteerMaxSteps = 64;  // steering steps from one piece at most
constexpr int64_t kBlockMaxVoxels = 64;  // voxels a block test reads at most (more: no claim)
constexpr double kDoubleEps = 2.220446049250313e-16;  // DBL_EPSILON

// piece_info's leaf test: decided by the piece's length (t1 - t0) len when that is farther from
// res than `tol` (which bounds the rounding of the length piece_info computes from the rounded end
// points), else by piece_info's own expressions (so the leaves are its leaves).
inline bool piece_leaf(const tdo_grid* g, const double a[3], const double b[3], const Piece& pc,
                       double len, double tol) {
  const double res = g->desc.res;
  const double est = (pc.t1 - pc.t0) * len;
  if (est > res + tol) return false;
  if (est < res - tol) return true;
  double p0[3], p1[3];
  seg_point(a, b, pc.t0, p0);
  seg_point(a, b, pc.t1, p1);
  double half2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double h = 0.5 * (p1[i] - p0[i]);
    half2 += h * h;
  }
  return !(2.0 * sqrt(half2) > res);
}

// Parameter t >= t0 such that every point of [a, b] (length len > 0) between t0 and t is
// farther than `need` (the clearance plus the steering margin) from every cube, from the distance
// field at p(t0): through p(t0) itself (its bound falls by the distance walked, 1-Lipschitz) and
// through the voxel holding it (the bound of the voxel's box holds up to the segment's exit from
// it, then falls likewise). t0 when neither bound reaches `need`. The margin (far above the
// rounding of the exit parameter and of the points) keeps the claim strict, also at clearance 0.
double steer_from(const tdo_grid* g, const double a[3], const double b[3], double len, double t0,
                  double need) {
  double p[3];
  seg_point(a, b, t0, p);
  int64_t v[3];
  if (!voxel_of(g, p, v)) return t0;
  const tdo_grid_desc& d = g->desc;
  const double res = d.res;
  const double df = static_cast<double>(g->df[v[0] + v[1] * g->stride_y + v[2] * g->stride_z]);
  const double df_lb = g->df_cap > 0.0 && df > g->df_cap ? g->df_cap : df;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  double off2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double e = p[i] - (o[i] + (static_cast<double>(v[i]) + 0.5) * res);
    off2 += e * e;
  }
  double t = t0;
  const double s_point = df_lb - sqrt(off2) - kHalfDiag * res - need;
  if (s_point > 0.0) t = t0 + s_point / len;
  const double s_box = voxel_gap_lower(df_lb, res) - need;
  if (s_box > 0.0) {
    double t_exit = HUGE_VAL;
    for (int i = 0; i < 3; ++i) {
      const double di = b[i] - a[i];
      if (di > 0.0) {
        t_exit = dmin(t_exit, (o[i] + static_cast<double>(v[i] + 1) * res - a[i]) / di);
      } else if (di < 0.0) {
        t_exit = dmin(t_exit, (o[i] + static_cast<double>(v[i]) * res - a[i]) / di);
      }
    }
    t = dmax(t, dmax(t_exit, t0) + s_box / len);
  }
  return t;
}

// True when no voxel whose box comes within r of the span box of [p0, p1] (per axis, a lower
// bound of the Euclidean gap) is occupied: then every cube, and every box that meets the grid
// there, is farther than r from the piece. With `boxes` the voxels must all lie in the grid
// (a box outside it marks no voxel). At most kBlockMaxVoxels voxels are read; more: false.
bool block_free(const tdo_grid* g, const double p0[3], const double p1[3], double r, bool boxes) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  // In voxels (the rounding of the product is far below the margin in r). Voxel i spans
  // [i, i + 1): those from floor(xa) to floor(xb) come within r; the one below floor(xa) ends
  // at xa or before, r away at least.
  const double inv = 1.0 / d.res;
  int64_t lo[3], hi[3];
  int64_t count = 1;
  for (int i = 0; i < 3; ++i) {
    const double xa = (dmin(p0[i], p1[i]) - r - o[i]) * inv;
    const double xb = (dmax(p0[i], p1[i]) + r - o[i]) * inv;
    const double top = static_cast<double>(n[i]);
    if (!(xa <= xb) || (boxes && (xa < 0.0 || xb >= top))) return false;
    if (xb < 0.0 || xa >= top) return true;           // no voxel of the grid: no cube
    lo[i] = xa < 0.0 ? 0 : static_cast<int64_t>(xa);  // truncation is floor from 0 on
    hi[i] = xb >= top ? n[i] - 1 : static_cast<int64_t>(xb);
    count *= hi[i] - lo[i] + 1;
    if (count > kBlockMaxVoxels) return false;
  }
  for (int64_t k = lo[2]; k <= hi[2]; ++k)
    for (int64_t j = lo[1]; j <= hi[1]; ++j) {
      const uint8_t* row = g->flags + j * g->stride_y + k * g->stride_z;
      for (int64_t i = lo[0]; i <= hi[0]; ++i)
        if ((row[i] & (kFlagOccupied | kFlagCube)) != 0) return false;
    }
  return true;
}

// cubes_clear's test of one leaf piece; `need` as for steer_from. The block test first: no cube
// near the piece (then cubes_clear's leaf test passes too: it finds no cube within c). A surface
// cube that fails the piece goes to *hit.
bool leaf_clear(const tdo_grid* g, const double a[3], const double b[3], const Piece& pc, double c,
                double need, uint32_t* hit) {
  double p0[3], p1[3];
  seg_point(a, b, pc.t0, p0);
  seg_point(a, b, pc.t1, p1);
  if (block_free(g, p0, p1, need, false)) return true;
  const PieceInfo pi = piece_info(g, a, b, pc);
  if (pi.lb >= c && pi.lb > 0.0) return true;
  if (pi.in_cube) return false;
  const int fast = bricks_clear_hit(g, pi.p0, pi.p1, c, hit);
  if (fast >= 0) return fast == 1;
  return for_each_cube_near(g, pi.p0, pi.p1, c, [&](const double* lo, const double* hi) {
    if (far_apart(pi.p0, pi.p1, lo, hi, c)) return true;
    if (!violates(segment_box_d2(pi.p0, pi.p1, lo, hi, c * c), c)) return true;
    *hit = cube_index(g, lo);
    return false;
  });
}

// True when surface cube `idx` certainly comes closer than c to [a, b]: by more than kHintMargin,
// or, at a clearance up to kHintMargin, the segment passes through the cube shrunk by
// kHintMargin on every side. Then cubes_clear finds a violation: the leaf holding the segment's
// nearest point to the cube is not skipped (its bound is below that distance), and its exact test
// visits this cube (a surface cube within c of the piece) and finds it closer than c.
bool cube_certainly_violates(const tdo_grid* g, uint32_t idx, const double a[3], const double b[3],
                             double c) {
  if (idx >= g->nvox || (g->flags[idx] & kFlagSurface) == 0) return false;
  const tdo_grid_desc& d = g->desc;
  const int64_t v[3] = {idx % g->stride_y, (idx / g->stride_y) % d.ny, idx / g->stride_z};
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  double lo[3], hi[3];
  for (int i = 0; i < 3; ++i) {
    lo[i] = o[i] + static_cast<double>(v[i]) * d.res;
    hi[i] = o[i] + static_cast<double>(v[i] + 1) * d.res;
  }
  if (c > kHintMargin) {
    const double m = c - kHintMargin;
    if (far_apart(a, b, lo, hi, m)) return false;
    // Quick: a point of the segment closer than m (box_certainly_violates' test).
    if (centre_point_d2(a, b, lo, hi) < m * m) return true;
    return segment_box_d2(a, b, lo, hi, m * m) < m * m;
  }
  if (!(d.res > 4.0 * kHintMargin)) return false;
  for (int i = 0; i < 3; ++i) {
    lo[i] += kHintMargin;
    hi[i] -= kHintMargin;
  }
  // A point of the segment (as seg_point evaluates it) inside the shrunk cube: the middle of the
  // parameter interval where every coordinate lies strictly between the shrunk faces (no point:
  // no claim).
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    const double di = b[i] - a[i];
    if (!(di < 0.0 || di > 0.0)) {
      if (!(a[i] > lo[i] && a[i] < hi[i])) return false;
      continue;
    }
    const double ta = (lo[i] - a[i]) / di, tb = (hi[i] - a[i]) / di;
    t0 = dmax(t0, dmin(ta, tb));
    t1 = dmin(t1, dmax(ta, tb));
  }
  if (!(t0 < t1)) return false;
  double p[3];
  seg_point(a, b, 0.5 * (t0 + t1), p);
  return !(point_box_d2(p, lo, hi) > 0.0);
}

// Extend *covered (every point of [a, b] up to it is farther than `need` from the cubes) by
// steering from it, or from t0 when that lies beyond, until a step gains less than
// kSteerMinStep voxels or reaches t1. *stalled: where the steering stopped last for a short step;
// it starts again only from beyond that point (after the leaves there were tested).
void steer(const tdo_grid* g, const double a[3], const double b[3], double len, double need,
           double t0, double t1, double* covered, double* stalled) {
  const double min_step = kSteerMinStep * g->desc.res / len;
  double from = dmax(t0, *covered);
  if (!(from > *stalled)) return;
  for (uint32_t s = 0; s < kSteerMaxSteps && from < t1; ++s) {
    const double t = steer_from(g, a, b, len, from, need);
    if (t > *covered) *covered = t;
    if (!(t - from >= min_step)) {
      *stalled = *covered;
      return;
    }
    from = t;
  }
}

// ---------------------------------------------------------------------------------------------
// Slab walk at small clearances (docs/design.md s.2). The segment is walked through the voxel
// slabs of its dominant axis X (|d_X| >= |d_Y|, |d_Z|), in the order of t. For slab i, with the
// segment's points q0, q1 on its two X planes (clamped to the segment), every voxel (i, j, k)
// whose j and k ranges meet the ranges of q0 and q1 grown by 2 need is read: a segment point p
// with p_X within `need` of the slab lies on the segment between q0 and q1 extended by need in X,
// which moves Y and Z by need at most (|d_Y| <= |d_X|), so every voxel within `need` of p (per
// axis, hence in Euclidean distance) is read in the slabs whose extended portion holds p.
// - A slab whose voxels are all free: its points are farther than `need` from every occupied
//   voxel, so no leaf of cubes_clear touching only such points can fail (the leaf test's points
//   and midpoints lie within rounding, far below the margin in `need`, of the segment).
// - An occupied surface voxel of a slab that cube_certainly_violates proves blocks the whole
//   segment: cubes_clear fails too (see there); the walk stops with "not clear".
// - An occupied voxel whose cube grown by `need` the whole segment misses (misses_grown_voxel):
//   every point of the segment is farther than `need` from it; it changes nothing.
// - Any other occupied voxel: the slab's parameter span is "open"; spans are merged into at most
//   kSlabSpans. The answer then comes from cubes_clear_steered's own walk over the pieces that
//   meet an open span widened by one voxel (far above the rounding of the parameters); every
//   other piece is proven clear, as the steering's skips are.
constexpr double kSlabMaxClearance = 0.25;  // of res: above it the slab walk is not used
constexpr int64_t kSlabMaxSlabs = 4096;     // slabs of one walk at most (longer: not used)
constexpr uint32_t kSlabSpans = 8;          // open parameter spans kept (more: merged)

struct SlabSpans {
  double u0[kSlabSpans], u1[kSlabSpans];  // open parameter spans, widened, in order of t
  uint32_t n;
};

// Voxel range [lo, hi] of the coordinates [x0, x1] (m) on an axis of origin o and n voxels,
// clamped to the grid; false when it misses the grid. In voxels the rounding of the product is
// far below the walk's margin (as block_free).
inline bool axis_range(double x0, double x1, double o, double inv, int32_t n, int64_t* lo,
                       int64_t* hi) {
  const double xa = (x0 - o) * inv, xb = (x1 - o) * inv;
  const double top = static_cast<double>(n);
  if (!(xa <= xb) || xb < 0.0 || xa >= top) return false;
  *lo = xa < 0.0 ? 0 : static_cast<int64_t>(xa);  // truncation is floor from 0 on
  *hi = xb >= top ? n - 1 : static_cast<int64_t>(xb);
  return true;
}

// axis_range in voxel units: the voxels [lo, hi] of [xa, xb] (voxels), clamped to n voxels.
inline bool voxel_range(double xa, double xb, int32_t n, int64_t* lo, int64_t* hi) {
  const double top = static_cast<double>(n);
  if (!(xa <= xb) || xb < 0.0 || xa >= top) return false;
  *lo = xa < 0.0 ? 0 : static_cast<int64_t>(xa);  // truncation is floor from 0 on
  *hi = xb >= top ? n - 1 : static_cast<int64_t>(xb);
  return true;
}

// Add the open span [u0, u1] (already widened) to *sp, merging with the last when they meet or
// when no slot is left.
inline void add_span(SlabSpans* sp, double u0, double u1) {
  if (sp->n > 0u && (u0 <= sp->u1[sp->n - 1u] || sp->n == kSlabSpans)) {
    sp->u1[sp->n - 1u] = dmax(sp->u1[sp->n - 1u], u1);
    return;
  }
  sp->u0[sp->n] = u0;
  sp->u1[sp->n] = u1;
  ++sp->n;
}

// True when the whole segment [a, b] misses the box of voxel (i, j, k) (per axis ax, ay, az)
// grown by r on every side: an empty parameter interval where every coordinate lies within the
// grown faces. Then every point of the segment is farther than r, less the rounding of the
// parameters (far below the walk's margin in r), from the voxel's cube.
bool misses_grown_voxel(const tdo_grid* g, int64_t i, int64_t j, int64_t k, int ax, int ay, int az,
                        const double a[3], const double b[3], double r) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  int64_t v[3];
  v[ax] = i;
  v[ay] = j;
  v[az] = k;
  double t0 = 0.0, t1 = 1.0;
  for (int n = 0; n < 3; ++n) {
    const double lo = o[n] + static_cast<double>(v[n]) * d.res - r;
    const double hi = o[n] + static_cast<double>(v[n] + 1) * d.res + r;
    const double dn = b[n] - a[n];
    if (!(dn < 0.0 || dn > 0.0)) {
      if (a[n] < lo || a[n] > hi) return true;
      continue;
    }
    const double ta = (lo - a[n]) / dn, tb = (hi - a[n]) / dn;
    t0 = dmax(t0, dmin(ta, tb));
    t1 = dmin(t1, dmax(ta, tb));
  }
  return t0 > t1;
}

// True when the piece meets an open span (then the walk must look at it).
inline bool meets_open(const SlabSpans& sp, const Piece& pc) {
  for (uint32_t k = 0; k < sp.n; ++k)
    if (pc.t1 > sp.u0[k] && pc.t0 < sp.u1[k]) return true;
  return false;
}

// The slab walk of [a, b] (length len > 0, inside the bounds) at clearance c (`need` as for
// steer_from): 1 clear, 0 not clear (*hint: the cube), -1 open spans in *sp, -2 not used.
__attribute__((noinline)) int slab_walk(const tdo_grid* g, const double a[3], const double b[3],
                                        double len, double c, double need, uint32_t* hint,
                                        SlabSpans* sp) {
  sp->n = 0u;
  const tdo_grid_desc& d = g->desc;
  const double res = d.res;
  if (!(c <= kSlabMaxClearance * res)) return -2;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t nv[3] = {d.nx, d.ny, d.nz};
  double dv[3];
  int ax = 0;
  for (int i = 0; i < 3; ++i) {
    dv[i] = b[i] - a[i];
    if (fabs(dv[i]) > fabs(dv[ax])) ax = i;
  }
  const int ay = (ax + 1) % 3, az = (ax + 2) % 3;
  const double inv = 1.0 / res;
  int64_t i0, i1;
  if (!axis_range(dmin(a[ax], b[ax]) - need, dmax(a[ax], b[ax]) + need, o[ax], inv, nv[ax], &i0,
                  &i1))
    return 1;  // no voxel of the grid within reach: no cube
  if (i1 - i0 + 1 > kSlabMaxSlabs || !(fabs(dv[ax]) > 0.0)) return -2;
  const int64_t stride[3] = {1, g->stride_y, g->stride_z};
  const double grow = 2.0 * need;
  const double widen = res / len;  // one voxel, in parameter
  // The slabs in the order of t: each starts where the last ended (its plane's parameter,
  // clamped to the segment; the rounding of the parameters and points is far below the margins).
  // From here in voxel units (rounding far below the margins): plane p lies at parameter
  // tp + p tr, and Y, Z at parameter t at yb + t yd, zb + t zd voxels.
  const bool up = dv[ax] > 0.0;
  const double invd = 1.0 / dv[ax];
  const double tp = (o[ax] - a[ax]) * invd, tr = res * invd;
  const double yb = (a[ay] - o[ay]) * inv, yd = dv[ay] * inv;
  const double zb = (a[az] - o[az]) * inv, zd = dv[az] * inv;
  const double gv = grow * inv;
  const auto plane_t = [&](int64_t plane) {
    return dmin(1.0, dmax(0.0, tp + static_cast<double>(plane) * tr));
  };
  int64_t ix = up ? i0 : i1;
  double t0 = plane_t(up ? ix : ix + 1);
  double y0 = yb + t0 * yd, z0 = zb + t0 * zd;
  // Bounded: one iteration per slab (at most kSlabMaxSlabs).
  for (int64_t s = 0; s <= i1 - i0; ++s, ix += up ? 1 : -1) {
    const double t1 = plane_t(up ? ix + 1 : ix);
    const double y1 = yb + t1 * yd, z1 = zb + t1 * zd;
    int64_t j0 = 0, j1 = -1, k0 = 0, k1 = -1;
    const bool near = voxel_range(dmin(y0, y1) - gv, dmax(y0, y1) + gv, nv[ay], &j0, &j1) &&
                      voxel_range(dmin(z0, z1) - gv, dmax(z0, z1) + gv, nv[az], &k0, &k1);
    bool open = false;
    for (int64_t k = k0; near && k <= k1; ++k) {
      const uint8_t* row = g->flags + ix * stride[ax] + k * stride[az];
      for (int64_t j = j0; j <= j1; ++j) {
        const uint8_t f = row[j * stride[ay]];
        if ((f & (kFlagOccupied | kFlagCube)) == 0) continue;
        // A voxel the segment misses grown by `need` (> c) cannot certainly violate c either
        // (that needs a point within c of its cube), so the miss test goes first: the same
        // violations, in the same order, and the same open spans.
        if (misses_grown_voxel(g, ix, j, k, ax, ay, az, a, b, need)) continue;
        const int64_t idx = ix * stride[ax] + j * stride[ay] + k * stride[az];
        if ((f & kFlagSurface) != 0 &&
            cube_certainly_violates(g, static_cast<uint32_t>(idx), a, b, c)) {
          *hint = static_cast<uint32_t>(idx) + 1u;
          return 0;
        }
        open = true;
      }
    }
    if (open) add_span(sp, t0 - widen, t1 + widen);
    t0 = t1;
    y0 = y1;
    z0 = z1;
  }
  return sp->n == 0u ? 1 : -1;
}

// cubes_clear with the same answer: the same halving walk over the same pieces, but a piece is
// skipped without its own bound when steering (steer) already covers it, and a leaf that is not
// covered gets leaf_clear (cubes_clear's own leaf test after the block test). Only provably clear
// parts are skipped, and every leaf tested is one of cubes_clear's, tested the same way, so both
// find the same violation or none. A bound reached: cubes_clear decides.
bool cubes_clear_steered(const tdo_grid* g, const double a[3], const double b[3], double c,
                         uint32_t* hint) {
  if (g->n_cubes == 0) return true;
  if (*hint != 0u && cube_certainly_violates(g, *hint - 1u, a, b, c)) return false;
  double len2 = 0.0;
  for (int i = 0; i < 3; ++i) len2 += (b[i] - a[i]) * (b[i] - a[i]);
  const double len = sqrt(len2);
  if (!(len > 0.0) || !isfinite(len)) return cubes_clear(g, a, b, c);
  df_ensure(g);
  const double need = c + kSteerRel * g->desc.res + quick_tol(c, bounds_scale(g));
  // A short segment (a grid path's step) without an occupied voxel near its span box is clear:
  // every cube is farther than need > c (block_free), as the walk below would find.
  if (need <= 0.5 * g->desc.res && len2 <= 4.0 * g->desc.res * g->desc.res &&
      block_free(g, a, b, need, false))
    return true;
  double mag = len;  // largest magnitude in the length's rounding: coordinates and the length
  for (int i = 0; i < 3; ++i) mag = dmax(mag, dmax(fabs(a[i]), fabs(b[i])));
  const double leaf_tol = 1e-9 * g->desc.res + 64.0 * kDoubleEps * mag;
  SlabSpans spans;
  const int slab = slab_walk(g, a, b, len, c, need, hint, &spans);
  if (slab >= 0) return slab == 1;
  const bool open_only = slab == -1;  // pieces outside the open spans are proven clear
  double covered = -1.0, stalled = -1.0;
  Piece stack[kStackCap];
  int top = 0;
  stack[top++] = Piece{0.0, 1.0};
  for (uint32_t pieces = 0; top > 0; ++pieces) {
    if (pieces >= kMaxPieces) return cubes_clear(g, a, b, c);
    const Piece pc = stack[--top];
    if (pc.t1 <= covered || (open_only && !meets_open(spans, pc))) continue;
    steer(g, a, b, len, need, pc.t0, pc.t1, &covered, &stalled);
    if (pc.t1 <= covered) continue;
    if (piece_leaf(g, a, b, pc, len, leaf_tol)) {
      uint32_t hit = 0xFFFFFFFFu;
      if (leaf_clear(g, a, b, pc, c, need, &hit)) continue;
      if (hit != 0xFFFFFFFFu) *hint = hit + 1u;
      return false;
    }
    if (top + 2 > kStackCap) return cubes_clear(g, a, b, c);
    const double tm = 0.5 * (pc.t0 + pc.t1);
    stack[top++] = Piece{tm, pc.t1};
    stack[top++] = Piece{pc.t0, tm};
  }
  return true;
}

}  // namespace

bool point_in_bounds(const tdo_grid* grid, tdo_vec3 p) {
  const double q[3] = {p.x, p.y, p.z};
  return inside_bounds(grid, q);
}

int segment_clear_steered(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                          uint32_t* hint, uint32_t* cube_hint) {
  double pa[3], pb[3];
  if (!load_segment_query(grid, a, b, clearance, pa, pb)) return 0;
  if (!inside_bounds(grid, pa) || !inside_bounds(grid, pb)) return 0;
  uint32_t none = 0u, no_cube = 0u;
  uint32_t* h = hint != nullptr ? hint : &none;
  uint32_t* hc = cube_hint != nullptr ? cube_hint : &no_cube;
  if (*h != 0u && box_certainly_violates(grid, *h - 1u, pa, pb, clearance)) return 0;
  uint32_t hit = 0xFFFFFFFFu;
  const bool ok = boxes_clear(grid, pa, pb, clearance, &hit) &&
                  cubes_clear_steered(grid, pa, pb, clearance, hc);
  if (hit != 0xFFFFFFFFu) *h = hit + 1u;
  return ok ? 1 : 0;
}

int block_clear(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance) {
  double pa[3], pb[3];
  if (!load_segment_query(grid, a, b, clearance, pa, pb)) return 0;
  if (!inside_bounds(grid, pa) || !inside_bounds(grid, pb)) return 0;
  const double r =
      clearance + kSteerRel * grid->desc.res + quick_tol(clearance, bounds_scale(grid));
  return block_free(grid, pa, pb, r, grid->n_boxes > 0u) ? 1 : 0;
}

#if defined(TDO_KEEP_BOUNDS)
double segment_cube_distance(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, uint32_t cube,
                             double cap) {
  double pa[3], pb[3];
  if (!load_segment_query(grid, a, b, 0.0, pa, pb) || cube >= grid->nvox ||
      (grid->flags[cube] & kFlagSurface) == 0)
    return -1.0;
  const tdo_grid_desc& d = grid->desc;
  const int64_t v[3] = {cube % grid->stride_y, (cube / grid->stride_y) % d.ny,
                        cube / grid->stride_z};
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  double lo[3], hi[3];  // the cube's faces as the cube loops compute them
  for (int i = 0; i < 3; ++i) {
    lo[i] = o[i] + static_cast<double>(v[i]) * d.res;
    hi[i] = o[i] + static_cast<double>(v[i] + 1) * d.res;
  }
  // The halvings of walk_pieces and the leaves of piece_info (its expressions), taken only where
  // the cube may come within the running minimum; leaf_min's update of the minimum.
  double best = cap;
  Piece stack[kStackCap];
  int top = 0;
  stack[top++] = Piece{0.0, 1.0};
  for (uint32_t pieces = 0; top > 0; ++pieces) {
    const Piece pc = stack[--top];
    double p0[3], p1[3], half2 = 0.0;
    seg_point(pa, pb, pc.t0, p0);
    seg_point(pa, pb, pc.t1, p1);
    if (far_apart(p0, p1, lo, hi, best)) continue;
    for (int i = 0; i < 3; ++i) {
      const double h = 0.5 * (p1[i] - p0[i]);
      half2 += h * h;
    }
    if (!(2.0 * sqrt(half2) > d.res)) {
      const double d2 = piece_info(grid, pa, pb, pc).in_cube ? 0.0 : segment_box_d2(p0, p1, lo, hi);
      if (d2 < best * best) best = sqrt(d2);
      if (!(best > 0.0)) break;
      continue;
    }
    if (pieces >= kMaxPieces || top + 2 > kStackCap) return -1.0;
    const double tm = 0.5 * (pc.t0 + pc.t1);
    stack[top++] = Piece{tm, pc.t1};
    stack[top++] = Piece{pc.t0, tm};
  }
  return best;
}
#endif

}  // namespace tdo_internal
