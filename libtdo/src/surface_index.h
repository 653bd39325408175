// Brick index of the surface cubes, for the exact distance queries of collision.cpp
// (docs/design.md s.0, "Distance to the cubes"). Internal to libtdo.
//
// The grid is cut into bricks of 4x4x4 voxels aligned at multiples of 4. Each brick keeps a 64-bit
// mask of its surface cubes (bit x + 4 (y + 4 z) for voxel (4 bx + x, 4 by + y, 4 bz + z)) and the
// tight bounding box of those cubes (2 bits per bound). A query collects the bricks whose tight box
// comes within a radius of a point or segment, sorts them by that gap, and visits their cubes in
// that order, so an exact minimum stops at the first brick that cannot hold anything nearer and a
// clearance test looks only at bricks closer than the clearance. Nothing scans voxels.
#ifndef TDO_SRC_SURFACE_INDEX_H
#define TDO_SRC_SURFACE_INDEX_H

#include <math.h>
#include <stdint.h>

#include "grid_internal.h"

namespace tdo_internal {

constexpr int32_t kBrickVoxels = 4;       // brick edge (voxels): 64 voxels, one mask bit each
constexpr uint32_t kMaxBrickCands = 128;  // bricks one query sorts; more: the caller scans

// Bricks a grid of this capacity may index: every grid whose axes all have 12 voxels or more
// fits (ceil(n/4)/n <= 5/16 there); thinner grids go without the index (bricks_valid = 0).
inline uint32_t brick_capacity(const GridCapacity& cap) {
  return cap.boxes_only != 0u ? 0u : cap.max_voxels / 32u + 64u;
}

// Bytes of arena of the index: the masks and the packed boxes.
size_t surface_index_footprint(const GridCapacity& cap);

// Build the index from the kFlagSurface bits (tdo_grid_finish, after marking the surface).
void surface_index_build(tdo_grid* g);

// Voxel (i, j, k) (inside the grid) is now a surface cube (on = true) or not (map updates).
void surface_index_set(tdo_grid* g, int64_t i, int64_t j, int64_t k, bool on);

// The voxels [lo, hi] (per axis, clamped to the grid) of the span box of [p0, p1] grown by r plus
// one voxel each side: a cube touching that box exactly (or within rounding) is included. False
// when the box misses the grid.
inline bool span_voxels(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                        int64_t lo[3], int64_t hi[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  for (int a = 0; a < 3; ++a) {
    const double mn = p0[a] < p1[a] ? p0[a] : p1[a];
    const double mx = p0[a] < p1[a] ? p1[a] : p0[a];
    const double va = floor((mn - r - o[a]) / d.res) - 1.0;
    const double vb = floor((mx + r - o[a]) / d.res) + 1.0;
    if (vb < 0.0 || va > static_cast<double>(n[a] - 1)) return false;
    lo[a] = va < 0.0 ? 0 : static_cast<int64_t>(va);
    hi[a] = vb > static_cast<double>(n[a] - 1) ? n[a] - 1 : static_cast<int64_t>(vb);
  }
  return true;
}

// A brick near a query: its index and the squared gap (m^2) between its tight box and the
// query's span box, a lower bound of the squared distance of each of its cubes.
struct BrickCand {
  double gap2;
  uint32_t brick;
};

// The span box [mn, mx] (m) of [p0, p1], and the voxel range [lo, hi] turned into bricks.
inline void brick_span(const double p0[3], const double p1[3], int64_t lo[3], int64_t hi[3],
                       double mn[3], double mx[3]) {
  for (int a = 0; a < 3; ++a) {
    mn[a] = p0[a] < p1[a] ? p0[a] : p1[a];
    mx[a] = p0[a] < p1[a] ? p1[a] : p0[a];
    lo[a] /= kBrickVoxels;
    hi[a] /= kBrickVoxels;
  }
}

// gap^2 (m^2) between the span box [mn, mx] and the tight box of the non-empty brick b, at brick
// coordinates (x, y, z): per axis the gap between the box's faces and the span, squared and summed
// in axis order.
inline double brick_gap2(const tdo_grid* g, uint32_t b, int64_t x, int64_t y, int64_t z,
                         const double mn[3], const double mx[3]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const uint32_t pk = g->brick_box[b];
  const int64_t base[3] = {x * kBrickVoxels, y * kBrickVoxels, z * kBrickVoxels};
  double gap2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    // The tight box's faces, by the same expressions as the cube bounds.
    const int64_t ci = base[a] + ((pk >> (2 * a)) & 3u);
    const int64_t cj = base[a] + ((pk >> (6 + 2 * a)) & 3u) + 1;
    const double blo = o[a] + static_cast<double>(ci) * d.res;
    const double bhi = o[a] + static_cast<double>(cj) * d.res;
    const double gp =
        (blo - mx[a] > 0.0 ? blo - mx[a] : 0.0) + (mn[a] - bhi > 0.0 ? mn[a] - bhi : 0.0);
    gap2 += gp * gp;
  }
  return gap2;
}

// Call f(BrickCand) for every non-empty brick that holds a voxel of the span box of [p0, p1]
// grown by r plus one voxel (the voxel range the scan of collision.cpp visits), in index order;
// stop when f returns false (then return false). Bounded by the bricks of that range.
template <class F>
bool for_each_brick_near(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                         F&& f) {
  const int32_t nb[3] = {g->nbx, g->nby, g->nbz};
  int64_t lo[3], hi[3];
  if (!span_voxels(g, p0, p1, r, lo, hi)) return true;
  double mn[3], mx[3];
  brick_span(p0, p1, lo, hi, mn, mx);
  for (int64_t z = lo[2]; z <= hi[2]; ++z)
    for (int64_t y = lo[1]; y <= hi[1]; ++y) {
      const int64_t row = nb[0] * (y + static_cast<int64_t>(nb[1]) * z);
      for (int64_t x = lo[0]; x <= hi[0]; ++x) {
        const uint32_t b = static_cast<uint32_t>(row + x);
        if (g->brick_mask[b] == 0u) continue;
        if (!f(BrickCand{brick_gap2(g, b, x, y, z, mn, mx), b})) return false;
      }
    }
  return true;
}

// Gap (m) on one axis between the span [mn, mx] and the whole brick number `b` of that axis, by
// brick_gap2's expressions with the brick's own faces (local voxels 0 and 4) in place of
// its tight box's (local voxels ci >= 0 and cj <= 4): the products and sums are monotone in the
// voxel index, so this face pair lies outside the tight one and the gap is at most the tight gap.
inline double brick_axis_gap(double o, double res, int64_t b, double mn, double mx) {
  const double blo = o + static_cast<double>(b * kBrickVoxels) * res;
  const double bhi = o + static_cast<double>(b * kBrickVoxels + kBrickVoxels) * res;
  return (blo - mx > 0.0 ? blo - mx : 0.0) + (mn - bhi > 0.0 ? mn - bhi : 0.0);
}

constexpr double kWithinMinVoxels = 2.0;  // limits (voxels) from which for_each_brick_within pays
// True when a walk of radius r whose caller skips bricks with gap2 >= lim^2 takes
// for_each_brick_within: lim^2 > 0 (its precondition) and r from kWithinMinVoxels up (within a few
// voxels the range holds few bricks, nearly all near: the plain walk is cheaper).
inline bool within_pays(const tdo_grid* g, double r, double lim) {
  return r > kWithinMinVoxels * g->desc.res && lim * lim > 0.0;
}
constexpr int64_t kWithinAxisCache = 8;  // x and y bricks whose gaps a walk computes once

// brick_axis_gap(o, res, b, mn, mx)^2, read from cache[b - lo] for the first kWithinAxisCache
// bricks from lo (filled with the same expression).
inline double axis_gap2(const double* cache, int64_t lo, double o, double res, int64_t b, double mn,
                        double mx) {
  if (b - lo < kWithinAxisCache) return cache[b - lo];
  const double gp = brick_axis_gap(o, res, b, mn, mx);
  return gp * gp;
}

// for_each_brick_near(g, p0, p1, r, f) without the bricks whose gap2 certainly reaches lim^2
// (lim^2 > 0: the callers check it; it calls no other walk, which keeps the stack chain short),
// which a caller skipping those never looks at; the others in the same order with the same gap2. A
// brick's gap2 is fl(fl(gx^2 + gy^2) + gz^2) of its tight gaps; with the whole-brick gaps of
// brick_axis_gap (each at most the tight one) the same sums are no larger (rounded addition and
// squaring of non-negative numbers are monotone), and fl(gy^2 + gz^2) is no larger still (gx^2 >=
// 0). So a row of bricks whose whole-brick fl(gy^2 + gz^2) reaches lim^2, or a brick whose
// whole-brick sum does, has gap2 >= lim^2 > 0 (the library builds with -ffp-contract=off: no fused
// multiply-add changes these roundings).
template <class F>
bool for_each_brick_within(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                           double lim, F&& f) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  int64_t lo[3], hi[3];
  if (!span_voxels(g, p0, p1, r, lo, hi)) return true;
  const double lim2 = lim * lim;
  double mn[3], mx[3];
  brick_span(p0, p1, lo, hi, mn, mx);
  const int32_t nb[3] = {g->nbx, g->nby, g->nbz};
  // The squared whole-brick gaps of the first kWithinAxisCache x and y bricks, once per walk.
  double gx2c[kWithinAxisCache], gy2c[kWithinAxisCache];
  for (int64_t x = lo[0]; x <= hi[0] && x - lo[0] < kWithinAxisCache; ++x) {
    const double gx = brick_axis_gap(o[0], d.res, x, mn[0], mx[0]);
    gx2c[x - lo[0]] = gx * gx;
  }
  for (int64_t y = lo[1]; y <= hi[1] && y - lo[1] < kWithinAxisCache; ++y) {
    const double gy = brick_axis_gap(o[1], d.res, y, mn[1], mx[1]);
    gy2c[y - lo[1]] = gy * gy;
  }
  for (int64_t z = lo[2]; z <= hi[2]; ++z) {
    const double gz = brick_axis_gap(o[2], d.res, z, mn[2], mx[2]);
    const double gz2 = gz * gz;
    for (int64_t y = lo[1]; y <= hi[1]; ++y) {
      const double gy2 = axis_gap2(gy2c, lo[1], o[1], d.res, y, mn[1], mx[1]);
      if (gy2 + gz2 >= lim2) continue;  // the whole row
      const int64_t row = nb[0] * (y + static_cast<int64_t>(nb[1]) * z);
      for (int64_t x = lo[0]; x <= hi[0]; ++x) {
        const uint32_t b = static_cast<uint32_t>(row + x);
        if (g->brick_mask[b] == 0u) continue;
        const double gx2 = axis_gap2(gx2c, lo[0], o[0], d.res, x, mn[0], mx[0]);
        if ((gx2 + gy2) + gz2 >= lim2) continue;
        if (!f(BrickCand{brick_gap2(g, b, x, y, z, mn, mx), b})) return false;
      }
    }
  }
  return true;
}

