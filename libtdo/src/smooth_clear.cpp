// Cheap verdicts on the smoothing's corner curves (smooth_clear.h).
#include "smooth_clear.h"

#include <math.h>

#include "collision_internal.h"
#include "grid_geometry.h"
#include "grid_internal.h"
#include "scalar.h"
#include "tdo/collision.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

constexpr double kMaxSpan = 1e6;        // of the tolerance: longest box side certified clear
constexpr int kBlockedSamples = 8;      // curve points tried, 1/16 of the parameter apart
constexpr double kInsideVoxels = 1e-6;  // voxel edges: depth inside a cube that counts
constexpr double kBlockReach = 1.5;     // voxel edges: widest margin tried with block_clear

// Point of the cubic Bezier c at parameter s (Bernstein form).
tdo_vec3 bezier_at(const tdo_vec3 c[4], double s) {
  const double u = 1.0 - s;
  return add(add(mul(c[0], u * u * u), mul(c[1], 3.0 * u * u * s)),
             add(mul(c[2], 3.0 * u * s * s), mul(c[3], s * s * s)));
}

// 1 when p lies inside a voxel cube, at least kInsideVoxels from each of its faces (inv: 1 / res;
// the rounding of the products is far below that depth).
int inside_cube(const tdo_grid* g, tdo_vec3 p, double inv) {
  const tdo_grid_desc& d = g->desc;
  const double q[3] = {(p.x - d.origin.x) * inv, (p.y - d.origin.y) * inv,
                       (p.z - d.origin.z) * inv};
  int64_t v[3];
  for (int i = 0; i < 3; ++i) {
    if (!(q[i] >= 0.0) || !(q[i] < static_cast<double>(i == 0 ? d.nx : (i == 1 ? d.ny : d.nz))))
      return 0;
    v[i] = static_cast<int64_t>(q[i]);  // truncation is floor from 0 on
    const double f = q[i] - static_cast<double>(v[i]);
    if (!(f >= kInsideVoxels) || !(f <= 1.0 - kInsideVoxels)) return 0;
  }
  return (g->flags[index_of(g, v[0], v[1], v[2])] & kFlagCube) != 0 ? 1 : 0;
}

}  // namespace

// The curve, its de Casteljau pieces and their chords lie in the box of the control points
// (halving keeps every coordinate within the range of its inputs), so each chord keeps
// clearance + tolerance, and lo, hi inside the bounds put every piece's control points there.
// tdo_collision_bezier_clear splits a piece only when its chord fails clearance + h (h the
// distance of its inner control points from the chord), so only when h > tolerance less
// rounding, and answers 0 only for a piece with h <= tolerance / 2 whose chord fails: none does
// (the margin is tolerance / 2, far above rounding). h is at most the largest second difference
// of the control points (|c1 - (2 c0 + c3) / 3| = |2 D0 + D1| / 3), 2 span at the root and 4x
// smaller per halving: with span <= kMaxSpan tolerance no piece deeper than 11 halvings splits,
// far within its piece budget (2^14) and stack (40).
int bezier_surely_clear(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                        double tolerance) {
  if (grid == nullptr || !(tolerance >= 1e-9)) return 0;
  // block_clear reads at most 64 voxels: a wider margin always needs more.
  if (!(clearance + tolerance < kBlockReach * grid->desc.res)) return 0;
  tdo_vec3 lo = c[0], hi = c[0];
  for (int i = 1; i < 4; ++i) {
    lo = v3(dmin(lo.x, c[i].x), dmin(lo.y, c[i].y), dmin(lo.z, c[i].z));
    hi = v3(dmax(hi.x, c[i].x), dmax(hi.y, c[i].y), dmax(hi.z, c[i].z));
  }
  const double span = dmax(hi.x - lo.x, dmax(hi.y - lo.y, hi.z - lo.z));
  if (!(span <= kMaxSpan * tolerance)) return 0;
  return block_clear(grid, lo, hi, clearance + tolerance);
}

// A 1 of tdo_collision_bezier_clear proves every curve point keeps the clearance and touches no
// obstacle, up to rounding far below these depths, so a point this far inside fails it.
int bezier_surely_blocked(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                          int from_end) {
  // A curve that fails a clearance of a voxel edge or more seldom enters a cube.
  if (grid == nullptr || grid->flags == nullptr || grid->n_cubes == 0u ||
      !(clearance < grid->desc.res))
    return 0;
  const double inv = 1.0 / grid->desc.res;
  for (int k = 0; k < kBlockedSamples; ++k) {
    const double s = static_cast<double>(k) / (2 * kBlockedSamples);
    const tdo_vec3 p = bezier_at(c, from_end ? 1.0 - s : s);
    if (inside_cube(grid, p, inv)) return 1;
  }
  return 0;
}

}  // namespace tdo_internal
