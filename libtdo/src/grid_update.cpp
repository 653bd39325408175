// Incremental changes to a finished grid (grid_update.h, docs/design.md s.0 "Map updates").
//
// The blocked rule is tdo_grid_finish's: a voxel is blocked when it is occupied, or its centre
// lies strictly closer than the clearance to a box (the arithmetic of grid.cpp's inflate_box) or
// to a cube (the clearance stencil, grid.cpp's build_stencil, shared). Per change:
// - box added: occupied voxels of its interior, blocked voxels of its grown range (an OR, as the
//   rebuild's union), appended to the large-box list every collision query scans;
// - cube set: flags, the stencil OR'ed in, surface flags of the cube and its face neighbours;
// - cube cleared: occupied re-derived from the boxes listed at the voxel, surface flags of the
//   face neighbours, and every voxel of its stencil re-derived (boxes of its bucket cell plus the
//   large list, cubes of its own stencil);
// - legal steps of the 3x3x3 block around every voxel whose blocked bit flipped;
// - distance field: lowered exactly within kDfReach voxels (plus clearance) of a new obstacle and
//   read as min(df, df_cap) beyond; a cleared cube leaves entries that are still lower bounds and
//   sets df_valid = 0, so collision queries stop reading the field as an upper bound.
// Every loop runs over the update's lists, a stencil, a 3x3x3 block or a box's grown range.
#include "tdo/grid_update.h"

#include <math.h>

#include "directions.h"
#include "grid_geometry.h"
#include "grid_internal.h"
#include "surface_index.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

constexpr int32_t kDfReach = 2;        // voxels beyond the clearance reach lowered exactly
constexpr uint64_t kMovesVisits = 27;  // voxel visits of one legal-step recomputation

// df entry (m, rounded down to float) for a squared distance of d2 voxel^2, as the rebuild has it.
float df_metres(uint64_t d2, double res) {
  if (d2 == 0u) return 0.0f;
  const double exact = sqrt(static_cast<double>(d2)) * res;
  float m = static_cast<float>(exact);
  m = nextafterf(m, 0.0f);
  if (static_cast<double>(m) > exact) m = nextafterf(m, 0.0f);
  return m;
}

// ---- the update's working state

struct Ctx {
  tdo_grid* g;
  uint32_t n_stencil;  // offsets in g->stencil (0 when the clearance is 0)
  int32_t df_reach;    // voxels around a new obstacle where the distance field is made exact
  int64_t reach;       // voxels: the largest stencil offset on an axis (0 for clearance 0)
  tdo_grid_update_result* out;
};

bool is_cube(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return in_grid(g, i, j, k) && (g->flags[index_of(g, i, j, k)] & kFlagCube) != 0;
}

bool is_buried(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  return is_cube(g, i - 1, j, k) && is_cube(g, i + 1, j, k) && is_cube(g, i, j - 1, k) &&
         is_cube(g, i, j + 1, k) && is_cube(g, i, j, k - 1) && is_cube(g, i, j, k + 1);
}

// Legal steps of voxel (i,j,k) from the blocked bits of its 3x3x3 block (grid.cpp compute_moves).
uint32_t moves_of(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  if ((g->flags[index_of(g, i, j, k)] & kFlagBlocked) != 0) return 0;
  uint32_t free27 = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (in_grid(g, i + dx, j + dy, k + dz) &&
            (g->flags[index_of(g, i + dx, j + dy, k + dz)] & kFlagBlocked) == 0)
          free27 |= 1u << cell_of(dx, dy, dz);
  uint32_t mask = 0;
  for (int d = 0; d < kNumDirs; ++d) {
    uint32_t need = 0;  // the 2x2 square or 2x2x2 cube the step sweeps
    for (int a = 0; a <= 1; ++a)
      for (int b = 0; b <= 1; ++b)
        for (int e = 0; e <= 1; ++e)
          need |= 1u << cell_of(a * dir_dx(d), b * dir_dy(d), e * dir_dz(d));
    if ((free27 & need) == need) mask |= 1u << d;
  }
  return mask;
}

// Set or clear the blocked bit of (i,j,k); the legal steps around it follow in refresh_moves.
void set_blocked(Ctx* x, int64_t i, int64_t j, int64_t k, bool blocked) {
  tdo_grid* g = x->g;
  uint8_t& f = g->flags[index_of(g, i, j, k)];
  ++x->out->cells_touched;
  if (((f & kFlagBlocked) != 0) == blocked) return;
  if (blocked) {
    f |= kFlagBlocked;
    ++g->n_blocked;
    ++x->out->blocked_on;
  } else {
    f = static_cast<uint8_t>(f & ~kFlagBlocked);
    --g->n_blocked;
    ++x->out->blocked_off;
  }
}

