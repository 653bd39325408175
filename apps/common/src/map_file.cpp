// Map file -> map_t (map_file.h).
#include "tdo_lcm/map_file.h"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <vector>

#include "tdo_io/map_io.h"
#include "tdo_io/octree_check.h"
#include "tdo_lcm/adapters.h"

namespace tdo_lcm {

Check map_msg_from_map(const tdo_io::Map& map, double clearance, tdo::map_t* out) {
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
  return map_from_occupancy(d, occupancy, map.boxes, clearance, out);
}

bool map_msg_from_file(const std::string& path, double clearance, tdo::map_t* out,
                       MapFileInfo* info, std::string* error) {
  tdo_io::Map map;
  if (!tdo_io::load_map(path, &map, error)) return false;
  tdo::map_t m{};
  const Check c = map_msg_from_map(map, clearance, &m);
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

bool octomap_msg_from_file(const std::string& path, double resolution, double clearance,
                           tdo::map_t* out, std::string* error) {
  tdo_io::LoadOptions opt;
  opt.resolution = resolution;
  tdo_io::Map map;
  if (!tdo_io::load_map(path, opt, &map, error)) return false;
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  const std::string header = "# Octomap OcTree binary file";
  if (map.kind != tdo_io::MapKind::OctoMap || bytes.size() < header.size() ||
      !std::equal(header.begin(), header.end(), bytes.begin())) {
    if (error != nullptr) *error = path + ": not an OctoMap binary file (.bt)";
    return false;
  }
  tdo::map_t m{};
  const Check c = map_from_occupancy(map.desc, {}, {}, clearance, &m);
  if (!c.ok() || bytes.size() > static_cast<std::size_t>(INT32_MAX)) {
    if (error != nullptr) *error = path + ": " + (c.ok() ? "too large" : c.detail);
    return false;
  }
  m.encoding = tdo::map_t::ENCODING_OCTOMAP_BT;
  m.n_bytes = static_cast<int32_t>(bytes.size());
  m.data = std::move(bytes);
  *out = std::move(m);
  return true;
}

Check octomap_to_rle(const tdo::map_t& m, uint64_t max_voxels, tdo::map_t* out) {
  if (m.encoding != tdo::map_t::ENCODING_OCTOMAP_BT)
    return fail(Reason::bad_encoding, "not ENCODING_OCTOMAP_BT");
  const int64_t n[3] = {m.size[0], m.size[1], m.size[2]};
  const double res = m.resolution;
  if (!(res > 0.0) || !std::isfinite(res) || n[0] <= 0 || n[1] <= 0 || n[2] <= 0)
    return fail(Reason::out_of_range, "resolution and sizes must be > 0");
  for (double o : m.origin)
    if (!std::isfinite(o)) return fail(Reason::non_finite, "origin");
  const uint64_t total =
      static_cast<uint64_t>(n[0]) * static_cast<uint64_t>(n[1]) * static_cast<uint64_t>(n[2]);
  if (total > max_voxels)
    return fail(
        Reason::map_capacity,
        std::to_string(total) + " voxels, more than the capacity of " + std::to_string(max_voxels));
  if (static_cast<std::size_t>(m.n_bytes) != m.data.size())
    return fail(Reason::count_mismatch, "n_bytes");

  // Checked without recursion before OctoMap reads it (its reader recurses once per level).
  tdo_io::OctreeInfo info;
  std::string why;
  const tdo_io::OctreeStatus st =
      tdo_io::check_octree(m.data.data(), m.data.size(), tdo_io::OctreeLimits{}, &info, &why);
  if (st != tdo_io::OctreeStatus::ok)
    return fail(Reason::bad_encoding,
                std::string("corrupt OcTree (") + tdo_io::octree_status_str(st) + "): " + why);
  if (!info.binary)
    return fail(Reason::bad_encoding, "an .ot stream; ENCODING_OCTOMAP_BT carries a binary .bt");

  std::unique_ptr<octomap::OcTree> tree;
  try {
    std::istringstream in(std::string(m.data.begin(), m.data.end()));
    tree = std::make_unique<octomap::OcTree>(0.1);
    if (!tree->readBinary(in)) return fail(Reason::bad_encoding, "cannot read the binary OcTree");
  } catch (const std::exception& e) {
    return fail(Reason::bad_encoding, std::string("cannot read the binary OcTree: ") + e.what());
  }
  if (!(tree->getResolution() > 0.0) || !std::isfinite(tree->getResolution()))
    return fail(Reason::bad_encoding, "OcTree resolution is not a positive number");

  std::vector<uint8_t> occ(total, 0u);
  constexpr double kEps = 1e-6;  // voxels: float noise in the tree's coordinates
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    if (!tree->isNodeOccupied(*it)) continue;
    const double half = it.getSize() / 2.0;
    const double c[3] = {it.getX(), it.getY(), it.getZ()};
    int64_t i0[3];
    int64_t i1[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const double lo = std::floor((c[a] - half - m.origin[a]) / res + kEps);
      const double hi = std::ceil((c[a] + half - m.origin[a]) / res - kEps) - 1.0;
      if (!(hi >= 0.0) || !(lo < static_cast<double>(n[a]))) {
        inside = false;
        break;
      }
      i0[a] = std::max<int64_t>(static_cast<int64_t>(lo), 0);
      i1[a] = std::min<int64_t>(static_cast<int64_t>(hi), n[a] - 1);
    }
    if (!inside) continue;
    for (int64_t k = i0[2]; k <= i1[2]; ++k)
      for (int64_t j = i0[1]; j <= i1[1]; ++j)
        for (int64_t i = i0[0]; i <= i1[0]; ++i)
          occ[static_cast<std::size_t>((k * n[1] + j) * n[0] + i)] = 1u;
  }
  const tdo_grid_desc d{m.size[0], m.size[1], m.size[2], res,
                        tdo_vec3{m.origin[0], m.origin[1], m.origin[2]}};
  std::vector<tdo_box> boxes;
  for (const auto& b : m.boxes) boxes.push_back(tdo_box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}});
  tdo::map_t r{};
  const Check c = map_from_occupancy(d, occ, boxes, m.clearance, &r);
  if (!c.ok()) return c;
  r.utime = m.utime;
  r.map_id = m.map_id;
  r.vehicle_id = m.vehicle_id;
  *out = std::move(r);
  return {};
}

}  // namespace tdo_lcm
