/**
 * @file config.h
 * @brief Capacities of a planner and the arena footprint they imply, in one place.
 *
 * Every buffer libtdo uses is sized from these numbers at init; nothing grows afterwards.
 */
#ifndef TDO_CONFIG_H
#define TDO_CONFIG_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Capacities fixed at init. Exceeding any of them returns a named status, never truncates. */
typedef struct tdo_capacity {
  uint32_t max_voxels;      /**< nx*ny*nz of the largest map; sizes the occupancy and move masks
                                 (5 bytes per voxel) and the per-voxel search slots (4 bytes per
                                 voxel and search direction). */
  uint32_t max_boxes;       /**< obstacle boxes kept for exact distance queries (48 bytes each) */
  uint32_t max_nodes;       /**< search states per direction (32 bytes each, plus 16 for the open
                                 list while max_open = 0; 20 and 14 in the 16-bit index build
                                 tdo_index16, see search.h): the state budget. max_voxels
                                 covers plain A*; heading states take states as they are created,
                                 and when they fill the pool the search ends in voxel states
                                 (tdo_search_output.fallback 3), which max_voxels covers.
                                 tdo_capacity_for_grid: max_voxels, for 27 headings
                                 min(27 max_voxels, max(max_voxels, 2^18)) */
  uint32_t max_path;        /**< voxels in one grid path (4 + 24 bytes each) */
  uint32_t max_clear_cells; /**< offsets in the clearance stencil: (2K+1)^3 with
                                 K = ceil(clearance/res + 0.5) covers a clearance (12 bytes each) */
  uint32_t max_expansions;  /**< default expansion budget of one search (both directions) */
  uint32_t max_box_refs;    /**< entries of the box bucket index of collision queries (4 bytes
                                 each): a box is listed in every coarse cell (4^3 voxels or more)
                                 that the box grown by max(clearance, 2 voxel edges) touches, when
                                 that is at most 64 cells (larger boxes go to a list every query
                                 scans). 0 = max_boxes * 64, which can never overflow; a non-zero
                                 value too small for the map makes tdo_grid_finish return
                                 TDO_ERR_BOX_CAPACITY. The grid also keeps a distance field (4 bytes
                                 per voxel), a few cell offsets (1/4 byte per voxel) and a brick
                                 index of the surface cubes (10 bytes per 32 voxels). */
  uint32_t dense_headings;  /**< 1: every voxel gets a 27-entry heading index per search direction
                                 (108 bytes per voxel and direction), so turn-penalised searches
                                 find a (voxel, heading) state in one read; 0: states of a voxel
                                 are chained from its slot, as plain A* stores it.
                                 tdo_capacity_for_grid sets 1 for 27 headings on grids of at most
                                 2^16 voxels, else 0 */
  uint32_t exact_heuristic; /**< 1: grid-distance tables (24 bytes per voxel) for the obstacle-aware
                                 retry of a turn-penalised search whose octile-guided try floods
                                 (search.h, tdo_search_output.fallback); 0: no retry.
                                 tdo_capacity_for_grid sets 1 for 27 headings, else 0 */
  uint32_t max_checks;      /**< segment clearance checks of one inflection correction (budget) */
  uint32_t max_shrinks;     /**< radius reductions per corner when smoothing (budget) */
  uint32_t max_samples;     /**< trajectory samples: flight time / dt + 1 (84 bytes each when
                                 stored, 0 with stream_samples) */
  uint32_t max_profile;     /**< speed-profile pieces: TDO_TRAJ_PIECES_PER_SEGMENT per path segment
                                 + 1 (see trajectory.h; 8 per segment + 1 is a slower minimum) */
  uint32_t max_violations;  /**< violations listed in a feasibility report (40 bytes each) */
  uint32_t max_refinements; /**< feasibility refinement rounds before TDO_ERR_INFEASIBLE */
  uint32_t stream_samples;  /**< 0: trajectory samples are stored (tdo_plan_result.samples);
                                 1: not stored, verified and measured in streaming passes (same
                                 numbers); 2: not stored, verified per profile piece in closed form
                                 (fallback to 1 per round: tdo_plan_result.sample_passes; the
                                 feasibility report's maxima are bounds and the energy the
                                 integral, trajectory.h); 1 and 2: read with tdo_planner_each_sample
                                 (tdo_traj_config.stream_samples). tdo_capacity_for_grid sets 2 on
                                 grids of TDO_GUIDE_MIN_VOXELS or more, else 0 */
  uint32_t max_open;        /**< search open-list items per direction (16 bytes each, plus 27 of
                                 slack); 0 = max_nodes (never full). Too small:
                                 TDO_ERR_OPEN_CAPACITY; tdo_search_output.peak_open measures a
                                 query's need. tdo_capacity_for_grid sets 0 */
  uint32_t max_axis;        /**< voxels along the longest grid axis; sizes the distance field's
                                 line scratch (8 bytes each). 0 = max_voxels (never too small). A
                                 grid with a longer axis: tdo_grid_reset returns
                                 TDO_ERR_MAP_CAPACITY. tdo_capacity_for_grid sets 0 */
  uint32_t boxes_only;      /**< 1: obstacles are boxes only (.tdomap maps), so the grid keeps no
                                 distance field (4 bytes per voxel less, and no line scratch);
                                 tdo_grid_add_voxel returns TDO_ERR_MAP_CAPACITY. 0: voxel
                                 obstacles too (voxel maps, OcTrees). tdo_capacity_for_grid
                                 sets 0 */
  uint32_t max_waypoints;   /**< waypoints after the correction (start and goal included); sizes
                                 the smoothing and trajectory segment arrays (3 segments per
                                 waypoint, about 280 bytes per waypoint). 0 = max_path + 2, the
                                 most a correction can return. More: the smoothing stage returns
                                 TDO_ERR_PATH_CAPACITY. tdo_capacity_for_grid sets 0 */
  uint32_t guide_shift;     /**< 0: no coarse guide. 1..7: turn-penalised searches first plan on
                                 coarse cells of 2^guide_shift voxels per edge and search a
                                 corridor around that plan, the whole grid only when the corridor
                                 holds no path (docs/design.md s.1, "The coarse guide"; about
                                 max_voxels / 2^(2 guide_shift + 1) cells of ~120 bytes).
                                 tdo_capacity_for_grid sets 2 for 27 headings on grids of
                                 TDO_GUIDE_MIN_VOXELS or more, else 0 */
} tdo_capacity;

