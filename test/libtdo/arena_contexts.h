// Library contexts on their own heap arenas, shared by the test suites: a planner (TestPlanner,
// optionally loaded by a callback) and any context carved from a tdo_arena by tdo_<stage>_init
// (TestContext: the trajectory stage, the correction).
#ifndef TDO_TEST_LIBTDO_ARENA_CONTEXTS_H
#define TDO_TEST_LIBTDO_ARENA_CONTEXTS_H

#include <cstddef>
#include <vector>

#include "tdo/tdo.h"

namespace tdo_test {

/** A planner living in an exactly footprint-sized heap block (so ASan sees any overrun). */
class TestPlanner {
 public:
  explicit TestPlanner(const tdo_capacity& cap) {
    cfg_.cap = cap;
    const size_t bytes = tdo_planner_footprint(&cfg_);
    if (bytes == 0) {
      status_ = TDO_ERR_INVALID_ARGUMENT;
      return;
    }
    mem_.assign(bytes, 0u);
    status_ = tdo_planner_init(&planner_, mem_.data(), bytes, &cfg_);
  }
  /** Then load(grid()) fills the grid (status: its status). */
  template <class Load>
  TestPlanner(const tdo_capacity& cap, Load&& load) : TestPlanner(cap) {
    if (status_ == TDO_OK) status_ = load(grid());
  }
  TestPlanner(const TestPlanner&) = delete;
  TestPlanner& operator=(const TestPlanner&) = delete;

  tdo_status status() const { return status_; }
  tdo_planner* planner() { return planner_; }
  tdo_grid* grid() { return tdo_planner_grid(planner_); }
  tdo_search* search() { return tdo_planner_search(planner_); }

 private:
  tdo_planner_config cfg_{};
  std::vector<unsigned char> mem_;
  tdo_planner* planner_ = nullptr;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

/** A context carved by Init from its own heap arena of Footprint(cfg) + slack bytes. */
template <class Ctx, class Cfg, size_t (*Footprint)(const Cfg*),
          tdo_status (*Init)(Ctx**, tdo_arena*, const Cfg*)>
class TestContext {
 public:
  explicit TestContext(const Cfg& cfg, size_t slack = 0u) : cfg_(cfg) {
    mem_.assign(Footprint(&cfg_) + slack, 0u);
    tdo_arena_init(&arena_, mem_.data(), mem_.size());
    status_ = Init(&ctx_, &arena_, &cfg_);
  }
  TestContext(const TestContext&) = delete;
  TestContext& operator=(const TestContext&) = delete;

  tdo_status status() const { return status_; }
  Ctx* ctx() { return ctx_; }

 private:
  Cfg cfg_;
  std::vector<unsigned char> mem_;
  tdo_arena arena_{};
  Ctx* ctx_ = nullptr;
  tdo_status status_ = TDO_ERR_INVALID_ARGUMENT;
};

using TestTraj = TestContext<tdo_traj, tdo_traj_config, tdo_traj_footprint, tdo_traj_init>;
using TestCorrector =
    TestContext<tdo_correct, tdo_correct_config, tdo_correct_footprint, tdo_correct_init>;

/** Reset `grid` to `desc`, add the boxes and voxel cubes, finish it at `clearance`. */
inline tdo_status load_grid(tdo_grid* grid, const tdo_grid_desc& desc,
                            const std::vector<tdo_box>& boxes, double clearance,
                            const std::vector<tdo_voxel>& cubes = {}) {
  tdo_status st = tdo_grid_reset(grid, &desc);
  for (size_t i = 0; i < boxes.size() && st == TDO_OK; ++i) st = tdo_grid_add_box(grid, &boxes[i]);
  for (size_t i = 0; i < cubes.size() && st == TDO_OK; ++i)
    st = tdo_grid_add_voxel(grid, cubes[i].i, cubes[i].j, cubes[i].k);
  return st == TDO_OK ? tdo_grid_finish(grid, clearance) : st;
}

}  // namespace tdo_test

#endif  // TDO_TEST_LIBTDO_ARENA_CONTEXTS_H
