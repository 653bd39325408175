#include "tdo/config.h"

#include <math.h>

#include "planner_internal.h"

extern "C" void tdo_capacity_for_grid(tdo_capacity* cap, int32_t nx, int32_t ny, int32_t nz,
                                      double clear_ratio, uint32_t headings, uint32_t node_cap) {
  if (cap == nullptr) return;
  *cap = tdo_capacity{};
  if (nx <= 0 || ny <= 0 || nz <= 0) return;
  const uint64_t n =
      static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny) * static_cast<uint64_t>(nz);
  const uint64_t cap32 = 0xFFFFFFF0u;
  cap->max_voxels = static_cast<uint32_t>(n < cap32 ? n : cap32);
  uint64_t nodes = n * (headings == 0 ? 1u : headings);
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
}

extern "C" size_t tdo_planner_footprint(const tdo_planner_config* cfg) {
  return tdo_internal::planner_footprint(cfg);
}
