// Brick index of the surface cubes (surface_index.h).
#include "surface_index.h"

#include <math.h>
#include <string.h>

#include "grid_geometry.h"

namespace tdo_internal {
namespace {

// Packed tight box of a brick: lo x, y, z then hi x, y, z, 2 bits each (voxels inside the brick).
uint16_t pack_box(uint64_t mask) {
  uint32_t lo[3] = {3u, 3u, 3u}, hi[3] = {0u, 0u, 0u};
  while (mask != 0u) {  // at most 64 iterations
    const uint32_t b = static_cast<uint32_t>(__builtin_ctzll(mask));
    mask &= mask - 1u;
    const uint32_t c[3] = {b & 3u, (b >> 2) & 3u, b >> 4};
    for (int a = 0; a < 3; ++a) {
      lo[a] = c[a] < lo[a] ? c[a] : lo[a];
      hi[a] = c[a] > hi[a] ? c[a] : hi[a];
    }
  }
  return static_cast<uint16_t>(lo[0] | (lo[1] << 2) | (lo[2] << 4) | (hi[0] << 6) | (hi[1] << 8) |
                               (hi[2] << 10));
}

inline int32_t bricks_along(int32_t n) { return (n + kBrickVoxels - 1) / kBrickVoxels; }

inline uint32_t brick_of(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return static_cast<uint32_t>(i / kBrickVoxels + g->nbx * (j / kBrickVoxels + g->nby * (k / kBrickVoxels)));
}

inline uint64_t bit_of(int64_t i, int64_t j, int64_t k) {
  return uint64_t{1} << ((i & 3) + 4 * ((j & 3) + 4 * (k & 3)));
}

}  // namespace

size_t surface_index_footprint(const GridCapacity& cap) {
  const size_t n = brick_capacity(cap);
  return tdo_arena_round(n * sizeof(uint64_t) + 1u) + tdo_arena_round(n * sizeof(uint16_t) + 1u);
}

void surface_index_build(tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  g->bricks_valid = 0;
  g->nbx = bricks_along(d.nx);
  g->nby = bricks_along(d.ny);
  g->nbz = bricks_along(d.nz);
  const uint64_t n = static_cast<uint64_t>(g->nbx) * static_cast<uint64_t>(g->nby) *
                     static_cast<uint64_t>(g->nbz);
  if (g->brick_mask == nullptr || n > brick_capacity(g->cap)) return;
  memset(g->brick_mask, 0, static_cast<size_t>(n) * sizeof(uint64_t));
  if (g->n_cubes > 0u) {
    for (int64_t k = 0; k < d.nz; ++k)
      for (int64_t j = 0; j < d.ny; ++j) {
        const uint8_t* row = g->flags + index_of(g, 0, j, k);
        for (int64_t i = 0; i < d.nx; ++i)
          if ((row[i] & kFlagSurface) != 0) g->brick_mask[brick_of(g, i, j, k)] |= bit_of(i, j, k);
      }
  }
  for (uint64_t b = 0; b < n; ++b) g->brick_box[b] = pack_box(g->brick_mask[b]);
  g->bricks_valid = 1;
}

void surface_index_set(tdo_grid* g, int64_t i, int64_t j, int64_t k, bool on) {
  if (!g->bricks_valid) return;
  const uint32_t b = brick_of(g, i, j, k);
  const uint64_t m = on ? (g->brick_mask[b] | bit_of(i, j, k)) : (g->brick_mask[b] & ~bit_of(i, j, k));
  if (m == g->brick_mask[b]) return;
  g->brick_mask[b] = m;
  g->brick_box[b] = pack_box(m);
}

uint32_t surface_bricks_near(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                             double tol, BrickCand* cand) {
  const tdo_grid_desc& d = g->desc;
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t nb[3] = {g->nbx, g->nby, g->nbz};
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  double mn[3], mx[3];
  int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    mn[a] = p0[a] < p1[a] ? p0[a] : p1[a];
    mx[a] = p0[a] < p1[a] ? p1[a] : p0[a];
    // Voxel range of the span box grown by r, one voxel of margin on each side (as the scan of
    // collision.cpp), then the bricks holding it.
    const double va = floor((mn[a] - r - o[a]) / d.res) - 1.0;
    const double vb = floor((mx[a] + r - o[a]) / d.res) + 1.0;
    if (vb < 0.0 || va > static_cast<double>(n[a] - 1)) return 0u;
    const int64_t ia = va < 0.0 ? 0 : static_cast<int64_t>(va);
    const int64_t ib = vb > static_cast<double>(n[a] - 1) ? n[a] - 1 : static_cast<int64_t>(vb);
    lo[a] = ia / kBrickVoxels;
    hi[a] = ib / kBrickVoxels;
    if (hi[a] > nb[a] - 1) hi[a] = nb[a] - 1;
  }
  const double lim = r + tol;
  const double lim2 = lim * lim;
  uint32_t count = 0;
  for (int64_t z = lo[2]; z <= hi[2]; ++z)
    for (int64_t y = lo[1]; y <= hi[1]; ++y) {
      const uint32_t row = static_cast<uint32_t>(nb[0] * (y + nb[1] * z));
      for (int64_t x = lo[0]; x <= hi[0]; ++x) {
        const uint32_t b = row + static_cast<uint32_t>(x);
        if (g->brick_mask[b] == 0u) continue;
        const uint32_t pk = g->brick_box[b];
        const int64_t base[3] = {x * kBrickVoxels, y * kBrickVoxels, z * kBrickVoxels};
        double gap2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const int64_t ci = base[a] + ((pk >> (2 * a)) & 3u);
          const int64_t cj = base[a] + ((pk >> (6 + 2 * a)) & 3u) + 1;
          const double blo = o[a] + static_cast<double>(ci) * d.res;
          const double bhi = o[a] + static_cast<double>(cj) * d.res;
          const double gp = (blo - mx[a] > 0.0 ? blo - mx[a] : 0.0) +
                            (mn[a] - bhi > 0.0 ? mn[a] - bhi : 0.0);
          gap2 += gp * gp;
        }
        if (gap2 > 0.0 && gap2 >= lim2) continue;
        if (count == kMaxBrickCands) return kMaxBrickCands + 1u;
        // Insertion in order of (gap2, brick): the bricks come in increasing index already.
        uint32_t at = count++;
        while (at > 0u && cand[at - 1u].gap2 > gap2) {
          cand[at] = cand[at - 1u];
          --at;
        }
        cand[at] = BrickCand{gap2, b};
      }
    }
  return count;
}

}  // namespace tdo_internal
