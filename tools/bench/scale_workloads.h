// The workloads of tdo-bench-scale: which map files, at which clearance, with which queries.
// Host-side bench code (allocates, reads files).
#ifndef TDO_TOOLS_BENCH_SCALE_WORKLOADS_H
#define TDO_TOOLS_BENCH_SCALE_WORKLOADS_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo/types.h"
#include "tdo_io/map_io.h"

namespace tdo_bench {

/** One start/goal pair. */
struct ScaleQuery {
  tdo_vec3 start{};  /**< m, world frame */
  tdo_vec3 goal{};   /**< m, world frame */
  std::string label; /**< G1 .. G5, scenario line, forest trial, "map" */
};

/** One map of a workload and its queries. */
struct ScaleMap {
  std::string file;         /**< map file (.tdomap, .3dmap, .bt) */
  tdo_io::LoadOptions load; /**< OcTree resolution */
  double clearance = 0.0;   /**< m */
  bool map_query = false;   /**< the query is the map file's own start and goal (.tdomap) */
  std::vector<ScaleQuery> queries;
};

/** A named workload: one or more maps. */
struct Workload {
  std::string name;
  std::string what; /**< one line for the report */
  bool rrt = true;  /**< RRTConnect + simplify runs here */
  std::vector<ScaleMap> maps;
};

/** Workload names in the default order (all of them run when none is chosen). */
const std::vector<std::string>& workload_names();

/**
 * @brief Describe workload `name` with the maps under `maps_dir` (the repository's maps/).
 * @param limit at most this many queries per map (0: the default, 1000 for MovingAI, else all)
 * @param rrt_movingai run RRTConnect + simplify on the MovingAI maps too
 * @return false with `error` for an unknown name, a missing map file or an unreadable query file
 *         (checked before anything runs).
 */
bool make_workload(const std::string& name, const std::string& maps_dir, uint64_t limit,
                   bool rrt_movingai, Workload* out, std::string* error);

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_SCALE_WORKLOADS_H
