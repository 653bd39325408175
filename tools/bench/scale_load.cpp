// tdo-bench-scale --load. See scale_load.h.
#include "scale_load.h"

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace tdo_bench {
namespace {

// CPU time of this thread (ms): on a shared machine it moves far less with the load than the
// wall clock does (caches are still shared).
double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double ms_since(double t0) { return cpu_ms() - t0; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The OctoMap library's own read of an OcTree file (.bt binary, .ot full); false when it fails.
bool octomap_read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string first;
  std::getline(in, first);
  in.seekg(0);
  if (first.rfind("# Octomap OcTree binary file", 0) == 0) {
    octomap::OcTree tree(0.1);
    return tree.readBinary(in) && tree.size() > 0;
  }
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(in));
  return tree != nullptr && tree->size() > 0;
}

// The occupied voxels of a voxel map as a binary OcTree stream at the map's resolution (each voxel
// one leaf, centred on the voxel's centre), so the OctoMap library can read "the same tree".
std::string tree_bytes(const tdo_io::Map& map) {
  const double r = map.desc.res;
  octomap::OcTree tree(r);
  for (const tdo_voxel& v : map.voxels) {
    const octomap::point3d p(static_cast<float>(map.desc.origin.x + (v.i + 0.5) * r),
                             static_cast<float>(map.desc.origin.y + (v.j + 0.5) * r),
                             static_cast<float>(map.desc.origin.z + (v.k + 0.5) * r));
    tree.updateNode(p, true);
  }
  std::ostringstream out(std::ios::binary);
  tree.writeBinary(out);
  return out.str();
}

bool tree_read(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  octomap::OcTree tree(0.1);
  return tree.readBinary(in) && tree.size() > 0;
}

// One map's medians (ms).
struct LoadRow {
  std::string file;
  std::string baseline;  // what the baseline is
  tdo_grid_desc desc{};
  size_t occupied = 0;
  double clearance = 0.0;
  double base_ms = 0.0;   // the format's own reader
  double tree_ms = 0.0;   // .3dmap: the OctoMap library reading its voxels as a tree (0: OcTree)
  double map_ms = 0.0;    // tdo_io::load_map
  double grid_ms = 0.0;   // tdo_io::load_into
  double total_ms = 0.0;  // load_map + load_into
  double first_ms = 0.0;  // the first collision query after load_into: builds the distance field
};

// A planner sized for `map` (search pools minimal: only its grid is used), initialised untimed.
struct GridHost {
  std::vector<unsigned char> arena;
  tdo_planner* planner = nullptr;
};

bool make_grid(const tdo_io::Map& map, double clearance, GridHost* h, std::string* error) {
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, 1u, 1u);
  h->arena.assign(tdo_planner_footprint(&cfg), 0);
  const tdo_status st = tdo_planner_init(&h->planner, h->arena.data(), h->arena.size(), &cfg);
  if (st != TDO_OK) *error = map.path + ": planner init: " + tdo_status_str(st);
  return st == TDO_OK;
}

