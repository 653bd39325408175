#include <math.h>
#include <string.h>

#include "directions.h"
#include "grid_geometry.h"
#include "grid_internal.h"
#include "surface_index.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

// Block every voxel whose centre lies strictly closer than c to the (closed) box.
void inflate_box(tdo_grid* g, const tdo_box& box, double c) {
  const tdo_grid_desc& d = g->desc;
  int64_t i0, i1, j0, j1, k0, k1;
  centre_range(d.origin.x, d.res, d.nx, box.min.x, box.max.x, c, &i0, &i1);
  centre_range(d.origin.y, d.res, d.ny, box.min.y, box.max.y, c, &j0, &j1);
  centre_range(d.origin.z, d.res, d.nz, box.min.z, box.max.z, c, &k0, &k1);
  const double c2 = c * c;
  for (int64_t k = k0; k <= k1; ++k) {
    const double gz =
        axis_gap(d.origin.z + (static_cast<double>(k) + 0.5) * d.res, box.min.z, box.max.z);
    for (int64_t j = j0; j <= j1; ++j) {
      const double gy =
          axis_gap(d.origin.y + (static_cast<double>(j) + 0.5) * d.res, box.min.y, box.max.y);
      for (int64_t i = i0; i <= i1; ++i) {
        const double gx =
            axis_gap(d.origin.x + (static_cast<double>(i) + 0.5) * d.res, box.min.x, box.max.x);
        if (gx * gx + gy * gy + gz * gz < c2) g->flags[index_of(g, i, j, k)] |= kFlagBlocked;
      }
    }
  }
}

}  // namespace

// Offsets (di,dj,dk) whose centre is strictly closer than c to the cube of voxel (0,0,0).
// Refused in constant time when the stencil cannot fit: every offset with |di|, |dj|, |dk| <= m
// lies inside when sqrt(3) (m - 1/2) r < c, so (2m + 1)^3 cells are a lower bound of the count.
// Past that check c / r is below sqrt(3) (cap^(1/3) / 2 + 2), so the loops run at most about
// 5.2 * cap + O(cap^(2/3)) times and every conversion to int32 is in range.
tdo_status build_stencil(tdo_grid* g, double c, uint32_t* count) {
  const double r = g->desc.res;
  const double ratio = c / r;
  if (!(ratio >= 0.0) || !(ratio < 1e9)) return TDO_ERR_CLEARANCE_CAPACITY;
  const double m = floor(ratio / sqrt(3.0) + 0.5) - 1.0;  // one voxel of margin for rounding
  const double side = 2.0 * m + 1.0;
  if (m >= 1.0 && side * side * side > static_cast<double>(g->cap.max_clear_cells))
    return TDO_ERR_CLEARANCE_CAPACITY;
  const int32_t reach = static_cast<int32_t>(ceil(ratio + 0.5));
  const double c2 = c * c;
  uint32_t n = 0;
  for (int32_t dk = -reach; dk <= reach; ++dk) {
    for (int32_t dj = -reach; dj <= reach; ++dj) {
      for (int32_t di = -reach; di <= reach; ++di) {
        const double gx = fmax(0.0, fabs(static_cast<double>(di)) * r - 0.5 * r);
        const double gy = fmax(0.0, fabs(static_cast<double>(dj)) * r - 0.5 * r);
        const double gz = fmax(0.0, fabs(static_cast<double>(dk)) * r - 0.5 * r);
        if (!(gx * gx + gy * gy + gz * gz < c2)) continue;
        if (n >= g->cap.max_clear_cells) return TDO_ERR_CLEARANCE_CAPACITY;
        g->stencil[3 * n] = di;
        g->stencil[3 * n + 1] = dj;
        g->stencil[3 * n + 2] = dk;
        ++n;
      }
    }
  }
  *count = n;
  return TDO_OK;
}

