/**
 * @file map_file.h
 * @brief A map file (.tdomap, MovingAI .3dmap, OctoMap .bt/.ot, read by tools/io) -> a map_t
 *        message: the boxes of a .tdomap as boxes, the occupied voxels of the others run-length
 *        encoded. Host code for the apps that publish maps (tdo-publish-map, the log generator).
 */
#ifndef TDO_LCM_MAP_FILE_H
#define TDO_LCM_MAP_FILE_H

#include <string>

#include "tdo/types.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

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

}  // namespace tdo_lcm

#endif  // TDO_LCM_MAP_FILE_H
