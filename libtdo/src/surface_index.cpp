// Brick index of the surface cubes (surface_index.h).
#include "surface_index.h"

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
  return static_cast<uint32_t>(i / kBrickVoxels +
                               g->nbx * (j / kBrickVoxels + g->nby * (k / kBrickVoxels)));
}

inline uint64_t bit_of(int64_t i, int64_t j, int64_t k) {
  return uint64_t{1} << ((i & 3) + 4 * ((j & 3) + 4 * (k & 3)));
}

}  // namespace

size_t surface_index_footprint(const GridCapacity& cap) {
  const size_t n = brick_capacity(cap);
  if (n == 0u) return 0u;  // boxes only: nothing is allocated
  return tdo_arena_round(n * sizeof(uint64_t) + 1u) + tdo_arena_round(n * sizeof(uint16_t) + 1u);
}

void surface_index_build(tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  g->bricks_valid = 0;
  g->nbx = bricks_along(d.nx);
  g->nby = bricks_along(d.ny);
  g->nbz = bricks_along(d.nz);
  const uint64_t n =
      static_cast<uint64_t>(g->nbx) * static_cast<uint64_t>(g->nby) * static_cast<uint64_t>(g->nbz);
  if (g->brick_mask == nullptr || n > brick_capacity(g->cap)) return;
  memset(g->brick_mask, 0, static_cast<size_t>(n) * sizeof(uint64_t));
  if (g->n_cubes > 0u) {
    for (int64_t k = 0; k < d.nz; ++k)
      for (int64_t j = 0; j < d.ny; ++j) {
        const uint8_t* row = g->flags + index_of(g, 0, j, k);
        for (int64_t i = next_flagged(row, 0, d.nx, kFlagSurface); i < d.nx;
             i = next_flagged(row, i + 1, d.nx, kFlagSurface))
          g->brick_mask[brick_of(g, i, j, k)] |= bit_of(i, j, k);
      }
  }
  for (uint64_t b = 0; b < n; ++b) g->brick_box[b] = pack_box(g->brick_mask[b]);
  g->bricks_valid = 1;
}

void surface_index_set(tdo_grid* g, int64_t i, int64_t j, int64_t k, bool on) {
  if (!g->bricks_valid) return;
  const uint32_t b = brick_of(g, i, j, k);
  const uint64_t m =
      on ? (g->brick_mask[b] | bit_of(i, j, k)) : (g->brick_mask[b] & ~bit_of(i, j, k));
  if (m == g->brick_mask[b]) return;
  g->brick_mask[b] = m;
  g->brick_box[b] = pack_box(m);
}

namespace {

// surface_bricks_sorted's insertion of one brick (gap2 below lim2 or 0) into cand.
struct SortedKeep {
  BrickCand* cand;
  double lim2;
  uint32_t count;
  bool operator()(const BrickCand& c) {
    if (c.gap2 > 0.0 && c.gap2 >= lim2) return true;
    if (count == kMaxBrickCands) return false;
    // Insertion by (gap2, brick): the bricks come in increasing index already.
    uint32_t at = count++;
    while (at > 0u && cand[at - 1u].gap2 > c.gap2) {
      cand[at] = cand[at - 1u];
      --at;
    }
    cand[at] = c;
    return true;
  }
};

// The two walks in frames of their own, side by side on the stack (not nested).
__attribute__((noinline)) bool sorted_near(const tdo_grid* g, const double p0[3],
                                           const double p1[3], double r, SortedKeep* k) {
  return for_each_brick_near(g, p0, p1, r, *k);
}
__attribute__((noinline)) bool sorted_within(const tdo_grid* g, const double p0[3],
                                             const double p1[3], double r, double lim,
                                             SortedKeep* k) {
  return for_each_brick_within(g, p0, p1, r, lim, *k);
}

}  // namespace

uint32_t surface_bricks_sorted(const tdo_grid* g, const double p0[3], const double p1[3], double r,
                               double lim, BrickCand* cand) {
  SortedKeep keep{cand, lim * lim, 0u};
  // The pruned walk leaves out only bricks `keep` skips: the same bricks in the same order.
  const bool fits = within_pays(g, r, lim) ? sorted_within(g, p0, p1, r, lim, &keep)
                                           : sorted_near(g, p0, p1, r, &keep);
  return fits ? keep.count : kMaxBrickCands + 1u;
}

}  // namespace tdo_internal
