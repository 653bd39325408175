// tdo-bench-scale --load. See scale_load.h.
#include "scale_load.h"

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

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

// The same map as the OctoMap library would hold it: a `.3dmap` describes its whole box, so every
// voxel of the box is a known leaf at the map's resolution centred on the voxel's centre, the
// listed voxels occupied and all others free (writeBinary keeps the maximum-likelihood tree,
// pruned). Written once to a temporary .bt file at `path`, which the timed read loads as it
// loads an OcTree map; false with a message when it cannot be written.
bool write_known_box_tree(const tdo_io::Map& map, const std::string& path, std::string* error) {
  const tdo_grid_desc& d = map.desc;
  const double r = d.res;
  std::vector<uint8_t> occupied(static_cast<size_t>(d.nx) * d.ny * d.nz, 0u);
  for (const tdo_voxel& v : map.voxels)
    occupied[static_cast<size_t>(v.i) +
             static_cast<size_t>(d.nx) * (v.j + static_cast<size_t>(d.ny) * v.k)] = 1u;
  octomap::OcTree tree(r);
  size_t n = 0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i, ++n) {
        const octomap::point3d p(static_cast<float>(d.origin.x + (i + 0.5) * r),
                                 static_cast<float>(d.origin.y + (j + 0.5) * r),
                                 static_cast<float>(d.origin.z + (k + 0.5) * r));
        tree.updateNode(p, occupied[n] != 0u, true);  // lazy: inner nodes once, below
      }
  tree.updateInnerOccupancy();
  std::ofstream out(path, std::ios::binary);
  if (!out || !tree.writeBinary(out) || !out.flush()) {
    *error = path + ": cannot write the same-map tree";
    return false;
  }
  return true;
}

