#include "tdo/config.h"

#include <math.h>

#include "planner_internal.h"
#include "tdo/trajectory.h"

extern "C" void tdo_capacity_for_grid(tdo_capacity* cap, int32_t nx, int32_t ny, int32_t nz,
                                      double clear_ratio, uint32_t headings, uint32_t node_cap) {
  if (cap == nullptr) return;
  *cap = tdo_capacity{};
  if (nx <= 0 || ny <= 0 || nz <= 0) return;
  const uint64_t n =
      static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny) * static_cast<uint64_t>(nz);
  const uint64_t cap32 = 0xFFFFFFF0u;
  cap->max_voxels = static_cast<uint32_t>(n < cap32 ? n : cap32);
  // The state pool of one search direction: one state per voxel covers plain A* and voxel states
  // (design s.1, "Memory and work"). Heading states take states from the same pool as the search
  // creates them, not 27 per voxel; a pool they fill ends in the voxel-state fallback. Small grids
  // keep room for every heading (at most kSmallPool states), so their searches never need it.
  constexpr uint64_t kSmallPool = 1u << 18;
  const uint64_t h = headings == 0 ? 1u : headings;
  uint64_t nodes = n;
  if (h > 1u) nodes = n * h < kSmallPool ? n * h : (n > kSmallPool ? n : kSmallPool);
  if (node_cap > 0 && nodes > node_cap) nodes = node_cap;
  cap->max_nodes = static_cast<uint32_t>(nodes < cap32 ? nodes : cap32);
  // A path visits each voxel at most once; 4x the box diagonal in steps covers realistic detours
  // while staying far below n on big maps.
  uint64_t path = 4u * (static_cast<uint64_t>(nx) + ny + nz) + 64u;
  if (path > n + 1u) path = n + 1u;
  cap->max_path = static_cast<uint32_t>(path);
  double ratio = clear_ratio > 0.0 && isfinite(clear_ratio) ? clear_ratio : 0.0;
  if (ratio > 64.0) ratio = 64.0;
  const uint32_t k = static_cast<uint32_t>(ceil(ratio + 0.5));
  cap->max_clear_cells = (2u * k + 1u) * (2u * k + 1u) * (2u * k + 1u);
  cap->max_expansions = cap->max_nodes < 0x7FFFFFFFu ? 2u * cap->max_nodes : 0xFFFFFFFFu;
  // The box count is not known here (callers set max_boxes afterwards), and the bucket index needs
  // at most 64 entries per box: 0 derives max_boxes * 64 at init, which can never overflow.
  cap->max_box_refs = 0;
  // Per voxel the search keeps what plain A* keeps (one slot per direction, the head of the
  // voxel's chain of heading states). Grids of at most 2^16 voxels (the paper's maps) add the dense
  // 27-entry index (216 bytes per voxel, at most 14 MB), which saves the chain walks: Map4's
  // search 26.1 M instructions with chains, 23.3 M with the index (docs/design.md s.1).
  cap->dense_headings = headings >= 27u && n <= (1u << 16) ? 1u : 0u;
  // The retry's tables and the coarse guide: tdo_capacity_guide, for heading states.
  tdo_capacity_guide(cap, nx, ny, nz, headings >= 27u ? 1 : 0);
  cap->max_checks = 100000u;  // correction: a few checks per point and scale, far above need
  cap->max_shrinks = 16u;     // radius x0.6 per shrink: 16 steps reach 0.03 % of the radius
  // A flight of 64 samples (0.64 s at dt = 0.01 s) per path voxel covers a slow, stop-heavy path.
  const uint64_t samples = 64u * static_cast<uint64_t>(cap->max_path) + 1024u;
  cap->max_samples = static_cast<uint32_t>(samples < (1u << 22) ? samples : (1u << 22));
  cap->max_profile = TDO_TRAJ_PIECES_PER_SEGMENT * (3u * cap->max_path + 4u) + 1u;
  // Big grids (the guide's) verify each profile piece in closed form and keep no samples
  // (design s.5): a stored flight costs 84 bytes per 0.01 s and a verification pass over it, which
  // on short plans of a big map costs more than the search. Small grids (Map1-5, the embedded
  // demos) keep their samples and finite-difference maxima.
  cap->stream_samples =
      n >= TDO_GUIDE_MIN_VOXELS ? TDO_TRAJ_SAMPLES_PIECES : TDO_TRAJ_SAMPLES_STORED;
  cap->max_violations = 64u;  // enough to show a pattern; the total is always counted
  cap->max_refinements = 8u;  // each round lowers local limits by 20 %: 8 rounds reach 17 %
}

extern "C" void tdo_capacity_guide(tdo_capacity* cap, int32_t nx, int32_t ny, int32_t nz,
                                   int turn_penalised) {
  if (cap == nullptr) return;
  const bool sized = nx > 0 && ny > 0 && nz > 0;
  const uint64_t n =
      sized ? static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny) * static_cast<uint64_t>(nz)
            : 0u;
  const bool on = sized && turn_penalised != 0;
  // The obstacle-aware retry (24 bytes per voxel) for the turn-penalised search, whose octile try
  // can flood (docs/performance.md), and the grid-distance tables of voxel states' grid_first;
  // plain searches never retry.
  cap->exact_heuristic = on ? 1u : 0u;
  // The coarse guide (guide.cpp) only runs on grids of TDO_GUIDE_MIN_VOXELS or more.
  cap->guide_shift = on && n >= TDO_GUIDE_MIN_VOXELS ? 2u : 0u;
}

extern "C" size_t tdo_planner_footprint(const tdo_planner_config* cfg) {
  return tdo_internal::planner_footprint(cfg);
}
