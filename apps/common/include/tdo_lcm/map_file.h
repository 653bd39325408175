/**
 * @file map_file.h
 * @brief A map file (.tdomap, MovingAI .3dmap, OctoMap .bt/.ot, read by mapio) -> a map_t
 *        message: the boxes of a .tdomap as boxes, the occupied voxels of the others run-length
 *        encoded. Host code for the apps that publish maps (tdo-publish-map, tdo-sim, the log
 *        generator).
 */
#ifndef TDO_LCM_MAP_FILE_H
#define TDO_LCM_MAP_FILE_H

#include <string>

#include "tdo/types.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_io {
struct Map;
}

namespace tdo_lcm {

/**
 * @brief A map read by mapio -> a run-length map message: the occupied voxels (x fastest; the
 *        ones outside the grid skipped) and the boxes (map_id, vehicle_id and utime left 0).
 * @param clearance m, the clearance hint sent with the map (>= 0)
 * @return map_from_occupancy's check.
 */
Check map_msg_from_map(const tdo_io::Map& map, double clearance, tdo::map_t* out);

/** What map_msg_from_file read besides the message: the file's default query, if any. */
struct MapFileInfo {
  bool has_query = false; /**< the file gave both a start and a goal */
  tdo_vec3 start{};       /**< m, world frame */
  tdo_vec3 goal{};        /**< m, world frame */
  std::size_t movers = 0; /**< moving spheres in the file (not in the message) */
};

/**
 * @brief Read `path` and build a run-length map message (map_id, vehicle_id and utime left for the
 *        caller: 0, -1, 0).
 * @param clearance m, the clearance hint sent with the map (>= 0)
 * @param[out] error "FILE: message" on failure (may be null)
 * @return true on success.
 */
bool map_msg_from_file(const std::string& path, double clearance, tdo::map_t* out,
                       MapFileInfo* info, std::string* error);

/**
 * @brief An OctoMap binary file (.bt) -> an ENCODING_OCTOMAP_BT message carrying the file's bytes
 *        unchanged, on the grid mapio gives the tree (its bounds padded by one voxel).
 * @param resolution m, grid voxel edge; 0 = the tree's
 * @return true on success; false with "FILE: message" (not a binary OcTree, unreadable, ...).
 */
bool octomap_msg_from_file(const std::string& path, double resolution, double clearance,
                           tdo::map_t* out, std::string* error);

/**
 * @brief Rasterise an ENCODING_OCTOMAP_BT message onto its own grid (resolution, origin, size):
 *        every occupied leaf marks every voxel its cube intersects (as mapio does for files).
 * @param max_voxels the receiver's capacity, checked before anything is allocated
 * @param[out] out the same map as ENCODING_RLE (ids, grid, clearance and boxes kept, no bytes)
 * The bytes are checked by tdo_io::check_octree (bounded, no recursion: depth, node count, tree
 * type, resolution) before the OctoMap library reads them.
 * @return ok; map_capacity; out_of_range (bad grid); bad_encoding (the bytes are not a binary
 *         OcTree, detail: why; a corrupt tree's detail starts "corrupt OcTree (<status>)").
 */
Check octomap_to_rle(const tdo::map_t& m, uint64_t max_voxels, tdo::map_t* out);

}  // namespace tdo_lcm

#endif  // TDO_LCM_MAP_FILE_H
