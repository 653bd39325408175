// Retry control of the turn-penalised search (docs/design.md s.1, "Retry with grid distances" and
// "Completeness"): the tries with the octile heuristic and with the grid-distance tables, their
// shares of the budget, and the voxel-state fallback when the heading states fill the pool.
#include "search_retry.h"

#include <math.h>
#include <stdint.h>

#include "grid_internal.h"
#include "search_state.h"
#include "search_tables.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {
namespace {

// Heuristic weights of the retries with the obstacle-aware heuristic (the last gets the rest of
// the budget).
constexpr int kRetries = 2;
// tdo_search_output.fallback of a search that ended in voxel states (run_pool_fallback).
constexpr uint32_t kPoolFallback = 3u;
constexpr double kRetryWeight[kRetries] = {2.0, 10.0};

// Every try of a turn-penalised search but the last gets max(kTryMin, nvox / kTryDiv) expansions.
constexpr uint32_t kTryMin = 20000;
constexpr uint32_t kTryDiv = 16;

inline int32_t iabs(int32_t a) { return a < 0 ? -a : a; }

}  // namespace

// The grid-distance tables of the sides (once per query: tdo_search_run clears side.hx before
// it): side k's distances to its target. False (the counts reported) when they show that the goal
// cannot be reached.
bool build_tables(tdo_search* ctx, Query& q, tdo_search_output* out) {
  if (ctx->side[0].hx != nullptr) return true;
  for (int k = 0; k < (q.bidir ? 2 : 1); ++k) {
    if (!exact_lower_bounds(ctx, q.grid, q.voxel[1 - k], q.voxel[k])) {
      search_report(q, out);
      return false;
    }
    store_lower_bounds(ctx->dj_dist, q.grid->nvox, ctx->hdist[k]);
    ctx->side[k].hx = ctx->hdist[k];
  }
  return true;
}

namespace {

// Set up retry t + 1 of a turn-penalised search after try t: the grid-distance tables, the
// retry's weight, no deviation terms. False (the counts reported) when the tables show that the
// goal cannot be reached.
bool start_retry(tdo_search* ctx, Query& q, int t, tdo_search_output* out) {
  if (!build_tables(ctx, q, out)) return false;
  q.best = HUGE_VAL;
  q.meet[0] = q.meet[1] = kNil;
  q.h_weight = q.h_weight > kRetryWeight[t] ? q.h_weight : kRetryWeight[t];
  // The deviation term and the turn bound aim at the straight line to the target, through walls:
  // they would flood as the octile distance did.
  q.dev_terms = 0;
  out->fallback = static_cast<uint32_t>(t + 1);
  return true;
}

// The heading states filled their node pool with expansion budget left, and voxel states, one per
// voxel and side, fit the pool: the voxel-state fallback can run. (A full open list stays a full
// open list: max_open is a caller's choice below the pool, design s.1 "Memory and work".)
bool pool_spent(const tdo_search* ctx, const Query& q, tdo_status st, uint32_t budget) {
  return st == TDO_ERR_NODE_CAPACITY && q.expansions < budget && ctx->cfg.max_nodes >= q.grid->nvox;
}

// The heading states' pool ran out: search again with voxel states (the pool holds one per voxel,
// so they reach every voxel plain A* reaches) with the rest of the budget, the input's weight and
// terms, and the tables in h when a retry built them. tdo_search_output.fallback says so (3): the
// plan's turn cost is not the heading search's (docs/design.md s.1, "Completeness").
tdo_status run_pool_fallback(tdo_search* ctx, Query& q, const tdo_search_input* in, uint32_t budget,
                             tdo_search_output* out) {
  q.best = HUGE_VAL;
  q.meet[0] = q.meet[1] = kNil;
  q.h_weight = in->h_weight > 1.0 ? in->h_weight : 1.0;
  q.dev_terms = 1;
  q.budget = budget;
  q.try_share = 0u;
  q.try_first = q.expansions;
  const tdo_status st = search_voxel_turns(ctx, q, TDO_GRID_FIRST_OFF, out);
  out->fallback = kPoolFallback;
  return st;
}

}  // namespace