uint32_t flips(const Ctx* x) { return x->out->blocked_on + x->out->blocked_off; }

// Legal steps of every voxel in [lo - 1, hi + 1] (clamped to the grid) when a blocked bit in
// [lo, hi] flipped since `flips_before`.
void refresh_moves(Ctx* x, const int64_t lo[3], const int64_t hi[3], uint32_t flips_before) {
  if (flips(x) == flips_before) return;
  tdo_grid* g = x->g;
  const int64_t n[3] = {g->desc.nx, g->desc.ny, g->desc.nz};
  int64_t a[3], b[3];
  for (int t = 0; t < 3; ++t) {
    a[t] = lo[t] - 1 < 0 ? 0 : lo[t] - 1;
    b[t] = hi[t] + 1 > n[t] - 1 ? n[t] - 1 : hi[t] + 1;
  }
  for (int64_t k = a[2]; k <= b[2]; ++k)
    for (int64_t j = a[1]; j <= b[1]; ++j)
      for (int64_t i = a[0]; i <= b[0]; ++i) {
        g->moves[index_of(g, i, j, k)] = moves_of(g, i, j, k);
        x->out->cells_touched += kMovesVisits + 1;
      }
}

// The voxels a set or cleared cube at v may change: v grown by the stencil's reach.
void stencil_range(const Ctx* x, const tdo_voxel& v, int64_t lo[3], int64_t hi[3]) {
  const int64_t p[3] = {v.i, v.j, v.k};
  for (int t = 0; t < 3; ++t) {
    lo[t] = p[t] - x->reach;
    hi[t] = p[t] + x->reach;
  }
}

// Lower the distance field over [lo, hi] (voxels, the new obstacle's occupied range) grown by
// df_reach; beyond, df_cap bounds it.
void lower_df(Ctx* x, const int64_t lo[3], const int64_t hi[3]) {
  tdo_grid* g = x->g;
  if (g->df == nullptr) return;
  const int64_t n[3] = {g->desc.nx, g->desc.ny, g->desc.nz};
  int64_t a[3], b[3];
  for (int t = 0; t < 3; ++t) {
    a[t] = lo[t] - x->df_reach < 0 ? 0 : lo[t] - x->df_reach;
    b[t] = hi[t] + x->df_reach > n[t] - 1 ? n[t] - 1 : hi[t] + x->df_reach;
  }
  for (int64_t k = a[2]; k <= b[2]; ++k)
    for (int64_t j = a[1]; j <= b[1]; ++j)
      for (int64_t i = a[0]; i <= b[0]; ++i) {
        const int64_t p[3] = {i, j, k};
        uint64_t d2 = 0;
        for (int t = 0; t < 3; ++t) {
          const int64_t gap = p[t] < lo[t] ? lo[t] - p[t] : (p[t] > hi[t] ? p[t] - hi[t] : 0);
          d2 += static_cast<uint64_t>(gap * gap);
        }
        const float m = df_metres(d2, g->desc.res);
        float& e = g->df[index_of(g, i, j, k)];
        if (m < e) e = m;
        ++x->out->cells_touched;
      }
  const double cap = static_cast<double>(x->df_reach) * g->desc.res;
  if (!(g->df_cap > 0.0) || cap < g->df_cap) g->df_cap = cap;
}

// 1 when box b blocks the voxel centre (i,j,k) at clearance c (inflate_box's test).
bool box_blocks(const tdo_grid* g, const tdo_box& b, int64_t i, int64_t j, int64_t k, double c) {
  const tdo_grid_desc& d = g->desc;
  // The distance test first: it rejects almost every box of a scanned list cheaply.
  const double gx = axis_gap(d.origin.x + (static_cast<double>(i) + 0.5) * d.res, b.min.x, b.max.x);
  const double gy = axis_gap(d.origin.y + (static_cast<double>(j) + 0.5) * d.res, b.min.y, b.max.y);
  const double gz = axis_gap(d.origin.z + (static_cast<double>(k) + 0.5) * d.res, b.min.z, b.max.z);
  if (!(gx * gx + gy * gy + gz * gz < c * c)) return false;
  int64_t lo[3], hi[3];
  centre_range(d.origin.x, d.res, d.nx, b.min.x, b.max.x, c, &lo[0], &hi[0]);
  centre_range(d.origin.y, d.res, d.ny, b.min.y, b.max.y, c, &lo[1], &hi[1]);
  centre_range(d.origin.z, d.res, d.nz, b.min.z, b.max.z, c, &lo[2], &hi[2]);
  return i >= lo[0] && i <= hi[0] && j >= lo[1] && j <= hi[1] && k >= lo[2] && k <= hi[2];
}

