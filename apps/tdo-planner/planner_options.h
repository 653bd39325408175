/**
 * @file planner_options.h
 * @brief The command-line options of a planner node's capacities and channels, shared by
 *        tdo-planner and tdo-replay (a replay must run with the capacities of the recorded
 * planner).
 */
#ifndef TDO_PLANNER_OPTIONS_H
#define TDO_PLANNER_OPTIONS_H

#include <CLI/CLI.hpp>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "planner_node.h"

namespace tdo_lcm {

/** Options that fill `cfg`; `max_size` holds NX NY NZ (copy into cfg with apply_max_size). */
inline void add_planner_options(CLI::App& app, PlannerConfig& cfg, std::vector<int>& max_size) {
  max_size = {cfg.max_nx, cfg.max_ny, cfg.max_nz};
  app.add_option("--vehicle-id", cfg.vehicle_id, "vehicle served; other requests are ignored")
      ->capture_default_str();
  app.add_option("--map-channel", cfg.map_channel, "maps in")->capture_default_str();
  app.add_option("--map-update-channel", cfg.map_update_channel, "map updates in")
      ->capture_default_str();
  app.add_option("--map-request-channel", cfg.map_request_channel,
                 "requests for a whole map out (when the map is stale)")
      ->capture_default_str();
  app.add_option("--request-channel", cfg.request_channel, "plan requests in")
      ->capture_default_str();
  app.add_option("--trajectory-channel", cfg.trajectory_channel, "trajectories out")
      ->capture_default_str();
  app.add_option("--feasibility-channel", cfg.feasibility_channel, "feasibility reports out")
      ->capture_default_str();
  app.add_option("--max-size", max_size, "capacity: voxels NX NY NZ of the largest map")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--max-nodes", cfg.max_nodes, "capacity: search states per direction")
      ->capture_default_str();
  app.add_option("--max-boxes", cfg.max_boxes, "capacity: obstacle boxes per map")
      ->capture_default_str();
  app.add_option("--max-clearance-ratio", cfg.max_clearance_ratio,
                 "capacity: largest clearance / resolution")
      ->capture_default_str();
  const std::map<std::string, int32_t> modes{{"stored", 0}, {"streamed", 1}, {"pieces", 2}};
  app.add_option("--samples", cfg.stream_samples,
                 "stored | streamed | pieces: trajectory samples kept in the arena, or regenerated "
                 "on demand (tdo_capacity.stream_samples; the same samples; pieces verifies each "
                 "profile piece in closed form: its feasibility maxima are bounds, its energy the "
                 "integral). Default: as tdo_capacity_for_grid sets it")
      ->transform(CLI::CheckedTransformer(modes));
}

inline void apply_max_size(const std::vector<int>& max_size, PlannerConfig* cfg) {
  cfg->max_nx = max_size[0];
  cfg->max_ny = max_size[1];
  cfg->max_nz = max_size[2];
}

}  // namespace tdo_lcm

#endif  // TDO_PLANNER_OPTIONS_H
