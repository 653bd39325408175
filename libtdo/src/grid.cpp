#include <math.h>
#include <string.h>

#include "directions.h"
#include "grid_internal.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

int64_t index_of(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return i + j * g->stride_y + k * g->stride_z;
}

bool in_grid(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return i >= 0 && j >= 0 && k >= 0 && i < g->desc.nx && j < g->desc.ny && k < g->desc.nz;
}

// Clamp a (finite) voxel coordinate into [-1, n] before converting it to an integer.
int64_t clamp_index(double v, int32_t n) {
  if (v < -1.0) return -1;
  if (v > static_cast<double>(n)) return n;
  return static_cast<int64_t>(v);
}

// Voxel range [lo, hi] along one axis whose cells intersect the open interval (a, b).
void interior_range(double o, double r, int32_t n, double a, double b, int64_t* lo, int64_t* hi) {
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
void centre_range(double o, double r, int32_t n, double a, double b, double c, int64_t* lo,
                  int64_t* hi) {
  const int64_t f = clamp_index(ceil((a - c - o) / r - 0.5), n);
  const int64_t l = clamp_index(floor((b + c - o) / r - 0.5), n);
  *lo = f < 0 ? 0 : f;
  *hi = l > n - 1 ? n - 1 : l;
}

double axis_gap(double p, double a, double b) {
  if (p < a) return a - p;
  if (p > b) return p - b;
  return 0.0;
}

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

tdo_status inflate_cubes(tdo_grid* g, double c) {
  uint32_t n_cells = 0;
  const tdo_status st = build_stencil(g, c, &n_cells);
  if (st != TDO_OK) return st;
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
  return TDO_OK;
}

// Cells of the 3x3x3 block that a step in direction d sweeps: the 2x2 square or 2x2x2 cube.
uint32_t swept_cells(int d) {
  uint32_t m = 0;
  const int dx = dir_dx(d), dy = dir_dy(d), dz = dir_dz(d);
  for (int a = 0; a <= 1; ++a)
    for (int b = 0; b <= 1; ++b)
      for (int e = 0; e <= 1; ++e) m |= 1u << cell_of(a * dx, b * dy, e * dz);
  return m;
}

void compute_moves(tdo_grid* g) {
  uint32_t need[kNumDirs];
  for (int d = 0; d < kNumDirs; ++d) need[d] = swept_cells(d);
  const tdo_grid_desc& desc = g->desc;
  for (int64_t k = 0; k < desc.nz; ++k) {
    for (int64_t j = 0; j < desc.ny; ++j) {
      for (int64_t i = 0; i < desc.nx; ++i) {
        const int64_t v = index_of(g, i, j, k);
        if ((g->flags[v] & kFlagBlocked) != 0) {
          g->moves[v] = 0;
          continue;
        }
        uint32_t free27 = 0;
        for (int dz = -1; dz <= 1; ++dz) {
          for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              if (!in_grid(g, i + dx, j + dy, k + dz)) continue;
              const int64_t w = v + dx + dy * g->stride_y + dz * g->stride_z;
              if ((g->flags[w] & kFlagBlocked) == 0) free27 |= 1u << cell_of(dx, dy, dz);
            }
          }
        }
        uint32_t mask = 0;
        for (int d = 0; d < kNumDirs; ++d)
          if ((free27 & need[d]) == need[d]) mask |= 1u << d;
        g->moves[v] = mask;
      }
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

// 1D lower envelope of the parabolas over f[0..n) (kDfInfinite = no site), written to
// df[base + q * stride]. Keys F <= 3 * 32767^2 and denominators <= 2 * 32767, so the cross
// products stay below 2^48 and the results below 2^32. Bounded: every site is pushed and popped
// at most once, and the evaluation sweep advances monotonically.
void edt_line(const uint32_t* f, int32_t* v, int32_t n, float* df, int64_t base, int64_t stride) {
  int32_t k = -1;
  for (int32_t q = 0; q < n; ++q) {
    if (f[q] == kDfInfinite) continue;
    const int64_t fq = parabola_key(f, q);
    // Pop the last site while the new parabola hides its part of the envelope:
    // s(v[k], q) <= s(v[k-1], v[k]) with s(a, b) = (F(b) - F(a)) / (2 (b - a)).
    while (k >= 1) {
      const int32_t a = v[k - 1], b = v[k];
      const int64_t fb = parabola_key(f, b);
      const int64_t n1 = fq - fb, d1 = 2 * static_cast<int64_t>(q - b);
      const int64_t n2 = fb - parabola_key(f, a), d2 = 2 * static_cast<int64_t>(b - a);
      if (n1 * d2 > n2 * d1) break;
      --k;
    }
    v[++k] = q;
  }
  if (k < 0) {  // no site on this line
    for (int32_t q = 0; q < n; ++q) df_store(df, base + q * stride, kDfInfinite);
    return;
  }
  int32_t j = 0;
  for (int32_t q = 0; q < n; ++q) {
    // Advance while the next parabola is lower from q on: s(v[j], v[j+1]) < q.
    while (j < k) {
      const int64_t num = parabola_key(f, v[j + 1]) - parabola_key(f, v[j]);
      const int64_t den = 2 * static_cast<int64_t>(v[j + 1] - v[j]);
      if (!(num < static_cast<int64_t>(q) * den)) break;
      ++j;
    }
    const int64_t dq = q - v[j];
    df_store(df, base + q * stride, static_cast<uint32_t>(dq * dq + f[v[j]]));
  }
}

// df of every voxel; see tdo_grid::df. Three passes (x, y, z lines) then conversion to metres.
void build_distance_field(tdo_grid* g) {
  const tdo_grid_desc& d = g->desc;
  const int32_t n_axis[3] = {d.nx, d.ny, d.nz};
  const uint32_t line_cap = df_line_capacity(g->cap);
  g->df_valid = 1;
  for (int a = 0; a < 3; ++a)
    if (static_cast<uint32_t>(n_axis[a]) > line_cap) g->df_valid = 0;
  if (!g->df_valid) {  // 0 everywhere: a valid lower bound, collision queries stay exact
    for (uint32_t v = 0; v < g->nvox; ++v) g->df[v] = 0.0f;
    return;
  }
  const int64_t strides[3] = {1, g->stride_y, g->stride_z};
  for (int axis = 0; axis < 3; ++axis) {
    const int32_t n = n_axis[axis];
    const int64_t stride = strides[axis];
    // Lines along `axis`, one per (u, w) position on the two other axes.
    const int32_t nu = axis == 0 ? d.ny : d.nx;
    const int32_t nw = axis == 2 ? d.ny : d.nz;
    for (int64_t w = 0; w < nw; ++w) {
      for (int64_t u = 0; u < nu; ++u) {
        const int64_t base = axis == 0   ? index_of(g, 0, u, w)
                             : axis == 1 ? index_of(g, u, 0, w)
                                         : index_of(g, u, w, 0);
        for (int32_t q = 0; q < n; ++q) {
          const int64_t v = base + q * stride;
          g->df_f[q] = axis == 0 ? ((g->flags[v] & kFlagOccupied) != 0 ? 0u : kDfInfinite)
                                 : df_load(g->df, v);
        }
        edt_line(g->df_f, g->df_v, n, g->df, base, stride);
      }
    }
  }
  const double res = d.res;
  for (uint32_t v = 0; v < g->nvox; ++v) {
    const uint32_t d2 = df_load(g->df, v);
    float m = HUGE_VALF;
    if (d2 == 0u) {
      m = 0.0f;
    } else if (d2 != kDfInfinite) {
      // Round down: float conversion may round up, and one more ulp absorbs the double rounding.
      const double exact = sqrt(static_cast<double>(d2)) * res;
      m = static_cast<float>(exact);
      m = nextafterf(m, 0.0f);
      if (static_cast<double>(m) > exact) m = nextafterf(m, 0.0f);
    }
    g->df[v] = m;
  }
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
    for (int64_t j = 0; j < d.ny; ++j)
      for (int64_t i = 0; i < d.nx; ++i) {
        uint8_t& f = g->flags[index_of(g, i, j, k)];
        if ((f & kFlagCube) != 0 && !is_buried(g, i, j, k)) f |= kFlagSurface;
      }
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
         tdo_arena_round(static_cast<size_t>(cap.max_boxes) * sizeof(uint32_t) + 1u);
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
  g->clearance = -1.0;
  *out = g;
  return TDO_OK;
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
  for (uint32_t v = 0; v < g->nvox; ++v)
    g->flags[v] = static_cast<uint8_t>((g->flags[v] & (kFlagOccupied | kFlagCube)) |
                                       ((g->flags[v] & kFlagOccupied) != 0 ? kFlagBlocked : 0));
  if (clearance > 0.0) {
    for (uint32_t b = 0; b < g->n_boxes; ++b) inflate_box(g, g->boxes[b], clearance);
    if (g->n_cubes > 0) {
      const tdo_status st = inflate_cubes(g, clearance);
      if (st != TDO_OK) return st;
    }
  }
  uint32_t blocked = 0;
  for (uint32_t v = 0; v < g->nvox; ++v) blocked += (g->flags[v] & kFlagBlocked) != 0 ? 1u : 0u;
  g->n_blocked = blocked;
  compute_moves(g);
  // Collision-query structures (collision.h): they change no blocked flag and no move.
  if (g->n_cubes > 0) mark_surface(g);
  if (g->cap.boxes_only == 0u) build_distance_field(g);
  const tdo_status bst = build_buckets(g, clearance);
  if (bst != TDO_OK) return bst;
  g->clearance = clearance;
  g->ready = 1;
  ++g->version;
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
