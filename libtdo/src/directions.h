// The 26 step directions of the voxel grid and their geometry. Internal to libtdo.
#ifndef TDO_SRC_DIRECTIONS_H
#define TDO_SRC_DIRECTIONS_H

#include <stdint.h>

namespace tdo_internal {

constexpr int kNumDirs = 26;          // 26-connected steps
constexpr uint8_t kHeadingNone = 26;  // heading of the start (forward) and goal (backward) state
constexpr int kNumHeadings = 27;      // 26 directions + none

// Cell index of offset (dx,dy,dz) in the 3x3x3 block around a voxel; 13 is the voxel itself.
constexpr int cell_of(int dx, int dy, int dz) { return (dz + 1) * 9 + (dy + 1) * 3 + (dx + 1); }
// Direction index 0..25 of a non-zero offset: cells in order with the centre skipped.
constexpr int dir_of_cell(int cell) { return cell < 13 ? cell : cell - 1; }
constexpr int cell_of_dir(int d) { return d < 13 ? d : d + 1; }
constexpr int dir_dx(int d) { return cell_of_dir(d) % 3 - 1; }
constexpr int dir_dy(int d) { return (cell_of_dir(d) / 3) % 3 - 1; }
constexpr int dir_dz(int d) { return cell_of_dir(d) / 9 - 1; }
// The opposite direction: cells mirror through the centre.
constexpr int dir_opposite(int d) { return 25 - d; }
// Number of non-zero components: 1 face step, 2 edge diagonal, 3 corner diagonal.
constexpr int dir_order(int d) {
  return (dir_dx(d) != 0 ? 1 : 0) + (dir_dy(d) != 0 ? 1 : 0) + (dir_dz(d) != 0 ? 1 : 0);
}

}  // namespace tdo_internal

#endif  // TDO_SRC_DIRECTIONS_H
