/**
 * @file grid.h
 * @brief The voxel grid: obstacle geometry, world/voxel conversion, blocked voxels and legal steps.
 *
 * Voxel (i,j,k) spans [origin + i*res, origin + (i+1)*res) on each axis; its centre is
 * origin + (i + 0.5)*res. A voxel is blocked when it intersects an obstacle or its centre is closer
 * than `clearance` to one. Steps are 26-connected with no corner or edge cutting (MovingAI rule).
 */
#ifndef TDO_GRID_H
#define TDO_GRID_H

#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Opaque grid; carved from the planner arena. */
typedef struct tdo_grid tdo_grid;

/** Size and placement of a grid. */
typedef struct tdo_grid_desc {
  int32_t nx;      /**< voxels along x (> 0) */
  int32_t ny;      /**< voxels along y (> 0) */
  int32_t nz;      /**< voxels along z (> 0) */
  double res;      /**< m per voxel edge (> 0) */
  tdo_vec3 origin; /**< m, world position of the minimum corner of voxel (0,0,0) */
} tdo_grid_desc;

/**
 * @brief Start a new map: clears all obstacles. The grid is not plannable until tdo_grid_finish.
 * @return TDO_ERR_INVALID_ARGUMENT for non-positive or non-finite sizes,
 *         TDO_ERR_MAP_CAPACITY when nx*ny*nz exceeds max_voxels or an axis exceeds a non-zero
 *         max_axis (config.h).
 */
tdo_status tdo_grid_reset(tdo_grid* grid, const tdo_grid_desc* desc);

/**
 * @brief Add an obstacle box (may reach outside the bounds; the outside part is ignored).
 * @return TDO_ERR_INVALID_BOX for max <= min or non-finite corners, TDO_ERR_BOX_CAPACITY when full.
 */
tdo_status tdo_grid_add_box(tdo_grid* grid, const tdo_box* box);

/**
 * @brief Mark voxel (i,j,k) as an occupied cube (voxel maps, OcTrees).
 * @return TDO_ERR_INVALID_ARGUMENT when the voxel lies outside the grid, TDO_ERR_MAP_CAPACITY when
 *         the planner was configured for boxes only (tdo_capacity.boxes_only).
 */
tdo_status tdo_grid_add_voxel(tdo_grid* grid, int32_t i, int32_t j, int32_t k);

/**
 * @brief Compute blocked voxels for `clearance` and the legal steps. Call again to change
 * clearance.
 * @param clearance m, >= 0, finite
 * @return TDO_ERR_INVALID_ARGUMENT for a negative or non-finite clearance,
 *         TDO_ERR_CLEARANCE_CAPACITY when the clearance stencil exceeds max_clear_cells.
 */
tdo_status tdo_grid_finish(tdo_grid* grid, double clearance);

/**
 * @brief Do the one-off work of a finished grid now rather than on first use: the legal steps
 * (otherwise computed by the first search) and the distance field (otherwise built by the first
 * collision query that needs it). Both are O(voxels) once per tdo_grid_finish; an online app calls
 * this when a map arrives so that no later query pays for it. Optional: results are the same
 * with or without it. Map updates (grid_update.h) keep prepared data current.
 * @return TDO_ERR_INVALID_ARGUMENT for a null grid, TDO_ERR_MAP_NOT_READY before a successful
 *         tdo_grid_finish.
 */
tdo_status tdo_grid_prepare(tdo_grid* grid);

/** @return the grid's size and placement. */
tdo_grid_desc tdo_grid_get_desc(const tdo_grid* grid);

/** @return the clearance (m) of the last tdo_grid_finish, or -1 when not finished. */
double tdo_grid_clearance(const tdo_grid* grid);

/** @return 1 when world point `p` lies inside the grid bounds (half-open), else 0. */
int tdo_grid_world_to_voxel(const tdo_grid* grid, tdo_vec3 p, tdo_voxel* out);

/** @return world position (m) of the centre of voxel v. */
tdo_vec3 tdo_grid_voxel_center(const tdo_grid* grid, tdo_voxel v);

/** @return 1 when voxel v is outside the grid or blocked for the search, else 0. */
int tdo_grid_is_blocked(const tdo_grid* grid, tdo_voxel v);

/** @return 1 when voxel v intersects obstacle geometry (clearance ignored), else 0. */
int tdo_grid_is_occupied(const tdo_grid* grid, tdo_voxel v);

/** @return number of blocked voxels after tdo_grid_finish. */
uint32_t tdo_grid_blocked_count(const tdo_grid* grid);

#ifdef __cplusplus
}
#endif

#endif /* TDO_GRID_H */
