/**
 * @file map_update.h
 * @brief map_update_t for the nodes: the content check, the adapter to tdo_grid_apply_update, and
 *        the sequence bookkeeping of the updates of one map (gap, stale, other map).
 *
 * A node keeps one MapUpdateSeq beside its grid: on_map() for every full map it loads, order()
 * for each update before applying it, applied() after. A gap, or an update the node could not
 * apply, makes the map stale until the next full map: the node asks for one (map_request_t) and
 * does not plan or follow on it as if it were current.
 */
#ifndef TDO_LCM_MAP_UPDATE_H
#define TDO_LCM_MAP_UPDATE_H

#include <cstddef>
#include <cstdint>
#include <string>

#include "tdo/grid_update.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/**
 * @brief Content checks of an update (no grid needed): count_mismatch, out_of_range (map_id < 0,
 *        seq < 1, a negative voxel index, a box with max <= min), non_finite (a box corner).
 */
Check map_update_check(const tdo::map_update_t& u);

/**
 * @brief decode an update, refuse it (other_vehicle) when it is for a vehicle other than
 *        `vehicle_id` (vehicle -1: for every vehicle), then map_update_check it.
 */
Check decode_map_update(const void* data, std::size_t size, int32_t vehicle_id,
                        tdo::map_update_t* u);

/**
 * @brief Apply a checked update to a finished grid (all of it or nothing).
 * @return ok; out_of_range (a voxel outside the grid), contradictory (a voxel set and cleared),
 *         map_capacity (boxes beyond the capacity, voxels on a boxes-only grid), grid_error
 *         (anything else the library refused; detail: the tdo_status name).
 */
Check map_update_apply(const tdo::map_update_t& u, tdo_grid* grid, tdo_grid_update_result* out);

/** Where the updates of the loaded map stand. */
class MapUpdateSeq {
 public:
  /** A full map `map_id` was loaded: its updates start at seq 1, the map is current. */
  void on_map(int64_t map_id);
  /** No map any more. */
  void clear();
  /**
   * @brief Whether update `u` is the next one of the loaded map.
   * @return ok; no_map; other_map (another map_id); stale_update (seq not after the last
   *         applied); map_stale (the map is already stale); gap (seq skips one: the map becomes
   *         stale).
   */
  Check order(const tdo::map_update_t& u);
  /** Update `seq` of the loaded map was applied. */
  void applied(int64_t seq) { last_seq_ = seq; }
  /** The map no longer matches the publisher's (an update could not be applied). */
  void mark_stale() { stale_ = have_map_; }

  bool stale() const { return stale_; }
  int64_t map_id() const { return have_map_ ? map_id_ : -1; }
  int64_t last_seq() const { return last_seq_; }

 private:
  bool have_map_ = false;
  bool stale_ = false;
  int64_t map_id_ = -1;
  int64_t last_seq_ = 0;
};

/**
 * @brief The map_request_t a node with a stale map sends (tdo-planner, tdo-avoid): the map it has
 *        (`updates`' map and last applied update), why, stamped with the wall clock.
 * @param program the sender, e.g. "tdo-planner"
 * @param seq the sender's request counter (incremented here)
 */
tdo::map_request_t make_map_request(const char* program, int32_t vehicle_id,
                                    const MapUpdateSeq& updates, const std::string& why,
                                    int64_t* seq);

}  // namespace tdo_lcm

#endif  // TDO_LCM_MAP_UPDATE_H
