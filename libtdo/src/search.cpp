// Stage 1: A* and bidirectional A* over (voxel, heading) states (docs/design.md s.1).
//
// Without penalties a voxel is one state (the heading field only remembers the last step), so the
// search is plain A* over voxels. With lambda or mu > 0 a state is (voxel, heading); the states of
// one voxel form a chain from a per-voxel slot, so lookups, meetings and capacity stay bounded,
// and an expansion creates states only for the children near the smallest queued f (partial
// expansion, expand_headed), so the pools hold about as many states as the search expands.
//
// The mechanisms it uses have their own files: search_state.h (index widths, states, per-voxel
// slots and chains, the state pool, the context), search_open.h (open lists), search_tables.cpp
// (the retry's grid-distance tables), search_retry.cpp (the tries, their budgets and the
// voxel-state fallback) and search_headed.h (which queries are turn-penalised). This file keeps
// the costs, the expansions and the search loop.
#include "tdo/search.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "tdo/config.h"
#if defined(__SSE2__)
#include <emmintrin.h>  // the scalar square root (sqrt_sd)
#endif

#include "directions.h"
#include "grid_internal.h"
#include "search_ends.h"
#include "search_headed.h"
#include "search_open.h"
#include "search_retry.h"
#include "search_state.h"
#include "search_tables.h"
#include "vec3.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {
namespace {

// Offsets of the steps as a table: the voxel-state relaxation reads them instead of dividing.
struct StepDelta {
  int8_t d[kNumDirs][3];
};
constexpr StepDelta make_step_delta() {
  StepDelta t{};
  for (int e = 0; e < kNumDirs; ++e) {
    t.d[e][0] = static_cast<int8_t>(dir_dx(e));
    t.d[e][1] = static_cast<int8_t>(dir_dy(e));
    t.d[e][2] = static_cast<int8_t>(dir_dz(e));
  }
  return t;
}
constexpr StepDelta kStepDelta = make_step_delta();

// Parent-step pruning of voxel-state expansions as bit operations: a neighbour u + e of state u,
// reached from its parent p = u - s over search-sense step s, was offered by p already when
// u + e = p + c for a legal step c of p (or u + e = p). The legal steps of p as a mask of the 27
// cells of p's 3x3x3 block, moved by s (one shift: cell index steps are 1, 3 and 9 per axis),
// are then cells of u's block; `keep[s]` drops the cells that wrapped around (outside u's block).
struct PruneTable {
  uint32_t keep[kNumDirs];  // cells o of u's block with o + s inside p's block
  uint8_t shift[kNumDirs];  // 13 + cell index offset of s (right shift of the mask << 13)
  uint32_t back[kNumDirs];  // direction bit of -s (u + e = p)
};
constexpr PruneTable make_prune_table() {
  PruneTable t{};
  for (int s = 0; s < kNumDirs; ++s) {
    const int dx = dir_dx(s), dy = dir_dy(s), dz = dir_dz(s);
    t.shift[s] = static_cast<uint8_t>(13 + dx + 3 * dy + 9 * dz);
    t.keep[s] = 0;
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
          if (x + dx >= -1 && x + dx <= 1 && y + dy >= -1 && y + dy <= 1 && z + dz >= -1 &&
              z + dz <= 1)
            t.keep[s] |= 1u << cell_of(x, y, z);
    t.back[s] = 1u << dir_opposite(s);
  }
  return t;
}
constexpr PruneTable kPrune = make_prune_table();

// Direction mask with bit d moved to bit dir_opposite(d) = 25 - d: a bit reversal of the 26 bits.
constexpr uint32_t opposite_mask(uint32_t m) {
  m = ((m >> 1) & 0x55555555u) | ((m & 0x55555555u) << 1);
  m = ((m >> 2) & 0x33333333u) | ((m & 0x33333333u) << 2);
  m = ((m >> 4) & 0x0F0F0F0Fu) | ((m & 0x0F0F0F0Fu) << 4);
  m = ((m >> 8) & 0x00FF00FFu) | ((m & 0x00FF00FFu) << 8);
  m = (m >> 16) | (m << 16);
  return m >> (32 - kNumDirs);  // bit d went to 31 - d
}
constexpr bool opposite_mask_ok() {
  for (int d = 0; d < kNumDirs; ++d)
    if (opposite_mask(1u << d) != 1u << dir_opposite(d)) return false;
  return true;
}
static_assert(opposite_mask_ok(), "opposite_mask");

// Steps of u that its parent (search-sense step s away, legal steps p_moves) offered already.
constexpr uint32_t pruned_steps(int s, uint32_t p_moves) {
  const uint64_t moved = (static_cast<uint64_t>(cells_of_dirs(p_moves)) << 13) >> kPrune.shift[s];
  return dirs_of_cells(static_cast<uint32_t>(moved) & kPrune.keep[s]) | kPrune.back[s];
}

// The same set step by step: e is pruned when s then e undoes s, or is one step c of p's mask.
// Bitwise, so checking every single-bit mask checks them all (compile time).
constexpr bool prune_table_ok() {
  for (int s = 0; s < kNumDirs; ++s)
    for (int c = 0; c <= kNumDirs; ++c) {
      const uint32_t p_moves = c < kNumDirs ? 1u << c : 0u;
      uint32_t want = 0;
      for (int e = 0; e < kNumDirs; ++e) {
        const int x = dir_dx(s) + dir_dx(e), y = dir_dy(s) + dir_dy(e), z = dir_dz(s) + dir_dz(e);
        if (x == 0 && y == 0 && z == 0)
          want |= 1u << e;
        else if (x >= -1 && x <= 1 && y >= -1 && y <= 1 && z >= -1 && z <= 1 &&
                 ((p_moves >> dir_of_cell(cell_of(x, y, z))) & 1u) != 0)
          want |= 1u << e;
      }
      if (pruned_steps(s, p_moves) != want) return false;
    }
  return true;
}
static_assert(prune_table_ok(), "parent-step pruning mask");

// A hint to load the cache line at p (GCC drops __builtin_prefetch here, so x86 gets the
// instruction itself; a prefetch never faults).
inline void prefetch(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  __asm__ volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p);
#endif
}

inline int32_t iabs(int32_t a) { return a < 0 ? -a : a; }

// 3D octile distance over (a, b, c) voxels along the axes.
inline double octile_of(int32_t a, int32_t b, int32_t c, double res) {
  if (a < b) {
    const int32_t t = a;
    a = b;
    b = t;
  }
  if (b < c) {
    const int32_t t = b;
    b = c;
    c = t;
  }
  if (a < b) {
    const int32_t t = a;
    a = b;
    b = t;
  }
  return res * (static_cast<double>(a) + (kSqrt2 - 1.0) * static_cast<double>(b) +
                (kSqrt3 - kSqrt2) * static_cast<double>(c));
}

// 3D octile distance to the side's target: admissible and consistent for the length part of the
// cost.
inline double octile(const Side& s, int32_t x, int32_t y, int32_t z, double res) {
  return octile_of(iabs(x - s.tx), iabs(y - s.ty), iabs(z - s.tz), res);
}

// Voxel-state searches (no heading costs) count g, h and f in voxel edges with the step lengths
// sqrt 2 and sqrt 3 rounded to multiples of 2^-kQuantBits: every g, h and f is then such a multiple
// below 2^(53 - kQuantBits), so the doubles add exactly (up to paths of 2^21 voxel edges; beyond,
// ordinary rounding). Equal sums of steps are equal bit for bit, whatever the order: a step towards
// the target along the octile path keeps f exactly, and such children take the LIFO stack rather
// than the heap (with real-valued sums rounding made f rise or fall by an ulp at random). The
// rounded lengths differ from the true ones by at most 2^-33 relative, so the path found is
// optimal for the true lengths within 2^-32 voxel edges per step; the reported costs are summed
// from the path with the true lengths.
constexpr int kQuantBits = 32;
constexpr double kQuant = 4294967296.0;  // 2^kQuantBits
constexpr double kSqrt2Q =
    static_cast<double>(static_cast<uint64_t>(kSqrt2 * kQuant + 0.5)) / kQuant;
constexpr double kSqrt3Q =
    static_cast<double>(static_cast<uint64_t>(kSqrt3 * kQuant + 0.5)) / kQuant;
static_assert(kQuantBits == 32, "kQuant");

// Octile distance of the voxel-state searches in voxel edges with the rounded lengths, without a
// branch per comparison: (hi - mid) face steps, (mid - lo) edge diagonals, lo corner diagonals,
// each term exact (at most 17 + 33 significant bits).
// Written as sum + (K2 - 2) (mid + lo) + (K3 - 2 K2 + 1) lo, which needs the largest and the
// smallest difference but not the middle one: the same exact value.
inline double octile_voxel(const Side& s, int32_t x, int32_t y, int32_t z) {
  const int32_t a = iabs(x - s.tx), b = iabs(y - s.ty), c = iabs(z - s.tz);
  const int32_t ab_max = a > b ? a : b, ab_min = a > b ? b : a;
  const int32_t hi = ab_max > c ? ab_max : c;
  const int32_t lo = ab_min < c ? ab_min : c;
  const int32_t sum = a + b + c;
  return static_cast<double>(sum) + (kSqrt2Q - 2.0) * static_cast<double>(sum - hi) +
         (kSqrt3Q - 2.0 * kSqrt2Q + 1.0) * static_cast<double>(lo);
}

