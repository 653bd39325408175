/**
 * @file map_io.h
 * @brief Host-side map and scenario readers for the tools (tdo-plan, bench). Not part of libtdo.
 *
 * Formats: `.tdomap` (docs/design.md s.10), MovingAI `.3dmap` / `.3dscen`, OctoMap OcTrees `.bt`
 * (binary) and `.ot` (full), read with the OctoMap library and voxelized (see load_map). Every
 * function reports failure as `false` plus a message of the form "FILE:LINE: message" (or
 * "FILE: message" when no line applies); none throws.
 */
#ifndef TDO_IO_MAP_IO_H
#define TDO_IO_MAP_IO_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo/config.h"
#include "tdo/grid.h"
#include "tdo/status.h"
#include "tdo/types.h"
#include "tdo_io/octree_check.h"

namespace tdo_io {

/** A moving sphere of a dynamic map: constant velocity, reflected at the bounds. */
struct Mover {
  int id;        /**< identifier from the map file */
  tdo_vec3 pos;  /**< m, world frame, position at t = 0 */
  tdo_vec3 vel;  /**< m/s, world frame */
  double radius; /**< m */
};

/** Which file format a map came from. */
enum class MapKind { TdoMap, MovingAI, OctoMap };

/** A map as read from a file: grid placement, obstacle geometry and optional default query. */
struct Map {
  MapKind kind = MapKind::TdoMap;
  tdo_grid_desc desc{};          /**< grid size and placement (origin m, res m) */
  std::vector<tdo_box> boxes;    /**< m, world frame, obstacle boxes (.tdomap) */
  std::vector<tdo_voxel> voxels; /**< occupied voxels (.3dmap, OcTrees) */
  bool has_start = false;        /**< the file gave a `start` */
  bool has_goal = false;         /**< the file gave a `goal` */
  tdo_vec3 start{};              /**< m, world frame, default query start */
  tdo_vec3 goal{};               /**< m, world frame, default query goal */
  std::vector<Mover> movers;     /**< moving spheres (dynamic maps) */
  std::string path;              /**< the file it was read from */
};

/** Options of load_map; the defaults are what load_map(path, out, error) uses. */
struct LoadOptions {
  double resolution = 0.0;            /**< m, voxel edge for OcTrees; 0 = the tree's resolution */
  uint64_t max_voxels = 100000000;    /**< cap on nx*ny*nz of an OcTree grid (0 = no cap): larger is
                                           an error, not an allocation of gigabytes */
  uint64_t max_file_bytes = 1u << 30; /**< files larger than this are refused before reading */
  OctreeLimits octree;                /**< OcTree streams: nodes, resolution (octree_check.h) */
};

/**
 * @brief Read a map, choosing the format by extension (.tdomap, .3dmap, .bt/.ot).
 *
 * OcTrees (`.bt` binary or `.ot` full format, told apart by the file's first line): the grid has
 * `options.resolution` (default: the tree's), its bounds are the tree's metric bounding box of
 * known space padded by one voxel on every side, and every occupied leaf, at any depth, marks each
 * grid voxel its cube intersects (as `voxels`). Unknown space is free. The stream is checked with
 * check_octree (octree_check.h) before the OctoMap library reads it; a refused stream's message
 * reads "corrupt OcTree (<status>): why". The OctoMap library's own messages on stderr are captured
 * and folded into `error`. Text quoted from a file is escaped and capped (text.h); a directory or
 * a file over `max_file_bytes` is refused before it is read.
 * @param[out] out the map (replaced)
 * @param[out] error "FILE:LINE: message" on failure (may be null)
 * @return true on success.
 */
bool load_map(const std::string& path, Map* out, std::string* error);

/** load_map with options (OcTree resolution, voxel cap). */
bool load_map(const std::string& path, const LoadOptions& options, Map* out, std::string* error);

/** One MovingAI scenario query. */
struct ScenQuery {
  tdo_vec3 start; /**< m, world frame (= voxel coordinates for .3dmap grids) */
  tdo_vec3 goal;  /**< m, world frame */
  double cost;    /**< optimal path cost from the file */
  int line;       /**< 1-based line in the .3dscen file */
};

/**
 * @brief Read a MovingAI `.3dscen` file (`version 1`, map name, then `sx sy sz gx gy gz cost
 * ratio`).
 * @param[out] out the queries in file order (replaced)
 * @param[out] error "FILE:LINE: message" on failure (may be null)
 * @return true on success.
 */
bool load_scen(const std::string& path, std::vector<ScenQuery>* out, std::string* error);

/**
 * @brief Planner capacities that fit `map` at `clearance` (tdo_capacity_for_grid plus the boxes).
 * @param headings 1 without heading costs, 27 with turn penalties
 * @param node_cap cap on search states per direction (0 = no cap)
 */
tdo_capacity capacity_for(const Map& map, double clearance, uint32_t headings, uint32_t node_cap);

/**
 * @brief Load `map` into a planner grid: tdo_grid_reset, every box and voxel, tdo_grid_finish.
 * @return TDO_OK or the first failing status.
 */
tdo_status load_into(const Map& map, tdo_grid* grid, double clearance);

}  // namespace tdo_io

#endif  // TDO_IO_MAP_IO_H