// A temporary file name of this process for `map` (removed after the bench).
std::string temp_tree_path(const std::string& map) {
  const std::string name = map.substr(map.find_last_of('/') + 1);
  return (std::filesystem::temp_directory_path() /
          ("tdo-bench-load-" + std::to_string(static_cast<long>(getpid())) + "-" + name + ".bt"))
      .string();
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
  bool octree = false;
  double base_ms = 0.0;     // OctoMap's read of the file (OcTree) or of the same-map tree (.3dmap)
  double blocked_ms = 0.0;  // .3dmap: OctoMap's read of its occupied voxels alone as a tree
  double map_ms = 0.0;      // tdo_io::load_map
  double grid_ms = 0.0;     // tdo_io::load_into
  double total_ms = 0.0;    // load_map + load_into
  double prepare_ms = 0.0;  // tdo_grid_prepare after load_into: legal steps and distance field
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

// The per-repetition timings of one map (ms).
struct Times {
  std::vector<double> base, blocked, map, grid, total, prepare;
};

int measure_into(const ScaleMap& sm, uint64_t repeat, const std::string& base_file,
                 const std::string& blocked_tree, GridHost* host, Times* t) {
  std::string err;
  for (uint64_t r = 0; r < repeat; ++r) {
    double t0 = cpu_ms();
    const bool ok = octomap_read(base_file);
    t->base.push_back(ms_since(t0));
    if (!blocked_tree.empty()) {
      t0 = cpu_ms();
      if (!tree_read(blocked_tree)) {
        std::fprintf(stderr, "tdo-bench-scale: %s: OctoMap cannot read its tree\n",
                     sm.file.c_str());
        return 2;
      }
      t->blocked.push_back(ms_since(t0));
    }
    t0 = cpu_ms();
    tdo_io::Map m;
    const bool loaded = ok && tdo_io::load_map(sm.file, sm.load, &m, &err);
    t->map.push_back(ms_since(t0));
    t0 = cpu_ms();
    tdo_grid* grid = tdo_planner_grid(host->planner);
    const tdo_status st = loaded ? tdo_io::load_into(m, grid, sm.clearance) : TDO_ERR_NO_PATH;
    t->grid.push_back(ms_since(t0));
    t->total.push_back(t->map.back() + t->grid.back());
    // Not part of the load: the one-off work an online app pays on map arrival, else the first
    // search and collision query (docs/design.md s.0).
    t0 = cpu_ms();
    const tdo_status pst = st == TDO_OK ? tdo_grid_prepare(grid) : st;
    t->prepare.push_back(ms_since(t0));
    if (!ok || !loaded || st != TDO_OK || pst != TDO_OK) {
      std::fprintf(stderr, "tdo-bench-scale: %s: load failed (%s%s)\n", sm.file.c_str(),
                   ok ? err.c_str() : "OctoMap cannot read the baseline tree",
                   pst != TDO_OK ? tdo_status_str(pst) : "");
      return 2;
    }
  }
  return 0;
}

int measure(const ScaleMap& sm, uint64_t repeat, LoadRow* row) {
  const bool octree = ends_with(sm.file, ".bt") || ends_with(sm.file, ".ot");
  row->file = sm.file;
  row->clearance = sm.clearance;
  row->octree = octree;
  row->baseline = octree ? "OctoMap read" : "OctoMap read of the same-map tree";
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
  const std::string base_file = octree ? sm.file : temp_tree_path(sm.file);
  if (!octree && !write_known_box_tree(map, base_file, &err)) {
    std::fprintf(stderr, "tdo-bench-scale: %s\n", err.c_str());
    return 2;
  }
  const std::string blocked_tree = octree ? std::string() : tree_bytes(map);
  Times t;
  const int st = measure_into(sm, repeat, base_file, blocked_tree, &host, &t);
  if (!octree) {
    std::error_code ec;
    std::filesystem::remove(base_file, ec);
  }
  if (st != 0) return st;
  row->base_ms = median(t.base);
  row->blocked_ms = octree ? 0.0 : median(t.blocked);
  row->map_ms = median(t.map);
  row->grid_ms = median(t.grid);
  row->total_ms = median(t.total);
  row->prepare_ms = median(t.prepare);
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
      "\nmap loading, median of %llu interleaved runs (thread CPU time, ms); baseline = the "
      "OctoMap "
      "library reading the same tree (OcTree: the file; .3dmap: every voxel of its box known, "
      "written once as a .bt); voxelization = tdo's load minus the format's own read (OcTree: "
      "OctoMap's read of the file inside load_map; .3dmap: the parse, load_map); blocked-only "
      "tree = OctoMap reading the .3dmap's occupied voxels alone as a tree; prepare = "
      "tdo_grid_prepare after the load (legal steps and distance field, else paid by the first "
      "search and collision query)\n\n",
      static_cast<unsigned long long>(repeat));
  std::printf(
      "| map | voxels | occupied | clearance m | baseline | baseline ms | load_map ms | "
      "load_into ms | tdo load ms | voxelization / baseline | tdo load / baseline | "
      "blocked-only tree ms | tdo load / blocked-only tree | prepare ms |\n");
  std::printf("|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const LoadRow& r : rows) {
    const std::string name = r.file.substr(r.file.find_last_of('/') + 1);
    const double voxelization = r.total_ms - (r.octree ? r.base_ms : r.map_ms);
    char blocked[64] = "-", blocked_ratio[64] = "-";
    if (!r.octree) {
      std::snprintf(blocked, sizeof blocked, "%.2f", r.blocked_ms);
      std::snprintf(blocked_ratio, sizeof blocked_ratio, "%.2f", r.total_ms / r.blocked_ms);
    }
    std::printf(
        "| %s | %dx%dx%d | %zu | %.2f | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s | "
        "%.2f |\n",
        name.c_str(), r.desc.nx, r.desc.ny, r.desc.nz, r.occupied, r.clearance, r.baseline.c_str(),
        r.base_ms, r.map_ms, r.grid_ms, r.total_ms, voxelization / r.base_ms,
        r.total_ms / r.base_ms, blocked, blocked_ratio, r.prepare_ms);
  }
  std::printf("\n");
  for (const LoadRow& r : rows) {
    // OcTrees: tdo's work beyond OctoMap's read of the file. Voxel maps: tdo's whole load (parse
    // and grid) against OctoMap reading the same map as a tree, and, for context, against it
    // reading the occupied voxels alone.
    const std::string name = r.file.substr(r.file.find_last_of('/') + 1);
    const double ratio = r.octree ? (r.total_ms - r.base_ms) / r.base_ms : r.total_ms / r.base_ms;
    std::printf("goal load %s: %s %.2fx the OctoMap read%s (goal <= 2x): %s", name.c_str(),
                r.octree ? "voxelization" : "load", ratio, r.octree ? "" : " of the same-map tree",
                ratio <= 2.0 ? "met" : "NOT met");
    if (!r.octree)
      std::printf("; %.2fx the read of its occupied voxels alone as a tree",
                  r.total_ms / r.blocked_ms);
    std::printf("\n");
  }
  return 0;
}

}  // namespace tdo_bench
