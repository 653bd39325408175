// The grid-distance tables of the turn-penalised search's retry (docs/design.md s.1, "Retry with
// grid distances").
#include "search_tables.h"

#include <math.h>
#include <stddef.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

#include "directions.h"
#include "grid_internal.h"
#include "search_state.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {
namespace {

// The Dijkstra queue: buckets of key width kDjWidth * res, a ring of kDjRing of them, each a
// doubly linked list of voxels (next in ctx->dj_heap, previous in ctx->dj_pos). Every step is at
// least res long, so a voxel whose key lies in the lowest non-empty bucket cannot be lowered by any
// other queued voxel (Dinitz): a bucket is settled in any order with the keys a heap would give,
// and the settled set and the keys are those of the heap's order. A step adds at most sqrt(3) res,
// so the keys in the queue span fewer than 4 buckets and a ring of 8 holds them apart.
constexpr uint32_t kDjRing = 8;
constexpr double kDjWidth = 1.0 - 1e-6;       // bucket width per res (below 1: rounding margin)
constexpr uint32_t kDjHead = 0xFFFFFFFDu;     // dj_pos of the first voxel of a bucket's list
constexpr uint32_t kDjSettled = 0xFFFFFFFEu;  // dj_pos of a settled voxel

struct DjQueue {
  uint32_t* next;
  uint32_t* prev;
  uint32_t head[kDjRing];
  double inv_width;  // 1/m

