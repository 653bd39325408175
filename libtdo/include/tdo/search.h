/**
 * @file search.h
 * @brief Stage 1: A* and bidirectional A* over (voxel, heading) states.
 *
 * Without penalties the heading carries no cost and every voxel is one state, so the search costs
 * no more than A* over voxels. With lambda or mu > 0 states are (voxel, heading); design:
 * docs/design.md s.1.
 */
#ifndef TDO_SEARCH_H
#define TDO_SEARCH_H

#include "tdo/arena.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Which search runs. */
typedef enum tdo_search_kind {
  TDO_SEARCH_ASTAR = 0, /**< unidirectional A* */
  TDO_SEARCH_BIDIR = 1  /**< bidirectional A* with the optimal stopping rule */
} tdo_search_kind;

/** What a turn-penalised search starts with (tdo_search_input.grid_first). The grid distances
 *  need the tables (tdo_search_config.exact_heuristic). docs/performance.md compares the three. */
typedef enum tdo_grid_first {
  TDO_GRID_FIRST_OFF = 0, /**< docs/design.md s.1's search with the octile distance; grid distances
                               only in its retry, when it floods (default) */
  TDO_GRID_FIRST_PLAIN = 1, /**< start as that retry: grid distances weighted by 2, no deviation
                                 term or turn bound */
  TDO_GRID_FIRST_TERMS = 2 /**< docs/design.md s.1's f with h = max(octile, grid distance), weighted
                                by h_weight, deviation term and turn bound kept; the retry as
                                with OFF when it floods */
} tdo_grid_first;

/** The states of a turn-penalised search (tdo_search_input.states). */
typedef enum tdo_state_space {
  TDO_STATES_HEADING = 0, /**< (voxel, heading): the turn cost is exact per heading (default) */
  TDO_STATES_VOXEL = 1    /**< one state per voxel, whose heading is the step it was reached by:
                               plain A*'s states and memory; the turn and deviation terms are
                               those of its parent chain, so the cost is not optimal;
                               grid_first puts the grid distances in h as for heading states */
} tdo_state_space;

/** A corridor that confines a search to some coarse cells of the grid (tdo_search_input.corridor;
 *  docs/design.md s.1, "The coarse guide"). A coarse cell is a block of 2^shift voxels per edge;
 *  cell c of voxel (i,j,k) is (i>>shift) + cnx * ((j>>shift) + cny * (k>>shift)). */
typedef struct tdo_search_corridor {
  const uint32_t* cells; /**< per coarse cell: bit n = (dx+1) + 3*(dy+1) + 9*(dz+1) set when the
                              cell at offset (dx,dy,dz), dx,dy,dz in -1..1, is in the corridor;
                              0 for a cell outside it (bit 13 is the cell itself) */
  int32_t shift;         /**< log2 of the coarse cell edge in voxels, 1..7 */
  int32_t cnx;           /**< coarse cells along x */
  int32_t cny;           /**< coarse cells along y */
} tdo_search_corridor;
/** Opaque search context; carved from an arena by tdo_search_init. */
typedef struct tdo_search tdo_search;

/** Capacities of one search context. */
typedef struct tdo_search_config {
  uint32_t max_voxels;      /**< largest grid it will search */
  uint32_t max_nodes;       /**< state pool per direction: < 2^31, or < 2^15 in the 16-bit index
                                 build (library tdo_index16, which also needs max_voxels < 2^16
                                 and grid axes < 256); beyond: TDO_ERR_INVALID_ARGUMENT at init.
                                 Heading states take states as they are created; max_voxels
                                 covers plain A* and voxel states (tdo_search_output.fallback 3) */
  uint32_t max_path;        /**< voxels in the returned path */
  uint32_t max_expansions;  /**< default budget when the input gives 0 */
  uint32_t dense_headings;  /**< 1: a 27-entry heading index per voxel (108 bytes per voxel and
                                 direction) for turn-penalised searches; 0: per-voxel chains */
  uint32_t exact_heuristic; /**< 1: grid-distance tables (24 bytes per voxel) for the retry of a
                                 flooding turn-penalised search (tdo_search_output.fallback) and for
                                 tdo_search_input.grid_first */
  uint32_t max_open;        /**< open-list items per direction (16 bytes each, 14 in tdo_index16,
                                 plus 27 entries of slack: one expansion's worth); a search whose
                                 open list holds more before an expansion stops with
                                 TDO_ERR_OPEN_CAPACITY (tdo_search_output.peak_open measures the
                                 need). 0 = max_nodes, which can never overflow */
} tdo_search_config;

