// OctoMap input for the host tools: read an OcTree with the OctoMap library and voxelize it.
#include "octomap_io.h"

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tdo_io/octree_check.h"

namespace tdo_io {
namespace detail {
namespace {

/**
 * Redirects file descriptor 2 into a temporary file while alive, so the OctoMap library's messages
 * ("Reading binary octree type OcTree", "ERROR: ...") do not reach the tool's stderr; finish()
 * returns what was written. Process-wide: the host tools read maps from one thread.
 */
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    std::cerr.flush();
    tmp_ = std::tmpfile();
    saved_ = ::dup(2);
    if (tmp_ != nullptr && saved_ >= 0 && ::dup2(::fileno(tmp_), 2) >= 0) active_ = true;
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  ~StderrCapture() { (void)finish(); }

  /** Restore stderr; return the captured text (once). */
  std::string finish() {
    std::string text;
    if (active_) {
      std::fflush(stderr);
      std::cerr.flush();
      ::dup2(saved_, 2);
      active_ = false;
      std::rewind(tmp_);
      char buf[512];
      std::size_t n = 0;
      while ((n = std::fread(buf, 1, sizeof buf, tmp_)) > 0 && text.size() < 65536)
        text.append(buf, n);
    }
    if (saved_ >= 0) {
      ::close(saved_);
      saved_ = -1;
    }
    if (tmp_ != nullptr) {
      std::fclose(tmp_);
      tmp_ = nullptr;
    }
    return text;
  }

 private:
  std::FILE* tmp_ = nullptr;
  int saved_ = -1;
  bool active_ = false;
};

/** The library's last "ERROR: ..." line (without the prefix), else its last line, else "". */
std::string library_message(const std::string& captured) {
  std::string last;
  std::string last_error;
  std::istringstream in(captured);
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) continue;
    last = line;
    if (line.rfind("ERROR: ", 0) == 0) last_error = line.substr(7);
  }
  return last_error.empty() ? last : last_error;
}

std::string with_library(const std::string& msg, const std::string& captured) {
  const std::string lib = library_message(captured);
  return lib.empty() ? msg : msg + " (OctoMap: " + lib + ")";
}

bool fail(std::string* error, const std::string& path, const std::string& msg) {
  *error = path + ": " + msg;
  return false;
}

/** The file's bytes; false with "FILE: message" when it is not a readable regular file. */
bool read_bytes(const std::string& path, uint64_t max_bytes, std::string* bytes,
                std::string* error) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return fail(error, path, "cannot open");
  const std::streamoff size = in.tellg();
  if (size < 0) return fail(error, path, "cannot read");
  if (static_cast<uint64_t>(size) > max_bytes)
    return fail(error, path,
                "file of " + std::to_string(size) + " bytes exceeds the limit of " +
                    std::to_string(max_bytes));
  bytes->resize(static_cast<std::size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(&(*bytes)[0], size)) return fail(error, path, "cannot read");
  return true;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// "; its grid alone needs an arena of B bytes": the footprint of a planner holding only this
// grid (one heading, one search state, no clearance stencil), a lower bound of any planner's.
std::string grid_bytes_note(const int64_t n[3], double total) {
  if (total > 4294967280.0 || n[0] > INT32_MAX || n[1] > INT32_MAX || n[2] > INT32_MAX)
    return "; more than 2^32 voxels: no planner arena can hold it";
  tdo_planner_config cfg{};
  tdo_capacity_for_grid(&cfg.cap, static_cast<int32_t>(n[0]), static_cast<int32_t>(n[1]),
                        static_cast<int32_t>(n[2]), 0.0, 1u, 1u);
  const std::size_t bytes = tdo_planner_footprint(&cfg);
  return bytes == 0 ? std::string()
                    : "; its grid alone needs an arena of " + std::to_string(bytes) + " bytes";
}

}  // namespace