// 1 when box b occupies voxel (i,j,k) (tdo_grid_add_box's interior test).
bool box_occupies(const tdo_grid* g, const tdo_box& b, int64_t i, int64_t j, int64_t k) {
  const tdo_grid_desc& d = g->desc;
  int64_t lo[3], hi[3];
  interior_range(d.origin.x, d.res, d.nx, b.min.x, b.max.x, &lo[0], &hi[0]);
  interior_range(d.origin.y, d.res, d.ny, b.min.y, b.max.y, &lo[1], &hi[1]);
  interior_range(d.origin.z, d.res, d.nz, b.min.z, b.max.z, &lo[2], &hi[2]);
  return i >= lo[0] && i <= hi[0] && j >= lo[1] && j <= hi[1] && k >= lo[2] && k <= hi[2];
}

// Bucket cell of voxel (i,j,k)'s centre: every box within bucket_reach of it is listed there.
uint32_t centre_cell(const tdo_grid* g, int64_t i, int64_t j, int64_t k) {
  const tdo_grid_desc& d = g->desc;
  const double p[3] = {d.origin.x + (static_cast<double>(i) + 0.5) * d.res,
                       d.origin.y + (static_cast<double>(j) + 0.5) * d.res,
                       d.origin.z + (static_cast<double>(k) + 0.5) * d.res};
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  const int32_t nc[3] = {g->ncx, g->ncy, g->ncz};
  int32_t cell[3];
  for (int t = 0; t < 3; ++t) {
    const double f = floor((p[t] - o[t]) / g->cell_edge);
    cell[t] =
        f < 0.0 ? 0 : (f > static_cast<double>(nc[t] - 1) ? nc[t] - 1 : static_cast<int32_t>(f));
  }
  return static_cast<uint32_t>(cell[0] + nc[0] * (cell[1] + nc[1] * cell[2]));
}

// Calls f(box) for the boxes listed at voxel (i,j,k) (large list first) until f returns true.
template <class F>
bool any_box_near(const tdo_grid* g, int64_t i, int64_t j, int64_t k, F&& f) {
  for (uint32_t r = 0; r < g->n_large; ++r)
    if (f(g->boxes[g->large_boxes[r]])) return true;
  const uint32_t c = centre_cell(g, i, j, k);
  for (uint32_t r = g->cell_start[c]; r < g->cell_start[c + 1]; ++r)
    if (f(g->boxes[g->box_refs[r]])) return true;
  return false;
}

// The blocked bit of (i,j,k) from scratch: occupied, a box or a cube closer than the clearance.
bool derive_blocked(Ctx* x, int64_t i, int64_t j, int64_t k) {
  const tdo_grid* g = x->g;
  if ((g->flags[index_of(g, i, j, k)] & kFlagOccupied) != 0) return true;
  const double c = g->clearance;
  if (!(c > 0.0)) return false;
  for (uint32_t s = 0; s < x->n_stencil; ++s) {
    ++x->out->cells_touched;
    if (is_cube(g, i + g->stencil[3 * s], j + g->stencil[3 * s + 1], k + g->stencil[3 * s + 2]))
      return true;
  }
  return any_box_near(g, i, j, k, [&](const tdo_box& b) { return box_blocks(g, b, i, j, k, c); });
}

void refresh_surface(Ctx* x, int64_t i, int64_t j, int64_t k) {
  tdo_grid* g = x->g;
  if (!in_grid(g, i, j, k)) return;
  uint8_t& f = g->flags[index_of(g, i, j, k)];
  x->out->cells_touched += 7;
  if ((f & kFlagCube) != 0 && !is_buried(g, i, j, k))
    f |= kFlagSurface;
  else
    f = static_cast<uint8_t>(f & ~kFlagSurface);
  surface_index_set(g, i, j, k, (f & kFlagSurface) != 0);
}

