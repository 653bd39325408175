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
                                 (5 bytes per voxel) and the per-voxel search slots (8 bytes per
                                 voxel and search direction). */
  uint32_t max_boxes;       /**< obstacle boxes kept for exact distance queries (48 bytes each) */
  uint32_t max_nodes;       /**< search states per direction (56 bytes each): at most
                                 max_voxels without heading costs, up to 27x that with them */
  uint32_t max_path;        /**< voxels in one grid path (4 + 24 bytes each) */
  uint32_t max_clear_cells; /**< offsets in the clearance stencil: (2K+1)^3 with
                                 K = ceil(clearance/res + 0.5) covers a clearance (12 bytes each) */
  uint32_t max_expansions;  /**< default expansion budget of one search (both directions) */
} tdo_capacity;

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

/** @return bytes of arena a planner with this configuration needs (0 if cfg is invalid). */
size_t tdo_planner_footprint(const tdo_planner_config* cfg);

#ifdef __cplusplus
}
#endif

#endif /* TDO_CONFIG_H */
