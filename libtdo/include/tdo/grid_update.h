/**
 * @file grid_update.h
 * @brief Incremental changes to a finished grid: voxel cubes set or cleared, boxes added.
 *
 * The work is proportional to the update, not to the map: blocked voxels (clearance) are
 * recomputed only within the clearance stencil of each changed voxel or box, legal steps only
 * around voxels whose blocked bit flipped, and the collision structures (collision.h) stay exact:
 * added boxes join the list every query scans, the distance field is lowered around new obstacles
 * and read as a lower bound only (docs/design.md s.0, "Map updates"). The result equals a grid
 * rebuilt from scratch with the same obstacles: same blocked voxels and legal steps, same
 * collision answers. A full rebuild (tdo_grid_finish) restores the fastest query structures.
 */
#ifndef TDO_GRID_UPDATE_H
#define TDO_GRID_UPDATE_H

#include <stdint.h>

#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** One incremental change; all of it applies or none (everything is checked first). */
typedef struct tdo_grid_update {
  const tdo_voxel* set;   /**< voxels that become occupied cubes (inside the grid) */
  uint32_t n_set;         /**< entries of set */
  const tdo_voxel* clear; /**< voxels whose cube is removed; a box covering one stays */
  uint32_t n_clear;       /**< entries of clear */
  const tdo_box* boxes;   /**< m, world frame: obstacle boxes added (may reach outside) */
  uint32_t n_boxes;       /**< entries of boxes */
  uint64_t max_cells;     /**< work budget in voxel visits (tdo_grid_update_work); 0: none */
} tdo_grid_update;

/** What an update did. */
typedef struct tdo_grid_update_result {
  uint32_t cubes_set;     /**< voxels that became cubes (already cubes are not counted) */
  uint32_t cubes_cleared; /**< cubes removed (voxels that were no cube are not counted) */
  uint32_t boxes_added;   /**< boxes appended */
  uint32_t blocked_on;    /**< voxels that became blocked */
  uint32_t blocked_off;   /**< voxels that became free */
  uint64_t cells_touched; /**< voxel visits of the update: the work done (<= the work bound) */
} tdo_grid_update_result;

/**
 * @brief Upper bound of the voxel visits tdo_grid_apply_update needs for `update` on `grid`:
 *        a constant per set or cleared voxel (from the clearance) plus each box's grown volume.
 * @return voxel visits; 0 for a null or unfinished grid or a null update.
 */
uint64_t tdo_grid_update_work(const tdo_grid* grid, const tdo_grid_update* update);

/**
 * @brief Apply `update` to a finished grid (at the clearance of its last tdo_grid_finish).
 * @param[out] out what changed (may be null)
 * @return TDO_ERR_MAP_NOT_READY for an unfinished grid; TDO_ERR_INVALID_ARGUMENT for null
 *         pointers with non-zero counts or a voxel outside the grid; TDO_ERR_INVALID_BOX;
 *         TDO_ERR_BOX_CAPACITY when the boxes would exceed max_boxes; TDO_ERR_MAP_CAPACITY for
 *         voxels on a boxes_only grid; TDO_ERR_UPDATE_CONTRADICTORY when one voxel is both set
 *         and cleared; TDO_ERR_BUDGET when the work bound exceeds max_cells. On any error the grid
 *         is unchanged.
 */
tdo_status tdo_grid_apply_update(tdo_grid* grid, const tdo_grid_update* update,
                                 tdo_grid_update_result* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_GRID_UPDATE_H */
