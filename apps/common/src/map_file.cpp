// Map file -> map_t (map_file.h).
#include "tdo_lcm/map_file.h"

#include <cstdint>
#include <vector>

#include "tdo_io/map_io.h"
#include "tdo_lcm/adapters.h"

namespace tdo_lcm {

bool map_msg_from_file(const std::string& path, double clearance, tdo::map_t* out,
                       MapFileInfo* info, std::string* error) {
  tdo_io::Map map;
  if (!tdo_io::load_map(path, &map, error)) return false;
  const tdo_grid_desc& d = map.desc;
  std::vector<uint8_t> occupancy;
  if (!map.voxels.empty()) {
    const uint64_t n =
        static_cast<uint64_t>(d.nx) * static_cast<uint64_t>(d.ny) * static_cast<uint64_t>(d.nz);
    occupancy.assign(n, 0u);
    for (const tdo_voxel& v : map.voxels) {
      if (v.i < 0 || v.j < 0 || v.k < 0 || v.i >= d.nx || v.j >= d.ny || v.k >= d.nz) continue;
      const uint64_t idx =
          static_cast<uint64_t>(v.i) +
          static_cast<uint64_t>(d.nx) * (static_cast<uint64_t>(v.j) +
                                         static_cast<uint64_t>(d.ny) * static_cast<uint64_t>(v.k));
      occupancy[idx] = 1u;
    }
  }
  tdo::map_t m{};
  const Check c = map_from_occupancy(d, occupancy, map.boxes, clearance, &m);
  if (!c.ok()) {
    if (error != nullptr) *error = path + ": " + reason_str(c.reason) + ": " + c.detail;
    return false;
  }
  m.map_id = 0;
  m.vehicle_id = -1;
  *out = std::move(m);
  if (info != nullptr) {
    info->has_query = map.has_start && map.has_goal;
    info->start = map.start;
    info->goal = map.goal;
    info->movers = map.movers.size();
  }
  return true;
}

}  // namespace tdo_lcm