namespace {

// Index i of the half-open span [o + i r, o + (i+1) r) holding p, computed the way the spans are:
// floor((p - o) / r) can be off by one within a rounding step of a face.
double span_index(double p, double o, double r) {
  double i = floor((p - o) / r);
  if (o + i * r > p) i -= 1.0;
  if (!(o + (i + 1.0) * r > p)) i += 1.0;
  return i;
}

bool is_cube(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return in_grid(g, i, j, k) && (g->flags[index_of(g, i, j, k)] & kFlagCube) != 0;
}

// A cube whose six face neighbours are cubes is never the nearest obstacle of an outside point:
// the nearest point then also lies on a cube with an exposed face.
bool is_buried(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return is_cube(g, i - 1, j, k) && is_cube(g, i + 1, j, k) && is_cube(g, i, j - 1, k) &&
         is_cube(g, i, j + 1, k) && is_cube(g, i, j, k - 1) && is_cube(g, i, j, k + 1);
}

// The stencil as rows along x: when every (dj, dk) of the stencil holds exactly the offsets
// di = -w .. w (the distance is monotone in |di|, so this holds unless rounding breaks it; it is
// checked, not assumed), rewrite it in place as one triple (dj, dk, w) per row and return true.
// Cells come from build_stencil with dk outer, dj middle and di ascending, so a row's cells are
// consecutive and the triples never overtake the cells still to be read.
bool stencil_rows(tdo_grid* g, uint32_t n_cells, uint32_t* n_rows) {
  const int32_t* s = g->stencil;
  for (uint32_t a = 0; a < n_cells;) {  // check every row first, then rewrite
    uint32_t b = a;
    while (b < n_cells && s[3 * b + 1] == s[3 * a + 1] && s[3 * b + 2] == s[3 * a + 2]) ++b;
    const int32_t w = s[3 * (b - 1)];
    if (w < 0 || s[3 * a] != -w || b - a != 2u * static_cast<uint32_t>(w) + 1u) return false;
    for (uint32_t c = a + 1; c < b; ++c)
      if (s[3 * c] != s[3 * (c - 1)] + 1) return false;
    a = b;
  }
  uint32_t rows = 0;
  for (uint32_t a = 0; a < n_cells;) {
    uint32_t b = a;
    while (b < n_cells && s[3 * b + 1] == s[3 * a + 1] && s[3 * b + 2] == s[3 * a + 2]) ++b;
    const int32_t dj = s[3 * a + 1], dk = s[3 * a + 2], w = s[3 * (b - 1)];
    g->stencil[3 * rows] = dj;
    g->stencil[3 * rows + 1] = dk;
    g->stencil[3 * rows + 2] = w;
    ++rows;
    a = b;
  }
  *n_rows = rows;
  return true;
}

// Block, from one run of cubes [i0, i1] in row (j, k), every voxel the stencil rows reach: per
// row (dj, dk, w) the span [i0 - w, i1 + w] of row (j + dj, k + dk). A run is the union of its
// cubes' stencils, since each stencil row is an interval.
void inflate_run(tdo_grid* g, uint32_t n_rows, int64_t i0, int64_t i1, int64_t j, int64_t k) {
  const tdo_grid_desc& d = g->desc;
  for (uint32_t r = 0; r < n_rows; ++r) {
    const int64_t b = j + g->stencil[3 * r], e = k + g->stencil[3 * r + 1];
    if (b < 0 || e < 0 || b >= d.ny || e >= d.nz) continue;
    const int64_t w = g->stencil[3 * r + 2];
    const int64_t lo = i0 - w < 0 ? 0 : i0 - w;
    const int64_t hi = i1 + w > d.nx - 1 ? d.nx - 1 : i1 + w;
    uint8_t* row = g->flags + index_of(g, 0, b, e);
    for (int64_t i = lo; i <= hi; ++i) row[i] |= kFlagBlocked;
  }
}

// Per voxel, the stencil at every cube: the general form, used when stencil_rows refuses.
void inflate_cells(tdo_grid* g, uint32_t n_cells) {
  const tdo_grid_desc& d = g->desc;
  for (int64_t k = 0; k < d.nz; ++k) {
    for (int64_t j = 0; j < d.ny; ++j) {
      for (int64_t i = 0; i < d.nx; ++i) {
        if ((g->flags[index_of(g, i, j, k)] & kFlagCube) == 0 || is_buried(g, i, j, k)) continue;
        for (uint32_t s = 0; s < n_cells; ++s) {
          const int64_t a = i + g->stencil[3 * s], b = j + g->stencil[3 * s + 1],
                        e = k + g->stencil[3 * s + 2];
          if (in_grid(g, a, b, e)) g->flags[index_of(g, a, b, e)] |= kFlagBlocked;
        }
      }
    }
  }
}

// Block every voxel whose centre lies strictly closer than c to a cube: the union of the
// stencil placed at every cube. Done per run of consecutive cubes along x and per stencil row,
// so the work is about the number of voxels blocked, not cubes x stencil cells.
tdo_status inflate_cubes(tdo_grid* g, double c) {
  uint32_t n_cells = 0;
  const tdo_status st = build_stencil(g, c, &n_cells);
  if (st != TDO_OK) return st;
  uint32_t n_rows = 0;
  if (!stencil_rows(g, n_cells, &n_rows)) {
    inflate_cells(g, n_cells);
    return TDO_OK;
  }
  const tdo_grid_desc& d = g->desc;
  for (int64_t k = 0; k < d.nz; ++k) {
    for (int64_t j = 0; j < d.ny; ++j) {
      const uint8_t* row = g->flags + index_of(g, 0, j, k);
      for (int64_t i = next_flagged(row, 0, d.nx, kFlagCube); i < d.nx;
           i = next_flagged(row, i, d.nx, kFlagCube)) {
        const int64_t i0 = i;
        while (i < d.nx && (row[i] & kFlagCube) != 0) ++i;
        inflate_run(g, n_rows, i0, i - 1, j, k);
      }
    }
  }
  return TDO_OK;
}

// Steps from the 3x3 free squares of the three planes around a voxel (dz = -1, 0, 1), bit
// (dy+1)*3 + (dx+1) of a square set when voxel (dx, dy) of that plane is free. A step
// (dx, dy, dz) sweeps the xy square {0, dx} x {0, dy} in plane 0 and, for dz != 0, in plane dz
// too (docs/design.md s.0), so square[p] = the xy steps whose square lies free in plane p.
struct StepSquares {
  uint16_t square[512];
  constexpr StepSquares() : square() {
    for (uint32_t p = 0; p < 512u; ++p) {
      uint32_t u = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          bool ok = true;
          for (int b = 0; b <= (dy != 0 ? 1 : 0); ++b)
            for (int a = 0; a <= (dx != 0 ? 1 : 0); ++a)
              if (((p >> ((b * dy + 1) * 3 + (a * dx + 1))) & 1u) == 0) ok = false;
          if (ok) u |= 1u << ((dy + 1) * 3 + (dx + 1));
        }
      square[p] = static_cast<uint16_t>(u);
    }
  }
};
constexpr StepSquares kStepSquares{};

// Free bits (dy+1)*3 of the voxels (x, -1), (x, 0), (x, +1) of one plane, x the voxel at `c`.
uint32_t free_column(const uint8_t* c, int64_t sy) {
  const uint32_t lo = static_cast<uint32_t>(c[-sy]), mid = static_cast<uint32_t>(c[0]),
                 hi = static_cast<uint32_t>(c[sy]), b = kFlagBlocked;  // b = 4: bit 2
  return (((lo & b) ^ b) >> 2) | (((mid & b) ^ b) << 1) | (((hi & b) ^ b) << 4);
}

// Free bits of the 3x3 square of one plane around the voxel at `c` (not on the grid's border).
uint32_t free_square(const uint8_t* c, int64_t sy) {
  return free_column(c - 1, sy) | (free_column(c, sy) << 1) | (free_column(c + 1, sy) << 2);
}

