// A planner that only hosts its grid (grid_host.h).
#include "tdo_lcm/grid_host.h"

#include <cmath>
#include <new>

#include "tdo/status.h"

namespace tdo_lcm {

bool GridHost::start(int32_t nx, int32_t ny, int32_t nz, uint32_t max_boxes,
                     double max_clearance_ratio, std::string* error) {
  auto fail_with = [&](const std::string& msg) {
    if (error != nullptr) *error = msg;
    return false;
  };
  if (planner_ != nullptr) return fail_with("already started");
  if (nx <= 0 || ny <= 0 || nz <= 0) return fail_with("the capacity sizes must be > 0");
  if (!(max_clearance_ratio >= 0.0) || !std::isfinite(max_clearance_ratio))
    return fail_with("the clearance ratio must be finite and >= 0");
  // One heading, one search state: the search arrays shrink to nothing, the grid stays full size.
  tdo_capacity_for_grid(&cfg_.cap, nx, ny, nz, max_clearance_ratio, 1u, 1u);
  cfg_.cap.max_boxes = max_boxes > 0 ? max_boxes : 1u;
  bytes_ = tdo_planner_footprint(&cfg_);
  if (bytes_ == 0) return fail_with("invalid grid configuration");
  const std::size_t words = (bytes_ + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t);
  arena_.reset(new (std::nothrow) std::max_align_t[words]);
  if (!arena_) return fail_with("cannot allocate an arena of " + std::to_string(bytes_) + " bytes");
  const tdo_status st = tdo_planner_init(&planner_, arena_.get(), bytes_, &cfg_);
  if (st != TDO_OK) {
    planner_ = nullptr;
    return fail_with(std::string("tdo_planner_init: ") + tdo_status_str(st));
  }
  return true;
}

}  // namespace tdo_lcm
