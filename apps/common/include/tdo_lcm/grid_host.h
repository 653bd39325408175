/**
 * @file grid_host.h
 * @brief A static-map grid for programs that do not plan (tdo-avoid, tdo-sim): libtdo makes grids
 *        only inside a planner's arena, so this hosts a planner sized for the grid alone (a search
 *        budget of one state, no heading index). Host code: the arena is allocated once, in start.
 */
#ifndef TDO_LCM_GRID_HOST_H
#define TDO_LCM_GRID_HOST_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "tdo/config.h"
#include "tdo/grid.h"
#include "tdo/planner.h"

namespace tdo_lcm {

class GridHost {
 public:
  /**
   * @brief Allocate and initialise for maps up to nx*ny*nz voxels and `max_boxes` boxes, with
   *        clearance / resolution up to `max_clearance_ratio`.
   * @param[out] error why not (may be null)
   */
  bool start(int32_t nx, int32_t ny, int32_t nz, uint32_t max_boxes, double max_clearance_ratio,
             std::string* error);

  /** @return the grid (null before a successful start). */
  tdo_grid* grid() { return planner_ != nullptr ? tdo_planner_grid(planner_) : nullptr; }
  /** @return the capacities the grid was made with (map_check uses them). */
  const tdo_capacity& capacity() const { return cfg_.cap; }
  /** @return bytes of the arena. */
  std::size_t arena_bytes() const { return bytes_; }

 private:
  tdo_planner_config cfg_{};
  std::unique_ptr<std::max_align_t[]> arena_;
  std::size_t bytes_ = 0;
  tdo_planner* planner_ = nullptr;
};

}  // namespace tdo_lcm

#endif  // TDO_LCM_GRID_HOST_H