// The free squares of the planes dz = -1, 0, +1 around a voxel off the grid's border, slid along
// x: the square of x + 1 is the square of x shifted by one column plus the column at x + 2.
struct Squares {
  uint32_t p[3];
  void load(const tdo_grid* g, const uint8_t* c) {
    for (int dz = -1; dz <= 1; ++dz) p[dz + 1] = free_square(c + dz * g->stride_z, g->stride_y);
  }
  void slide(const tdo_grid* g, const uint8_t* c) {  // c: the new voxel
    constexpr uint32_t kKeep = 0x1B6u;  // columns dx = 0, +1 of each row, moved to -1, 0
    for (int dz = -1; dz <= 1; ++dz)
      p[dz + 1] =
          ((p[dz + 1] & kKeep) >> 1) | (free_column(c + 1 + dz * g->stride_z, g->stride_y) << 2);
  }
  // moves_of from the squares: three table reads instead of 26 mask tests. Direction d of cell
  // (dz+1)*9 + (dy+1)*3 + (dx+1) is that cell with the centre skipped (directions.h): dz = -1
  // gives bits 0..8, dz = 0 bits 9..16, dz = +1 bits 17..25.
  uint32_t moves() const {
    const uint32_t u0 = kStepSquares.square[p[1]];
    const uint32_t um = kStepSquares.square[p[0]];
    const uint32_t up = kStepSquares.square[p[2]];
    return (u0 & um) | ((u0 & 0xFu) << 9) | ((u0 >> 5) << 13) | ((u0 & up) << 17);
  }
};

// Legal steps of voxel (i, j, k) from its 3x3x3 block (any voxel of the grid; cells outside it
// count as blocked): the free squares of its planes, gathered within the grid's bounds only.
uint32_t moves_of(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  const int64_t v = index_of(g, i, j, k);
  if ((g->flags[v] & kFlagBlocked) != 0) return 0;
  const tdo_grid_desc& d = g->desc;
  const int x0 = i > 0 ? -1 : 0, x1 = i < d.nx - 1 ? 1 : 0;
  const int y0 = j > 0 ? -1 : 0, y1 = j < d.ny - 1 ? 1 : 0;
  const int z0 = k > 0 ? -1 : 0, z1 = k < d.nz - 1 ? 1 : 0;
  Squares sq{{0u, 0u, 0u}};
  for (int dz = z0; dz <= z1; ++dz)
    for (int dy = y0; dy <= y1; ++dy) {
      const uint8_t* row = g->flags + v + dy * g->stride_y + dz * g->stride_z;
      for (int dx = x0; dx <= x1; ++dx)
        if ((row[dx] & kFlagBlocked) == 0) sq.p[dz + 1] |= 1u << ((dy + 1) * 3 + (dx + 1));
    }
  return sq.moves();
}

// Blocked bits of the 8 voxels x .. x+7 of the 3x3 rows around row (j, k), ORed (one byte each).
uint64_t blocked_9rows(const tdo_grid* g, const uint8_t* row, int64_t x) {
  constexpr uint64_t kBlockedBytes = 0x0404040404040404ull;  // kFlagBlocked in every byte
  uint64_t any = 0;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      uint64_t w;
      memcpy(&w, row + x + dy * g->stride_y + dz * g->stride_z, sizeof w);
      any |= w;
    }
  }
  return any & kBlockedBytes;
}

// Moves of voxels [a, b) of row `row` (a >= 1, b <= nx - 1, so off the border in x).
void span_moves(const tdo_grid* g, const uint8_t* row, uint32_t* moves, int64_t a, int64_t b) {
  Squares sq;
  sq.load(g, row + a);
  for (int64_t i = a; i < b; ++i) {
    if (i > a) sq.slide(g, row + i);
    moves[i] = sq.moves();  // 0 for a blocked voxel: every square needs the centre free
  }
}

// Moves of one row (j, k) with 0 < j < ny - 1 and 0 < k < nz - 1: 8 voxels at a time whose
// 3x3x3 blocks hold no blocked voxel get every step, the others span_moves; the row's two end
// voxels go through moves_of.
void row_moves(tdo_grid* g, int64_t j, int64_t k) {
  constexpr uint32_t kAllMoves = (1u << kNumDirs) - 1u;
  const int64_t nx = g->desc.nx, v0 = index_of(g, 0, j, k);
  const uint8_t* row = g->flags + v0;
  uint32_t* moves = g->moves + v0;
  if (nx < 3) {
    for (int64_t i = 0; i < nx; ++i) moves[i] = moves_of(g, i, j, k);
    return;
  }
  moves[0] = moves_of(g, 0, j, k);
  moves[nx - 1] = moves_of(g, nx - 1, j, k);
  int64_t i = 1;
  for (; i + 8 < nx; i += 8) {  // voxels i .. i+7 and their neighbours i-1 .. i+8
    if ((blocked_9rows(g, row, i - 1) | blocked_9rows(g, row, i) | blocked_9rows(g, row, i + 1)) ==
        0) {
      for (int64_t t = 0; t < 8; ++t) moves[i + t] = kAllMoves;
    } else {
      span_moves(g, row, moves, i, i + 8);
    }
  }
  if (i < nx - 1) span_moves(g, row, moves, i, nx - 1);
}