// Square root of x >= 0, correctly rounded as IEEE 754 requires of sqrt() (the same bits). GCC
// calls libm's sqrt out of line in parts of the search (errno handling), which spills the
// registers around every call; the instruction itself cannot set errno.
inline double sqrt_nonneg(double x) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_setzero_pd(), _mm_set_sd(x)));
#else
  return sqrt(x);
#endif
}

// acos on [-1, 1] by Abramowitz and Stegun 4.4.46 (absolute error <= 2e-8 rad): the deviation
// only orders the open list, and libm's acos was a tenth of a turn-penalised search's time.
inline double acos_fast(double c) {
  const double x = c < 0.0 ? -c : c;
  const double p =
      1.5707963050 +
      x * (-0.2145988016 +
           x * (0.0889789874 +
                x * (-0.0501743046 +
                     x * (0.0308918810 +
                          x * (-0.0170881256 + x * (0.0066700901 + x * -0.0012624911))))));
  const double r = sqrt_nonneg(1.0 - x) * p;
  return c < 0.0 ? kPi - r : r;
}

// Deviation in [0,1] of travel direction `travel` from the target direction (vx, vy, vz) of norm
// n > 0 (voxel units).
inline double deviation_to(const tdo_search* ctx, int travel, double vx, double vy, double vz,
                           double n) {
  double c =
      (ctx->unit[travel][0] * vx + ctx->unit[travel][1] * vy + ctx->unit[travel][2] * vz) / n;
  if (c > 1.0) c = 1.0;
  if (c < -1.0) c = -1.0;
  return acos_fast(c) * (1.0 / kPi);
}

// Deviation in [0,1]: angle between the search's travel direction and the direction to its target.
inline double deviation(const tdo_search* ctx, const Side& s, int travel, int32_t x, int32_t y,
                        int32_t z) {
  if (travel >= kNumDirs) return 0.0;
  const double vx = s.tx - x, vy = s.ty - y, vz = s.tz - z;
  const double n = sqrt_nonneg(vx * vx + vy * vy + vz * vz);
  if (!(n > 0.0)) return 0.0;
  return deviation_to(ctx, travel, vx, vy, vz, n);
}

// deviation() of a voxel-state search, and the split of turn_bound: from the table
// (VoxelTurnTables.dev) near the target, else computed (split -2).
inline DevEntry deviation_voxel(const tdo_search* ctx, const Side& s, int travel, int32_t x,
                                int32_t y, int32_t z) {
  const VoxelTurnTables* t = ctx->vtt;
  const int32_t vx = s.tx - x, vy = s.ty - y, vz = s.tz - z;
  const int32_t ax = iabs(vx), ay = iabs(vy), az = iabs(vz);
  if (t == nullptr || travel >= kNumDirs || (ax | ay | az) >= kDevAxis)
    return DevEntry{deviation(ctx, s, travel, x, y, z), -2.0};
  const int m = (vx < 0 ? 1 : 0) | (vy < 0 ? 2 : 0) | (vz < 0 ? 4 : 0);
  return t->dev[az][ay][ax][t->reflect[m][travel]];
}

// Least turn penalty (m) still to pay from a state whose heading deviates by T = dev*pi from the
// target direction: the turns must add up to T (the path's later steps would otherwise stay in a
// cone that misses the target) and each is at least kMinTurn = m. With n turns the penalty is at
// least lambda/pi^2 * max(T^2 / n, n m^2) (convex penalty: equal turns are cheapest); the smallest
// over n is min(T^2 / floor(T/m), ceil(T/m) m^2), a lower bound (`exact`: A* and the optimal stop
// of bidir need it). The first-meet search (the paper's stop, no optimality claim) is guided by
// T^2 / floor(T/m) alone, which can exceed the bound between multiples of m by up to
// lambda (m/pi)^2 (docs/performance.md: the plans it finds have fewer turns on Map5).
inline double turn_bound(const tdo_search* ctx, const Query& q, double dev) {
  if (!(dev > 1e-9) || !(ctx->turn_lambda > 0.0)) return 0.0;
  // dev in (0, 1], so the quotient is in (0, 5.2): truncation is the floor, without a libm call.
  const double k = static_cast<double>(static_cast<int>(dev * kPi / kMinTurn));
  if (k < 1.0) return ctx->turn_lambda * dev * dev;
  const double split = dev * dev / k;
  if (!q.exact_turns) return ctx->turn_lambda * split;
  const double m = kMinTurn / kPi;
  const double more = (k + 1.0) * m * m;
  return ctx->turn_lambda * (split < more ? split : more);
}

// turn_bound() of a deviation with its split from the table (DevEntry; -2: not there): the same
// arithmetic without the divisions.
inline double turn_bound_split(const tdo_search* ctx, const Query& q, const DevEntry& e) {
  const double dev = e.dev;
  if (!(dev > 1e-9) || !(ctx->turn_lambda > 0.0)) return 0.0;
  if (e.split < -1.5 || q.exact_turns) return turn_bound(ctx, q, dev);
  if (e.split < 0.0) return ctx->turn_lambda * dev * dev;  // below one kMinTurn
  return ctx->turn_lambda * e.split;
}

// Heuristic of a state at voxel v = (x, y, z): the octile distance, or with an exact table the
// larger of it and the table's bound (both are consistent lower bounds of the remaining length).
inline double heuristic(const Side& s, uint32_t v, int32_t x, int32_t y, int32_t z, double res) {
  const double o = octile(s, x, y, z, res);
  if (s.hx == nullptr) return o;
  const double e = static_cast<double>(s.hx[v]);
  return e > o ? e : o;
}

// Priority of a turn-penalised state given by its fields (cost g, voxel v at (x, y, z), heading);
// its heuristic goes to *h_out.
inline double priority_headed(const tdo_search* ctx, const Query& q, const Side& s, int back,
                              double g, uint32_t v, int32_t x, int32_t y, int32_t z, int heading,
                              double* h_out) {
  const double h = heuristic(s, v, x, y, z, q.grid->desc.res);
  *h_out = h;
  if (heading >= kNumDirs || !q.dev_terms) return g + q.h_weight * h;
  const int travel = back ? dir_opposite(heading) : heading;
  const double dev = deviation(ctx, s, travel, x, y, z);
  return g + q.h_weight * (h + turn_bound(ctx, q, dev)) + q.mu * dev;
}

template <bool kHeaded>
inline double priority(const tdo_search* ctx, const Query& q, const Side& s, int back,
                       const Node& n, float* h_out) {
  if (kHeaded) {
    double h;
    const double f = priority_headed(ctx, q, s, back, n.g, n.voxel, n.x, n.y, n.z, n.heading, &h);
    *h_out = static_cast<float>(h);
    return f;
  }
  double h = octile_voxel(s, n.x, n.y, n.z);
  if (q.voxel_turns && s.hx != nullptr) {
    const double e = static_cast<double>(s.hx[n.voxel]) * q.inv_res;
    h = e > h ? e : h;
  }
  *h_out = static_cast<float>(h);
  if (!q.voxel_turns) return n.g + h;
  if (n.heading >= kNumDirs || !q.dev_terms) return n.g + q.h_weight * h;
  const DevEntry e =
      deviation_voxel(ctx, s, back ? dir_opposite(n.heading) : n.heading, n.x, n.y, n.z);
  const double dev = e.dev;
  return n.g + q.h_weight * (h + turn_bound_split(ctx, q, e) * q.inv_res) + q.mu * q.inv_res * dev;
}

// The parts of a turn-penalised state's priority that depend on its voxel alone: the heuristic and
// the vector to the side's target (deviation() in parts), shared by the pivots of one voxel.
struct Target {
  double h;           // m, heuristic()
  double vx, vy, vz;  // voxels, target minus voxel
  double n;           // voxels, norm of (vx, vy, vz)
};

inline Target target_of(const Query& q, const Side& s, const Node& u) {
  Target t;
  t.h = heuristic(s, u.voxel, u.x, u.y, u.z, q.grid->desc.res);
  t.vx = s.tx - u.x;
  t.vy = s.ty - u.y;
  t.vz = s.tz - u.z;
  t.n = q.dev_terms ? sqrt_nonneg(t.vx * t.vx + t.vy * t.vy + t.vz * t.vz)
                    : 0.0;  // unused without them
  return t;
}

// priority<true>() of a state with cost g and `heading` in the voxel of t: the same arithmetic, so
// the same bits.
inline double priority_at(const tdo_search* ctx, const Query& q, int back, double g, int heading,
                          const Target& t) {
  if (heading >= kNumDirs || !q.dev_terms) return g + q.h_weight * t.h;
  const int travel = back ? dir_opposite(heading) : heading;
  const double dev = t.n > 0.0 ? deviation_to(ctx, travel, t.vx, t.vy, t.vz, t.n) : 0.0;
  return g + q.h_weight * (t.h + turn_bound(ctx, q, dev)) + q.mu * dev;
}

// The A* fast path: a child whose f does not exceed the expanded state's goes on the LIFO stack
// (unidirectional A* only, while there is room). Returns false when the open list must take it.
inline bool push_stack(Side& s, uint32_t idx, double f) {
  if (!s.use_stack || f > s.f_cur || s.n_stack >= kStackCap) return false;
  s.stack[s.n_stack].f = f;
  s.stack[s.n_stack].node = static_cast<Index>(idx);
  ++s.n_stack;
  s.nodes[idx].heap = kInStack;
  return true;
}

// push() of a turn-penalised state whose f and h are known.
inline void push_headed(Side& s, uint32_t idx, double f, double h) {
  OpenItem it;
  it.node = static_cast<Index>(idx);
  it.f = f;
  it.h = static_cast<float>(h);
  if (!push_stack(s, idx, it.f)) enqueue(s, it);
}

// Queue state idx with its priority; inlined into the voxel-state relaxation (kHeaded false).
template <bool kHeaded>
inline void push(tdo_search* ctx, const Query& q, Side& s, int back, uint32_t idx) {
  OpenItem it;
  float h;
  it.node = static_cast<Index>(idx);
  it.f = priority<kHeaded>(ctx, q, s, back, s.nodes[idx], &h);
  it.h = h;
  if (!push_stack(s, idx, it.f)) {
    enqueue(s, it);
  } else if (!kHeaded) {
    prefetch(q.grid->moves + s.nodes[idx].voxel);  // expanded soon
  }
}

// A pivot state turned in place: its parent holds the same voxel.
inline bool is_pivot(const Side& s, const Node& n) {
  return n.parent != kNil && s.nodes[n.parent].voxel == n.voxel;
}

// A join of headings hf (forward) and hb (backward) beyond theta_max is a pivot.
inline bool sharp_join(const tdo_search* ctx, const Query& q, int hf, int hb) {
  return q.constrained && hf < kNumDirs && hb < kNumDirs && ((ctx->cand[hf] >> hb) & 1u) == 0;
}

// Voxel-state searches with turn costs (tdo_search_input.states): the turn from heading a to b in
// voxel edges, plus the pivot surcharge when it is beyond theta_max (a sharp step is taken
// directly at the price of a pivot).
inline double voxel_turn(const tdo_search* ctx, const Query& q, int a, int b) {
  const double t = ctx->turn[a][b] + (sharp_join(ctx, q, a, b) ? q.pivot_cost : 0.0);
  return t * q.inv_res;
}

// voxel_turn() from the table when the search has one (the same bits).
inline double vturn_of(const tdo_search* ctx, const Query& q, int a, int b) {
  return ctx->vtt != nullptr ? ctx->vtt->vturn[a][b] : voxel_turn(ctx, q, a, b);
}

// Offer the state just reached on side `a` as a meeting point with every state of the other side
// in the same voxel; the join adds the turn between the two headings.
template <bool kHeaded>
inline void meet(tdo_search* ctx, Query& q, int a, uint32_t idx) {
  const Side& me = ctx->side[a];
  const Side& other = ctx->side[1 - a];
  const Node& n = me.nodes[idx];
  // Voxel-state searches: a voxel outside the box of the other side's states holds none of them
  // (the box spares the read of its slot, a cache miss while the sides are apart).
  if (!kHeaded && kStateBox &&
      (n.x < other.box_lo[0] || n.x > other.box_hi[0] || n.y < other.box_lo[1] ||
       n.y > other.box_hi[1] || n.z < other.box_lo[2] || n.z > other.box_hi[2]))
    return;
  for (uint32_t o = slot_first(other, n.voxel); o != kNil; o = other.nodes[o].next) {
    const Node& m = other.nodes[o];
    double c = n.g + m.g;
    if (kHeaded) {
      const int hf = a == 0 ? n.heading : m.heading, hb = a == 0 ? m.heading : n.heading;
      // A pivot state continues straight on, through a state of the other side that did not turn
      // there: any other join would turn twice in one voxel and split one turn's price.
      const bool pn = is_pivot(me, n), pm = is_pivot(other, m);
      if ((pn || pm) && (pn == pm || hf != hb)) continue;
      c += ctx->turn[hf][hb];
      if (sharp_join(ctx, q, hf, hb)) c += q.pivot_cost;  // the join itself is a sharp turn
    } else if (q.voxel_turns) {
      c += vturn_of(ctx, q, a == 0 ? n.heading : m.heading, a == 0 ? m.heading : n.heading);
    }
    if (c < q.best) {
      q.best = c;
      q.meet[a] = idx;
      q.meet[1 - a] = o;
    }
  }
}

// Turn-penalised searches: offer state (w, heading) at cost ng, priority f and heuristic h
// (priority_headed or priority_at of these fields) with parent ui over forward-sense step `step`
// (-1: a pivot, the same voxel): create it, or lower its cost. Voxel-state searches use
// relax_voxel. u: a copy of state ui.
inline tdo_status relax(tdo_search* ctx, Query& q, int back, uint32_t ui, const Node& u, uint32_t w,
                        int heading, int step, double ng, double f, double h) {
  Side& s = ctx->side[back];
  const uint32_t first = slot_first(s, w);
  uint32_t idx = find_state(s, w, heading);
  if (idx != kNil) {
    Node& n = s.nodes[idx];
    if (n.heap == kNil || !(ng < n.g)) return TDO_OK;  // closed, or no cheaper
    n.g = ng;
    n.parent = static_cast<Index>(ui);
    n.heading = static_cast<uint8_t>(heading);
    if (n.heap != kInStack) {  // on the stack f only fell: it stays next in line
      OpenItem it;
      it.node = static_cast<Index>(idx);
      it.f = f;
      it.h = static_cast<float>(h);
      sift_up(s, n.heap, it);
    }
  } else {
    const int dx = step >= 0 ? kStepDelta.d[step][0] : 0;
    const int dy = step >= 0 ? kStepDelta.d[step][1] : 0;
    const int dz = step >= 0 ? kStepDelta.d[step][2] : 0;
    idx = new_state(ctx, s, ui, u, w, ng, dx, dy, dz, heading, first);
    if (idx == kNil) return TDO_ERR_NODE_CAPACITY;
    index_state(s, w, heading, idx, first == kNil);
    slot_set(s, w, idx);
    push_headed(s, idx, f, h);
  }
  if (q.bidir) meet<true>(ctx, q, back, idx);
  return TDO_OK;
}

constexpr uint32_t kAllCells =
    (1u << kNumHeadings) - 1u;  // a corridor cell with every neighbour in

// Class of a voxel's place along one axis of its coarse cell (m = cell edge - 1): 0 on the low
// face, 2 on the high face, 1 inside (kCorridorSteps).
inline int axis_class(int32_t c, int32_t m) { return (c & m) == 0 ? 0 : ((c & m) == m ? 2 : 1); }

// kCorridorSteps.m[a][n]: the steps from a voxel whose place in its coarse cell is class a (per
// axis 0 low face, 1 inside, 2 high face: a = ax + 3 ay + 9 az) that land in the neighbour cell n
// (cell_of numbering): a step leaves the cell on an axis where the voxel is on the low face and
// the step goes down, or on the high face and it goes up. A constant table (read-only memory).
struct CorridorSteps {
  uint32_t m[kNumHeadings][kNumHeadings];
};
constexpr int corridor_cross(int c, int d) {
  return c == 0 && d < 0 ? -1 : (c == 2 && d > 0 ? 1 : 0);
}
constexpr CorridorSteps make_corridor_steps() {
  CorridorSteps t{};
  for (int a = 0; a < kNumHeadings; ++a)
    for (int d = 0; d < kNumDirs; ++d)
      t.m[a][cell_of(corridor_cross(a % 3, dir_dx(d)), corridor_cross((a / 3) % 3, dir_dy(d)),
                     corridor_cross(a / 9, dir_dz(d)))] |= 1u << d;
  return t;
}
constexpr CorridorSteps kCorridorSteps = make_corridor_steps();

// The steps from voxel (x,y,z) that stay in the corridor: those whose voxel's coarse cell is in it.
// A voxel inside its cell, or in a cell whose 26 neighbours are all in, loses none.
inline uint32_t corridor_steps(const tdo_search_corridor* c, int32_t x, int32_t y, int32_t z) {
  const int32_t sh = c->shift;
  const uint32_t cell = static_cast<uint32_t>(
      (x >> sh) + c->cnx * ((y >> sh) + c->cny * static_cast<int64_t>(z >> sh)));
  const uint32_t in = c->cells[cell];
  if (in == kAllCells) return kAllMoves;
  const int32_t m = (1 << sh) - 1;
  const int a = axis_class(x, m) + 3 * axis_class(y, m) + 9 * axis_class(z, m);
  uint32_t out = 0;  // steps into cells outside the corridor
  for (uint32_t b = ~in & kAllCells; b != 0; b &= b - 1u)
    out |= kCorridorSteps.m[a][__builtin_ctz(b)];
  return kAllMoves & ~out;
}

// The legal steps of state u: the grid's, confined to the corridor when there is one.
inline uint32_t legal_steps(const Query& q, const Node& u) {
  const uint32_t moves = q.grid->moves[u.voxel];
  if (q.corridor == nullptr) return moves;
  return moves & corridor_steps(q.corridor, u.x, u.y, u.z);
}

// Split the legal search-sense steps of state u into those expanded directly and the sharp ones
// (beyond theta_max of the heading, or deviating more than D_th) reached only through a pivot.
// Straight ahead is always direct, and a pivot state only goes straight on: so every turn of a path
// is paid exactly once, and every legal step stays reachable from every state (completeness).
template <bool kHeaded>
inline void classify(const tdo_search* ctx, const Query& q, int back, const Node& u,
                     uint32_t* direct, uint32_t* sharp) {
  const uint32_t moves = legal_steps(q, u);
  *direct = moves;
  *sharp = 0;
  if (!kHeaded || u.heading >= kNumDirs) return;
  const Side& s = ctx->side[back];
  const int travel = back ? dir_opposite(u.heading) : u.heading;
  if (is_pivot(s, u)) {  // it turned in place already: it goes straight on
    *direct = moves & (1u << travel);
    return;
  }
  *direct = moves & ctx->cand[travel];
  *sharp = moves & ~ctx->cand[travel];
  if (q.d_th > 0.0) {
    for (uint32_t m = *direct & ~(1u << travel); m != 0; m &= m - 1u) {
      const int e = __builtin_ctz(m);
      if (deviation(ctx, s, e, u.x + dir_dx(e), u.y + dir_dy(e), u.z + dir_dz(e)) > q.d_th) {
        *direct &= ~(1u << e);
        *sharp |= 1u << e;
      }
    }
  }
}

// The tables of voxel-state searches with turn costs: voxel_turn() of every pair of headings
// (VoxelTurnTables.vturn) and the dominance table (VoxelTurnTables.prune): a neighbour
// w = p + c of the parent p is left out of u's expansion when p's own offer of it, step length plus
// turn, undercuts the way through u by a margin, so the relaxation could not lower w's cost: the
// pruning of the plain searches (pruned_steps) restricted to the steps where the turns keep the
// triangle inequality. Built once per lambda, pivot cost and voxel edge.
void vt_prune_ensure(tdo_search* ctx, const Query& q) {
  VoxelTurnTables* t = ctx->vtt;
  if (t == nullptr) return;
  const double key[4] = {ctx->turn_lambda, q.constrained ? q.pivot_cost : -1.0, q.inv_res,
                         ctx->cand_theta};
  if (memcmp(key, t->key, sizeof(key)) == 0) return;
  for (int a = 0; a < kNumHeadings; ++a)
    for (int b = 0; b < kNumHeadings; ++b) t->vturn[a][b] = voxel_turn(ctx, q, a, b);
  constexpr double kMargin = 1e-6;  // voxel edges: far above the rounding of the costs
  for (int back = 0; back < 2; ++back)
    for (int hp = 0; hp < kNumHeadings; ++hp)
      for (int si = 0; si < kNumDirs; ++si) {
        const int d_pu = back ? dir_opposite(si) : si;
        const double via_u0 = ctx->step_q[si] + t->vturn[hp][d_pu];
        uint32_t m = 0;
        // The steps e with si + e a step (not back to p): pruned_steps' cells.
        for (uint32_t b = pruned_steps(si, kAllMoves) & ~kPrune.back[si]; b != 0; b &= b - 1u) {
          const int e = __builtin_ctz(b);
          const int c = dir_of_cell(
              cell_of(dir_dx(si) + dir_dx(e), dir_dy(si) + dir_dy(e), dir_dz(si) + dir_dz(e)));
          const int d_uw = back ? dir_opposite(e) : e;
          const int d_pw = back ? dir_opposite(c) : c;
          const double via_p = ctx->step_q[c] + t->vturn[hp][d_pw];
          const double via_u = via_u0 + ctx->step_q[e] + t->vturn[d_pu][d_uw];
          if (via_p + kMargin <= via_u) m |= 1u << e;
        }
        t->prune[back][hp][si] = m;
      }
  memcpy(t->key, key, sizeof(key));
}

// Grow the box of side s's states (Side.box_lo) by the 3x3x3 block of state n, which is being
// expanded: every state is the root or a child of an expanded state, so the box holds them all.
inline void box_add(Side& s, const Node& n) {
  if (!kStateBox) return;
  const int32_t c[3] = {n.x, n.y, n.z};
  for (int k = 0; k < 3; ++k) {
    s.box_lo[k] = c[k] - 1 < s.box_lo[k] ? c[k] - 1 : s.box_lo[k];
    s.box_hi[k] = c[k] + 1 > s.box_hi[k] ? c[k] + 1 : s.box_hi[k];
  }
}

// Voxel-state searches (no heading costs): offer voxel w, whose open state is `idx` (kNil: not
// reached yet), at cost ng with parent ui over search-sense step e (forward-sense d): relax
// without the heading lookup, the closed test (the slot word holds it) and the heading index.
inline tdo_status relax_voxel(tdo_search* ctx, Query& q, int back, uint32_t ui, uint32_t w, int e,
                              int d, double ng, uint32_t idx) {
  Side& s = ctx->side[back];
  if (idx != kNil) {
    Node& n = s.nodes[idx];
    if (!(ng < n.g)) return TDO_OK;
    n.g = ng;
    n.parent = static_cast<Index>(ui);
    n.heading = static_cast<uint8_t>(d);
    if (n.heap != kInStack) {  // on the stack f only fell: it stays next in line
      OpenItem it;
      float h;
      it.node = static_cast<Index>(idx);
      it.f = priority<false>(ctx, q, s, back, n, &h);
      it.h = h;
      if (n.heap >= kBucketBit) {  // in a later bucket (kNil and kInStack do not come here)
        unlink(s, idx);
        enqueue(s, it);
      } else {
        sift_up(s, n.heap, it);
      }
    }
  } else {
    idx = new_state(ctx, s, ui, s.nodes[ui], w, ng, kStepDelta.d[e][0], kStepDelta.d[e][1],
                    kStepDelta.d[e][2], d, kNil);
    if (idx == kNil) return TDO_ERR_NODE_CAPACITY;
    slot_set(s, w, idx);
    push<false>(ctx, q, s, back, idx);
  }
  if (q.bidir) meet<false>(ctx, q, back, idx);
  return TDO_OK;
}

// Expansion of a voxel state: a neighbour one legal step away from u's parent p was already offered
// by p at no greater cost (triangle inequality of step lengths), so it is skipped unlooked-up. The
// slots of the other neighbours are read first (their cache misses overlap), then the neighbours
// are relaxed in step order as before.
tdo_status expand_voxel(tdo_search* ctx, Query& q, int back, uint32_t ui) {
  Side& s = ctx->side[back];
  const tdo_grid* g = q.grid;
  const Node u = s.nodes[ui];
  uint32_t mask = legal_steps(q, u);  // search-sense steps
  if (u.parent != kNil) {
    const int s_in = back ? dir_opposite(u.heading) : u.heading;  // search-sense step p -> u
    const uint32_t p_moves = g->moves[static_cast<int64_t>(u.voxel) - ctx->offset[s_in]];
    uint32_t pruned = pruned_steps(s_in, p_moves);
    if (q.voxel_turns)  // p offered those for less only where the turns allow (vt_prune_ensure)
      pruned = ctx->vtt != nullptr
                   ? pruned & (ctx->vtt->prune[back][s.nodes[u.parent].heading][s_in] |
                               kPrune.back[s_in])
                   : 0u;
    mask &= ~pruned;
  }
  uint32_t state[kNumDirs];  // open state of each step's voxel, kNil when not reached yet
  for (uint32_t m = mask; m != 0; m &= m - 1u) {
    const int e = __builtin_ctz(m);
    const uint32_t w = static_cast<uint32_t>(static_cast<int64_t>(u.voxel) + ctx->offset[e]);
    const uint32_t i = s.slot[w];
    if (i != kNil && (i & kSlotClosed) != 0) {
      mask &= ~(1u << e);  // expanded already
      continue;
    }
    state[e] = i;
  }
  for (; mask != 0; mask &= mask - 1u) {
    const int e = __builtin_ctz(mask);
    const uint32_t w = static_cast<uint32_t>(static_cast<int64_t>(u.voxel) + ctx->offset[e]);
    const int d = back ? dir_opposite(e) : e;
    const double ng = u.g + ctx->step_q[e] + (q.voxel_turns ? vturn_of(ctx, q, u.heading, d) : 0.0);
    const tdo_status st = relax_voxel(ctx, q, back, ui, w, e, d, ng, state[e]);
    if (st != TDO_OK) return st;
  }
  return TDO_OK;
}

// A child of a turn-penalised state that need not be offered: its state exists and is closed, or
// costs no more.
inline bool settled(const Side& s, uint32_t w, int heading, double ng) {
  const uint32_t idx = find_state(s, w, heading);
  return idx != kNil && (s.nodes[idx].heap == kNil || !(s.nodes[idx].g < ng));
}