bool load_octomap(const std::string& path, const LoadOptions& options, Map* out,
                  std::string* error) {
  out->kind = MapKind::OctoMap;
  if (!(options.resolution >= 0.0) || !std::isfinite(options.resolution))
    return fail(error, path, "resolution must be finite and >= 0 (0 = the tree's)");

  // The whole stream is checked (bounded, no recursion) before OctoMap reads it.
  std::string bytes;
  if (!read_bytes(path, options.max_file_bytes, &bytes, error)) return false;
  OctreeInfo info;
  std::string why;
  const OctreeStatus st = check_octree(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(),
                                       options.octree, &info, &why);
  if (st == OctreeStatus::not_octomap) return fail(error, path, "not an OctoMap file: " + why);
  if (st != OctreeStatus::ok)
    return fail(error, path, std::string("corrupt OcTree (") + octree_status_str(st) + "): " + why);
  const bool binary = info.binary;
  std::istringstream in(std::move(bytes), std::ios::binary);

  std::unique_ptr<octomap::OcTree> tree;
  std::string captured;
  try {
    StderrCapture capture;
    if (binary) {
      tree = std::make_unique<octomap::OcTree>(0.1);
      if (!tree->readBinary(in)) {
        captured = capture.finish();
        return fail(error, path, with_library("cannot read the binary OcTree", captured));
      }
    } else {
      std::unique_ptr<octomap::AbstractOcTree> abstract(octomap::AbstractOcTree::read(in));
      captured = capture.finish();
      if (!abstract) return fail(error, path, with_library("cannot read the OcTree", captured));
      auto* oc = dynamic_cast<octomap::OcTree*>(abstract.get());
      if (oc == nullptr) {
        return fail(error, path,
                    "tree type '" + abstract->getTreeType() + "' is not supported (only OcTree)");
      }
      (void)abstract.release();
      tree.reset(oc);
    }
    captured += capture.finish();
  } catch (const std::exception& e) {
    return fail(error, path,
                with_library(std::string("cannot read the OcTree: ") + e.what(), captured));
  }

  if (tree->size() != info.nodes)
    return fail(error, path,
                "the OctoMap library read " + std::to_string(tree->size()) + " nodes, the check " +
                    std::to_string(info.nodes));
  const double res = options.resolution > 0.0 ? options.resolution : tree->getResolution();
  double lo[3];
  double hi[3];
  tree->getMetricMin(lo[0], lo[1], lo[2]);
  tree->getMetricMax(hi[0], hi[1], hi[2]);
  // Grid: known-space bounding box padded by one voxel on each side.
  int64_t n[3];
  double origin[3];
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil((hi[a] - lo[a]) / res - 1e-6);
    if (!(cells >= 0.0) || cells > 2e9) return fail(error, path, "tree bounds are not usable");
    n[a] = static_cast<int64_t>(cells) + 2;
    origin[a] = lo[a] - res;
  }
  const double total =
      static_cast<double>(n[0]) * static_cast<double>(n[1]) * static_cast<double>(n[2]);
  if (total > 4294967280.0 ||
      (options.max_voxels > 0 && total > static_cast<double>(options.max_voxels))) {
    return fail(error, path,
                "grid too large: " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                    std::to_string(n[2]) + " = " + number(total) + " voxels at resolution " +
                    number(res) + " m exceeds the cap of " + std::to_string(options.max_voxels) +
                    " (--max-voxels, or a coarser resolution)" + grid_bytes_note(n, total));
  }
  out->desc.nx = static_cast<int32_t>(n[0]);
  out->desc.ny = static_cast<int32_t>(n[1]);
  out->desc.nz = static_cast<int32_t>(n[2]);
  out->desc.res = res;
  out->desc.origin = tdo_vec3{origin[0], origin[1], origin[2]};

  // Every occupied leaf (any depth) marks every voxel its cube intersects (open interiors).
  constexpr double kEps = 1e-6;  // voxels: tolerance for float noise in the tree's coordinates
  std::vector<uint8_t> occ(static_cast<std::size_t>(total), 0);
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    if (!tree->isNodeOccupied(*it)) continue;
    const double half = it.getSize() / 2.0;
    const double c[3] = {it.getX(), it.getY(), it.getZ()};
    int64_t i0[3];
    int64_t i1[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      i0[a] = static_cast<int64_t>(std::floor((c[a] - half - origin[a]) / res + kEps));
      i1[a] = static_cast<int64_t>(std::ceil((c[a] + half - origin[a]) / res - kEps)) - 1;
      i0[a] = std::max<int64_t>(i0[a], 0);
      i1[a] = std::min<int64_t>(i1[a], n[a] - 1);
      if (i1[a] < i0[a]) inside = false;
    }
    if (!inside) continue;
    for (int64_t k = i0[2]; k <= i1[2]; ++k)
      for (int64_t j = i0[1]; j <= i1[1]; ++j)
        for (int64_t i = i0[0]; i <= i1[0]; ++i)
          occ[static_cast<std::size_t>((k * n[1] + j) * n[0] + i)] = 1;
  }
  std::size_t count = 0;
  for (uint8_t v : occ) count += v;
  out->voxels.reserve(count);
  for (int64_t k = 0; k < n[2]; ++k)
    for (int64_t j = 0; j < n[1]; ++j)
      for (int64_t i = 0; i < n[0]; ++i)
        if (occ[static_cast<std::size_t>((k * n[1] + j) * n[0] + i)] != 0)
          out->voxels.push_back(
              tdo_voxel{static_cast<int32_t>(i), static_cast<int32_t>(j), static_cast<int32_t>(k)});
  return true;
}

}  // namespace detail
}  // namespace tdo_io
