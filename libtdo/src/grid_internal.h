// Layout of tdo_grid, shared by the grid and the search. Internal to libtdo.
#ifndef TDO_SRC_GRID_INTERNAL_H
#define TDO_SRC_GRID_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "tdo/arena.h"
#include "tdo/grid.h"

namespace tdo_internal {
constexpr uint8_t kFlagOccupied = 1u;  // voxel intersects obstacle geometry
constexpr uint8_t kFlagCube = 2u;      // voxel cube itself is an obstacle (voxel maps, OcTrees)
constexpr uint8_t kFlagBlocked = 4u;   // occupied, or centre closer than clearance to an obstacle

struct GridCapacity {
  uint32_t max_voxels;
  uint32_t max_boxes;
  uint32_t max_clear_cells;
};
size_t grid_footprint(const GridCapacity& cap);
tdo_status grid_init(tdo_grid** out, tdo_arena* arena, const GridCapacity& cap);
}  // namespace tdo_internal

struct tdo_grid {
  tdo_internal::GridCapacity cap;
  tdo_grid_desc desc;  // current size and placement
  uint32_t nvox;       // nx*ny*nz, 0 before the first reset
  int64_t stride_y;    // nx
  int64_t stride_z;    // nx*ny
  uint8_t* flags;      // kFlag* per voxel, index i + j*nx + k*nx*ny
  uint32_t* moves;     // bit d set when step d from this voxel is legal (pipeline.md s.0)
  tdo_box* boxes;      // obstacle boxes, exact geometry
  uint32_t n_boxes;
  int32_t* stencil;    // clearance stencil: 3 offsets per cell
  uint32_t n_cubes;    // voxels marked as cubes
  uint32_t n_blocked;  // blocked voxels after finish
  double clearance;    // m, of the last finish; -1 when not finished
  int ready;           // 1 after a successful finish
};

#endif  // TDO_SRC_GRID_INTERNAL_H
