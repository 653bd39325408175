// The planners tdo-bench-scale compares, set up on one map: the full tdo pipeline, plain A* (both
// libtdo, each in its own arena), OMPL RRTConnect + simplify (tools/baselines) and the textbook A*
// (textbook_astar.h, a check of the A* costs). Host-side bench code.
#ifndef TDO_TOOLS_BENCH_SCALE_RUNNER_H
#define TDO_TOOLS_BENCH_SCALE_RUNNER_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "baselines.h"
#include "scale_workloads.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"
#include "textbook_astar.h"

namespace tdo_bench {

/** Planner ids, in table order. */
enum ScalePlanner { kScaleTdo = 0, kScaleAstar = 1, kScaleRrt = 2, kScaleTextbook = 3 };
constexpr int kScalePlanners = 4;
/** ScaleMapRun::create's `samples` that keeps the library's default (tdo_capacity_for_grid). */
constexpr uint32_t kScaleSamplesDefault = 0xFFFFFFFFu;

/** Table name of a planner id. */
const char* scale_planner_name(int planner);

/** One planner on one query. */
struct ScaleOutcome {
  bool ran = false;    /**< the planner ran on this query */
  bool ok = false;     /**< a path from the exact start to the exact goal keeping the clearance */
  std::string status;  /**< "ok", "ok_infeasible" (tdo: path found, trajectory over the limits) or
                            why not */
  double ms = 0.0;     /**< ms, wall time of planning, best of the repeats */
  uint32_t turns = 0;  /**< tdo_metrics.turns of the final path (not for the textbook) */
  double length = 0.0; /**< m, tdo_metrics.length_m of the final path (not for the textbook) */
  double cost = 0.0;   /**< m, grid search cost between voxel centres (astar, textbook) */
};

/** What setting up one planner cost. */
struct ScaleSetup {
  size_t arena_bytes = 0; /**< tdo_planner_footprint of its configuration (0: no libtdo arena) */
  double rss_mb = 0.0;    /**< MB, growth of the resident set while it was set up */
  double ms = 0.0;        /**< ms, arena init and grid load (tdo_io::load_into) */
};

/** The planners on one map at one clearance. */
class ScaleMapRun {
 public:
  /**
   * @brief Set up tdo (capacity_for with 27 headings), astar (capacity_for without headings; its
   *        tools/baselines Environment also serves RRTConnect's collision checks and the path
   *        measurements), RRTConnect + simplify when `rrt`, and the textbook A* on A*'s blocked
   *        voxels. `node_cap`: search states per direction of both libtdo planners (capacity_for;
   *        0 = voxels x headings). `states`: the tdo search's tdo_state_space; with
   *        TDO_STATES_VOXEL tdo is sized without headings but keeps the retry tables, as tdo-plan
   *        --states voxel. `guide`: tdo's coarse guide on grids of 2^19 voxels or more
   *        (tdo_capacity.guide_shift 2), as tdo-plan --guide. `samples`: tdo's
   *        tdo_capacity.stream_samples (TDO_TRAJ_SAMPLES_STORED, _STREAMED or _PIECES), or
   *        kScaleSamplesDefault for tdo_capacity_for_grid's choice.
   *        @return null with `error` on a set-up failure.
   */
  static std::unique_ptr<ScaleMapRun> create(const tdo_io::Map& map, double clearance,
                                             uint32_t node_cap, int states, bool guide, bool rrt,
                                             uint32_t samples, std::string* error);
  ~ScaleMapRun();
  ScaleMapRun(const ScaleMapRun&) = delete;
  ScaleMapRun& operator=(const ScaleMapRun&) = delete;

  /** Run `planner` on `q` `repeat` times (seeded with `seed`); the best time is kept. */
  ScaleOutcome run(int planner, const ScaleQuery& q, uint64_t seed, uint64_t repeat);
  /** tdo's stages: TDO_PLAN_TRAJECTORY (the default, the full pipeline) or TDO_PLAN_SEARCH (the
   *  search alone, its grid path measured as A*'s). */
  void set_tdo_depth(tdo_plan_depth depth) { depth_ = depth; }
  /** Whether `planner` takes part on this map. */
  bool has(int planner) const;
  const ScaleSetup& setup(int planner) const { return setup_[planner]; }
  /** tdo plans run so far that reached the trajectory stage, and those of them that verified a
   *  round over the samples (tdo_plan_result.sample_passes > 0: with pieces, the fallbacks). */
  uint64_t tdo_trajectories() const { return tdo_trajectories_; }
  uint64_t tdo_sampled() const { return tdo_sampled_; }

 private:
  ScaleMapRun() = default;
  ScaleOutcome run_tdo(const ScaleQuery& q, uint64_t repeat);
  ScaleOutcome run_astar(const ScaleQuery& q, uint64_t repeat);
  ScaleOutcome grid_outcome(const tdo_plan_result& res, const ScaleQuery& q, ScaleOutcome o) const;
  ScaleOutcome run_rrt(const ScaleQuery& q, uint64_t seed, uint64_t repeat);
  ScaleOutcome run_textbook(const ScaleQuery& q, uint64_t repeat);

  double clearance_ = 0.0;
  int states_ = TDO_STATES_HEADING;             // tdo_plan_params.states of tdo
  tdo_plan_depth depth_ = TDO_PLAN_TRAJECTORY;  // tdo_plan_params.depth of tdo
  uint64_t tdo_trajectories_ = 0, tdo_sampled_ = 0;
  std::unique_ptr<unsigned char[]> tdo_memory_;
  tdo_planner* tdo_ = nullptr;
  std::unique_ptr<tdo_baselines::Environment> env_;  // A*'s planner
  std::unique_ptr<tdo_baselines::Planner> rrt_;
  std::unique_ptr<TextbookAstar> textbook_;
  ScaleSetup setup_[kScalePlanners];
};

/** MB, the process's resident set now (VmRSS of /proc/self/status; 0 when unreadable). */
double rss_now_mb();
/** MB, the process's peak resident set (VmHWM; 0 when unreadable). */
double rss_peak_mb();
/** Reset the peak resident set to the current one (/proc/self/clear_refs); false if refused. */
bool rss_reset_peak();

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_SCALE_RUNNER_H