  // (through int64_t: the keys stay far below 2^63 buckets, and the signed conversion is one
  // instruction where the unsigned one tests the range first)
  uint64_t bucket(double d) const {
    return static_cast<uint64_t>(static_cast<int64_t>(d * inv_width));
  }
  void insert(uint32_t v, uint64_t b) {
    uint32_t& h = head[b & (kDjRing - 1u)];
    next[v] = h;
    prev[v] = kDjHead;
    if (h != kNil) prev[h] = v;
    h = v;
  }
  void unlink(uint32_t v, uint64_t b) {
    if (prev[v] == kDjHead)
      head[b & (kDjRing - 1u)] = next[v];
    else
      next[prev[v]] = next[v];
    if (next[v] != kNil) prev[next[v]] = prev[v];
  }
};

// The Dijkstra stops once its smallest key exceeds kDjReach times the distance of the other root
// (or settles everything): the turn-penalised searches rarely leave that ball, and outside it the
// key it stopped at is still a lower bound of every unsettled voxel's distance.
constexpr double kDjReach = 2.0;

#if defined(__SSE2__)
// Step lengths (m) of the cells of each row of three of a 3x3x3 block, as the two overlapping
// pairs (x = -1, 0) and (x = 0, +1) the Dijkstra compares; the centre and the second copy of the
// middle cell are +inf, so their tests always fail.
struct RowLengths {
  alignas(16) double lo[9][2];
  alignas(16) double hi[9][2];
  alignas(32) double quad[9][4];  // the row's three cells and the next voxel (+inf), AVX2
};

RowLengths row_lengths(const tdo_search* ctx) {
  RowLengths t;
  for (int k = 0; k < 9; ++k) {
    for (int x = 0; x < 3; ++x) {
      const int c = 3 * k + x;
      const double len = c == 13 ? HUGE_VAL : ctx->step_len[dir_of_cell(c)];
      if (x < 2) t.lo[k][x] = len;
      if (x > 0) t.hi[k][x - 1] = x == 1 ? HUGE_VAL : len;
      t.quad[k][x] = len;
    }
    t.quad[k][3] = HUGE_VAL;
  }
  return t;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TDO_DJ_AVX2 1
// The steps of the block around u whose cost test passes (bit d: direction d), four cells of a row
// at a time (the row's three and the next voxel, whose length is +inf). The same additions and
// comparisons as the SSE2 path, so the same bits; used when the processor has AVX2.
// The rows start from three pointers, one per layer, a row stride apart (sy, sz: the grid's
// strides), so the loop keeps strides in registers instead of nine row offsets.
__attribute__((target("avx2"))) uint32_t lower_dirs_avx2(const double* at_u, int64_t sy, int64_t sz,
                                                         const RowLengths& lens, double du) {
  const __m256d vdu = _mm256_set1_pd(du);
  uint32_t dirs = 0;
  const double* layer = at_u - 1 - sz - sy;  // the first cell of row 0
#pragma GCC unroll 3
  for (int z = 0; z < 3; ++z) {
#pragma GCC unroll 3
    for (int y = 0; y < 3; ++y) {
      const int k = 3 * z + y;
      const __m256d sum = _mm256_add_pd(vdu, _mm256_load_pd(lens.quad[k]));
      __m256d lt = _mm256_cmp_pd(sum, _mm256_loadu_pd(layer + y * sy), _CMP_LT_OQ);
      // The middle row's cells -1 and +1 side by side (its centre never passes): the mask comes
      // out by direction, rows after it one bit lower than by cell.
      if (k == 4) lt = _mm256_permute4x64_pd(lt, 0xD8);  // lanes 0, 2, 1, 3
      dirs |= static_cast<uint32_t>(_mm256_movemask_pd(lt)) << (k > 4 ? 3 * k - 1 : 3 * k);
    }
    layer += sz;
  }
  return dirs;  // (lane 3 is never set)
}
#endif

// The cells of row k of u's block (its middle cell at r) whose cost test passes, by the SSE2 pairs.
inline uint32_t row_cells(__m128d vdu, const double* r, const RowLengths& lens, int k) {
  const int lo =
      _mm_movemask_pd(_mm_cmplt_pd(_mm_add_pd(vdu, _mm_load_pd(lens.lo[k])), _mm_loadu_pd(r - 1)));
  const int hi =
      _mm_movemask_pd(_mm_cmplt_pd(_mm_add_pd(vdu, _mm_load_pd(lens.hi[k])), _mm_loadu_pd(r)));
  return static_cast<uint32_t>(lo | (hi << 1)) << (3 * k);  // hi: bit 1 alone
}

// The direction mask of each row of three of a block.
constexpr uint32_t row_dirs(int k) { return dirs_of_cells(7u << (3 * k)); }
constexpr uint32_t kRowDirs[9] = {row_dirs(0), row_dirs(1), row_dirs(2), row_dirs(3), row_dirs(4),
                                  row_dirs(5), row_dirs(6), row_dirs(7), row_dirs(8)};

// The cells of the block of a voxel near an end of the table (part of its block lies outside
// [0, nvox)): a row without legal steps is skipped, a row read inside the table is tested as in
// the inner loop, and the cells of a row that reaches outside it all pass here (step() tests them).
uint32_t edge_cells(const double* dist, uint32_t u, uint32_t nvox, const int64_t* rows,
                    const RowLengths& lens, double du, uint32_t moves) {
  const __m128d vdu = _mm_set1_pd(du);
  uint32_t cells = 0;
  for (int k = 0; k < 9; ++k) {
    if ((moves & kRowDirs[k]) == 0u) continue;
    const int64_t r = static_cast<int64_t>(u) + rows[k];
    if (r >= 1 && r + 2 <= static_cast<int64_t>(nvox))
      cells |= row_cells(vdu, dist + r, lens, k);
    else
      cells |= 7u << (3 * k);
  }
  return cells;
}
#endif

// exact_lower_bounds's Dijkstra; kAvx2: the block tests by lower_dirs_avx2 (flood_avx2 only).
template <bool kAvx2>
bool flood(tdo_search* ctx, const tdo_grid* g, uint32_t root, uint32_t other) {
  double* dist = ctx->dj_dist;
  const uint32_t nvox = g->nvox;
  DjQueue qu;
  qu.next = ctx->dj_heap;
  qu.prev = ctx->dj_pos;
  for (uint32_t k = 0; k < kDjRing; ++k) qu.head[k] = kNil;
  qu.inv_width = 1.0 / (kDjWidth * g->desc.res);
  for (uint32_t v = 0; v < nvox; ++v) {
    dist[v] = HUGE_VAL;
    qu.prev[v] = kNil;
  }
  dist[root] = 0.0;
  qu.insert(root, 0u);
#if defined(__SSE2__)
  const RowLengths lens = row_lengths(ctx);
  // Voxels whose whole 3x3x3 block of linear indices lies in [0, nvox).
  const int64_t reach = ctx->block_row[8] + 1;  // largest index offset of the block
  const uint32_t inner_lo = static_cast<uint32_t>(reach);
  // (reach + 1: the AVX2 test reads one voxel past the block)
  const uint32_t inner_hi = static_cast<int64_t>(nvox) > reach + 1 ? nvox - inner_lo - 1u : 0u;
  int64_t rows[9];
  for (int k = 0; k < 9; ++k) rows[k] = ctx->block_row[k];
#endif
  double limit = HUGE_VAL;
  bool reached = false;
  uint64_t cur = 0;  // current bucket
  // The smallest key beyond the limit (the voxels of the bucket where the Dijkstra stops that lie
  // beyond it: so does every later one); +inf while none is.
  double rest = HUGE_VAL;
  // Every queued voxel lies in a bucket of the ring: kDjRing empty buckets in a row, and the queue
  // is empty.
  uint32_t empty = 0;
  while (empty < kDjRing) {
    uint32_t u = qu.head[cur & (kDjRing - 1u)];
    if (u == kNil) {
      ++empty;
      ++cur;
      continue;
    }
    empty = 0;
    // The bucket's list is taken out of the queue whole and walked: no step joins or leaves it
    // (see DjQueue), so its voxels need no unlinking one by one.
    qu.head[cur & (kDjRing - 1u)] = kNil;
    while (u != kNil) {
      const uint32_t after = qu.next[u];
      const double du = dist[u];
      if (du > limit) {
        rest = du < rest ? du : rest;
        u = after;
        continue;
      }
      qu.prev[u] = kDjSettled;
      if (u == other) {
        reached = true;
        limit = kDjReach * du;
      }
      // The cost test comes first: a settled neighbour fails it too (its key lies at most one
      // bucket, under res, above du, and a step adds at least res), so most steps end after one
      // load; the bucket test after it only guards the list being walked and the settled voxels
      // (their keys lie in buckets up to the current one).
      const auto step = [&](int e) {
        const uint32_t w = static_cast<uint32_t>(static_cast<int64_t>(u) + ctx->offset[e]);
        const double nd = du + ctx->step_len[e];
        if (!(nd < dist[w])) return;
        const uint32_t pw = qu.prev[w];
        const uint64_t b = qu.bucket(nd);
        if (pw != kNil) {
          const uint64_t bw = qu.bucket(dist[w]);
          if (bw <= cur) return;  // cannot happen (see DjQueue)
          dist[w] = nd;
          if (b == bw) return;  // lowered within its bucket: its place in the queue stays
          qu.unlink(w, bw);
        }
        dist[w] = nd;
        qu.insert(w, b > cur ? b : cur + 1u);
      };
      const uint32_t moves = g->moves[u];
#if defined(__SSE2__)
      if (u >= inner_lo && u < inner_hi) {
        // The cost tests of the 27 cells of u's block two at a time: each row of three cells is
        // contiguous (a voxel on a face of the grid reads voxels of other rows there, inside the
        // table, whose steps `moves` drops). Only the legal steps that lower a key are taken, in
        // step order: a step changes the key of its own voxel alone, so the tests stay true.
        uint32_t dirs = 0;
#if defined(TDO_DJ_AVX2)
        if constexpr (kAvx2) dirs = lower_dirs_avx2(dist + u, g->stride_y, g->stride_z, lens, du);
#endif
        if constexpr (!kAvx2) {
          uint32_t cells = 0;
          const __m128d vdu = _mm_set1_pd(du);
#pragma GCC unroll 9
          for (int k = 0; k < 9; ++k)
            cells |= row_cells(vdu, dist + (static_cast<int64_t>(u) + rows[k]), lens, k);
          dirs = dirs_of_cells(cells);
        }
        for (uint32_t m = dirs & moves; m != 0; m &= m - 1u) step(__builtin_ctz(m));
      } else if (moves != 0u) {
        const uint32_t cells = edge_cells(dist, u, nvox, rows, lens, du, moves);
        for (uint32_t m = dirs_of_cells(cells) & moves; m != 0; m &= m - 1u) step(__builtin_ctz(m));
      }
#else
      if (moves == kAllMoves) {  // open space: the steps in the same order, without the mask
#pragma GCC unroll 26
        for (int e = 0; e < kNumDirs; ++e) step(e);
      } else {
        for (uint32_t m = moves; m != 0; m &= m - 1u) step(__builtin_ctz(m));
      }
#endif
      // Settled: its bound loses 1e-12 relative so that rounding of the sums never lifts it above
      // a path's summed cost. No later test changes (a settled key fails every cost test).
      dist[u] = du * (1.0 - 1e-12);
      u = after;
    }
    if (rest < HUGE_VAL) break;
    ++cur;
  }
  if (!reached) return false;
  // Unsettled voxels: the smallest key left in the queue bounds their distance from below. When
  // the queue ran empty they are not connected to the root and keep HUGE_VAL.
  if (!(rest < HUGE_VAL)) return true;
  for (uint32_t k = 0; k < kDjRing; ++k)
    for (uint32_t v = qu.head[k]; v != kNil; v = qu.next[v]) rest = dist[v] < rest ? dist[v] : rest;
  for (uint32_t v = 0; v < nvox; ++v)
    if (qu.prev[v] != kDjSettled) dist[v] = rest;
  return true;
}

#if defined(TDO_DJ_AVX2)
// The Dijkstra compiled for AVX2, lower_dirs_avx2 inlined into its loop (flatten: the template
// itself is compiled for the baseline target). The same additions and comparisons, so the same
// keys.
__attribute__((target("avx2"), noinline, flatten)) bool flood_avx2(tdo_search* ctx,
                                                                   const tdo_grid* g, uint32_t root,
                                                                   uint32_t other) {
  return flood<true>(ctx, g, root, other);
}
#endif

}  // namespace

// Lower bounds of the grid distance (m) from every voxel to voxel `root` in dist[]: exact for the
// voxels the Dijkstra settled (26-connected legal moves, the search's step lengths), the key it
// stopped at for the others. Moves are symmetric (a step is legal when the box of its two voxels
// is free), so distances from the root are distances to it. Bounded: each voxel is settled once,
// and between two settled voxels the current bucket passes fewer than kDjRing empty ones.
// @return false when the Dijkstra ran out without reaching voxel `other` (no path).
bool exact_lower_bounds(tdo_search* ctx, const tdo_grid* g, uint32_t root, uint32_t other) {
#if defined(TDO_DJ_AVX2)
  if (__builtin_cpu_supports("avx2")) return flood_avx2(ctx, g, root, other);
#endif
  return flood<false>(ctx, g, root, other);  // no AVX2 (processor, or clang and other targets)
}

namespace {

#if defined(TDO_DJ_AVX2)
// store_lower_bounds's loop for [0, n - n % 8), eight keys at a time with AVX2: the same
// conversions and tests as the SSE2 loop, so the same bits.
__attribute__((target("avx2"), noinline)) uint32_t store_lower_avx2(const double* dist, uint32_t n,
                                                                    float* table) {
  const __m256i even = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  uint32_t v = 0;
  for (; v + 8u <= n; v += 8u) {
#pragma GCC unroll 2
    for (uint32_t h = 0; h < 8u; h += 4u) {
      const __m256d d = _mm256_loadu_pd(dist + v + h);
      const __m128 f = _mm256_cvtpd_ps(d);
      const __m256d up = _mm256_cmp_pd(_mm256_cvtps_pd(f), d, _CMP_GT_OQ);
      const __m128i up32 =
          _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(up), even));
      const __m128i bits = _mm_add_epi32(_mm_castps_si128(f), up32);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(table + v + h), bits);
    }
  }
  return v;
}
#endif

}  // namespace