/** Grids of this many voxels or more get the coarse guide from tdo_capacity_for_grid (2^19: the
 *  forest_gen forests, 541,008 voxels, are guided; Map1-5 are not). */
#define TDO_GUIDE_MIN_VOXELS 524288u

/** Configuration of a whole planner. */
typedef struct tdo_planner_config {
  tdo_capacity cap; /**< capacities, see tdo_capacity */
} tdo_planner_config;

/**
 * @brief Capacities that fit a grid of nx*ny*nz voxels with clearance/res up to `clear_ratio`.
 * @param[out] cap filled with max_voxels = n, max_nodes = n * headings (capped at `node_cap` when
 *             node_cap > 0), max_path = nx+ny+nz scaled for detours, and a matching stencil.
 * @param headings 1 for searches without heading costs, 27 for turn-penalised searches.
 */
void tdo_capacity_for_grid(tdo_capacity* cap, int32_t nx, int32_t ny, int32_t nz,
                           double clear_ratio, uint32_t headings, uint32_t node_cap);

/**
 * @brief The search aids of `cap` for a grid of nx*ny*nz voxels, the one rule tdo-plan,
 *        tdo-bench-scale and tdo_capacity_for_grid share: with `turn_penalised` (a search with
 *        heading costs, heading or voxel states) the obstacle-aware retry's tables
 *        (exact_heuristic 1) and, on grids of TDO_GUIDE_MIN_VOXELS or more, the coarse guide
 *        (guide_shift 2), whose corridor keeps the states a search creates near the plan's;
 *        without, neither (0). Other fields are left as they are; a non-positive size sets
 *        neither.
 */
void tdo_capacity_guide(tdo_capacity* cap, int32_t nx, int32_t ny, int32_t nz, int turn_penalised);

/** @return bytes of arena a planner with this configuration needs (0 if cfg is invalid). */
size_t tdo_planner_footprint(const tdo_planner_config* cfg);

#ifdef __cplusplus
}
#endif

#endif /* TDO_CONFIG_H */