/** One query. */
typedef struct tdo_search_input {
  const tdo_grid* grid;    /**< finished grid to search */
  tdo_vec3 start;          /**< m, world frame */
  tdo_vec3 goal;           /**< m, world frame */
  tdo_search_kind kind;    /**< A* or bidirectional */
  double lambda;           /**< m of cost per (turn/pi)^2, >= 0; 0 = no turn penalty */
  double mu;               /**< m of f per unit deviation, >= 0; 0 = no deviation term */
  double theta_max;        /**< rad; steps within theta_max of the heading are expanded directly,
                                sharper ones only through a pivot (turn in place at the turn cost
                                plus a surcharge). <= 0 or >= pi: unconstrained */
  double h_weight;         /**< heuristic weight w >= 1 of turn-penalised searches: f = g + w*h.
                                1 (or 0) keeps h admissible; larger trades cost for speed (the
                                cost found is at most w times the best). Ignored without
                                penalties, so plain A* and bidir stay optimal */
  double d_th;             /**< deviation threshold in (0, 1): steps deviating more from the target
                                direction go through a pivot too. <= 0 or >= 1: off */
  uint32_t max_expansions; /**< expansions allowed (both directions); 0 = configured default */
  int first_meet;          /**< bidirectional only: 1 = stop as soon as the two searches meet (the
                                paper's Algorithm 1, line 12); 0 = stop by the optimal rule (the
                                smaller f of either side reaches the best meeting cost) */
  int grid_first;          /**< turn-penalised searches: a tdo_grid_first. PLAIN skips the octile
                                try and starts as its retry does; TERMS keeps the f of the octile
                                try with grid distances in h. Faster where walls make the octile
                                try flood, slower on open maps (docs/performance.md). Needs the
                                tables (tdo_search_config.exact_heuristic); without them, or
                                outside 0..2: TDO_ERR_INVALID_ARGUMENT. Plain A* and bidir ignore
                                it */
  int states;              /**< turn-penalised searches: a tdo_state_space (0 = heading states);
                                outside 0..1: TDO_ERR_INVALID_ARGUMENT */
  const tdo_search_corridor* corridor; /**< NULL: the whole grid. Else steps enter only the
                                corridor's cells (start and goal must lie in it, else
                                TDO_ERR_INVALID_ARGUMENT), and a turn-penalised search makes one
                                try (no retry): TDO_ERR_NO_PATH then says "not in this corridor" */
} tdo_search_input;

/**
 * @brief Extra cost (m) of a pivot: lambda * (theta_max / pi)^2, the price of the sharpest direct
 *        turn, so a pivot never undercuts a direct step. 0 when unconstrained.
 */
double tdo_search_pivot_cost(double lambda, double theta_max);

/** Result of one query. Arrays point into the context and stay valid until the next run. */
typedef struct tdo_search_output {
  double cost;           /**< m, sum of step lengths between voxel centres (penalties excluded) */
  double penalized_cost; /**< m, cost plus turn penalties (equals cost when lambda = 0) */
  uint32_t expansions;   /**< states expanded, both directions */
  uint32_t pivots;       /**< pivots (sharp turns in place) on the returned path */
  uint32_t n_path;       /**< voxels in path, start voxel first, goal voxel last */
  const tdo_voxel* path; /**< the voxel path */
  uint32_t peak_open;    /**< most open-list items (states waiting for expansion and items of
                              deferred children) a direction held before one of its expansions,
                              every try counted: the smallest max_open this query runs with */
  uint32_t peak_nodes;   /**< most states a direction held in any try: the smallest max_nodes
                              this query runs with */
  uint32_t states;       /**< states created, both directions, every try (the roots included) */
  uint32_t fallback;     /**< turn-penalised search: 0 = found by the first try (octile heuristic);
                              1 or 2 = by a retry with the obstacle-aware heuristic weighted by 2
                              or 10 (the try before flooded: more than max(20000, voxels / 16)
                              expansions, progress towards the targets too slow to finish within
                              half of them (first try only), or a full node pool; with
                              grid_first the octile try is skipped, so at least 1). 3 = the
                              heading states filled the node pool (max_nodes) in every try,
                              and voxel states (tdo_state_space) found the path with the rest of
                              the budget: a plan whenever plain A* has one, at a turn cost that
                              is not the heading search's (needs max_nodes >= the grid's voxels;
                              else the pool's status). expansions counts every try */
  uint32_t guide;        /**< set by the planner (tdo_capacity.guide_shift): 0 = no coarse guide,
                              1 = found in the guide's corridor, 2 = the corridor held no path and
                              the whole grid was searched, 3 = a short query answered by its
                              whole-grid try (docs/design.md s.1) */
  uint32_t guide_expansions; /**< the guide's spent short try, coarse search and corridor search;
                              expansions counts the search that returned */
  uint32_t direct;           /**< set by the planner: 1 = the straight segment from start to goal
                              keeps the clearance and no search ran (n_path = 0; cost = its
                              length; docs/design.md s.1, "The direct route") */
} tdo_search_output;

/** @return arena bytes tdo_search_init carves for `cfg`. */
size_t tdo_search_footprint(const tdo_search_config* cfg);

/**
 * @brief Carve a search context from `arena`.
 * @return TDO_ERR_INVALID_ARGUMENT for zero capacities, TDO_ERR_ARENA_TOO_SMALL when it does not
 * fit.
 */
tdo_status tdo_search_init(tdo_search** ctx, tdo_arena* arena, const tdo_search_config* cfg);

/**
 * @brief Plan on the grid. Allocates nothing.
 * @return TDO_ERR_START_OUT_OF_BOUNDS / TDO_ERR_GOAL_OUT_OF_BOUNDS, TDO_ERR_START_BLOCKED /
 *         TDO_ERR_GOAL_BLOCKED, TDO_ERR_START_EQUALS_GOAL, TDO_ERR_NO_PATH, TDO_ERR_NODE_CAPACITY,
 *         TDO_ERR_OPEN_CAPACITY, TDO_ERR_PATH_CAPACITY, TDO_ERR_BUDGET, TDO_ERR_MAP_NOT_READY,
 * TDO_ERR_INVALID_ARGUMENT.
 */
tdo_status tdo_search_run(tdo_search* ctx, const tdo_search_input* in, tdo_search_output* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SEARCH_H */