// Expansion of a turn-penalised state with deferred children (partial expansion): of the children
// of closed state ui (its direct steps, and its pivots: turning in place to a sharp step at the
// turn cost plus the pivot surcharge, so every legal step stays reachable and the search complete)
// only those whose f does not exceed `limit` become states. The others wait behind one open-list
// item of ui (kDeferItem) whose f is the smallest of theirs and whose h field holds the set of
// their search-sense steps (`todo`); popped, it calls this again with its f plus
// q.defer_margin as the limit (offering at least the child at that f, so an item comes back at
// most 26 times). A state's cost is final once it is closed, so its children's f are the same bits
// every time. The search loop's limit is the next queued f plus q.defer_margin: children that
// close are created at once (the turn of a direct step costs at most pivot_cost, and the margin
// adds one voxel edge), which saves most item pops; the sharp turns and the children far above
// wait, and most are never offered. Map1: 3,517 states for 2,527 expansions instead of 11,971 for
// 2,652 (docs/performance.md). A child in a voxel that the other side has reached is offered at
// once, so a meeting is seen as soon as both sides have a state there.
tdo_status expand_headed(tdo_search* ctx, Query& q, int back, uint32_t ui, double limit,
                         uint32_t todo) {
  Side& s = ctx->side[back];
  const Side& other = ctx->side[1 - back];
  const Node u = s.nodes[ui];
  uint32_t direct;  // search-sense steps expanded directly
  uint32_t sharp;   // search-sense steps reached through a pivot only
  classify<true>(ctx, q, back, u, &direct, &sharp);
  direct &= todo;
  sharp &= todo;
  const double* turn_row = ctx->turn[u.heading];  // symmetric: turn[d][h] = turn[h][d]
  double next = HUGE_VAL;                         // smallest f of a deferred child
  uint32_t left = 0;                              // search-sense steps of the deferred children
  for (uint32_t mask = direct; mask != 0; mask &= mask - 1u) {
    const int e = __builtin_ctz(mask);         // search-direction step
    const int d = back ? dir_opposite(e) : e;  // forward-sense direction of the step
    const uint32_t w = static_cast<uint32_t>(static_cast<int64_t>(u.voxel) + ctx->offset[e]);
    const double ng = u.g + ctx->step_len[e] + turn_row[d];
    double h;
    const double f =
        priority_headed(ctx, q, s, back, ng, w, static_cast<Coord>(u.x + kStepDelta.d[e][0]),
                        static_cast<Coord>(u.y + kStepDelta.d[e][1]),
                        static_cast<Coord>(u.z + kStepDelta.d[e][2]), d, &h);
    if (!(f > limit) || (q.bidir && slot_first(other, w) != kNil)) {
      const tdo_status st = relax(ctx, q, back, ui, u, w, d, e, ng, f, h);
      if (st != TDO_OK) return st;
    } else if (!settled(s, w, d, ng)) {
      left |= 1u << e;
      next = f < next ? f : next;
    }
  }
  if (sharp != 0) {
    // Every pivot stays in u's voxel: one heuristic and target vector (target_of). By increasing
    // turn from the heading (the turn cost is symmetric and grows with the angle): once g + w h of
    // a pivot exceeds both the limit and the smallest deferred f, no later pivot is offered or
    // lowers it (the deviation terms are >= 0), so they stay deferred unevaluated. The 1e-9 m
    // margin keeps equal angles whose table entries differ by rounding in.
    const Target t = target_of(q, s, u);
    const bool meets = q.bidir && slot_first(other, u.voxel) != kNil;
    uint32_t rest = back ? opposite_mask(sharp) : sharp;  // forward-sense directions
    const uint8_t* order = ctx->by_angle[u.heading];
    const double g0 = u.g + q.pivot_cost;
    const double wh = q.h_weight * t.h;
    // The deviation of a pivot's direction is at least its turn from the heading minus the
    // heading's own deviation (triangle inequality of angles), theta / pi = sqrt(turn / lambda):
    // mu times that, less 1e-7 for acos_fast's error, joins the lower bound, still growing with
    // the turn (dev_bound false: no deviation term, no turn table or no target direction).
    const bool dev_bound = q.dev_terms && q.mu > 0.0 && ctx->turn_lambda > 0.0 && t.n > 0.0;
    const double dev_u = dev_bound ? deviation_to(ctx, back ? dir_opposite(u.heading) : u.heading,
                                                  t.vx, t.vy, t.vz, t.n)
                                   : 0.0;
    const double inv_lambda = dev_bound ? 1.0 / ctx->turn_lambda : 0.0;
    // Without D_th every sharp step lies beyond theta_max: the pivots start after the leading
    // candidates of the order (D_th makes some candidates sharp).
    for (int k = q.d_th > 0.0 ? 0 : ctx->first_sharp[u.heading]; k < kNumDirs && rest != 0; ++k) {
      const int d = order[k];
      if (((rest >> d) & 1u) == 0) continue;
      const double ng = g0 + turn_row[d];
      double lb = ng + wh;
      if (dev_bound) {
        const double dev_lb = sqrt_nonneg(turn_row[d] * inv_lambda) - dev_u - 1e-7;
        if (dev_lb > 0.0) lb += q.mu * dev_lb;
      }
      if (lb > limit && lb > next + 1e-9 && !meets) break;
      rest &= ~(1u << d);
      const double f = priority_at(ctx, q, back, ng, d, t);
      if (!(f > limit) || meets) {
        const tdo_status st = relax(ctx, q, back, ui, u, u.voxel, d, -1, ng, f, t.h);
        if (st != TDO_OK) return st;
      } else if (!settled(s, u.voxel, d, ng)) {
        left |= 1u << (back ? dir_opposite(d) : d);
        next = f < next ? f : next;
      }
    }
    left |= back ? opposite_mask(rest) : rest;  // not evaluated: f above next
  }
  if (left == 0) return TDO_OK;
  if (s.n_open >= ctx->cfg.max_nodes) return TDO_ERR_NODE_CAPACITY;
  OpenItem it;
  it.f = next;
  memcpy(&it.h, &left, sizeof(it.h));  // orders ties as the unsigned bits of h do (key_of)
  it.node = static_cast<Index>(ui | kDeferItem);
  sift_up(s, s.n_open++, it);
  return TDO_OK;
}

void add_root(tdo_search* ctx, const Query& q, int back, bool headed) {
  Side& s = ctx->side[back];
  const tdo_voxel& v = q.v[back];
  const tdo_voxel& t = q.v[1 - back];
  s.tx = t.i;
  s.ty = t.j;
  s.tz = t.k;
  Node& n = s.nodes[0];
  n.g = 0.0;
  n.parent = kNil;
  n.voxel = static_cast<VoxelId>(q.voxel[back]);
  n.next = kNil;
  n.x = static_cast<Coord>(v.i);
  n.y = static_cast<Coord>(v.j);
  n.z = static_cast<Coord>(v.k);
  n.heading = kHeadingNone;
  s.n_nodes = 1;
  s.box_lo[0] = s.box_hi[0] = v.i;  // the root (box_add grows it by the blocks expanded)
  s.box_lo[1] = s.box_hi[1] = v.j;
  s.box_lo[2] = s.box_hi[2] = v.k;
  s.n_open = 0;
  s.n_stack = 0;
  s.f_cur = -HUGE_VAL;  // the root goes to the heap
  // The stack changes no order that matters to a stopping rule: unidirectional A* (f <= fmin)
  // and the first-meet bidirectional search (it stops at the first meeting, whatever the f).
  s.use_stack = !q.bidir || q.first_meet;
  s.bucketed = !q.bidir && !headed && ctx->cfg.max_nodes <= kBucketMaxNodes;
  s.n_future = 0;
  s.inv_width = 1.0 / kWidth;  // buckets are of voxel-state searches: f in voxel edges
  for (uint32_t k = 0; k < kRing; ++k) s.head[k] = kNil;
  if (s.bucketed) {
    float h;
    s.cur = bucket_of(s, priority<false>(ctx, q, s, back, n, &h));
  }
  index_state(s, n.voxel, kHeadingNone, 0, true);
  slot_set(s, n.voxel, 0);
  if (headed)
    push<true>(ctx, q, s, back, 0);
  else
    push<false>(ctx, q, s, back, 0);
}

// f of the state a side expands next (the stack top first); HUGE_VAL when both are empty.
inline double top_of(const Side& s) {
  if (s.n_stack > 0) return s.stack[s.n_stack - 1u].f;
  return s.n_open > 0 ? s.open[0].f : HUGE_VAL;
}

// Voxel-state searches: start loading the slots of the 3x3x3 block around voxel v (one line
// per row of three) and its move mask while the open list is reordered.
inline void prefetch_block(const tdo_search* ctx, const Query& q, const Side& s, int back,
                           const Node& n) {
  const uint32_t v = n.voxel;
  prefetch(q.grid->moves + v);
  if (n.parent != kNil)  // the parent's move mask, for the pruning in expand_voxel
    prefetch(q.grid->moves +
             (static_cast<int64_t>(v) - ctx->offset[back ? dir_opposite(n.heading) : n.heading]));
  // Rows outside the pool (a voxel on the grid's faces) are clamped to its ends: no branches.
  const int64_t last = static_cast<int64_t>(ctx->cfg.max_voxels) - 1;
  for (int k = 0; k < 9; ++k) {
    int64_t w = static_cast<int64_t>(v) + ctx->block_row[k];
    w = w < 0 ? 0 : w;
    w = w > last ? last : w;
    prefetch(s.slot + w);
  }
}

// A try that is not the last is given up early once it has spent 1/kTryProbe of its expansions
// without a meeting and its progress so far, extrapolated, needs more than 1/kFloodFactor of them
// (flooding).
constexpr uint32_t kTryProbe = 8;
constexpr double kFloodFactor = 2.0;

// The flood test of such a try, after each expansion of a state. Progress is how much closer to
// its target (the try's own heuristic: octile, or with the tables the grid distance) the closest
// state each side has expanded lies: the sides must together close the start-goal distance h_root
// before they can meet (the straight-line picture). A try that has closed P of it in e expansions
// is projected to need e * h_root / P; when that exceeds half the try's share it is stopped as if
// it had run out (the retry follows). The searches the octile guides well close the gap at a
// steady rate (on Map1-3 and Map5 the projections stay near a third of half of kTryMin:
// docs/performance.md); a wall the octile cannot see stops all progress while the states flood the
// region behind it. Only the first try, which has the retries behind it, is tested; a meeting ends
// the test (the search is about to stop).
inline bool flooding(Query& q, int back, const Side& s, const Node& n) {
  const double h = heuristic(s, n.voxel, n.x, n.y, n.z, q.grid->desc.res);
  if (h < q.h_best[back]) q.h_best[back] = h;
  const uint32_t spent = q.expansions - q.try_first;
  if (spent < q.try_share / kTryProbe || q.best < HUGE_VAL) return false;
  const double progress = (q.h_root - q.h_best[0]) + (q.bidir ? q.h_root - q.h_best[1] : 0.0);
  return static_cast<double>(spent) * q.h_root * kFloodFactor >
         static_cast<double>(q.try_share) * progress;
}