int measure(const ScaleMap& sm, uint64_t repeat, LoadRow* row) {
  const bool octree = ends_with(sm.file, ".bt") || ends_with(sm.file, ".ot");
  row->file = sm.file;
  row->clearance = sm.clearance;
  row->baseline = octree ? "OctoMap read" : ".3dmap parse";
  std::string err;
  tdo_io::Map map;
  GridHost host;
  if (!tdo_io::load_map(sm.file, sm.load, &map, &err) ||
      !make_grid(map, sm.clearance, &host, &err)) {
    std::fprintf(stderr, "tdo-bench-scale: %s\n", err.c_str());
    return 2;
  }
  row->desc = map.desc;
  row->occupied = map.voxels.size();
  const std::string tree = octree ? std::string() : tree_bytes(map);
  std::vector<double> base, treet, mapt, gridt, total, first;
  for (uint64_t r = 0; r < repeat; ++r) {
    double t0 = cpu_ms();
    const bool ok = octree ? octomap_read(sm.file) : tdo_io::load_map(sm.file, sm.load, &map, &err);
    base.push_back(ms_since(t0));
    if (!octree) {
      t0 = cpu_ms();
      if (!tree_read(tree)) {
        std::fprintf(stderr, "tdo-bench-scale: %s: OctoMap cannot read its tree\n",
                     sm.file.c_str());
        return 2;
      }
      treet.push_back(ms_since(t0));
    }
    t0 = cpu_ms();
    tdo_io::Map m;
    const bool loaded = ok && tdo_io::load_map(sm.file, sm.load, &m, &err);
    mapt.push_back(ms_since(t0));
    t0 = cpu_ms();
    const tdo_status st = loaded
                              ? tdo_io::load_into(m, tdo_planner_grid(host.planner), sm.clearance)
                              : TDO_ERR_NO_PATH;
    gridt.push_back(ms_since(t0));
    total.push_back(mapt.back() + gridt.back());
    // Not part of the load: the distance field is built on first use (docs/design.md s.0).
    const tdo_grid* grid = tdo_planner_grid(host.planner);
    tdo_voxel mid{m.desc.nx / 2, m.desc.ny / 2, m.desc.nz / 2};
    t0 = cpu_ms();
    (void)tdo_collision_point_distance(grid, tdo_grid_voxel_center(grid, mid), 1.0);
    first.push_back(ms_since(t0));
    if (!ok || !loaded || st != TDO_OK) {
      std::fprintf(stderr, "tdo-bench-scale: %s: load failed (%s%s)\n", sm.file.c_str(),
                   err.c_str(), st != TDO_OK ? tdo_status_str(st) : "");
      return 2;
    }
  }
  row->base_ms = median(base);
  row->tree_ms = octree ? 0.0 : median(treet);
  row->map_ms = median(mapt);
  row->grid_ms = median(gridt);
  row->total_ms = median(total);
  row->first_ms = median(first);
  return 0;
}

}  // namespace

int run_load_bench(const std::vector<Workload>& workloads, uint64_t repeat) {
  std::vector<LoadRow> rows;
  std::vector<std::string> seen;
  for (const Workload& w : workloads) {
    for (const ScaleMap& sm : w.maps) {
      if (ends_with(sm.file, ".tdomap")) continue;  // boxes: nothing to voxelize from a reader
      if (std::find(seen.begin(), seen.end(), sm.file) != seen.end()) continue;
      seen.push_back(sm.file);
      LoadRow row;
      const int st = measure(sm, repeat, &row);
      if (st != 0) return st;
      rows.push_back(row);
    }
  }
  std::printf(
      "\nmap loading, median of %llu interleaved runs (thread CPU time, ms); "
      "voxelization = tdo's load minus the baseline\n\n",
      static_cast<unsigned long long>(repeat));
  std::printf(
      "| map | voxels | occupied | clearance m | baseline | baseline ms | load_map ms | "
      "load_into ms | tdo load ms | voxelization / baseline | tdo load / baseline | "
      "first query ms |\n");
  std::printf("|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const LoadRow& r : rows) {
    const std::string name = r.file.substr(r.file.find_last_of('/') + 1);
    const double voxelization = r.total_ms - r.base_ms;
    std::printf(
        "| %s | %dx%dx%d | %zu | %.2f | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
        name.c_str(), r.desc.nx, r.desc.ny, r.desc.nz, r.occupied, r.clearance, r.baseline.c_str(),
        r.base_ms, r.map_ms, r.grid_ms, r.total_ms, voxelization / r.base_ms,
        r.total_ms / r.base_ms, r.first_ms);
    if (r.tree_ms > 0.0)  // the same voxels as an OcTree: the reader it would have as one
      std::printf(
          "| %s | | | | OctoMap read of its voxels as a tree | %.2f | | | | %.2f | %.2f | |\n",
          name.c_str(), r.tree_ms, voxelization / r.tree_ms, r.total_ms / r.tree_ms);
  }
  std::printf("\n");
  for (const LoadRow& r : rows) {
    // OcTrees: tdo's work beyond OctoMap's read of the file. Voxel maps: tdo's whole load
    // against OctoMap reading the same voxels as a tree (against the parse alone in the table).
    const bool tree = r.tree_ms > 0.0;
    const double ratio = tree ? r.total_ms / r.tree_ms : (r.total_ms - r.base_ms) / r.base_ms;
    std::printf("goal load %s: %s %.2fx the OctoMap read%s (goal <= 2x): %s\n",
                r.file.substr(r.file.find_last_of('/') + 1).c_str(), tree ? "load" : "voxelization",
                ratio, tree ? " of its voxels as a tree" : "", ratio <= 2.0 ? "met" : "NOT met");
  }
  return 0;
}

}  // namespace tdo_bench
