// The coarse guide of the turn-penalised search (docs/design.md s.1, "The coarse guide").
#include "guide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "grid_internal.h"
#include "search_headed.h"

namespace tdo_internal {

constexpr int kCorridorShift = 13;  // the mask bit of the cell itself (dx = dy = dz = 0)
constexpr uint32_t kCorridorBit = 1u << kCorridorShift;  // tdo_search_corridor: the cell is in
constexpr uint32_t kAllCells = (1u << 27) - 1u;          // tdo_search_corridor: every neighbour in
// The second route (docs/design.md s.1, "The coarse guide", step 3): searched in its own corridor
// when its coarse cost is within kAltMargin of the route's and kAltOutside of its cells lie
// outside the route's corridor; its plan is kept when its grid path is kAltGain shorter.
constexpr double kAltMargin = 0.02;
constexpr uint32_t kAltOutside = 3u;
constexpr double kAltGain = 0.02;
// Short queries (docs/design.md s.1, "The coarse guide", step 0): ends at most kShortCells coarse
// cell edges apart (Manhattan distance) are searched on the whole grid first, with a budget of
// kShortBudget expansions per voxel of that distance (plus kShortBase).
constexpr int32_t kShortCells = 8;
constexpr uint32_t kShortBudget = 12u;
constexpr uint32_t kShortBase = 16u;

struct Guide {
  GuideCapacity cap;
  tdo_grid* coarse;     // cell free when one of its voxels is free and deep (build_coarse)
  tdo_grid* shallow;    // cell free when one of its voxels keeps the clearance
  tdo_search* search;   // the coarse search
  uint32_t* cells;      // max_cells corridor masks (tdo_search_corridor.cells), else 0
  uint32_t* marked;     // cells whose mask is not 0
  uint32_t max_marked;  // 27 per coarse path cell
  uint32_t n_marked;
  uint32_t* avoid;  // max_avoid masks of blocks of 2^3 cells: the second route's corridor
  uint32_t max_avoid;
  tdo_voxel* route;           // max_path cells: the coarse route
  tdo_voxel* kept;            // max_path voxels: the second route's plan
  const tdo_grid* built_for;  // the fine grid the coarse grid was built from
  uint32_t built_version;     // its tdo_grid.version then
  tdo_search_corridor corridor;
};

namespace {

GridCapacity coarse_grid_cap(const GuideCapacity& cap) {
  // clearance 0: a 3^3 stencil; no boxes; voxel obstacles (the distance field exists but no query
  // reads it).
  return GridCapacity{cap.max_cells, 0u, 27u, 0u, 0u, 0u};
}

// The coarse search has no penalties: one state per cell, no retry tables.
tdo_search_config coarse_search_cfg(const GuideCapacity& cap) {
  return tdo_search_config{
      cap.max_cells, cap.max_nodes, cap.max_path, 2u * cap.max_nodes, 0u, 0u, 0u};
}

uint32_t avoid_capacity(const GuideCapacity& cap) { return cap.max_cells / 2u + 1024u; }

// The coarse grid `out` of `fine`: a cell is an obstacle unless a voxel of it is free and at least
// `depth` farther than the clearance from every obstacle voxel (the distance field; without one,
// every free voxel counts).
tdo_status build_one(Guide* gd, tdo_grid* out, const tdo_grid* fine, double depth) {
  const int32_t sh = gd->cap.shift;
  const int32_t e = (1 << sh) - 1;
  tdo_grid_desc d = fine->desc;
  d.nx = (d.nx + e) >> sh;
  d.ny = (d.ny + e) >> sh;
  d.nz = (d.nz + e) >> sh;
  d.res = fine->desc.res * static_cast<double>(1 << sh);
  tdo_status st = tdo_grid_reset(out, &d);
  if (st != TDO_OK) return st;
  uint32_t* free_cell = gd->cells;  // scratch: 1 when a voxel of the cell is free
  const uint32_t n =
      static_cast<uint32_t>(d.nx) * static_cast<uint32_t>(d.ny) * static_cast<uint32_t>(d.nz);
  memset(free_cell, 0, n * sizeof(uint32_t));
  const uint8_t* f = fine->flags;
  df_ensure(fine);
  const float* df = fine->df_valid ? fine->df : nullptr;
  const float deep = df != nullptr ? static_cast<float>(fine->clearance + depth) : 0.0f;
  for (int32_t k = 0; k < fine->desc.nz; ++k) {
    for (int32_t j = 0; j < fine->desc.ny; ++j) {
      uint32_t* row =
          free_cell + static_cast<uint32_t>(d.nx) *
                          (static_cast<uint32_t>(j >> sh) +
                           static_cast<uint32_t>(d.ny) * static_cast<uint32_t>(k >> sh));
      for (int32_t i = 0; i < fine->desc.nx; ++i, ++f)
        if ((*f & kFlagBlocked) == 0 && (df == nullptr || df[f - fine->flags] >= deep))
          row[i >> sh] = 1u;
    }
  }
  uint32_t c = 0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i, ++c)
        if (free_cell[c] == 0u && (st = tdo_grid_add_voxel(out, i, j, k)) != TDO_OK) return st;
  memset(free_cell, 0, n * sizeof(uint32_t));
  return tdo_grid_finish(out, 0.0);
}

// The coarse grids of `fine`: the route's with "deep" free voxels (one voxel edge more than the
// clearance), the second route's with every voxel that keeps the clearance.
tdo_status build_coarse(Guide* gd, const tdo_grid* fine) {
  tdo_status st = build_one(gd, gd->coarse, fine, fine->desc.res);
  if (st == TDO_OK) st = build_one(gd, gd->shallow, fine, 0.0);
  if (st != TDO_OK) return st;
  const tdo_grid_desc d = gd->coarse->desc;
  gd->corridor.cells = gd->cells;
  gd->corridor.shift = gd->cap.shift;
  gd->corridor.cnx = d.nx;
  gd->corridor.cny = d.ny;
  gd->built_for = fine;
  gd->built_version = fine->version;
  return TDO_OK;
}

// A cell of `d` at least one cell from every face: its 26 neighbours lie inside the grid.
inline bool interior(const tdo_grid_desc& d, int32_t i, int32_t j, int32_t k) {
  return i > 0 && j > 0 && k > 0 && i < d.nx - 1 && j < d.ny - 1 && k < d.nz - 1;
}

// Mark cell c, (i,j,k) of the coarse grid, as in the corridor.
inline void mark_cell(Guide* gd, uint32_t c) {
  if (gd->cells[c] != 0u || gd->n_marked >= gd->max_marked) return;
  gd->cells[c] = kCorridorBit;
  gd->marked[gd->n_marked++] = c;
}

// Mark cell (i,j,k) as in the corridor (outside the coarse grid: nothing).
void mark(Guide* gd, const tdo_grid_desc& d, int32_t i, int32_t j, int32_t k) {
  if (i < 0 || j < 0 || k < 0 || i >= d.nx || j >= d.ny || k >= d.nz) return;
  mark_cell(
      gd, static_cast<uint32_t>(i) + static_cast<uint32_t>(d.nx) *
                                         (static_cast<uint32_t>(j) +
                                          static_cast<uint32_t>(d.ny) * static_cast<uint32_t>(k)));
}

// The tdo_search_corridor.cells mask of marked cell c = (i,j,k): the cells of its 3x3x3 block in
// the corridor. `off`: the linear offsets of the block's cells, in mask bit order.
uint32_t neighbour_mask(const Guide* gd, const tdo_grid_desc& d, uint32_t c, int32_t i, int32_t j,
                        int32_t k, const int64_t* off) {
  uint32_t mask = 0;
  if (interior(d, i, j, k)) {  // no bounds to test: the 9 rows of three cells
    for (int r = 0; r < 9; ++r) {
      const uint32_t* row = gd->cells + (static_cast<int64_t>(c) + off[3 * r + 1]);
      mask |= (((row[-1] >> kCorridorShift) & 1u) | ((row[0] >> (kCorridorShift - 1)) & 2u) |
               ((row[1] >> (kCorridorShift - 2)) & 4u))
              << (3 * r);
    }
    return mask;
  }
  for (int n = 0; n < 27; ++n) {
    const int32_t x = i + n % 3 - 1, y = j + (n / 3) % 3 - 1, z = k + n / 9 - 1;
    if (x < 0 || y < 0 || z < 0 || x >= d.nx || y >= d.ny || z >= d.nz) continue;
    mask |= ((gd->cells[static_cast<int64_t>(c) + off[n]] >> kCorridorShift) & 1u) << n;
  }
  return mask;
}

// The corridor: the cells of the coarse path and their 26 neighbours, each with the mask of its
// neighbours in the corridor (tdo_search_corridor.cells). Cells away from the grid's faces skip
// the bounds tests.
void build_corridor(Guide* gd, const tdo_voxel* path, uint32_t n_path) {
  const tdo_grid_desc d = gd->coarse->desc;
  const int64_t sy = d.nx;
  const int64_t sz = static_cast<int64_t>(d.nx) * d.ny;
  int64_t off[27];  // bit n = (dx+1) + 3 (dy+1) + 9 (dz+1)
  for (int n = 0; n < 27; ++n) off[n] = (n % 3 - 1) + ((n / 3) % 3 - 1) * sy + (n / 9 - 1) * sz;
  gd->n_marked = 0;
  for (uint32_t p = 0; p < n_path; ++p) {
    const tdo_voxel& v = path[p];
    if (interior(d, v.i, v.j, v.k)) {
      const int64_t c = v.i + v.j * sy + v.k * sz;
      for (int n = 0; n < 27; ++n) mark_cell(gd, static_cast<uint32_t>(c + off[n]));
      continue;
    }
    for (int32_t dz = -1; dz <= 1; ++dz)
      for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx) mark(gd, d, v.i + dx, v.j + dy, v.k + dz);
  }
  for (uint32_t m = 0; m < gd->n_marked; ++m) {
    const uint32_t c = gd->marked[m];
    const int32_t i = static_cast<int32_t>(c % static_cast<uint32_t>(d.nx));
    const int32_t j =
        static_cast<int32_t>((c / static_cast<uint32_t>(d.nx)) % static_cast<uint32_t>(d.ny));
    const int32_t k = static_cast<int32_t>(c / static_cast<uint32_t>(sz));
    gd->cells[c] |= neighbour_mask(gd, d, c, i, j, k, off);
  }
}