template <bool kHeaded>
tdo_status search_loop(tdo_search* ctx, Query& q) {
  Side& fw = ctx->side[0];
  Side& bw = ctx->side[1];
  add_root(ctx, q, 0, kHeaded);
  if (q.bidir) add_root(ctx, q, 1, kHeaded);
  // Bounded: every iteration expands one state, or pops the item of an expanded state's deferred
  // children, which offers at least one of them and so comes back at most 26 times per expanded
  // state; or it returns. Expansions stop at the budget.
  for (;;) {
    int back = 0;
    if (!q.bidir) {
      if (fw.n_open == 0 && fw.n_stack == 0 && fw.n_future > 0)
        advance(fw, [&](const Node& n, float* h) { return priority<false>(ctx, q, fw, 0, n, h); });
      if (fw.n_open == 0 && fw.n_stack == 0) return TDO_ERR_NO_PATH;
      const uint32_t top = fw.n_stack > 0 ? fw.stack[fw.n_stack - 1].node : fw.open[0].node;
      if ((top & kDeferItem) == 0 && fw.nodes[top].voxel == q.voxel[1]) {
        q.best = fw.nodes[top].g;
        q.meet[0] = top;
        return TDO_OK;
      }
    } else {
      // Stop when either side's smallest f reaches the best meeting cost: every path cheaper than
      // it would have to pass an open state of both sides (consistent heuristics, exact compare).
      const double top_f = top_of(fw), top_b = top_of(bw);
      if (!(q.best > top_f) || !(q.best > top_b) || (q.first_meet && q.best < HUGE_VAL))
        return q.best < HUGE_VAL ? TDO_OK : TDO_ERR_NO_PATH;
      back = fw.n_open + fw.n_stack <= bw.n_open + bw.n_stack ? 0 : 1;
    }
    if (q.expansions >= q.budget) return TDO_ERR_BUDGET;
    Side& s = ctx->side[back];
    // Open-list capacity (max_open): checked before each expansion, which adds at most
    // kOpenSlack items, so the list never outgrows the max_open + kOpenSlack entries carved.
    const uint32_t n_queued = s.n_open + s.n_future;
    if (n_queued > q.peak_open) q.peak_open = n_queued;
    if (n_queued > ctx->max_open) return TDO_ERR_OPEN_CAPACITY;
    uint32_t ui;
    float popped_h = 0.0f;  // h of the item taken from the heap
    if (s.n_stack > 0) {
      --s.n_stack;
      ui = s.stack[s.n_stack].node;
      s.f_cur = s.stack[s.n_stack].f;
      if (!kHeaded) prefetch_block(ctx, q, s, back, s.nodes[ui]);
      s.nodes[ui].heap = kNil;
    } else {
      s.f_cur = s.open[0].f;
      popped_h = s.open[0].h;
      if (!kHeaded) prefetch_block(ctx, q, s, back, s.nodes[s.open[0].node]);
      ui = pop(s);
    }
    if (kHeaded && (ui & kDeferItem) != 0) {
      uint32_t todo;  // the item's h field: its steps (expand_headed)
      memcpy(&todo, &popped_h, sizeof(todo));
      const tdo_status st =
          expand_headed(ctx, q, back, ui & ~kDeferItem, s.f_cur + q.defer_margin, todo);
      if (st != TDO_OK) return st;
      continue;
    }
    ++q.expansions;
    // ui is closed now: pop() and the stack set its heap position to kNil.
    if (kHeaded && q.try_share != 0 && flooding(q, back, s, s.nodes[ui])) return TDO_ERR_BUDGET;
    if (!kHeaded) s.slot[s.nodes[ui].voxel] |= static_cast<Index>(kSlotClosed);
    if (!kHeaded && q.bidir) box_add(s, s.nodes[ui]);
    // Children whose f is not above the next queued f plus the margin are created now (those up
    // to the next f would be popped before anything else), the rest are deferred.
    const double next_f = kHeaded ? top_of(s) : 0.0;
    const tdo_status st =
        kHeaded ? expand_headed(ctx, q, back, ui,
                                (next_f > s.f_cur ? next_f : s.f_cur) + q.defer_margin, kAllMoves)
                : expand_voxel(ctx, q, back, ui);
    if (st != TDO_OK) return st;
  }
}

// The search loop, then every slot it set back to kNil (the states' voxels, from the pools).
template <bool kHeaded>
tdo_status run_search(tdo_search* ctx, Query& q) {
  const tdo_status st = search_loop<kHeaded>(ctx, q);
  for (int k = 0; k < (q.bidir ? 2 : 1); ++k) {
    Index* slot = ctx->side[k].slot;
    const Node* nodes = ctx->side[k].nodes;
    const uint32_t n = ctx->side[k].n_nodes;
    q.states += n;
    if (n > q.peak_nodes) q.peak_nodes = n;
    for (uint32_t i = 0; i < n; ++i) slot[nodes[i].voxel] = kNil;
  }
  return st;
}

double step_length(const tdo_voxel& a, const tdo_voxel& b, double res) {
  const int order = (a.i != b.i ? 1 : 0) + (a.j != b.j ? 1 : 0) + (a.k != b.k ? 1 : 0);
  return order == 3 ? res * kSqrt3 : order == 2 ? res * kSqrt2 : order == 1 ? res : 0.0;
}

// Append the voxels of a parent chain; a pivot repeats its parent's voxel and is skipped.
// `reverse` fills from path[pos - 1] downwards. Returns the number of voxels (counted even when
// `fill` is 0) and counts pivots.
uint64_t walk_chain(tdo_search* ctx, const Side& s, uint32_t from, uint32_t skip_voxel, int fill,
                    int reverse, uint64_t pos, uint32_t* pivots) {
  uint64_t count = 0;
  uint32_t prev = skip_voxel;
  uint32_t guard = 0;
  for (uint32_t i = from; i != kNil && guard <= s.n_nodes; i = s.nodes[i].parent, ++guard) {
    const Node& n = s.nodes[i];
    if (pivots != nullptr && n.parent != kNil && s.nodes[n.parent].voxel == n.voxel) ++*pivots;
    if (n.voxel == prev) continue;
    prev = n.voxel;
    if (fill) ctx->path[reverse ? pos - 1u - count : pos + count] = tdo_voxel{n.x, n.y, n.z};
    ++count;
  }
  return count;
}

tdo_status write_path(tdo_search* ctx, const Query& q, tdo_search_output* out) {
  const Side& fw = ctx->side[0];
  const Side& bw = ctx->side[1];
  const uint32_t meet_voxel = fw.nodes[q.meet[0]].voxel;
  const uint64_t n_fw = walk_chain(ctx, fw, q.meet[0], kNil, 0, 1, 0, nullptr);
  const uint64_t n_bw = q.bidir ? walk_chain(ctx, bw, q.meet[1], meet_voxel, 0, 0, 0, nullptr) : 0;
  const uint64_t count = n_fw + n_bw;
  if (count > ctx->cfg.max_path) return TDO_ERR_PATH_CAPACITY;
  uint32_t pivots = 0;
  walk_chain(ctx, fw, q.meet[0], kNil, 1, 1, n_fw, &pivots);
  if (q.bidir) walk_chain(ctx, bw, q.meet[1], meet_voxel, 1, 0, n_fw, &pivots);
  double cost = 0.0;
  for (uint64_t i = 1; i < count; ++i)
    cost += step_length(ctx->path[i - 1], ctx->path[i], q.grid->desc.res);
  out->cost = cost;
  out->penalized_cost = q.best;
  out->n_path = static_cast<uint32_t>(count);
  out->path = ctx->path;
  if (q.bidir && sharp_join(ctx, q, fw.nodes[q.meet[0]].heading, bw.nodes[q.meet[1]].heading))
    ++pivots;
  out->pivots = pivots;
  return TDO_OK;
}

// ctx->unit[d]: the unit vector of direction d.
inline void set_unit(tdo_search* ctx, int d) {
  const int dx = dir_dx(d), dy = dir_dy(d), dz = dir_dz(d);
  const double n = sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
  ctx->unit[d][0] = dx / n;
  ctx->unit[d][1] = dy / n;
  ctx->unit[d][2] = dz / n;
}

void prepare_tables(tdo_search* ctx, const tdo_grid* g, double lambda, double theta_max) {
  for (int k = 0; k < 9; ++k)
    ctx->block_row[k] = (k / 3 - 1) * g->stride_z + (k % 3 - 1) * g->stride_y;
  for (int d = 0; d < kNumDirs; ++d) {
    const int dx = dir_dx(d), dy = dir_dy(d), dz = dir_dz(d);
    const int order = dir_order(d);
    ctx->step_len[d] = g->desc.res * (order == 3 ? kSqrt3 : order == 2 ? kSqrt2 : 1.0);
    ctx->step_q[d] = order == 3 ? kSqrt3Q : order == 2 ? kSqrt2Q : 1.0;
    ctx->offset[d] = dx + dy * g->stride_y + dz * g->stride_z;
    set_unit(ctx, d);
  }
  if (ctx->cand_theta < theta_max || theta_max < ctx->cand_theta) {
    for (int a = 0; a < kNumDirs; ++a) {
      ctx->cand[a] = 0;
      for (int b = 0; b < kNumDirs; ++b) {
        double c = 0.0;
        for (int i = 0; i < 3; ++i) c += ctx->unit[a][i] * ctx->unit[b][i];
        // 1e-9 rad of slack keeps exact 45 and 90 degree neighbours in at their limit
        if (c >= cos(theta_max + 1e-9) || !(theta_max > 0.0) || !(theta_max < kPi))
          ctx->cand[a] |= 1u << b;
      }
    }
    ctx->cand[kHeadingNone] = (1u << kNumDirs) - 1u;
    for (int a = 0; a < kNumDirs; ++a) {
      int k = 0;
      while (k < kNumDirs && ((ctx->cand[a] >> ctx->by_angle[a][k]) & 1u) != 0) ++k;
      ctx->first_sharp[a] = static_cast<uint8_t>(k);
    }
    ctx->cand_theta = theta_max;
  }
  if (!(ctx->turn_lambda < lambda) && !(lambda < ctx->turn_lambda)) return;  // cached
  for (int a = 0; a < kNumHeadings; ++a) {
    for (int b = 0; b < kNumHeadings; ++b) {
      if (a >= kNumDirs || b >= kNumDirs || !(lambda > 0.0)) {
        ctx->turn[a][b] = 0.0;
        continue;
      }
      double c = 0.0;
      for (int i = 0; i < 3; ++i) c += ctx->unit[a][i] * ctx->unit[b][i];
      if (c > 1.0) c = 1.0;
      if (c < -1.0) c = -1.0;
      const double t = acos(c) / kPi;
      ctx->turn[a][b] = lambda * t * t;  // symmetric bit for bit (the search relies on it)
    }
  }
  ctx->turn_lambda = lambda;
}