void refresh_surface_around(Ctx* x, int64_t i, int64_t j, int64_t k) {
  refresh_surface(x, i, j, k);
  refresh_surface(x, i - 1, j, k);
  refresh_surface(x, i + 1, j, k);
  refresh_surface(x, i, j - 1, k);
  refresh_surface(x, i, j + 1, k);
  refresh_surface(x, i, j, k - 1);
  refresh_surface(x, i, j, k + 1);
}

void add_box(Ctx* x, const tdo_box& b) {
  tdo_grid* g = x->g;
  const tdo_grid_desc& d = g->desc;
  const uint32_t idx = g->n_boxes;
  g->boxes[g->n_boxes++] = b;
  g->large_boxes[g->n_large++] = idx;
  ++x->out->boxes_added;
  int64_t lo[3], hi[3];
  interior_range(d.origin.x, d.res, d.nx, b.min.x, b.max.x, &lo[0], &hi[0]);
  interior_range(d.origin.y, d.res, d.ny, b.min.y, b.max.y, &lo[1], &hi[1]);
  interior_range(d.origin.z, d.res, d.nz, b.min.z, b.max.z, &lo[2], &hi[2]);
  if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) return;  // occupies no voxel
  const uint32_t before = flips(x);
  for (int64_t k = lo[2]; k <= hi[2]; ++k)
    for (int64_t j = lo[1]; j <= hi[1]; ++j)
      for (int64_t i = lo[0]; i <= hi[0]; ++i) {
        g->flags[index_of(g, i, j, k)] |= kFlagOccupied;
        set_blocked(x, i, j, k, true);
      }
  lower_df(x, lo, hi);
  refresh_moves(x, lo, hi, before);  // the occupied voxels (with c < res / 2 not all inflated)
  const double c = g->clearance;
  if (c > 0.0) {
    centre_range(d.origin.x, d.res, d.nx, b.min.x, b.max.x, c, &lo[0], &hi[0]);
    centre_range(d.origin.y, d.res, d.ny, b.min.y, b.max.y, c, &lo[1], &hi[1]);
    centre_range(d.origin.z, d.res, d.nz, b.min.z, b.max.z, c, &lo[2], &hi[2]);
    for (int64_t k = lo[2]; k <= hi[2]; ++k)
      for (int64_t j = lo[1]; j <= hi[1]; ++j)
        for (int64_t i = lo[0]; i <= hi[0]; ++i)
          if (box_blocks(g, b, i, j, k, c)) set_blocked(x, i, j, k, true);
    refresh_moves(x, lo, hi, before);
  }
}

void set_cube(Ctx* x, const tdo_voxel& v) {
  tdo_grid* g = x->g;
  uint8_t& f = g->flags[index_of(g, v.i, v.j, v.k)];
  ++x->out->cells_touched;
  if ((f & kFlagCube) != 0) return;
  f |= kFlagCube | kFlagOccupied;
  ++g->n_cubes;
  ++x->out->cubes_set;
  refresh_surface_around(x, v.i, v.j, v.k);
  const uint32_t before = flips(x);
  set_blocked(x, v.i, v.j, v.k, true);
  for (uint32_t s = 0; s < x->n_stencil; ++s) {
    const int64_t i = v.i + g->stencil[3 * s], j = v.j + g->stencil[3 * s + 1],
                  k = v.k + g->stencil[3 * s + 2];
    if (in_grid(g, i, j, k)) set_blocked(x, i, j, k, true);
  }
  int64_t lo[3], hi[3];
  stencil_range(x, v, lo, hi);
  refresh_moves(x, lo, hi, before);
  const int64_t p[3] = {v.i, v.j, v.k};
  lower_df(x, p, p);
}