void clear_corridor(Guide* gd) {
  for (uint32_t m = 0; m < gd->n_marked; ++m) gd->cells[gd->marked[m]] = 0u;
  gd->n_marked = 0;
}

// The second route's corridor on the shallow grid (shift 1: blocks of 2^3 cells): every block but
// those of `route` more than one block from the blocks of its ends. False when the blocks do not
// fit.
bool build_avoid(Guide* gd, const tdo_voxel* route, uint32_t n, tdo_search_corridor* c) {
  const tdo_grid_desc d = gd->coarse->desc;
  *c = tdo_search_corridor{gd->avoid, 1, (d.nx + 1) >> 1, (d.ny + 1) >> 1};
  const int32_t cnz = (d.nz + 1) >> 1;
  const uint64_t nb =
      static_cast<uint64_t>(c->cnx) * static_cast<uint64_t>(c->cny) * static_cast<uint64_t>(cnz);
  if (nb > gd->max_avoid || n < 2u || n > gd->max_marked) return false;
  for (uint32_t b = 0; b < nb; ++b) gd->avoid[b] = kAllCells;
  auto near_block = [](const tdo_voxel& v, const tdo_voxel& e) {
    return abs((v.i >> 1) - (e.i >> 1)) <= 1 && abs((v.j >> 1) - (e.j >> 1)) <= 1 &&
           abs((v.k >> 1) - (e.k >> 1)) <= 1;
  };
  uint32_t n_out = 0;  // the blocks taken out, listed in gd->marked (no corridor is built now)
  for (uint32_t p = 0; p < n; ++p) {
    const uint32_t b = static_cast<uint32_t>(
        (route[p].i >> 1) + c->cnx * ((route[p].j >> 1) + c->cny * int64_t{route[p].k >> 1}));
    if (near_block(route[p], route[0]) || near_block(route[p], route[n - 1u]) || gd->avoid[b] == 0u)
      continue;
    gd->avoid[b] = 0u;
    gd->marked[n_out++] = b;
  }
  const int64_t sz = static_cast<int64_t>(c->cnx) * c->cny;
  for (uint32_t m = 0; m < n_out; ++m) {  // the neighbours of a block taken out lose its bit
    const int64_t b = gd->marked[m];
    const int32_t i = static_cast<int32_t>(b % c->cnx);
    const int32_t j = static_cast<int32_t>((b / c->cnx) % c->cny);
    const int32_t k = static_cast<int32_t>(b / sz);
    for (int32_t dz = -1; dz <= 1; ++dz)
      for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx) {
          const int32_t x = i + dx, y = j + dy, z = k + dz;
          if (x < 0 || y < 0 || z < 0 || x >= c->cnx || y >= c->cny || z >= cnz) continue;
          gd->avoid[b + dx + dy * c->cnx + dz * sz] &=
              ~(1u << ((1 - dz) * 9 + (1 - dy) * 3 + (1 - dx)));
        }
  }
  return true;
}