size_t heading_index_bytes(const tdo_search_config& cfg) {
  return cfg.dense_headings ? static_cast<size_t>(cfg.max_voxels) * kNumHeadings * sizeof(Index)
                            : 0u;
}

// Open-list items one expansion adds at most: 26 children (direct steps and pivots) and one item
// of deferred children.
constexpr uint32_t kOpenSlack = kNumDirs + 1u;

// Open-list entries carved per side. The list never holds more items than states (each open state
// once, each item of deferred children stands for an expanded state), so max_nodes always suffices;
// a smaller max_open gets max_open + kOpenSlack (the check in search_loop).
uint32_t open_entries(const tdo_search_config& cfg) {
  if (cfg.max_open == 0u || static_cast<uint64_t>(cfg.max_open) + kOpenSlack >= cfg.max_nodes)
    return cfg.max_nodes;
  return cfg.max_open + kOpenSlack;
}

size_t side_bytes(const tdo_search_config& cfg) {
  return tdo_arena_round(static_cast<size_t>(cfg.max_voxels) * sizeof(Index)) +
         (cfg.exact_heuristic
              ? tdo_arena_round(static_cast<size_t>(cfg.max_voxels) * sizeof(float))  // hdist
              : 0u) +
         tdo_arena_round(heading_index_bytes(cfg)) +
         tdo_arena_round(static_cast<size_t>(cfg.max_nodes) * sizeof(Node)) +
         tdo_arena_round(static_cast<size_t>(open_entries(cfg)) * sizeof(OpenItem));
}

// The Dijkstra of exact_lower_bounds needs its keys and two links per voxel (kDjBytes) while it
// runs, only between tries, when no search state is alive: it borrows the backward side's node
// pool when that is large enough (max_nodes >= max_voxels / 2 with 32-byte states), else it gets
// its own arrays. The tables the search reads keep 4 bytes per voxel and side.
constexpr size_t kDjBytes = sizeof(double) + 2u * sizeof(uint32_t);
bool dj_in_pool(const tdo_search_config& cfg) {
  return static_cast<uint64_t>(cfg.max_nodes) * sizeof(Node) >=
         static_cast<uint64_t>(cfg.max_voxels) * kDjBytes;
}

// VoxelTurnTables.dev and .reflect, and the unit vectors they are made of (set_unit, as
// prepare_tables sets them).
void dev_table_fill(tdo_search* ctx) {
  VoxelTurnTables* t = ctx->vtt;
  for (int d = 0; d < kNumDirs; ++d) {
    const int dx = dir_dx(d), dy = dir_dy(d), dz = dir_dz(d);
    set_unit(ctx, d);
    for (int m = 0; m < 8; ++m)
      t->reflect[m][d] = static_cast<uint8_t>(dir_of_cell(
          cell_of((m & 1) != 0 ? -dx : dx, (m & 2) != 0 ? -dy : dy, (m & 4) != 0 ? -dz : dz)));
  }
  for (int c = 0; c < kDevAxis; ++c)
    for (int b = 0; b < kDevAxis; ++b)
      for (int a = 0; a < kDevAxis; ++a) {
        const double vx = a, vy = b, vz = c;
        const double n = sqrt_nonneg(vx * vx + vy * vy + vz * vz);
        for (int d = 0; d < kNumDirs; ++d) {
          DevEntry& e = t->dev[c][b][a][d];
          e.dev = n > 0.0 ? deviation_to(ctx, d, vx, vy, vz, n) : 0.0;
          // turn_bound's split (its division and its floor as there)
          const double k = static_cast<double>(static_cast<int>(e.dev * kPi / kMinTurn));
          e.split = k < 1.0 ? -1.0 : e.dev * e.dev / k;
        }
      }
}

// The query's counters (expansions, open-list and state peaks, states), every try counted.
void report_counts(const Query& q, tdo_search_output* out) {
  out->expansions = q.expansions;
  out->peak_open = q.peak_open;
  out->peak_nodes = q.peak_nodes;
  out->states = q.states;
}

}  // namespace
}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" size_t tdo_search_footprint(const tdo_search_config* cfg) {
  if (cfg == nullptr || cfg->max_voxels == 0 || cfg->max_nodes == 0 || cfg->max_path == 0) return 0;
  return tdo_arena_round(sizeof(tdo_search)) + 2u * side_bytes(*cfg) +
         (cfg->max_voxels >= TDO_GUIDE_MIN_VOXELS ? tdo_arena_round(sizeof(VoxelTurnTables)) : 0u) +
         (cfg->exact_heuristic && !dj_in_pool(*cfg)
              ? tdo_arena_round(static_cast<size_t>(cfg->max_voxels) * kDjBytes)
              : 0u) +
         tdo_arena_round(static_cast<size_t>(cfg->max_path) * sizeof(tdo_voxel));
}