void clear_cube(Ctx* x, const tdo_voxel& v) {
  tdo_grid* g = x->g;
  uint8_t& f = g->flags[index_of(g, v.i, v.j, v.k)];
  ++x->out->cells_touched;
  if ((f & kFlagCube) == 0) return;
  const bool boxed = any_box_near(
      g, v.i, v.j, v.k, [&](const tdo_box& b) { return box_occupies(g, b, v.i, v.j, v.k); });
  f = static_cast<uint8_t>(f & ~(kFlagCube | kFlagOccupied | kFlagSurface));
  if (boxed) f |= kFlagOccupied;
  --g->n_cubes;
  ++x->out->cubes_cleared;
  g->df_valid = 0;  // entries stay lower bounds, no longer upper bounds
  refresh_surface_around(x, v.i, v.j, v.k);
  const uint32_t before = flips(x);
  set_blocked(x, v.i, v.j, v.k, derive_blocked(x, v.i, v.j, v.k));
  for (uint32_t s = 0; s < x->n_stencil; ++s) {
    const int64_t i = v.i + g->stencil[3 * s], j = v.j + g->stencil[3 * s + 1],
                  k = v.k + g->stencil[3 * s + 2];
    if (in_grid(g, i, j, k)) set_blocked(x, i, j, k, derive_blocked(x, i, j, k));
  }
  int64_t lo[3], hi[3];
  stencil_range(x, v, lo, hi);
  refresh_moves(x, lo, hi, before);
}

bool valid_box(const tdo_box& b) {
  return finite3(b.min) && finite3(b.max) && b.max.x > b.min.x && b.max.y > b.min.y &&
         b.max.z > b.min.z;
}

// Checks that change nothing; TDO_OK when the update can be applied in full.
tdo_status check_update(const tdo_grid* g, const tdo_grid_update* u) {
  if ((u->n_set > 0 && u->set == nullptr) || (u->n_clear > 0 && u->clear == nullptr) ||
      (u->n_boxes > 0 && u->boxes == nullptr))
    return TDO_ERR_INVALID_ARGUMENT;
  if ((u->n_set > 0 || u->n_clear > 0) && g->cap.boxes_only != 0u) return TDO_ERR_MAP_CAPACITY;
  if (static_cast<uint64_t>(g->n_boxes) + u->n_boxes > g->cap.max_boxes)
    return TDO_ERR_BOX_CAPACITY;
  for (uint32_t b = 0; b < u->n_boxes; ++b)
    if (!valid_box(u->boxes[b])) return TDO_ERR_INVALID_BOX;
  for (uint32_t s = 0; s < u->n_set; ++s)
    if (!in_grid(g, u->set[s].i, u->set[s].j, u->set[s].k)) return TDO_ERR_INVALID_ARGUMENT;
  for (uint32_t s = 0; s < u->n_clear; ++s)
    if (!in_grid(g, u->clear[s].i, u->clear[s].j, u->clear[s].k)) return TDO_ERR_INVALID_ARGUMENT;
  if (u->max_cells > 0 && tdo_grid_update_work(g, u) > u->max_cells) return TDO_ERR_BUDGET;
  return TDO_OK;
}

// TDO_ERR_UPDATE_CONTRADICTORY when a voxel is both set and cleared (a scratch flag marks the set
// voxels and is removed again).
tdo_status check_contradiction(tdo_grid* g, const tdo_grid_update* u) {
  for (uint32_t s = 0; s < u->n_set; ++s)
    g->flags[index_of(g, u->set[s].i, u->set[s].j, u->set[s].k)] |= kFlagMark;
  tdo_status st = TDO_OK;
  for (uint32_t s = 0; s < u->n_clear && st == TDO_OK; ++s)
    if ((g->flags[index_of(g, u->clear[s].i, u->clear[s].j, u->clear[s].k)] & kFlagMark) != 0)
      st = TDO_ERR_UPDATE_CONTRADICTORY;
  for (uint32_t s = 0; s < u->n_set; ++s) {
    uint8_t& f = g->flags[index_of(g, u->set[s].i, u->set[s].j, u->set[s].k)];
    f = static_cast<uint8_t>(f & ~kFlagMark);
  }
  return st;
}

int32_t df_reach_of(const tdo_grid* g) {
  return static_cast<int32_t>(ceil(g->bucket_reach / g->desc.res)) + kDfReach;
}

uint64_t cube3(int64_t side) {
  const uint64_t s = static_cast<uint64_t>(side);
  return s * s * s;
}