// Cells of `alt` farther than one cell from every cell of `route`.
uint32_t cells_outside(const tdo_voxel* alt, uint32_t n_alt, const tdo_voxel* route, uint32_t n) {
  uint32_t outside = 0;
  for (uint32_t p = 0; p < n_alt; ++p) {
    bool near = false;
    for (uint32_t q = 0; q < n && !near; ++q)
      near = abs(alt[p].i - route[q].i) <= 1 && abs(alt[p].j - route[q].j) <= 1 &&
             abs(alt[p].k - route[q].k) <= 1;
    outside += near ? 0u : 1u;
  }
  return outside;
}

// The route is as short as the octile distance between its ends: no second route is tried.
bool straight_route(const tdo_voxel* route, uint32_t n, double cost, double res) {
  int32_t d[3] = {abs(route[n - 1u].i - route[0].i), abs(route[n - 1u].j - route[0].j),
                  abs(route[n - 1u].k - route[0].k)};
  for (int a = 0; a < 2; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (d[b] > d[a]) {
        const int32_t t = d[a];
        d[a] = d[b];
        d[b] = t;
      }
  const double octile = d[2] * sqrt(3.0) + (d[1] - d[2]) * sqrt(2.0) + (d[0] - d[1]);
  return cost <= octile * res * (1.0 + 1e-9);
}

// A second coarse route `alt` (its path is the coarse search's, valid until its next run): the
// shortest on the shallow grid that avoids the blocks of `route` but near its ends. True when it
// is worth a corridor search (kAltMargin, kAltOutside).
bool second_route(Guide* gd, const tdo_search_input& ci, const tdo_voxel* route, uint32_t n,
                  double cost, tdo_search_output* alt, GuideReport* report) {
  if (straight_route(route, n, cost, gd->coarse->desc.res)) return false;
  tdo_search_corridor av;
  if (!build_avoid(gd, route, n, &av)) return false;
  tdo_search_input ai = ci;
  ai.grid = gd->shallow;
  ai.corridor = &av;
  if (tdo_search_run(gd->search, &ai, alt) != TDO_OK) return false;
  report->expansions += alt->expansions;
  return alt->cost <= cost * (1.0 + kAltMargin) &&
         cells_outside(alt->path, alt->n_path, route, n) >= kAltOutside;
}

// The query's search confined to the corridor of a coarse route, with voxel states: (voxel,
// heading) states flood the corridor as they flood the grid (geb079 G4 and G5: 0.55 and 1.1
// million expansions in about 1,000 cells).
tdo_status corridor_search(Guide* gd, tdo_search* fine, const tdo_search_input* in,
                           const tdo_voxel* route, uint32_t n, tdo_search_output* out,
                           GuideReport* report) {
  build_corridor(gd, route, n);
  report->corridor = gd->n_marked;
  tdo_search_input fi = *in;
  fi.corridor = &gd->corridor;
  fi.states = TDO_STATES_VOXEL;
  const tdo_status st = tdo_search_run(fine, &fi, out);
  clear_corridor(gd);
  report->expansions += out->expansions;
  return st;
}

// The guide applies to turn-penalised searches whose coarse grid fits; plain A* and bidirectional
// A* stay exact on the whole grid.
bool applies(const Guide* gd, const tdo_search_input* in) {
  const tdo_grid* g = in->grid;
  if (gd == nullptr || g == nullptr || !g->ready) return false;
  if (!search_headed(in)) return false;
  const int32_t e = (1 << gd->cap.shift) - 1;
  const uint64_t n = static_cast<uint64_t>((g->desc.nx + e) >> gd->cap.shift) *
                     static_cast<uint64_t>((g->desc.ny + e) >> gd->cap.shift) *
                     static_cast<uint64_t>((g->desc.nz + e) >> gd->cap.shift);
  return n <= gd->cap.max_cells;
}

// The expansion budget of a short query's whole-grid search; 0 when the query is not short.
uint32_t short_budget(const Guide* gd, const tdo_search_input* in) {
  tdo_voxel e[2];
  if (!tdo_grid_world_to_voxel(in->grid, in->start, &e[0]) ||
      !tdo_grid_world_to_voxel(in->grid, in->goal, &e[1]))
    return 0u;
  const int32_t d = abs(e[1].i - e[0].i) + abs(e[1].j - e[0].j) + abs(e[1].k - e[0].k);
  if (d > (kShortCells << gd->cap.shift)) return 0u;
  const uint32_t budget = kShortBudget * static_cast<uint32_t>(d) + kShortBase;
  return in->max_expansions != 0u && in->max_expansions < budget ? in->max_expansions : budget;
}

// A short query's search on the whole grid with voxel states (as the corridor's) and its budget:
// for so few voxels the coarse route and the corridor cost more than they save. TDO_OK or
// TDO_ERR_NO_PATH (voxel states reach every voxel plain A* reaches: a proof) are final; any other
// status (the budget spent) leaves the query to the corridor.
bool short_search(Guide* gd, tdo_search* fine, const tdo_search_input* in, tdo_search_output* out,
                  GuideReport* report, tdo_status* st) {
  const uint32_t budget = short_budget(gd, in);
  if (budget == 0u) return false;
  tdo_search_input wi = *in;
  wi.states = TDO_STATES_VOXEL;
  wi.max_expansions = budget;
  *st = tdo_search_run(fine, &wi, out);
  if (*st == TDO_OK || *st == TDO_ERR_NO_PATH) {
    report->used = 3;
    return true;
  }
  report->expansions = out->expansions;  // spent before the coarse route
  return false;
}

}  // namespace

