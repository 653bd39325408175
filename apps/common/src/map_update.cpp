// map_update_t for the nodes (map_update.h).
#include "tdo_lcm/map_update.h"

#include <cmath>
#include <string>
#include <vector>

#include "tdo_lcm/node_status.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {

namespace {

bool counts_match(const tdo::map_update_t& u) {
  return u.n_set >= 0 && u.n_clear >= 0 && u.n_boxes >= 0 &&
         u.set.size() == static_cast<std::size_t>(u.n_set) &&
         u.clear.size() == static_cast<std::size_t>(u.n_clear) &&
         u.boxes.size() == static_cast<std::size_t>(u.n_boxes);
}

Check check_voxels(const std::vector<std::vector<int32_t>>& v, const char* name) {
  for (std::size_t n = 0; n < v.size(); ++n)
    for (int a = 0; a < 3; ++a)
      if (v[n][static_cast<std::size_t>(a)] < 0)
        return fail_field(Reason::out_of_range, std::string(name),
                          std::string(name) + "[" + std::to_string(n) + "] has a negative index");
  return Check{};
}

std::vector<tdo_voxel> voxels_of(const std::vector<std::vector<int32_t>>& v) {
  std::vector<tdo_voxel> out;
  out.reserve(v.size());
  for (const auto& x : v) out.push_back(tdo_voxel{x[0], x[1], x[2]});
  return out;
}

}  // namespace

Check map_update_check(const tdo::map_update_t& u) {
  if (!counts_match(u)) return fail(Reason::count_mismatch, "array counts differ from the arrays");
  if (u.map_id < 0)
    return fail_field(Reason::out_of_range, "map_id",
                      "map_id " + std::to_string(u.map_id) + " < 0");
  if (u.seq < 1)
    return fail_field(Reason::out_of_range, "seq", "seq " + std::to_string(u.seq) + " < 1");
  Check c = check_voxels(u.set, "set");
  if (c.ok()) c = check_voxels(u.clear, "clear");
  if (!c.ok()) return c;
  for (std::size_t b = 0; b < u.boxes.size(); ++b) {
    const std::string f = "boxes[" + std::to_string(b) + "]";
    for (int a = 0; a < 6; ++a)
      if (!std::isfinite(u.boxes[b][static_cast<std::size_t>(a)]))
        return fail_field(Reason::non_finite, f, f + " has a non-finite corner");
    for (int a = 0; a < 3; ++a)
      if (!(u.boxes[b][static_cast<std::size_t>(a) + 3] > u.boxes[b][static_cast<std::size_t>(a)]))
        return fail_field(Reason::out_of_range, f, f + " has max <= min");
  }
  return Check{};
}

Check decode_map_update(const void* data, std::size_t size, int32_t vehicle_id,
                        tdo::map_update_t* u) {
  Check c = decode(data, size, u);
  if (c.ok() && u->vehicle_id != -1 && u->vehicle_id != vehicle_id)
    c = fail(Reason::other_vehicle, "update for vehicle " + std::to_string(u->vehicle_id));
  if (c.ok()) c = map_update_check(*u);
  return c;
}

Check map_update_apply(const tdo::map_update_t& u, tdo_grid* grid, tdo_grid_update_result* out) {
  const std::vector<tdo_voxel> set = voxels_of(u.set), clear = voxels_of(u.clear);
  std::vector<tdo_box> boxes;
  boxes.reserve(u.boxes.size());
  for (const auto& b : u.boxes)
    boxes.push_back(tdo_box{tdo_vec3{b[0], b[1], b[2]}, tdo_vec3{b[3], b[4], b[5]}});
  tdo_grid_update up{};
  up.set = set.data();
  up.n_set = static_cast<uint32_t>(set.size());
  up.clear = clear.data();
  up.n_clear = static_cast<uint32_t>(clear.size());
  up.boxes = boxes.data();
  up.n_boxes = static_cast<uint32_t>(boxes.size());
  const tdo_status st = tdo_grid_apply_update(grid, &up, out);
  switch (st) {
    case TDO_OK:
      return Check{};
    case TDO_ERR_INVALID_ARGUMENT:
      return fail(Reason::out_of_range, "a voxel of the update lies outside the map's grid");
    case TDO_ERR_UPDATE_CONTRADICTORY:
      return fail(Reason::contradictory, "the update sets and clears the same voxel");
    case TDO_ERR_BOX_CAPACITY:
    case TDO_ERR_MAP_CAPACITY:
      return fail(Reason::map_capacity,
                  std::string("tdo_grid_apply_update: ") + tdo_status_str(st));
    default:
      return fail(Reason::grid_error, std::string("tdo_grid_apply_update: ") + tdo_status_str(st));
  }
}

void MapUpdateSeq::on_map(int64_t map_id) {
  have_map_ = true;
  stale_ = false;
  map_id_ = map_id;
  last_seq_ = 0;
}

void MapUpdateSeq::clear() {
  have_map_ = false;
  stale_ = false;
  map_id_ = -1;
  last_seq_ = 0;
}

Check MapUpdateSeq::order(const tdo::map_update_t& u) {
  if (!have_map_) return fail(Reason::no_map, "an update before any map");
  if (u.map_id != map_id_)
    return fail(Reason::other_map, "update for map " + std::to_string(u.map_id) + ", the map is " +
                                       std::to_string(map_id_));
  if (u.seq <= last_seq_)
    return fail(Reason::stale_update, "update " + std::to_string(u.seq) +
                                          " is not after the last applied, " +
                                          std::to_string(last_seq_));
  if (stale_)
    return fail(Reason::map_stale,
                "map " + std::to_string(map_id_) + " is stale: waiting for the whole map");
  if (u.seq != last_seq_ + 1) {
    stale_ = true;
    return fail(Reason::gap, "update " + std::to_string(u.seq) + " after " +
                                 std::to_string(last_seq_) + ": " +
                                 std::to_string(u.seq - last_seq_ - 1) + " missing");
  }
  return Check{};
}

tdo::map_request_t make_map_request(const char* program, int32_t vehicle_id,
                                    const MapUpdateSeq& updates, const std::string& why,
                                    int64_t* seq) {
  tdo::map_request_t r{};
  r.utime = wall_utime();
  r.seq = (*seq)++;
  r.program = program;
  r.vehicle_id = vehicle_id;
  r.map_id = updates.map_id();
  r.last_seq = updates.last_seq();
  r.reason = why;
  return r;
}

}  // namespace tdo_lcm
