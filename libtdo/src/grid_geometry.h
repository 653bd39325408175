// Voxel arithmetic of the grid, shared by the full build (grid.cpp) and the incremental update
// (grid_update.cpp), whose results must be identical. Internal to libtdo.
#ifndef TDO_SRC_GRID_GEOMETRY_H
#define TDO_SRC_GRID_GEOMETRY_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "grid_internal.h"

namespace tdo_internal {

inline int64_t index_of(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return i + j * g->stride_y + k * g->stride_z;
}

inline bool in_grid(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return i >= 0 && j >= 0 && k >= 0 && i < g->desc.nx && j < g->desc.ny && k < g->desc.nz;
}

// Clamp a (finite) voxel coordinate into [-1, n] before converting it to an integer.
inline int64_t clamp_index(double v, int32_t n) {
  if (v < -1.0) return -1;
  if (v > static_cast<double>(n)) return n;
  return static_cast<int64_t>(v);
}

// Voxel range [lo, hi] along one axis whose cells intersect the open interval (a, b).
inline void interior_range(double o, double r, int32_t n, double a, double b, int64_t* lo,
                           int64_t* hi) {
  // cell i spans [o + i r, o + (i+1) r); it meets (a, b) iff o + i r < b and o + (i+1) r > a.
  const int64_t first0 = clamp_index(floor((a - o) / r) - 1.0, n);
  const int64_t last0 = clamp_index(ceil((b - o) / r) + 1.0, n);
  int64_t first = first0 < 0 ? 0 : first0;
  int64_t last = last0 > n - 1 ? n - 1 : last0;
  while (first <= last && !(o + static_cast<double>(first + 1) * r > a)) ++first;
  while (last >= first && !(o + static_cast<double>(last) * r < b)) --last;
  *lo = first;
  *hi = last;
}

// Voxel range [lo, hi] along one axis whose centres lie within [a - c, b + c].
inline void centre_range(double o, double r, int32_t n, double a, double b, double c, int64_t* lo,
                         int64_t* hi) {
  const int64_t f = clamp_index(ceil((a - c - o) / r - 0.5), n);
  const int64_t l = clamp_index(floor((b + c - o) / r - 0.5), n);
  *lo = f < 0 ? 0 : f;
  *hi = l > n - 1 ? n - 1 : l;
}

// Distance from p to the interval [a, b] along one axis (0 inside).
inline double axis_gap(double p, double a, double b) {
  if (p < a) return a - p;
  if (p > b) return p - b;
  return 0.0;
}

// Next x >= i in `row` (n voxels) whose flags have any bit of `bit`, or n; 8 voxels per word.
inline int64_t next_flagged(const uint8_t* row, int64_t i, int64_t n, uint8_t bit) {
  const uint64_t bytes = 0x0101010101010101ull * bit;
  while (i + 8 <= n) {
    uint64_t w;
    memcpy(&w, row + i, sizeof w);
    if ((w & bytes) != 0) break;
    i += 8;
  }
  while (i < n && (row[i] & bit) == 0) ++i;
  return i;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_GRID_GEOMETRY_H