// The table of a side: each key rounded down to a float, so a lower bound stays one (+inf stays
// +inf: an unreachable voxel).
// A float that rounded up is lowered by one unit in the last place: for the positive finite
// floats a distance rounds to, the next float towards zero is the bit pattern minus one (what
// nextafterf(f, 0) returns, without its call on every second value).
// With SSE2, four at a time by the same conversions (cvtpd2ps rounds as the cast does, to nearest)
// and the same test; the mask of a lane that rounded up is all ones, -1 added to its bits.
void store_lower_bounds(const double* dist, uint32_t nvox, float* table) {
  uint32_t v = 0;
#if defined(TDO_DJ_AVX2)
  if (__builtin_cpu_supports("avx2")) v = store_lower_avx2(dist, nvox, table);
#endif
#if defined(__SSE2__)
  for (; v + 4u <= nvox; v += 4u) {
    const __m128d d0 = _mm_loadu_pd(dist + v), d1 = _mm_loadu_pd(dist + v + 2u);
    const __m128 f0 = _mm_cvtpd_ps(d0), f1 = _mm_cvtpd_ps(d1);
    const __m128d up0 = _mm_cmpgt_pd(_mm_cvtps_pd(f0), d0),
                  up1 = _mm_cmpgt_pd(_mm_cvtps_pd(f1), d1);
    const __m128 up =
        _mm_shuffle_ps(_mm_castpd_ps(up0), _mm_castpd_ps(up1), _MM_SHUFFLE(2, 0, 2, 0));
    const __m128i bits =
        _mm_add_epi32(_mm_castps_si128(_mm_movelh_ps(f0, f1)), _mm_castps_si128(up));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(table + v), bits);
  }
#endif
  for (; v < nvox; ++v) {
    float f = static_cast<float>(dist[v]);
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    bits -= static_cast<double>(f) > dist[v] ? 1u : 0u;
    memcpy(&f, &bits, sizeof(f));
    table[v] = f;
  }
}

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal
