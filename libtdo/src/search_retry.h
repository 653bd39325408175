// Retry control of the turn-penalised search (search_retry.cpp) and what it calls in search.cpp.
// Internal to libtdo.
#ifndef TDO_SRC_SEARCH_RETRY_H
#define TDO_SRC_SEARCH_RETRY_H

#include <stdint.h>

#include "search_state.h"
#include "tdo/search.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {

// search_retry.cpp: the tries of a heading-state search, with the retries and the voxel-state
// fallback; the grid-distance tables of the sides (false, the counts reported, when they show the
// goal unreachable); the heuristic weight of retry t (0 or 1).
tdo_status run_headed(tdo_search* ctx, Query& q, const tdo_search_input* in,
                      tdo_search_output* out);
bool build_tables(tdo_search* ctx, Query& q, tdo_search_output* out);
double retry_weight(int t);

// search.cpp: one try of the heading-state search, the voxel-state search with turn costs, the
// path of the last search, the query's counters, the octile distance.
tdo_status search_try(tdo_search* ctx, Query& q);
tdo_status search_voxel_turns(tdo_search* ctx, Query& q, int grid_first, tdo_search_output* out);
tdo_status search_write_path(tdo_search* ctx, const Query& q, tdo_search_output* out);
void search_report(const Query& q, tdo_search_output* out);
double search_octile(int32_t a, int32_t b, int32_t c, double res);

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

#endif  // TDO_SRC_SEARCH_RETRY_H
