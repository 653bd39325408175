// The turn-deviation search's states and context (docs/design.md s.1, "Memory and work"): index
// widths, the state and open-list item layouts, the per-voxel slots and chains that index the
// states of a voxel, the state pool, and the context tdo_search_init carves. Internal to libtdo;
// compiled into each library variant (tdo, tdo_index16: TDO_SEARCH_INDEX16), whose symbols live
// in their own inline namespace.
#ifndef TDO_SRC_SEARCH_STATE_H
#define TDO_SRC_SEARCH_STATE_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "directions.h"
#include "tdo/search.h"

#if defined(TDO_SEARCH_INDEX16)
#define TDO_SEARCH_NS index16
#else
#define TDO_SEARCH_NS index32
#endif

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {

// Index widths. Built with TDO_SEARCH_INDEX16 (small configurations: docs/embedded.md) the search
// stores state indices, voxel indices and per-voxel slots in 16 bits and voxel coordinates in 8:
// a state takes 20 bytes instead of 32, an open-list item 14 instead of 16, a slot 2 instead of 4,
// for max_nodes < 2^15 per direction, max_voxels < 2^16 and grid axes < 256 (tdo_search_init and
// tdo_search_run check them). The code is the same for both widths; only these types change.
#if defined(TDO_SEARCH_INDEX16)
typedef uint16_t Index;    // state index, open-list position, per-voxel slot
typedef uint16_t VoxelId;  // linear voxel index
typedef uint8_t Coord;     // voxel coordinate
#define TDO_SEARCH_PACKED(align) __attribute__((packed, aligned(align)))
#else
typedef uint32_t Index;
typedef uint32_t VoxelId;
typedef uint16_t Coord;
#define TDO_SEARCH_PACKED(align)
#endif
// "No state": all ones of an Index (every index and position stays below it). The voxel arrays of
// exact_lower_bounds use it too (voxel indices stay below it as well: kMaxVoxels).
constexpr uint32_t kNil = static_cast<Index>(~0u);
constexpr uint32_t kTopBit = (kNil >> 1) + 1u;  // flag bit of an Index (kSlotClosed, kDeferItem)
constexpr uint64_t kMaxVoxels = static_cast<VoxelId>(~0u);  // max_voxels at most this
constexpr double kPi = 3.14159265358979323846;
constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kSqrt3 = 1.73205080756887729353;
constexpr int32_t kMaxAxis = static_cast<Coord>(~0u);  // node coordinates are Coord
// Smallest angle between two different step directions: acos(sqrt(2/3)), face to edge diagonal
// and edge to corner diagonal (rad).
constexpr double kMinTurn = 0.61547970867038734;

struct TDO_SEARCH_PACKED(4) Node {
  double g;         // m, cost from this side's root: length plus turn penalties
  Index parent;     // node towards this side's root, kNil at the root
  VoxelId voxel;    // linear voxel index
  Index next;       // next state of the same voxel, kNil at the end of the chain
  Index heap;       // position in the open list (or kInStack, kBucketBit | ...), kNil once closed
  Coord x, y, z;    // voxel coordinates
  uint8_t heading;  // forward-sense step direction into (forward) / out of (backward) the voxel
};
static_assert(sizeof(Node) == (sizeof(Index) == 2 ? 20 : 32), "Node layout");

// node before h: the 8 bytes that end with h, read as one little-endian word and shifted right by
// kKeyShift bits, are (h bits << (8 * sizeof(Index)) | node), the key's low half (key_of).
struct TDO_SEARCH_PACKED(2) OpenItem {
  double f;    // m, g + h (+ mu * deviation)
  Index node;  // node index; smaller wins ties of f and h (deterministic allocation order)
  float h;     // m, heuristic; smaller h wins ties of f
};
static_assert(sizeof(OpenItem) == (sizeof(Index) == 2 ? 14 : 16), "OpenItem layout");
constexpr uint32_t kArity =
    4;  // 4-ary heap: half the depth of a binary heap, children share a line

// Per-voxel slot: the first state of the voxel's chain in the bits below kTopBit, kNil when the
// voxel has none, and kSlotClosed once the voxel's only state is expanded (searches without heading
// costs), so closed neighbours are skipped without touching the node pool. A search ends by setting
// the slots of its states' voxels back to kNil (run_search), so no generation stamp is needed and a
// slot takes one Index.
constexpr uint32_t kSlotClosed = kTopBit;
constexpr uint32_t kSlotIndex = kTopBit - 1u;
// Open-list item that stands for the deferred children of an expanded turn-penalised state
// (expand_headed): its f is the smallest of their f, so most are never popped.
constexpr uint32_t kDeferItem = kTopBit;

// Unidirectional A* keeps children whose f does not exceed their parent's on a small LIFO stack
// instead of the heap: they are expanded next anyway (f <= fmin keeps A* optimal), which skips a
// heap push and pop for most states on open ground. Full stack: the heap takes the child. The
// turn-penalised searches hold at most 7 items there on Map1-6 and plain A* 11 on Map1, so the
// 16-bit build (small configurations) keeps 64: 1.3 KB per context instead of 20 KB.
constexpr uint32_t kStackCap = sizeof(Index) == 2 ? 64u : 1024u;
constexpr uint32_t kInStack = kNil - 1u;  // Node::heap of a state on the stack

// Open list of unidirectional voxel-state A* (plain A*, consistent octile heuristic): buckets by
// floor(f / width). Only the current bucket (and every item whose bucket is not above it) is in
// the heap `open`, ordered exactly by (f, h, node); the later buckets are doubly linked lists
// through Node::next (next) and Node::heap (kBucketBit | previous item, or kBucketBit |
// (kBucketHeadBase + ring slot) at the head), in a ring of kRing: no memory beyond the heap's.
// Every item of a later bucket has a larger f than every heap item, so the pop order is the heap's.
// Bounded ring: an item is queued while its parent, whose f lies at most at the end of the current
// bucket, is expanded, and a step raises f by at most 2 sqrt(3) voxel edges (step length plus the
// change of the octile distance), so it lands fewer than 2 + 2 sqrt(3) / kWidth buckets ahead;
// decrease-key only lowers f.
constexpr uint32_t kRing = 64;            // ring slots, a power of two > 2 + 2 sqrt(3) / kWidth
constexpr double kWidth = 0.0625;         // bucket width per res
constexpr uint32_t kBucketBit = kTopBit;  // Node::heap of a state in a later bucket
constexpr uint32_t kBucketHeadBase = kTopBit - 256u;   // list head: kBucketBit | (this + ring slot)
constexpr uint32_t kBucketMaxNodes = kBucketHeadBase;  // larger pools keep the plain heap
static_assert((kRing & (kRing - 1u)) == 0 && kRing > 3.0 + 2.0 * kSqrt3 / kWidth,
              "bucket ring too small for the largest f step (one bucket of rounding margin)");

struct TDO_SEARCH_PACKED(2) StackItem {
  double f;    // m, f when pushed (<= the f of every open heap state at that time)
  Index node;  // node index
};

// Side.box_lo: the 32-bit build only (the big grids, whose slot arrays miss the cache; the 16-bit
// build's firmware keeps its flash).
constexpr bool kStateBox = sizeof(Index) == 4;
struct Side {
  Index* slot;           // per voxel: see kSlotClosed
  Index* heading_index;  // dense_headings: 27 states per voxel, valid while its slot is set
  Node* nodes;           // state pool, max_nodes
  OpenItem* open;        // binary min-heap, max_nodes
  uint32_t n_nodes;
  uint32_t n_open;
  int32_t tx, ty, tz;            // target voxel of this side's heuristic
  int32_t box_lo[3], box_hi[3];  // bidirectional voxel-state searches: holds every state's voxel
  StackItem stack[kStackCap];    // A* fast path (forward side only)
  // Turn-penalised searches: per voxel a lower bound (m) of the grid distance to this side's target
  // (exact_lower_bounds); nullptr = the octile distance alone.
  const float* hx;
  uint32_t n_stack;
  double f_cur;   // f of the state being expanded
  int use_stack;  // 1 for unidirectional A*
  // Buckets (kBucketBit): unidirectional voxel-state A* only (forward side).
  int bucketed;
  uint32_t n_future;     // items in later buckets
  uint64_t cur;          // current bucket
  double inv_width;      // 1/voxel edge (f of voxel-state searches is in voxel edges)
  uint32_t head[kRing];  // first item of each later bucket, kNil when empty
};

// Direction mask (bit d = direction d) to cell mask (bit c = cell c, the centre 13 clear) and back.
constexpr uint32_t cells_of_dirs(uint32_t m) { return (m & 0x1FFFu) | ((m >> 13) << 14); }
constexpr uint32_t dirs_of_cells(uint32_t c) { return (c & 0x1FFFu) | ((c >> 14) << 13); }
constexpr uint32_t kAllMoves = (1u << kNumDirs) - 1u;  // move mask of a voxel with every step legal

// Voxel-state searches with turn costs (vt_prune_ensure in search.cpp): voxel_turn() of every
// pair of headings, and prune[back][hp][s]: the search-sense steps e of a state reached over step s
// from a parent of heading hp whose neighbour the parent offered for less than the way through the
// state, turns included.
// dev[c][b][a][t]: deviation_to() of direction t from the target vector (a, b, c), 0 <= a, b, c <
// kDevAxis (0 at the target), the same bits: negating an axis of both vectors keeps every product
// and sum bit for bit, so reflect[m][d], direction d with the axes of mask m (bit 0 x, 1 y, 2 z)
// negated, serves the other octants (dev_table_fill, once per context).
// split: turn_bound's dev^2 / floor(dev pi / kMinTurn) of that deviation, -1 below one kMinTurn.
constexpr int kDevAxis = 16;
struct DevEntry {
  double dev, split;
};
struct VoxelTurnTables {
  double vturn[kNumHeadings][kNumHeadings];  // voxel edges
  uint32_t prune[2][kNumHeadings][kNumDirs];
  double key[4];  // lambda, pivot cost, 1/voxel edge and theta_max the tables were built for
  DevEntry dev[kDevAxis][kDevAxis][kDevAxis][kNumDirs];
  uint8_t reflect[8][kNumDirs];
};

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

struct tdo_search {
  tdo_search_config cfg;
  uint32_t max_open;  // open-list items per side before TDO_ERR_OPEN_CAPACITY (see open_entries)
  tdo_internal::Side side[2];                                           // 0 forward, 1 backward
  tdo_voxel* path;                                                      // max_path voxels
  double turn[tdo_internal::kNumHeadings][tdo_internal::kNumHeadings];  // m, lambda*(angle/pi)^2
  double turn_lambda;                       // lambda the turn table was built for
  double step_len[tdo_internal::kNumDirs];  // m
  int64_t block_row[9];  // linear index offsets of the 9 rows of three of a 3x3x3 block (centre)
  double step_q[tdo_internal::kNumDirs];   // voxel edges, rounded (kSqrt2Q): voxel-state searches
  int64_t offset[tdo_internal::kNumDirs];  // linear index offset of each step
  double unit[tdo_internal::kNumDirs][3];  // unit vector of each step
  uint32_t cand[tdo_internal::kNumHeadings];  // steps within theta_max of each heading
  // by_angle[h]: the 26 directions by increasing angle from direction h (ties: smaller index)
  uint8_t by_angle[tdo_internal::kNumDirs][tdo_internal::kNumDirs];
  // first_sharp[h]: how many leading entries of by_angle[h] lie in cand[h] (no sharp step there)
  uint8_t first_sharp[tdo_internal::kNumDirs];
  double cand_theta;  // theta_max the cand table was built for
  // The tables of voxel-state searches with turn costs; nullptr in searches of fewer than
  // TDO_GUIDE_MIN_VOXELS voxels (small targets keep their memory; the search computes the turns).
  tdo_internal::VoxelTurnTables* vtt;
  // Exact heuristic of turn-penalised searches (exact_lower_bounds): per side, max_voxels grid
  // distances (m) to the side's target; the Dijkstra's bucket lists (DjQueue), max_voxels each.
  float* hdist[2];    // rounded down from the Dijkstra's keys (lower bounds stay lower bounds)
  double* dj_dist;    // the Dijkstra's keys (m), max_voxels (dj_in_pool: in side[1].nodes)
  uint32_t* dj_heap;  // next voxel in the bucket
  uint32_t* dj_pos;   // previous voxel in the bucket, kDjHead, kDjSettled or kNil (not reached)
};

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {

struct Query {
  const tdo_grid* grid;
  uint32_t voxel[2];  // start voxel, goal voxel
  tdo_voxel v[2];
  int bidir;
  double mu;
  double h_weight;      // >= 1
  int first_meet;       // stop at the first meeting
  double d_th;          // deviation threshold, 0 = off
  double pivot_cost;    // m, surcharge of a pivot
  double defer_margin;  // m, expand_headed: children up to this far above the next f are created
  int constrained;      // theta_max active
  int dev_terms;        // 1: f has the deviation term and the turn lower bound (0 in the retry)
  int exact_turns;      // 1: the turn part of h is a lower bound (A*, bidir's optimal stop)
  int voxel_turns;      // 1: voxel-state search with turn costs (tdo_search_input.states)
  const tdo_search_corridor* corridor;  // confines the steps, nullptr: the whole grid
  double inv_res;  // 1/voxel edge: metres to the voxel edges of voxel-state searches
  uint32_t budget;
  // Flood test of a try that is not the last (search_loop, kTryProbe): 0 = off.
  uint32_t try_share;  // the try's expansions (max(kTryMin, nvox / kTryDiv))
  uint32_t try_first;  // expansions before the try
  double h_root;       // m, heuristic() of the start (its target: the goal)
  double h_best[2];    // m, smallest heuristic() of a state each side expanded
  // results
  double best;
  uint32_t meet[2];
  uint32_t expansions;
  uint32_t peak_open;  // largest open list (heap plus later buckets) of a side before its expansion
  uint32_t peak_nodes;  // most states one side held at the end of a try
  uint32_t states;      // states created, both sides, every try
};

namespace {  // one copy per translation unit

// First state of voxel v's chain (the kSlotClosed bit dropped), kNil when it has none.
inline uint32_t slot_first(const Side& s, uint32_t v) {
  const uint32_t i = s.slot[v];
  return i == kNil ? kNil : (i & kSlotIndex);
}

inline void slot_set(Side& s, uint32_t v, uint32_t idx) { s.slot[v] = static_cast<Index>(idx); }

// Record state idx as (voxel w, heading) in the dense index; `first` = the voxel's first state of
// this query, whose other entries are cleared first.
inline void index_state(Side& s, uint32_t w, int heading, uint32_t idx, bool first) {
  if (s.heading_index == nullptr) return;
  Index* row = s.heading_index + static_cast<size_t>(w) * kNumHeadings;
  static_assert(kNil == static_cast<Index>(~0u), "all-ones bytes fill kNil");
  if (first) {
#if defined(__SSE2__)
    // Overlapping 16-byte stores (GCC makes the memset a byte-wise rep stos here).
    constexpr size_t kBytes = kNumHeadings * sizeof(Index);
    static_assert(kBytes >= 16, "row of at least one store");
    const __m128i ones = _mm_set1_epi32(-1);
    unsigned char* p = reinterpret_cast<unsigned char*>(row);
    for (size_t o = 0; o + 16u < kBytes; o += 16u)
      _mm_storeu_si128(reinterpret_cast<__m128i*>(p + o), ones);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + kBytes - 16u), ones);
#else
    memset(row, 0xFF, kNumHeadings * sizeof(Index));
#endif
  }
  row[heading] = static_cast<Index>(idx);
}

// Allocate the state (w, heading) reached from ui over a step of (dx, dy, dz) voxels at cost ng,
// chained before `next` (the voxel's previous first state, kNil for none). kNil: the pool is full.
// u: a copy of state ui.
inline uint32_t new_state(const tdo_search* ctx, Side& s, uint32_t ui, const Node& u, uint32_t w,
                          double ng, int dx, int dy, int dz, int heading, uint32_t next) {
  if (s.n_nodes >= ctx->cfg.max_nodes) return kNil;
  const uint32_t idx = s.n_nodes++;
  Node& n = s.nodes[idx];
  n.g = ng;
  n.parent = static_cast<Index>(ui);
  n.voxel = static_cast<VoxelId>(w);
  n.next = static_cast<Index>(next);
  n.x = static_cast<Coord>(u.x + dx);
  n.y = static_cast<Coord>(u.y + dy);
  n.z = static_cast<Coord>(u.z + dz);
  n.heading = static_cast<uint8_t>(heading);
  return idx;
}

// State (w, heading) of a turn-penalised side, kNil when it has none.
inline uint32_t find_state(const Side& s, uint32_t w, int heading) {
  uint32_t idx = slot_first(s, w);
  if (s.heading_index != nullptr) {
    if (idx != kNil) idx = s.heading_index[static_cast<size_t>(w) * kNumHeadings + heading];
  } else {
    while (idx != kNil && s.nodes[idx].heading != heading) idx = s.nodes[idx].next;
  }
  return idx;
}

}  // namespace
}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

#endif  // TDO_SRC_SEARCH_STATE_H