extern "C" tdo_status tdo_search_init(tdo_search** out, tdo_arena* arena,
                                      const tdo_search_config* cfg) {
  if (out == nullptr || arena == nullptr || cfg == nullptr || cfg->max_voxels == 0 ||
      cfg->max_nodes == 0 || cfg->max_path == 0 || cfg->max_nodes > kSlotIndex ||
      cfg->max_voxels > kMaxVoxels)
    return TDO_ERR_INVALID_ARGUMENT;
  tdo_search* ctx = static_cast<tdo_search*>(tdo_arena_alloc(arena, sizeof(tdo_search)));
  if (ctx == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  memset(ctx, 0, sizeof(*ctx));
  ctx->cfg = *cfg;
  if (ctx->cfg.max_expansions == 0) ctx->cfg.max_expansions = 0xFFFFFFFFu;
  ctx->max_open = cfg->max_open != 0u ? cfg->max_open : 0xFFFFFFFFu;  // 0: max_nodes bounds it
  ctx->turn_lambda = -1.0;
  ctx->cand_theta = -1.0;
  ctx->vtt = nullptr;
  if (cfg->max_voxels >= TDO_GUIDE_MIN_VOXELS) {  // the guide's grids (voxel-state searches)
    ctx->vtt = static_cast<VoxelTurnTables*>(tdo_arena_alloc(arena, sizeof(VoxelTurnTables)));
    if (ctx->vtt == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    ctx->vtt->key[0] = -2.0;  // no tables yet (vt_prune_ensure)
    dev_table_fill(ctx);
  }
  for (int a = 0; a < kNumDirs; ++a) {
    double c[kNumDirs];
    for (int b = 0; b < kNumDirs; ++b) {
      const double na = sqrt(static_cast<double>(dir_dx(a) * dir_dx(a) + dir_dy(a) * dir_dy(a) +
                                                 dir_dz(a) * dir_dz(a)));
      const double nb = sqrt(static_cast<double>(dir_dx(b) * dir_dx(b) + dir_dy(b) * dir_dy(b) +
                                                 dir_dz(b) * dir_dz(b)));
      c[b] = (dir_dx(a) * dir_dx(b) + dir_dy(a) * dir_dy(b) + dir_dz(a) * dir_dz(b)) / (na * nb);
      ctx->by_angle[a][b] = static_cast<uint8_t>(b);
    }
    // Insertion sort by decreasing cosine, stable (ties keep the smaller index first).
    for (int i = 1; i < kNumDirs; ++i) {
      const uint8_t v = ctx->by_angle[a][i];
      int j = i;
      for (; j > 0 && c[ctx->by_angle[a][j - 1]] < c[v]; --j)
        ctx->by_angle[a][j] = ctx->by_angle[a][j - 1];
      ctx->by_angle[a][j] = v;
    }
  }
  for (int k = 0; k < 2; ++k) {
    Side& s = ctx->side[k];
    s.slot = static_cast<Index*>(tdo_arena_alloc(arena, cfg->max_voxels * sizeof(Index)));
    s.heading_index = nullptr;
    if (cfg->dense_headings) {
      s.heading_index = static_cast<Index*>(tdo_arena_alloc(arena, heading_index_bytes(*cfg)));
      if (s.heading_index == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    }
    s.nodes = static_cast<Node*>(tdo_arena_alloc(arena, cfg->max_nodes * sizeof(Node)));
    s.open = static_cast<OpenItem*>(
        tdo_arena_alloc(arena, static_cast<size_t>(open_entries(*cfg)) * sizeof(OpenItem)));
    if (s.slot == nullptr || s.nodes == nullptr || s.open == nullptr)
      return TDO_ERR_ARENA_TOO_SMALL;
    memset(s.slot, 0xFF, cfg->max_voxels * sizeof(Index));  // kNil: no states
    s.hx = nullptr;
    ctx->hdist[k] = nullptr;
    if (cfg->exact_heuristic) {
      ctx->hdist[k] = static_cast<float*>(tdo_arena_alloc(arena, cfg->max_voxels * sizeof(float)));
      if (ctx->hdist[k] == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    }
  }
  ctx->dj_dist = nullptr;
  ctx->dj_heap = nullptr;
  ctx->dj_pos = nullptr;
  if (cfg->exact_heuristic) {
    // Keys first (8-byte aligned, as the pool and the arena are), then the two link arrays.
    void* dj = dj_in_pool(*cfg) ? static_cast<void*>(ctx->side[1].nodes)
                                : tdo_arena_alloc(arena, cfg->max_voxels * kDjBytes);
    if (dj == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    ctx->dj_dist = static_cast<double*>(dj);
    ctx->dj_heap = reinterpret_cast<uint32_t*>(ctx->dj_dist + cfg->max_voxels);
    ctx->dj_pos = ctx->dj_heap + cfg->max_voxels;
  }
  ctx->path = static_cast<tdo_voxel*>(tdo_arena_alloc(arena, cfg->max_path * sizeof(tdo_voxel)));
  if (ctx->path == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  *out = ctx;
  return TDO_OK;
}

namespace tdo_internal {
namespace {}  // namespace
}  // namespace tdo_internal

namespace tdo_internal {
namespace {

// The penalised cost (m) of the path in ctx->path: its length plus the turn penalty of every pair
// of consecutive steps (and the pivot surcharge of the sharp ones); the sharp turns are counted.
double path_penalty(const tdo_search* ctx, const Query& q, uint32_t n, uint32_t* sharp) {
  double pen = 0.0;
  int prev = -1;
  *sharp = 0;
  for (uint32_t i = 1; i < n; ++i) {
    const tdo_voxel& a = ctx->path[i - 1];
    const tdo_voxel& b = ctx->path[i];
    const int d = dir_of_cell(cell_of(b.i - a.i, b.j - a.j, b.k - a.k));
    if (prev >= 0) {
      pen += ctx->turn[prev][d];
      if (sharp_join(ctx, q, prev, d)) {
        pen += q.pivot_cost;
        ++*sharp;
      }
    }
    prev = d;
  }
  return pen;
}

tdo_status run_voxel_turns(tdo_search* ctx, Query& q, int grid_first, tdo_search_output* out) {
  q.voxel_turns = 1;
  q.inv_res = 1.0 / q.grid->desc.res;
  // grid_first: the grid-distance tables in h (metres, so scaled to voxel edges in priority); PLAIN
  // as the heading search's first retry (weight 2, no deviation terms), TERMS with the f unchanged.
  if (grid_first != TDO_GRID_FIRST_OFF && !build_tables(ctx, q, out)) return TDO_ERR_NO_PATH;
  if (grid_first == TDO_GRID_FIRST_PLAIN) {
    q.h_weight = q.h_weight > retry_weight(0) ? q.h_weight : retry_weight(0);
    q.dev_terms = 0;
  }
  vt_prune_ensure(ctx, q);
  const tdo_status st = run_search<false>(ctx, q);
  report_counts(q, out);
  if (st != TDO_OK) return st;
  if (grid_first == TDO_GRID_FIRST_PLAIN) out->fallback = 1;  // as the heading search reports it
  const tdo_status wp = write_path(ctx, q, out);
  if (wp != TDO_OK) return wp;
  uint32_t sharp = 0;
  out->penalized_cost = out->cost + path_penalty(ctx, q, out->n_path, &sharp);
  out->pivots = sharp;
  return TDO_OK;
}

}  // namespace
}  // namespace tdo_internal

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {

// What search_retry.cpp calls (search_retry.h).
tdo_status search_try(tdo_search* ctx, Query& q) { return run_search<true>(ctx, q); }
tdo_status search_voxel_turns(tdo_search* ctx, Query& q, int grid_first, tdo_search_output* out) {
  return run_voxel_turns(ctx, q, grid_first, out);
}
tdo_status search_write_path(tdo_search* ctx, const Query& q, tdo_search_output* out) {
  return write_path(ctx, q, out);
}
void search_report(const Query& q, tdo_search_output* out) { report_counts(q, out); }
double search_octile(int32_t a, int32_t b, int32_t c, double res) {
  return octile_of(a, b, c, res);
}

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

namespace tdo_internal {
namespace {

// A corridor fits the grid, and the start and goal voxels lie in it.
bool corridor_holds(const tdo_search_corridor* c, const tdo_grid* g, const tdo_voxel* ends) {
  if (c->cells == nullptr || c->shift < 1 || c->shift > 7) return false;
  const int32_t e = (1 << c->shift) - 1;
  if (c->cnx != (g->desc.nx + e) >> c->shift || c->cny != (g->desc.ny + e) >> c->shift)
    return false;
  for (int k = 0; k < 2; ++k) {
    const uint32_t cell = static_cast<uint32_t>(
        (ends[k].i >> c->shift) +
        c->cnx * ((ends[k].j >> c->shift) + c->cny * static_cast<int64_t>(ends[k].k >> c->shift)));
    if ((c->cells[cell] & (1u << 13)) == 0) return false;
  }
  return true;
}

}  // namespace
}  // namespace tdo_internal

extern "C" tdo_status tdo_search_run(tdo_search* ctx, const tdo_search_input* in,
                                     tdo_search_output* out) {
  if (ctx == nullptr || in == nullptr || out == nullptr || in->grid == nullptr)
    return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  const tdo_grid* g = in->grid;
  if (!g->ready) return TDO_ERR_MAP_NOT_READY;
  moves_ensure(g);  // the legal steps, once per finish (tdo_grid_prepare pays it ahead)
  if (g->nvox > ctx->cfg.max_voxels || g->desc.nx > kMaxAxis || g->desc.ny > kMaxAxis ||
      g->desc.nz > kMaxAxis)
    return TDO_ERR_MAP_CAPACITY;
  if (!isfinite(in->lambda) || !isfinite(in->mu) || in->lambda < 0.0 || in->mu < 0.0 ||
      !isfinite(in->theta_max) || !isfinite(in->d_th) || !isfinite(in->h_weight) ||
      in->h_weight < 0.0 || (in->kind != TDO_SEARCH_ASTAR && in->kind != TDO_SEARCH_BIDIR) ||
      !finite3(in->start) || !finite3(in->goal) || in->grid_first < TDO_GRID_FIRST_OFF ||
      in->grid_first > TDO_GRID_FIRST_TERMS ||
      (in->grid_first != TDO_GRID_FIRST_OFF && ctx->cfg.exact_heuristic == 0) ||  // tables
      in->states < TDO_STATES_HEADING || in->states > TDO_STATES_VOXEL)
    return TDO_ERR_INVALID_ARGUMENT;
  Query q;
  memset(&q, 0, sizeof(q));
  q.grid = g;
  const tdo_status ends = search_ends_ok(g, in->start, in->goal, q.v);  // as the direct route
  if (ends != TDO_OK) return ends;
  if (in->corridor != nullptr && !corridor_holds(in->corridor, g, q.v))
    return TDO_ERR_INVALID_ARGUMENT;
  q.corridor = in->corridor;
  for (int k = 0; k < 2; ++k)
    q.voxel[k] = static_cast<uint32_t>(q.v[k].i + q.v[k].j * g->stride_y + q.v[k].k * g->stride_z);
  if (q.voxel[0] == q.voxel[1]) {  // distinct points in one voxel: a one-voxel path
    ctx->path[0] = q.v[0];
    out->n_path = 1;
    out->path = ctx->path;
    return TDO_OK;
  }
  q.bidir = in->kind == TDO_SEARCH_BIDIR;
  q.mu = in->mu;
  q.dev_terms = 1;
  q.h_weight = in->h_weight > 1.0 ? in->h_weight : 1.0;
  q.first_meet = in->first_meet != 0;
  q.exact_turns = !q.bidir || !q.first_meet;
  q.constrained = search_constrained(in->theta_max);
  q.d_th = search_d_th(in->d_th);
  q.pivot_cost = tdo_search_pivot_cost(in->lambda, in->theta_max);
  q.defer_margin = q.pivot_cost + g->desc.res;  // the dearest direct turn, one voxel edge more
  q.budget = in->max_expansions != 0 ? in->max_expansions : ctx->cfg.max_expansions;
  q.best = HUGE_VAL;
  q.meet[0] = q.meet[1] = kNil;
  prepare_tables(ctx, g, in->lambda, q.constrained ? in->theta_max : 0.0);
  const bool headed = search_headed(in);
  for (int k = 0; k < 2; ++k) ctx->side[k].hx = nullptr;
  if (headed && in->states == TDO_STATES_VOXEL) return run_voxel_turns(ctx, q, in->grid_first, out);
  if (!headed) {  // plain A* and bidirectional A*: the octile distance, nothing else
    const tdo_status st = run_search<false>(ctx, q);
    report_counts(q, out);
    if (st != TDO_OK) return st;
    const tdo_status wp = write_path(ctx, q, out);
    out->penalized_cost = out->cost;  // no penalties (q.best counts rounded voxel edges)
    return wp;
  }
  return run_headed(ctx, q, in, out);
}

extern "C" double tdo_search_pivot_cost(double lambda, double theta_max) {
  if (!(lambda > 0.0) || !(theta_max > 0.0) || !(theta_max < kPi)) return 0.0;
  const double t = theta_max / kPi;
  return lambda * t * t;
}