GuideCapacity guide_capacity(uint32_t max_voxels, int32_t shift) {
  GuideCapacity cap{};
  if (shift < 1 || shift > 7) return cap;
  // A grid's cells: n / 8^shift plus the partial cells along its faces; max_voxels / 2^(2 shift +
  // 1) covers grids whose shortest axis has 2^(shift+1) voxels or more.
  const uint64_t cells = static_cast<uint64_t>(max_voxels) >> (2 * shift + 1);
  cap.max_cells = static_cast<uint32_t>(cells + 4096u);
  cap.max_nodes = cap.max_cells;
  cap.max_path = 4096u;
  cap.shift = shift;
  return cap;
}

size_t guide_footprint(const GuideCapacity& cap) {
  if (cap.max_cells == 0u) return 0u;
  const tdo_search_config sc = coarse_search_cfg(cap);
  return tdo_arena_round(sizeof(Guide)) + 2u * grid_footprint(coarse_grid_cap(cap)) +
         tdo_search_footprint(&sc) + tdo_arena_round(cap.max_cells * sizeof(uint32_t)) +
         tdo_arena_round(27u * cap.max_path * sizeof(uint32_t)) +
         tdo_arena_round(avoid_capacity(cap) * sizeof(uint32_t)) +
         2u * tdo_arena_round(cap.max_path * sizeof(tdo_voxel));
}

