// A plain textbook A* over a dense voxel grid: the baseline libtdo's search is measured against.
//
// What makes it "textbook" (and what it deliberately shares with any competent implementation):
// - its own dense byte array of blocked voxels, index x + y*nx + z*nx*ny;
// - std::priority_queue (binary heap) with lazy deletion: an improved node is pushed again and the
//   stale entries are skipped when popped;
// - generation stamps instead of clearing the g / closed arrays before each query;
// - 26-connected MovingAI moves (costs 1, sqrt2, sqrt3) with no corner or edge cutting, checked on
//   the fly while expanding (with bounds checks), no precomputed move table;
// - 3D octile heuristic, ties broken by f only (the heap's order among equal f is unspecified).
//
// Host-side bench code: it allocates freely (std::vector) and is not part of libtdo.
#ifndef TDO_BENCH_TEXTBOOK_ASTAR_H
#define TDO_BENCH_TEXTBOOK_ASTAR_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tdo_bench {

/** Result of one textbook query. */
struct TextbookResult {
  bool found = false;       /**< a path was found */
  double cost = 0.0;        /**< voxel edges, optimal path length (0 when start == goal) */
  uint64_t expansions = 0;  /**< nodes expanded (popped, not stale, not the goal) */
  uint32_t path_voxels = 0; /**< voxels on the reconstructed path, start and goal included */
};

class TextbookAstar {
 public:
  /**
   * @brief Take the grid: `blocked[x + y*nx + z*nx*ny]` is non-zero for a blocked voxel.
   * Sizes every per-voxel array once; queries reuse them.
   */
  TextbookAstar(int32_t nx, int32_t ny, int32_t nz, std::vector<uint8_t> blocked);

  /** @brief Plan from voxel s to voxel g (both must be inside the grid). */
  TextbookResult run(int32_t sx, int32_t sy, int32_t sz, int32_t gx, int32_t gy, int32_t gz);

  /** @return bytes held by the per-voxel arrays and the heap's current capacity. */
  size_t memory_bytes() const;

 private:
  struct Entry {
    double f;    // voxel edges, g + h
    double g;    // voxel edges, g when pushed (stale when larger than the node's current g)
    uint32_t v;  // linear voxel index
  };
  struct ByF {  // min-heap on f only
    bool operator()(const Entry& a, const Entry& b) const { return a.f > b.f; }
  };

  bool is_free(int32_t x, int32_t y, int32_t z) const;
  double octile(int32_t x, int32_t y, int32_t z) const;

  int32_t nx_, ny_, nz_;
  int64_t sy_, sz_;               // strides: nx, nx*ny
  std::vector<uint8_t> blocked_;  // 1 = blocked
  std::vector<double> g_;         // voxel edges, valid when seen_[v] == gen_
  std::vector<uint32_t> parent_;  // predecessor voxel, valid when seen_[v] == gen_
  std::vector<uint32_t> seen_;    // generation in which g_/parent_ were written
  std::vector<uint32_t> closed_;  // generation in which the voxel was expanded
  uint32_t gen_ = 0;
  int32_t gx_ = 0, gy_ = 0, gz_ = 0;  // goal of the current query
  std::vector<Entry> heap_storage_;   // kept between queries so the heap does not reallocate
};

}  // namespace tdo_bench

#endif  // TDO_BENCH_TEXTBOOK_ASTAR_H