// Voxels of a box's range along one axis grown by `grow` voxels (interior or centre range).
uint64_t span(int64_t lo, int64_t hi, int64_t grow) {
  return lo <= hi ? static_cast<uint64_t>(hi - lo + 1 + 2 * grow) : 0u;
}

}  // namespace
}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" uint64_t tdo_grid_update_work(const tdo_grid* g, const tdo_grid_update* u) {
  if (g == nullptr || u == nullptr || !g->ready || g->nvox == 0) return 0;
  const double c = g->clearance;
  const int64_t reach = c > 0.0 ? static_cast<int64_t>(ceil(c / g->desc.res + 0.5)) : 0;
  const uint64_t stencil = cube3(2 * reach + 1);      // offsets of the clearance stencil
  const uint64_t df = cube3(2 * df_reach_of(g) + 1);  // distance-field block of one voxel
  const uint64_t moves = cube3(2 * reach + 3) * (kMovesVisits + 1);  // legal steps renewed
  const uint64_t per_set = 1 + 49 + stencil + 1 + moves + df;
  const uint64_t per_clear = 1 + 49 + (stencil + 1) * (stencil + 1) + moves;
  uint64_t work = stencil + u->n_set * per_set + u->n_clear * per_clear;
  const tdo_grid_desc& d = g->desc;
  for (uint32_t b = 0; b < u->n_boxes && u->boxes != nullptr; ++b) {
    const tdo_box& x = u->boxes[b];
    if (!valid_box(x)) continue;
    int64_t lo[3], hi[3], clo[3], chi[3];
    interior_range(d.origin.x, d.res, d.nx, x.min.x, x.max.x, &lo[0], &hi[0]);
    interior_range(d.origin.y, d.res, d.ny, x.min.y, x.max.y, &lo[1], &hi[1]);
    interior_range(d.origin.z, d.res, d.nz, x.min.z, x.max.z, &lo[2], &hi[2]);
    centre_range(d.origin.x, d.res, d.nx, x.min.x, x.max.x, c, &clo[0], &chi[0]);
    centre_range(d.origin.y, d.res, d.ny, x.min.y, x.max.y, c, &clo[1], &chi[1]);
    centre_range(d.origin.z, d.res, d.nz, x.min.z, x.max.z, c, &clo[2], &chi[2]);
    const uint64_t occ = span(lo[0], hi[0], 0) * span(lo[1], hi[1], 0) * span(lo[2], hi[2], 0);
    const int64_t r = df_reach_of(g);
    const uint64_t dfv = span(lo[0], hi[0], r) * span(lo[1], hi[1], r) * span(lo[2], hi[2], r);
    const uint64_t inf =
        span(clo[0], chi[0], 0) * span(clo[1], chi[1], 0) * span(clo[2], chi[2], 0);
    const uint64_t grown =  // the larger of the two ranges, grown by one voxel for the steps
        span(clo[0], chi[0], 1) * span(clo[1], chi[1], 1) * span(clo[2], chi[2], 1) +
        span(lo[0], hi[0], 1) * span(lo[1], hi[1], 1) * span(lo[2], hi[2], 1);
    work += occ + inf + grown * (kMovesVisits + 1) + dfv;
  }
  return work;
}

extern "C" tdo_status tdo_grid_apply_update(tdo_grid* g, const tdo_grid_update* u,
                                            tdo_grid_update_result* out) {
  tdo_grid_update_result scratch{};
  tdo_grid_update_result* res = out != nullptr ? out : &scratch;
  *res = tdo_grid_update_result{};
  if (g == nullptr || u == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!g->ready || g->nvox == 0) return TDO_ERR_MAP_NOT_READY;
  tdo_status st = check_update(g, u);
  if (st == TDO_OK) st = check_contradiction(g, u);
  if (st != TDO_OK) return st;
  // The field as the finish left it, so that the update lowers it exactly as before: the first
  // update after a finish without a collision query builds it (O(voxels), once).
  df_ensure(g);
  const int64_t reach =
      g->clearance > 0.0 ? static_cast<int64_t>(ceil(g->clearance / g->desc.res + 0.5)) : 0;
  Ctx x{g, 0u, df_reach_of(g), reach, res};
  if ((u->n_set > 0 || u->n_clear > 0) && g->clearance > 0.0 &&
      build_stencil(g, g->clearance, &x.n_stencil) != TDO_OK)
    return TDO_ERR_CLEARANCE_CAPACITY;  // unreachable: the finish built the same stencil
  // Boxes first, then clears (they see the new boxes), then sets.
  for (uint32_t b = 0; b < u->n_boxes; ++b) add_box(&x, u->boxes[b]);
  for (uint32_t s = 0; s < u->n_clear; ++s) clear_cube(&x, u->clear[s]);
  for (uint32_t s = 0; s < u->n_set; ++s) set_cube(&x, u->set[s]);
  ++g->version;  // data derived from the grid (the search's coarse guide) is rebuilt
  return TDO_OK;
}