tdo_status guide_init(Guide** out, tdo_arena* arena, const GuideCapacity& cap) {
  *out = nullptr;
  if (cap.max_cells == 0u) return TDO_OK;  // no guide
  Guide* gd = static_cast<Guide*>(tdo_arena_alloc(arena, sizeof(Guide)));
  if (gd == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  memset(static_cast<void*>(gd), 0, sizeof(*gd));
  gd->cap = cap;
  tdo_status st = grid_init(&gd->coarse, arena, coarse_grid_cap(cap));
  if (st == TDO_OK) st = grid_init(&gd->shallow, arena, coarse_grid_cap(cap));
  if (st != TDO_OK) return st;
  const tdo_search_config sc = coarse_search_cfg(cap);
  st = tdo_search_init(&gd->search, arena, &sc);
  if (st != TDO_OK) return st;
  gd->max_marked = 27u * cap.max_path;
  gd->cells = static_cast<uint32_t*>(tdo_arena_alloc(arena, cap.max_cells * sizeof(uint32_t)));
  gd->marked = static_cast<uint32_t*>(tdo_arena_alloc(arena, gd->max_marked * sizeof(uint32_t)));
  gd->max_avoid = avoid_capacity(cap);
  gd->avoid = static_cast<uint32_t*>(tdo_arena_alloc(arena, gd->max_avoid * sizeof(uint32_t)));
  gd->route = static_cast<tdo_voxel*>(tdo_arena_alloc(arena, cap.max_path * sizeof(tdo_voxel)));
  gd->kept = static_cast<tdo_voxel*>(tdo_arena_alloc(arena, cap.max_path * sizeof(tdo_voxel)));
  if (gd->cells == nullptr || gd->marked == nullptr || gd->avoid == nullptr ||
      gd->route == nullptr || gd->kept == nullptr)
    return TDO_ERR_ARENA_TOO_SMALL;
  memset(gd->cells, 0, cap.max_cells * sizeof(uint32_t));
  *out = gd;
  return TDO_OK;
}

tdo_status guide_search(Guide* gd, tdo_search* fine, const tdo_search_input* in,
                        tdo_search_output* out, GuideReport* report) {
  memset(report, 0, sizeof(*report));
  if (!applies(gd, in)) return tdo_search_run(fine, in, out);
  tdo_status st_short = TDO_OK;
  if (short_search(gd, fine, in, out, report, &st_short)) return st_short;
  if ((gd->built_for != in->grid || gd->built_version != in->grid->version) &&
      build_coarse(gd, in->grid) != TDO_OK) {
    gd->built_for = nullptr;
    return tdo_search_run(fine, in, out);
  }
  tdo_search_input ci = *in;
  ci.grid = gd->coarse;
  ci.corridor = nullptr;
  ci.max_expansions = 0;
  // The coarse route is the shortest: turn-penalised coarse routes came out longer than plain A*'s
  // grid paths on geb079 (docs/design.md s.1).
  ci.kind = TDO_SEARCH_BIDIR;
  ci.lambda = 0.0;
  ci.mu = 0.0;
  ci.theta_max = 0.0;
  ci.d_th = 0.0;
  ci.first_meet = 0;
  tdo_search_output co;
  if (tdo_search_run(gd->search, &ci, &co) == TDO_OK && co.n_path <= gd->cap.max_path) {
    report->expansions += co.expansions;
    report->coarse_path = co.n_path;
    const uint32_t n = co.n_path;
    memcpy(gd->route, co.path, n * sizeof(tdo_voxel));
    // The second route's search first, its plan copied (gd->kept): the route's plan, the one
    // returned most often, is then the search's last and stays in place.
    tdo_search_output alt;      // the second coarse route
    tdo_search_output alt_out;  // its plan
    tdo_status st_alt = TDO_ERR_NO_PATH;
    if (second_route(gd, ci, gd->route, n, co.cost, &alt, report)) {
      st_alt = corridor_search(gd, fine, in, alt.path, alt.n_path, &alt_out, report);
      if (st_alt == TDO_OK && alt_out.n_path <= gd->cap.max_path) {
        memcpy(gd->kept, alt_out.path, alt_out.n_path * sizeof(tdo_voxel));
        alt_out.path = gd->kept;
      } else {
        st_alt = TDO_ERR_NO_PATH;  // no plan, or one longer than the copy's room
      }
    }
    const tdo_status st = corridor_search(gd, fine, in, gd->route, n, out, report);
    const bool alt_better = st_alt == TDO_OK && alt_out.cost < out->cost * (1.0 - kAltGain);
    if (st == TDO_OK || st_alt == TDO_OK) {
      if (st != TDO_OK || alt_better) *out = alt_out;
      report->used = 1;
      return TDO_OK;
    }
  }
  report->used = 2;
  // The whole grid with voxel states too: heading states flood it (Simple at clearance 0: 12.5 M
  // instructions per such query, against 0.3 M for the corridor's voxel states).
  tdo_search_input wi = *in;
  wi.states = TDO_STATES_VOXEL;
  return tdo_search_run(fine, &wi, out);
}

}  // namespace tdo_internal
