#include "tdo/planner.h"

#include <string.h>

#include "grid_internal.h"
#include "planner_internal.h"

namespace tdo_internal {
namespace {

bool valid(const tdo_planner_config* cfg) {
  return cfg != nullptr && cfg->cap.max_voxels > 0 && cfg->cap.max_nodes > 0 &&
         cfg->cap.max_path > 0 && cfg->cap.max_waypoints != 1u;  // a path has two ends
}

GridCapacity grid_cap(const tdo_planner_config& cfg) {
  return GridCapacity{cfg.cap.max_voxels,   cfg.cap.max_boxes, cfg.cap.max_clear_cells,
                      cfg.cap.max_box_refs, cfg.cap.max_axis,  cfg.cap.boxes_only};
}

tdo_search_config search_cfg(const tdo_planner_config& cfg) {
  return tdo_search_config{cfg.cap.max_voxels,     cfg.cap.max_nodes,      cfg.cap.max_path,
                           cfg.cap.max_expansions, cfg.cap.dense_headings, cfg.cap.exact_heuristic,
                           cfg.cap.max_open};
}

}  // namespace

size_t planner_footprint(const tdo_planner_config* cfg) {
  if (!valid(cfg)) return 0;
  const tdo_search_config sc = search_cfg(*cfg);
  // The arena start may be misaligned by up to TDO_ARENA_ALIGN - 1 bytes.
  return (TDO_ARENA_ALIGN - 1u) + tdo_arena_round(sizeof(tdo_planner)) +
         grid_footprint(grid_cap(*cfg)) + tdo_search_footprint(&sc) +
         guide_footprint(
             guide_capacity(cfg->cap.max_voxels, static_cast<int32_t>(cfg->cap.guide_shift))) +
         pipeline_footprint(cfg);
}

}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" tdo_status tdo_planner_init(tdo_planner** out, void* memory, size_t bytes,
                                       const tdo_planner_config* cfg) {
  if (out == nullptr || memory == nullptr || !valid(cfg)) return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  if (bytes < planner_footprint(cfg)) return TDO_ERR_ARENA_TOO_SMALL;
  tdo_arena arena;
  tdo_arena_init(&arena, memory, bytes);
  tdo_planner* p = static_cast<tdo_planner*>(tdo_arena_alloc(&arena, sizeof(tdo_planner)));
  if (p == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  memset(p, 0, sizeof(*p));
  p->cfg = *cfg;
  tdo_status st = grid_init(&p->grid, &arena, grid_cap(*cfg));
  if (st != TDO_OK) return st;
  const tdo_search_config sc = search_cfg(*cfg);
  st = tdo_search_init(&p->search, &arena, &sc);
  if (st != TDO_OK) return st;
  st = guide_init(&p->guide, &arena,
                  guide_capacity(cfg->cap.max_voxels, static_cast<int32_t>(cfg->cap.guide_shift)));
  if (st != TDO_OK) return st;
  st = pipeline_init(p, &arena);
  if (st != TDO_OK) return st;
  p->arena = arena;
  *out = p;
  return TDO_OK;
}

extern "C" tdo_grid* tdo_planner_grid(tdo_planner* planner) {
  return planner != nullptr ? planner->grid : nullptr;
}

extern "C" tdo_search* tdo_planner_search(tdo_planner* planner) {
  return planner != nullptr ? planner->search : nullptr;
}

extern "C" size_t tdo_planner_arena_used(const tdo_planner* planner) {
  return planner != nullptr ? planner->arena.used : 0u;
}