double retry_weight(int t) { return kRetryWeight[t]; }

// The tries of a turn-penalised search on heading states (tdo_search_run has set up q).
tdo_status run_headed(tdo_search* ctx, Query& q, const tdo_search_input* in,
                      tdo_search_output* out) {
  const tdo_grid* g = q.grid;
  // Turn-penalised search, first with the octile heuristic and the deviation term. They know no
  // walls, so in front of one the (voxel, heading) states flood the whole region behind it. When
  // a try expands more than max(kTryMin, nvox / kTryDiv) states (the first one: or is projected
  // to, see flooding) or fills the node pool, the search
  // starts again with the obstacle-aware heuristic (grid distances to each side's target,
  // exact_lower_bounds) weighted by kRetryWeight, ordered by g + w h alone: bounded-suboptimal
  // (with the optimal stopping rule the penalised cost is at most w times the best), but it follows
  // the free space. The tries share the expansion budget; the last one gets all that is left.
  // One table for both sides (the goal's, with the landmark bound D(start) - D(v) backward) was
  // tried and not kept: rooted at the landmark, the backward side learns nothing about the
  // direction to the start (geb079 2.7 times the expansions; docs/performance.md).
  const uint32_t budget = q.budget;
  // No tables: no retry. In a corridor neither: its caller falls back to the whole grid.
  const int retries = ctx->cfg.exact_heuristic && q.corridor == nullptr ? kRetries : 0;
  const uint32_t share = g->nvox / kTryDiv > kTryMin ? g->nvox / kTryDiv : kTryMin;
  q.h_root = search_octile(iabs(q.v[1].i - q.v[0].i), iabs(q.v[1].j - q.v[0].j),
                           iabs(q.v[1].k - q.v[0].k), g->desc.res);
  tdo_status st = TDO_OK;
  // grid_first PLAIN: the octile try is skipped, the search starts as the first retry. TERMS: the
  // first try has the tables too (its f otherwise unchanged), and its progress is measured in
  // them.
  int t = 0;
  if (in->grid_first == TDO_GRID_FIRST_PLAIN) {
    if (!start_retry(ctx, q, 0, out)) return TDO_ERR_NO_PATH;
    t = 1;
  } else if (in->grid_first == TDO_GRID_FIRST_TERMS) {
    if (!build_tables(ctx, q, out)) return TDO_ERR_NO_PATH;
    const double d = static_cast<double>(ctx->side[0].hx[q.voxel[0]]);
    q.h_root = d > q.h_root ? d : q.h_root;  // heuristic() of the start
  }
  for (; t <= retries; ++t) {  // bounded: retries + 1 tries
    const uint64_t cut = static_cast<uint64_t>(q.expansions) + share;
    q.budget = t < retries && cut < budget ? static_cast<uint32_t>(cut) : budget;
    // The flood test (flooding) runs in the first try only: the retries follow the free space.
    q.try_share = t == 0 && t < retries ? share : 0u;
    q.try_first = q.expansions;
    q.h_best[0] = q.h_best[1] = q.h_root;
    st = search_try(ctx, q);
    const bool retry =
        t < retries && q.expansions < budget &&
        (st == TDO_ERR_BUDGET || st == TDO_ERR_NODE_CAPACITY || st == TDO_ERR_OPEN_CAPACITY);
    if (!retry) break;
    if (!start_retry(ctx, q, t, out)) return TDO_ERR_NO_PATH;
  }
  if (pool_spent(ctx, q, st, budget)) return run_pool_fallback(ctx, q, in, budget, out);
  search_report(q, out);
  if (st != TDO_OK) return st;
  return search_write_path(ctx, q, out);
}

}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal
