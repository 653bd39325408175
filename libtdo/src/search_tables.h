// The grid-distance tables of the turn-penalised search's retry (docs/design.md s.1, "Retry with
// grid distances"): a bucketed Dijkstra from each side's target. Internal to libtdo.
#ifndef TDO_SRC_SEARCH_TABLES_H
#define TDO_SRC_SEARCH_TABLES_H

#include <stdint.h>

#include "search_state.h"
#include "tdo/grid.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {

// Lower bounds of the grid distance (m) from every voxel to voxel `root` in ctx->dj_dist. False
// when the Dijkstra ran out without reaching voxel `other` (no path). search_tables.cpp.
bool exact_lower_bounds(tdo_search* ctx, const tdo_grid* g, uint32_t root, uint32_t other);

// The table of a side from the Dijkstra's keys: each rounded down to a float.
void store_lower_bounds(const double* dist, uint32_t nvox, float* table);

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

#endif  // TDO_SRC_SEARCH_TABLES_H