// The bricks of for_each_brick_near whose gap is below lim (m) or 0, sorted by gap2 then index,
// into cand[kMaxBrickCands]. Returns their number, or kMaxBrickCands + 1 when there are more
// (cand is then unusable).
uint32_t surface_bricks_sorted(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                               double lim, BrickCand* cand);

// The bits of a brick's mask whose local voxel (bit x + 4 (y + 4 z)) lies in [lo[a], hi[a]] on
// every axis a (local voxels, clamped to 0 .. 3; an empty range gives 0).
inline uint64_t brick_local_mask(const int64_t lo[3], const int64_t hi[3]) {
  int64_t l[3], h[3];
  for (int a = 0; a < 3; ++a) {
    l[a] = lo[a] < 0 ? 0 : lo[a];
    h[a] = hi[a] > kBrickVoxels - 1 ? kBrickVoxels - 1 : hi[a];
    if (l[a] > h[a]) return 0u;
  }
  const uint64_t row = ((uint64_t{1} << (h[0] - l[0] + 1)) - 1u) << l[0];
  uint64_t m = 0u;
  for (int64_t z = l[2]; z <= h[2]; ++z)
    for (int64_t y = l[1]; y <= h[1]; ++y) m |= row << (4 * (y + 4 * z));
  return m;
}

// The cube faces (m) of brick `brick` per axis: faces[a][l] = origin + (base[a] + l) res for
// l = 0 .. kBrickVoxels, base[a] the brick's first voxel on axis a (the same expressions as every
// other cube bound of the collision queries). The surface cube of mask bit b, at local coordinates
// (b & 3, (b >> 2) & 3, b >> 4), spans faces[a][l] .. faces[a][l + 1] on each axis.
inline void brick_faces(const tdo_grid* g, uint32_t brick, int64_t base[3],
                        double faces[3][kBrickVoxels + 1]) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const uint32_t nbx = static_cast<uint32_t>(g->nbx), nby = static_cast<uint32_t>(g->nby);
  base[0] = static_cast<int64_t>(brick % nbx) * kBrickVoxels;
  base[1] = static_cast<int64_t>(brick / nbx % nby) * kBrickVoxels;
  base[2] = static_cast<int64_t>(brick / nbx / nby) * kBrickVoxels;
  for (int a = 0; a < 3; ++a)
    for (int l = 0; l <= kBrickVoxels; ++l)
      faces[a][l] = o[a] + static_cast<double>(base[a] + l) * d.res;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_SURFACE_INDEX_H
