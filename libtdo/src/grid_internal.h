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
constexpr uint8_t kFlagSurface = 8u;   // cube with a face neighbour that is not a cube (or outside
                                       // the grid): only these can hold the nearest obstacle point
constexpr uint8_t kFlagMark = 16u;     // scratch of grid_update.cpp, 0 between calls

struct GridCapacity {
  uint32_t max_voxels;
  uint32_t max_boxes;
  uint32_t max_clear_cells;
  uint32_t max_box_refs = 0;  // bucket index entries; 0 = max_boxes * kRefsPerBoxDefault
  uint32_t max_axis = 0;      // voxels along the longest axis; 0 = not limited (max_voxels)
  uint32_t boxes_only = 0;    // 1: no voxel obstacles, so no distance field (tdo_capacity)
};

// Distance field and box buckets (collision queries, built by tdo_grid_finish).
constexpr uint32_t kDfMaxAxis = 32768;         // longest axis the exact EDT handles (voxels):
                                               // 3 * (n-1)^2 stays below 2^32
constexpr uint32_t kDfInfinite = 0xFFFFFFFFu;  // squared distance "no occupied voxel on the line"
constexpr int32_t kCellVoxels = 4;             // first choice of the bucket cell edge (voxels)
constexpr int32_t kReachVoxels = 2;            // bucket reach: max(clearance, 2 voxel edges) (m)
constexpr uint32_t kLargeBoxCells = 64;        // boxes touching more cells go to the large list
constexpr uint32_t kRefsPerBoxDefault = kLargeBoxCells;  // so a derived capacity never overflows

// Cells of the bucket index a grid of max_voxels may need (the cell edge grows until it fits).
inline uint32_t bucket_cell_capacity(uint32_t max_voxels) { return max_voxels / 16u + 64u; }
// Entries of the distance field: one per voxel, none for boxes only.
inline uint32_t df_capacity(const GridCapacity& cap) {
  return cap.boxes_only != 0u ? 0u : cap.max_voxels;
}
// Entries of the line scratch of the exact EDT: the longest axis a grid of this capacity can have.
inline uint32_t df_line_capacity(const GridCapacity& cap) {
  if (cap.boxes_only != 0u) return 0u;
  const uint32_t n =
      cap.max_axis > 0u && cap.max_axis < cap.max_voxels ? cap.max_axis : cap.max_voxels;
  return n < kDfMaxAxis ? n : kDfMaxAxis;
}
// Bucket index entries: the configured capacity, or the derived default when it is 0.
uint32_t box_ref_capacity(const GridCapacity& cap);
size_t grid_footprint(const GridCapacity& cap);
tdo_status grid_init(tdo_grid** out, tdo_arena* arena, const GridCapacity& cap);
// The clearance stencil of c into g->stencil (*count offsets), TDO_ERR_CLEARANCE_CAPACITY when it
// does not fit; grid.cpp (tdo_grid_finish) and grid_update.cpp share it.
tdo_status build_stencil(tdo_grid* g, double c, uint32_t* count);
// Build the distance field (tdo_grid::df) of the last tdo_grid_finish when it is not built yet:
// every reader calls this first. O(voxels) once per finish, nothing after (docs/design.md s.0).
void df_ensure(const tdo_grid* g);
// Compute the legal steps (tdo_grid::moves) of the last tdo_grid_finish when they are not computed
// yet: the search calls this first (tdo_search_run). O(voxels) once per finish; nothing before the
// grid is finished.
void moves_ensure(const tdo_grid* g);
}  // namespace tdo_internal

struct tdo_grid {
  tdo_internal::GridCapacity cap;
  tdo_grid_desc desc;  // current size and placement
  uint32_t nvox;       // nx*ny*nz, 0 before the first reset
  int64_t stride_y;    // nx
  int64_t stride_z;    // nx*ny
  uint8_t* flags;      // kFlag* per voxel, index i + j*nx + k*nx*ny
  uint32_t* moves;     // bit d set when step d from this voxel is legal (docs/design.md s.0);
                       // valid only while moves_built (moves_ensure)
  int moves_built;     // 1 when moves holds the steps of the last finish; 0: moves_ensure builds
                       // them (map updates keep built steps exact, grid_update.cpp)
  tdo_box* boxes;      // obstacle boxes, exact geometry
  uint32_t n_boxes;
  int32_t* stencil;    // clearance stencil: 3 offsets per cell
  uint32_t n_cubes;    // voxels marked as cubes
  uint32_t n_blocked;  // blocked voxels after finish
  double clearance;    // m, of the last finish; -1 when not finished
  int ready;           // 1 after a successful finish
  uint32_t version;    // changes with every finish: whoever derives data from the grid (the
                       // search's coarse guide, guide.cpp) rebuilds it when this moves on

  // Distance field (built on first use after tdo_grid_finish, df_ensure): per voxel, the exact
  // Euclidean distance (m) from its centre to the centre of the nearest occupied voxel, rounded
  // down to float; +inf without any. df_valid = 0 when an axis exceeds kDfMaxAxis: every entry is
  // then 0, still a lower bound; also after a map update cleared a cube (grid_update.cpp): entries
  // are lower bounds only. Read by the collision queries against voxel obstacles, the coarse guide
  // and map updates, each through df_ensure; boxes_only grids have none.
  float* df;       // m, max_voxels entries (nullptr when boxes_only)
  uint32_t* df_f;  // EDT line scratch: squared distances (voxel^2), df_line_capacity entries
  int32_t* df_v;   // EDT line scratch: parabola sites (voxel index), df_line_capacity entries
  int df_valid;    // 1 when df holds the exact field (set by tdo_grid_finish, before df_ensure)
  int df_built;    // 1 when df holds the entries described above; 0: df_ensure builds them
  double df_cap;   // m; > 0: read df as min(df, df_cap) for lower bounds (set by map updates,
                   // which lower df only near new obstacles); 0: no cap (tdo_grid_finish)

  // Bucket index of the boxes over coarse cells of cell_vox^3 voxels, CSR: the boxes of cell
  // c = x + ncx * (y + ncy * z) are box_refs[cell_start[c] .. cell_start[c+1]). A box is listed in
  // every cell that the box grown by bucket_reach (plus a rounding slack) touches, unless that is
  // more than kLargeBoxCells cells: then it is in large_boxes, which every query scans.
  uint32_t* cell_start;   // bucket_cell_capacity + 1 entries
  uint32_t* box_refs;     // box_ref_capacity entries
  uint32_t* large_boxes;  // max_boxes entries
  uint32_t n_large;       // boxes in large_boxes
  uint32_t n_refs;        // entries used in box_refs
  int32_t cell_vox;       // cell edge (voxels)
  double cell_edge;       // m, cell_vox * res
  int32_t ncx, ncy, ncz;  // cells per axis
  double bucket_reach;    // m, max(clearance, kReachVoxels * res): every box closer than this to
                          // a point is listed in the point's cell

  // Brick index of the surface cubes (surface_index.h), built by tdo_grid_finish and kept by map
  // updates: per brick of 4^3 voxels a mask of its surface cubes and their packed tight box.
  uint64_t* brick_mask;   // brick_capacity entries (nullptr when boxes_only)
  uint16_t* brick_box;    // brick_capacity entries
  int32_t nbx, nby, nbz;  // bricks per axis
  int bricks_valid;       // 1 when the index holds the surface of the grid (0: too many bricks)
};

#endif  // TDO_SRC_GRID_INTERNAL_H