void compute_moves(tdo_grid* g) {
  const tdo_grid_desc& desc = g->desc;
  for (int64_t k = 0; k < desc.nz; ++k) {
    for (int64_t j = 0; j < desc.ny; ++j) {
      if (j > 0 && k > 0 && j < desc.ny - 1 && k < desc.nz - 1) {
        row_moves(g, j, k);
        continue;
      }
      for (int64_t i = 0; i < desc.nx; ++i) g->moves[index_of(g, i, j, k)] = moves_of(g, i, j, k);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Distance field: exact squared Euclidean distance transform (Felzenszwalb-Huttenlocher), one
// axis at a time, in integer voxel units with exact int64 comparisons (no rounding decides which
// parabola wins). Squared distances live in the df array as uint32 until the final conversion.

inline uint32_t df_load(const float* df, int64_t v) {
  uint32_t u;
  memcpy(&u, df + v, sizeof u);
  return u;
}

inline void df_store(float* df, int64_t v, uint32_t u) { memcpy(df + v, &u, sizeof u); }

// F(x) = f(x) + x^2 of the parabola rooted at site x (voxel^2).
inline int64_t parabola_key(const uint32_t* f, int32_t x) {
  return static_cast<int64_t>(f[x]) + static_cast<int64_t>(x) * x;
}

// 1D lower envelope of the parabolas over f[0..n) (kDfInfinite = no site): its sites into v[0..m)
// and their values, in place, into f[0..m) (f[j] = f[v[j]]; v[j] >= j, so each value is read
// before an entry over it is written); returns m, 0 without a site. Keys F <= 3 * 32767^2 and
// denominators <= 2 * 32767, so the cross products stay below 2^48. Bounded: every site is pushed
// and popped at most once. The keys of the two topmost sites are kept, not recomputed.
int32_t edt_envelope(uint32_t* f, int32_t* v, int32_t n) {
  int32_t k = -1;
  int64_t fa = 0, fb = 0;  // keys of v[k - 1] and v[k]
  for (int32_t q = 0; q < n; ++q) {
    if (f[q] == kDfInfinite) continue;
    const int64_t fq = parabola_key(f, q);
    // Pop the last site while the new parabola hides its part of the envelope:
    // s(v[k], q) <= s(v[k-1], v[k]) with s(a, b) = (F(b) - F(a)) / (2 (b - a)).
    while (k >= 1) {
      const int32_t a = v[k - 1], b = v[k];
      const int64_t n1 = fq - fb, d1 = 2 * static_cast<int64_t>(q - b);
      const int64_t n2 = fb - fa, d2 = 2 * static_cast<int64_t>(b - a);
      if (n1 * d2 > n2 * d1) break;
      --k;
      fb = fa;
      if (k >= 1) fa = parabola_key(f, v[k - 1]);
    }
    fa = fb;
    fb = fq;
    v[++k] = q;
  }
  for (int32_t j = 0; j <= k; ++j) f[j] = f[v[j]];
  return k + 1;
}

// F of envelope site j (compacted values fs, sites v).
inline int64_t site_key(const uint32_t* fs, const int32_t* v, int32_t j) {
  return static_cast<int64_t>(fs[j]) + static_cast<int64_t>(v[j]) * v[j];
}

// The envelope of m >= 1 sites evaluated at q = 0 .. n-1, put(q, squared distance) in increasing q
// (the results stay below 2^32). Parabola j is the lowest from q on until its crossing with
// parabola j + 1, s(v[j], v[j+1]) = num / den: the sweep moves on once q > num / den, tested as
// q * den > num (no division). The sweep advances monotonically.
template <class Put>
void edt_eval(const uint32_t* fs, const int32_t* v, int32_t m, int32_t n, Put&& put) {
  const int32_t k = m - 1;
  int32_t j = 0;
  int64_t fj = site_key(fs, v, 0);
  int64_t fj1 = k >= 1 ? site_key(fs, v, 1) : 0;
  int64_t num = fj1 - fj, den = k >= 1 ? 2 * static_cast<int64_t>(v[1] - v[0]) : 1;
  for (int32_t q = 0; q < n; ++q) {
    while (j<k&& static_cast<int64_t>(q) * den> num) {
      ++j;
      fj = fj1;
      if (j < k) {
        fj1 = site_key(fs, v, j + 1);
        num = fj1 - fj;
        den = 2 * static_cast<int64_t>(v[j + 1] - v[j]);
      }
    }
    const int64_t dq = q - v[j];
    put(q, static_cast<uint32_t>(dq * dq + fs[j]));
  }
}

// The first pass of the EDT, along z: per voxel the squared distance to the nearest occupied voxel
// of its z line (kDfInfinite: none; the same values as the envelope of that line), by one sweep up
// and one down over whole planes, so every access is contiguous. Linear distances (< nz <=
// kDfMaxAxis) until a plane is no longer read, then squared.
void edt_pass_z(tdo_grid* g) {
  const int64_t plane = g->stride_z, nz = g->desc.nz;
  // Only uint32 accesses in this pass (the field is read as float after the last pass); the
  // loops are branch-free so that they vectorise.
  uint32_t* df = reinterpret_cast<uint32_t*>(g->df);
  for (int64_t p = 0; p < plane; ++p) df[p] = (g->flags[p] & kFlagOccupied) != 0 ? 0u : kDfInfinite;
  for (int64_t k = 1; k < nz; ++k) {
    const uint8_t* f = g->flags + k * plane;
    uint32_t* row = df + k * plane;
    const uint32_t* below = row - plane;
    for (int64_t p = 0; p < plane; ++p) {
      const uint32_t b = below[p];
      const uint32_t up = b != kDfInfinite ? b + 1u : kDfInfinite;
      row[p] = (f[p] & kFlagOccupied) != 0 ? 0u : up;
    }
  }
  const auto square = [df, plane](int64_t k) {
    uint32_t* row = df + k * plane;
    for (int64_t p = 0; p < plane; ++p) {
      const uint32_t v = row[p];
      row[p] = v != kDfInfinite ? v * v : kDfInfinite;
    }
  };
  for (int64_t k = nz - 2; k >= 0; --k) {
    uint32_t* row = df + k * plane;
    const uint32_t* above = row + plane;
    for (int64_t p = 0; p < plane; ++p) {
      const uint32_t a = above[p];
      const uint32_t down = a != kDfInfinite ? a + 1u : kDfInfinite;
      row[p] = down < row[p] ? down : row[p];
    }
    square(k + 1);
  }
  square(0);
}

// Metres from a squared distance in voxel^2, rounded down (see tdo_grid::df).
float df_metres(uint32_t d2, double res) {
  if (d2 == 0u) return 0.0f;
  if (d2 == kDfInfinite) return HUGE_VALF;
  // Round down: float conversion may round up, and one more ulp absorbs the double rounding.
  // One ulp towards zero of a positive float is its bit pattern minus one (as nextafterf).
  const double exact = sqrt(static_cast<double>(d2)) * res;
  float m = static_cast<float>(exact);
  uint32_t bits;
  memcpy(&bits, &m, sizeof bits);
  if (bits != 0u) --bits;
  memcpy(&m, &bits, sizeof m);
  if (static_cast<double>(m) > exact && bits != 0u) {
    --bits;
    memcpy(&m, &bits, sizeof m);
  }
  return m;
}

// One EDT pass over the line of n entries of df from `base` with step `stride` (voxels), in place.
// The lines of a pass are visited in memory order (a y line after the y line of the next x, a z
// line after that of the next (x, y)), so consecutive lines share their cache lines. `last`: the
// final pass, which writes metres (df_metres) instead of squared distances.
void edt_strided(tdo_grid* g, int64_t base, int64_t stride, int32_t n, bool last) {
  uint32_t* f = g->df_f;
  float* line = g->df + base;
  for (int32_t q = 0; q < n; ++q) f[q] = df_load(line, q * stride);
  const int32_t m = edt_envelope(f, g->df_v, n);
  const double res = g->desc.res;
  if (m == 0) {  // no site: every entry is kDfInfinite already
    if (last)
      for (int32_t q = 0; q < n; ++q) line[q * stride] = HUGE_VALF;
    return;
  }
  if (last)
    edt_eval(f, g->df_v, m, n, [line, stride, res](int32_t q, uint32_t d2) {
      line[q * stride] = df_metres(d2, res);
    });
  else
    edt_eval(f, g->df_v, m, n,
             [line, stride](int32_t q, uint32_t d2) { df_store(line, q * stride, d2); });
}

// df of every voxel; see tdo_grid::df. Three passes: z (plane sweeps), y (strided lines within a
// plane, consecutive lines sharing cache lines) and x (contiguous lines, written in metres). The
// squared distance is separable, so the pass order gives the same integers as any other. Needs
// no scratch beyond the two line buffers, so it can run after compute_moves (df_ensure).
void build_distance_field(tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  if (!g->df_valid) {  // 0 everywhere: a valid lower bound, collision queries stay exact
    for (uint32_t v = 0; v < g->nvox; ++v) g->df[v] = 0.0f;
    return;
  }
  edt_pass_z(g);
  const int64_t plane = g->stride_z;
  if (d.ny > 1)
    for (int64_t k = 0; k < d.nz; ++k)
      for (int64_t x = 0; x < d.nx; ++x) edt_strided(g, k * plane + x, d.nx, d.ny, false);
  for (int64_t r = 0; r < static_cast<int64_t>(d.ny) * d.nz; ++r)
    edt_strided(g, r * d.nx, 1, d.nx, true);
}

// Whether every axis fits the exact transform (kDfMaxAxis and the line buffers).
int df_fits(const tdo_grid* g) {
  const uint32_t line_cap = df_line_capacity(g->cap);
  const int32_t n_axis[3] = {g->desc.nx, g->desc.ny, g->desc.nz};
  for (int a = 0; a < 3; ++a)
    if (static_cast<uint32_t>(n_axis[a]) > line_cap) return 0;
  return 1;
}

// ---------------------------------------------------------------------------------------------
// Bucket index of the boxes (see tdo_grid::cell_start).

inline int32_t ceil_div(int32_t a, int32_t b) { return (a + b - 1) / b; }

// Cell range [lo, hi] along one axis touched by the closed interval [a, b]; false when none.
bool cell_range(double o, double e, int32_t nc, double a, double b, int32_t* lo, int32_t* hi) {
  const double fa = floor((a - o) / e), fb = floor((b - o) / e);
  if (fb < 0.0 || fa > static_cast<double>(nc - 1)) return false;
  *lo = fa < 0.0 ? 0 : static_cast<int32_t>(fa);
  *hi = fb > static_cast<double>(nc - 1) ? nc - 1 : static_cast<int32_t>(fb);
  return true;
}

// Cells touched by box b grown by `grow` (m); false when it misses the grid's cells entirely.
bool box_cells(const tdo_grid* g, const tdo_box& b, double grow, int32_t lo[3], int32_t hi[3]) {
  const tdo_grid_desc& d = g->desc;
  const double e = g->cell_edge;
  return cell_range(d.origin.x, e, g->ncx, b.min.x - grow, b.max.x + grow, &lo[0], &hi[0]) &&
         cell_range(d.origin.y, e, g->ncy, b.min.y - grow, b.max.y + grow, &lo[1], &hi[1]) &&
         cell_range(d.origin.z, e, g->ncz, b.min.z - grow, b.max.z + grow, &lo[2], &hi[2]);
}

tdo_status build_buckets(tdo_grid* g, double clearance) {
  const tdo_grid_desc& d = g->desc;
  const uint32_t cell_cap = bucket_cell_capacity(g->cap.max_voxels);
  // Grow the cell edge until the cells fit: bounded, 2^30 voxels cover any int32 axis.
  int32_t e = kCellVoxels;
  for (int step = 0; step < 30; ++step) {
    const uint64_t cells = static_cast<uint64_t>(ceil_div(d.nx, e)) * ceil_div(d.ny, e) *
                           static_cast<uint64_t>(ceil_div(d.nz, e));
    if (cells <= cell_cap) break;
    e = e <= (1 << 29) ? 2 * e : e;
  }
  g->cell_vox = e;
  g->cell_edge = static_cast<double>(e) * d.res;
  g->ncx = ceil_div(d.nx, e);
  g->ncy = ceil_div(d.ny, e);
  g->ncz = ceil_div(d.nz, e);
  const uint32_t n_cells = static_cast<uint32_t>(g->ncx) * g->ncy * g->ncz;
  if (n_cells > cell_cap) return TDO_ERR_MAP_CAPACITY;  // not reachable for int32 axes
  g->bucket_reach = fmax(clearance, kReachVoxels * d.res);
  // The slack keeps a box listed in every cell that a rounded query point may fall into.
  const double grow = g->bucket_reach + 1e-6 * g->cell_edge;
  const uint32_t ref_cap = box_ref_capacity(g->cap);
  for (uint32_t c = 0; c <= n_cells; ++c) g->cell_start[c] = 0;
  // Pass 1: count the entries of every cell (shifted by one for the prefix sum).
  uint64_t total = 0;
  uint32_t n_large = 0;
  for (uint32_t b = 0; b < g->n_boxes; ++b) {
    int32_t lo[3], hi[3];
    if (!box_cells(g, g->boxes[b], grow, lo, hi)) continue;
    const uint64_t touched = static_cast<uint64_t>(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) *
                             static_cast<uint64_t>(hi[2] - lo[2] + 1);
    if (touched > kLargeBoxCells) {
      g->large_boxes[n_large++] = b;
      continue;
    }
    total += touched;
    if (total > ref_cap) return TDO_ERR_BOX_CAPACITY;
    for (int32_t z = lo[2]; z <= hi[2]; ++z)
      for (int32_t y = lo[1]; y <= hi[1]; ++y)
        for (int32_t x = lo[0]; x <= hi[0]; ++x)
          ++g->cell_start[1u + static_cast<uint32_t>(x + g->ncx * (y + g->ncy * z))];
  }
  for (uint32_t c = 0; c < n_cells; ++c) g->cell_start[c + 1] += g->cell_start[c];
  // Pass 2: fill, boxes in index order within each cell; cell_start[c] runs ahead as the cursor
  // and is shifted back afterwards.
  for (uint32_t b = 0; b < g->n_boxes; ++b) {
    int32_t lo[3], hi[3];
    if (!box_cells(g, g->boxes[b], grow, lo, hi)) continue;
    const uint64_t touched = static_cast<uint64_t>(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) *
                             static_cast<uint64_t>(hi[2] - lo[2] + 1);
    if (touched > kLargeBoxCells) continue;
    for (int32_t z = lo[2]; z <= hi[2]; ++z)
      for (int32_t y = lo[1]; y <= hi[1]; ++y)
        for (int32_t x = lo[0]; x <= hi[0]; ++x)
          g->box_refs[g->cell_start[static_cast<uint32_t>(x + g->ncx * (y + g->ncy * z))]++] = b;
  }
  for (uint32_t c = n_cells; c > 0; --c) g->cell_start[c] = g->cell_start[c - 1];
  g->cell_start[0] = 0;
  g->n_refs = static_cast<uint32_t>(total);
  g->n_large = n_large;
  return TDO_OK;
}

// kFlagSurface on every cube that is not buried (see is_buried).
void mark_surface(tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  for (int64_t k = 0; k < d.nz; ++k)
    for (int64_t j = 0; j < d.ny; ++j) {
      uint8_t* row = g->flags + index_of(g, 0, j, k);
      for (int64_t i = next_flagged(row, 0, d.nx, kFlagCube); i < d.nx;
           i = next_flagged(row, i + 1, d.nx, kFlagCube))
        if (!is_buried(g, i, j, k)) row[i] |= kFlagSurface;
    }
}

constexpr uint64_t kEveryByte = 0x0101010101010101ull;  // one in every byte of a word

// Blocked = occupied on every voxel, other bits but occupied and cube cleared: 8 voxels per
// 64-bit word, the rest one at a time.
void reset_blocked(tdo_grid* g) {
  constexpr uint64_t kKeep = kEveryByte * (kFlagOccupied | kFlagCube);
  constexpr uint64_t kOcc = kEveryByte * kFlagOccupied;
  static_assert(kFlagBlocked == kFlagOccupied << 2, "blocked is occupied shifted by two");
  const uint32_t n = g->nvox, words = n / 8u;
  for (uint32_t w = 0; w < words; ++w) {
    uint64_t x;
    memcpy(&x, g->flags + 8u * w, sizeof x);
    x = (x & kKeep) | ((x & kOcc) << 2);
    memcpy(g->flags + 8u * w, &x, sizeof x);
  }
  for (uint32_t v = 8u * words; v < n; ++v)
    g->flags[v] = static_cast<uint8_t>((g->flags[v] & (kFlagOccupied | kFlagCube)) |
                                       ((g->flags[v] & kFlagOccupied) != 0 ? kFlagBlocked : 0));
}

// Blocked voxels: the blocked bits of 8 voxels per word, counted with one popcount.
uint32_t count_blocked(const tdo_grid* g) {
  constexpr uint64_t kBlocked = kEveryByte * kFlagBlocked;
  const uint32_t n = g->nvox, words = n / 8u;
  uint32_t blocked = 0;
  for (uint32_t w = 0; w < words; ++w) {
    uint64_t x;
    memcpy(&x, g->flags + 8u * w, sizeof x);
    blocked += static_cast<uint32_t>(__builtin_popcountll(x & kBlocked));
  }
  for (uint32_t v = 8u * words; v < n; ++v) blocked += (g->flags[v] & kFlagBlocked) != 0 ? 1u : 0u;
  return blocked;
}

}  // namespace

uint32_t box_ref_capacity(const GridCapacity& cap) {
  if (cap.max_box_refs > 0) return cap.max_box_refs;
  const uint64_t n = static_cast<uint64_t>(cap.max_boxes) * kRefsPerBoxDefault;
  return static_cast<uint32_t>(n < 0xFFFFFFF0u ? n : 0xFFFFFFF0u);
}

size_t grid_footprint(const GridCapacity& cap) {
  const size_t line = df_line_capacity(cap);
  return tdo_arena_round(sizeof(tdo_grid)) + tdo_arena_round(static_cast<size_t>(cap.max_voxels)) +
         tdo_arena_round(static_cast<size_t>(cap.max_voxels) * sizeof(uint32_t)) +
         tdo_arena_round(static_cast<size_t>(cap.max_boxes) * sizeof(tdo_box) + 1u) +
         tdo_arena_round(static_cast<size_t>(cap.max_clear_cells) * 3u * sizeof(int32_t) + 1u) +
         // distance field and its EDT line scratch (none for boxes only)
         tdo_arena_round(static_cast<size_t>(df_capacity(cap)) * sizeof(float)) +
         tdo_arena_round(line * sizeof(uint32_t)) + tdo_arena_round(line * sizeof(int32_t)) +
         // bucket index: cell offsets, box references, large boxes
         tdo_arena_round((static_cast<size_t>(bucket_cell_capacity(cap.max_voxels)) + 1u) *
                         sizeof(uint32_t)) +
         tdo_arena_round(static_cast<size_t>(box_ref_capacity(cap)) * sizeof(uint32_t) + 1u) +
         tdo_arena_round(static_cast<size_t>(cap.max_boxes) * sizeof(uint32_t) + 1u) +
         surface_index_footprint(cap);
}

tdo_status grid_init(tdo_grid** out, tdo_arena* arena, const GridCapacity& cap) {
  if (out == nullptr || arena == nullptr || cap.max_voxels == 0) return TDO_ERR_INVALID_ARGUMENT;
  tdo_grid* g = static_cast<tdo_grid*>(tdo_arena_alloc(arena, sizeof(tdo_grid)));
  if (g == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  memset(static_cast<void*>(g), 0, sizeof(*g));  // all-zero is a valid tdo_grid
  g->cap = cap;
  g->flags = static_cast<uint8_t*>(tdo_arena_alloc(arena, cap.max_voxels));
  g->moves = static_cast<uint32_t*>(tdo_arena_alloc(arena, cap.max_voxels * sizeof(uint32_t)));
  g->boxes = static_cast<tdo_box*>(tdo_arena_alloc(arena, cap.max_boxes * sizeof(tdo_box) + 1u));
  g->stencil = static_cast<int32_t*>(
      tdo_arena_alloc(arena, cap.max_clear_cells * 3u * sizeof(int32_t) + 1u));
  if (g->flags == nullptr || g->moves == nullptr || g->boxes == nullptr || g->stencil == nullptr)
    return TDO_ERR_ARENA_TOO_SMALL;
  const size_t line = df_line_capacity(cap);
  if (cap.boxes_only == 0u) {
    g->df = static_cast<float*>(tdo_arena_alloc(arena, df_capacity(cap) * sizeof(float)));
    g->df_f = static_cast<uint32_t*>(tdo_arena_alloc(arena, line * sizeof(uint32_t)));
    g->df_v = static_cast<int32_t*>(tdo_arena_alloc(arena, line * sizeof(int32_t)));
    if (g->df == nullptr || g->df_f == nullptr || g->df_v == nullptr)
      return TDO_ERR_ARENA_TOO_SMALL;
  }
  g->cell_start = static_cast<uint32_t*>(tdo_arena_alloc(
      arena, (static_cast<size_t>(bucket_cell_capacity(cap.max_voxels)) + 1u) * sizeof(uint32_t)));
  g->box_refs = static_cast<uint32_t*>(
      tdo_arena_alloc(arena, static_cast<size_t>(box_ref_capacity(cap)) * sizeof(uint32_t) + 1u));
  g->large_boxes = static_cast<uint32_t*>(
      tdo_arena_alloc(arena, static_cast<size_t>(cap.max_boxes) * sizeof(uint32_t) + 1u));
  if (g->cell_start == nullptr || g->box_refs == nullptr || g->large_boxes == nullptr)
    return TDO_ERR_ARENA_TOO_SMALL;
  if (cap.boxes_only == 0u) {
    const size_t nb = brick_capacity(cap);
    g->brick_mask = static_cast<uint64_t*>(tdo_arena_alloc(arena, nb * sizeof(uint64_t) + 1u));
    g->brick_box = static_cast<uint16_t*>(tdo_arena_alloc(arena, nb * sizeof(uint16_t) + 1u));
    if (g->brick_mask == nullptr || g->brick_box == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  }
  g->clearance = -1.0;
  *out = g;
  return TDO_OK;
}

void df_ensure(const tdo_grid* cg) {
  if (cg == nullptr || cg->df == nullptr || cg->df_built || cg->nvox == 0) return;
  // The grid is never defined const (it is carved from the caller's arena): the field is a cache
  // of the const queries, filled once per finish.
  tdo_grid* g = const_cast<tdo_grid*>(cg);
  build_distance_field(g);
  g->df_built = 1;
}

void moves_ensure(const tdo_grid* cg) {
  if (cg == nullptr || cg->moves_built || !cg->ready || cg->nvox == 0) return;
  // As df_ensure: the legal steps are a cache of the finished grid, filled once per finish.
  tdo_grid* g = const_cast<tdo_grid*>(cg);
  compute_moves(g);
  g->moves_built = 1;
}

}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" tdo_status tdo_grid_reset(tdo_grid* g, const tdo_grid_desc* desc) {
  if (g == nullptr || desc == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (desc->nx <= 0 || desc->ny <= 0 || desc->nz <= 0 || !isfinite(desc->res) ||
      !(desc->res > 0.0) || !finite3(desc->origin))
    return TDO_ERR_INVALID_ARGUMENT;
  const uint64_t n = static_cast<uint64_t>(desc->nx) * static_cast<uint64_t>(desc->ny) *
                     static_cast<uint64_t>(desc->nz);
  if (n > g->cap.max_voxels) return TDO_ERR_MAP_CAPACITY;
  const uint32_t axis = g->cap.max_axis;
  if (axis > 0u &&
      (static_cast<uint32_t>(desc->nx) > axis || static_cast<uint32_t>(desc->ny) > axis ||
       static_cast<uint32_t>(desc->nz) > axis))
    return TDO_ERR_MAP_CAPACITY;
  g->desc = *desc;
  g->nvox = static_cast<uint32_t>(n);
  g->stride_y = desc->nx;
  g->stride_z = static_cast<int64_t>(desc->nx) * desc->ny;
  memset(g->flags, 0, g->nvox);  // n <= max_voxels: fits size_t on 32-bit targets
  g->n_boxes = 0;
  g->n_cubes = 0;
  g->n_blocked = 0;
  g->clearance = -1.0;
  g->ready = 0;
  g->df_built = 0;
  g->moves_built = 0;
  return TDO_OK;
}

extern "C" tdo_status tdo_grid_add_box(tdo_grid* g, const tdo_box* box) {
  if (g == nullptr || box == nullptr || g->nvox == 0) return TDO_ERR_INVALID_ARGUMENT;
  if (!finite3(box->min) || !finite3(box->max) || !(box->max.x > box->min.x) ||
      !(box->max.y > box->min.y) || !(box->max.z > box->min.z))
    return TDO_ERR_INVALID_BOX;
  if (g->n_boxes >= g->cap.max_boxes) return TDO_ERR_BOX_CAPACITY;
  g->boxes[g->n_boxes++] = *box;
  const tdo_grid_desc& d = g->desc;
  int64_t i0, i1, j0, j1, k0, k1;
  interior_range(d.origin.x, d.res, d.nx, box->min.x, box->max.x, &i0, &i1);
  interior_range(d.origin.y, d.res, d.ny, box->min.y, box->max.y, &j0, &j1);
  interior_range(d.origin.z, d.res, d.nz, box->min.z, box->max.z, &k0, &k1);
  for (int64_t k = k0; k <= k1; ++k)
    for (int64_t j = j0; j <= j1; ++j)
      for (int64_t i = i0; i <= i1; ++i) g->flags[index_of(g, i, j, k)] |= kFlagOccupied;
  g->ready = 0;
  return TDO_OK;
}

extern "C" tdo_status tdo_grid_add_voxel(tdo_grid* g, int32_t i, int32_t j, int32_t k) {
  if (g == nullptr || g->nvox == 0 || !in_grid(g, i, j, k)) return TDO_ERR_INVALID_ARGUMENT;
  if (g->cap.boxes_only != 0u) return TDO_ERR_MAP_CAPACITY;  // no distance field for voxels
  uint8_t& f = g->flags[index_of(g, i, j, k)];
  if ((f & kFlagCube) == 0) ++g->n_cubes;
  f |= kFlagOccupied | kFlagCube;
  g->ready = 0;
  return TDO_OK;
}

extern "C" tdo_status tdo_grid_finish(tdo_grid* g, double clearance) {
  if (g == nullptr || g->nvox == 0 || !isfinite(clearance) || clearance < 0.0)
    return TDO_ERR_INVALID_ARGUMENT;
  g->ready = 0;
  reset_blocked(g);
  if (clearance > 0.0) {
    for (uint32_t b = 0; b < g->n_boxes; ++b) inflate_box(g, g->boxes[b], clearance);
    if (g->n_cubes > 0) {
      const tdo_status st = inflate_cubes(g, clearance);
      if (st != TDO_OK) return st;
    }
  }
  g->n_blocked = count_blocked(g);
  // Collision-query structures (collision.h): they change no blocked flag and no move. The
  // distance field and the legal steps are built on first use (df_ensure, moves_ensure;
  // tdo_grid_prepare; docs/design.md s.0).
  if (g->n_cubes > 0) mark_surface(g);
  surface_index_build(g);
  g->df_built = 0;
  g->df_valid = g->cap.boxes_only == 0u ? df_fits(g) : 0;
  g->df_cap = 0.0;  // the field is exact again (grid_update.cpp caps it)
  g->moves_built = 0;
  const tdo_status bst = build_buckets(g, clearance);
  if (bst != TDO_OK) return bst;
  g->clearance = clearance;
  g->ready = 1;
  ++g->version;
  return TDO_OK;
}

extern "C" tdo_status tdo_grid_prepare(tdo_grid* g) {
  if (g == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!g->ready) return TDO_ERR_MAP_NOT_READY;
  moves_ensure(g);
  df_ensure(g);
  return TDO_OK;
}

extern "C" tdo_grid_desc tdo_grid_get_desc(const tdo_grid* g) {
  return g != nullptr ? g->desc : tdo_grid_desc{};
}

extern "C" double tdo_grid_clearance(const tdo_grid* g) {
  return g != nullptr && g->ready ? g->clearance : -1.0;
}

extern "C" int tdo_grid_world_to_voxel(const tdo_grid* g, tdo_vec3 p, tdo_voxel* out) {
  if (g == nullptr || g->nvox == 0 || !finite3(p)) return 0;
  const tdo_grid_desc& d = g->desc;
  const double fi = span_index(p.x, d.origin.x, d.res);
  const double fj = span_index(p.y, d.origin.y, d.res);
  const double fk = span_index(p.z, d.origin.z, d.res);
  if (fi < 0.0 || fj < 0.0 || fk < 0.0 || fi >= static_cast<double>(d.nx) ||
      fj >= static_cast<double>(d.ny) || fk >= static_cast<double>(d.nz))
    return 0;
  if (out != nullptr) {
    out->i = static_cast<int32_t>(fi);
    out->j = static_cast<int32_t>(fj);
    out->k = static_cast<int32_t>(fk);
  }
  return 1;
}

extern "C" tdo_vec3 tdo_grid_voxel_center(const tdo_grid* g, tdo_voxel v) {
  if (g == nullptr) return tdo_vec3{0.0, 0.0, 0.0};
  const tdo_grid_desc& d = g->desc;
  return tdo_vec3{d.origin.x + (static_cast<double>(v.i) + 0.5) * d.res,
                  d.origin.y + (static_cast<double>(v.j) + 0.5) * d.res,
                  d.origin.z + (static_cast<double>(v.k) + 0.5) * d.res};
}

extern "C" int tdo_grid_is_blocked(const tdo_grid* g, tdo_voxel v) {
  if (g == nullptr || g->nvox == 0 || !in_grid(g, v.i, v.j, v.k)) return 1;
  return (g->flags[index_of(g, v.i, v.j, v.k)] & kFlagBlocked) != 0 ? 1 : 0;
}

extern "C" int tdo_grid_is_occupied(const tdo_grid* g, tdo_voxel v) {
  if (g == nullptr || g->nvox == 0 || !in_grid(g, v.i, v.j, v.k)) return 0;
  return (g->flags[index_of(g, v.i, v.j, v.k)] & kFlagOccupied) != 0 ? 1 : 0;
}

extern "C" uint32_t tdo_grid_blocked_count(const tdo_grid* g) {
  return g != nullptr ? g->n_blocked : 0u;
}
