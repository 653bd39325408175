#include "textbook_astar.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <queue>
#include <utility>

namespace tdo_bench {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kSqrt3 = 1.73205080756887729353;

// Bit of cell (dx,dy,dz) of the 3x3x3 block around a voxel, each in {-1,0,1}.
constexpr int cell(int dx, int dy, int dz) { return (dz + 1) * 9 + (dy + 1) * 3 + (dx + 1); }

struct Move {
  int dx, dy, dz;
  double cost;    // voxel edges
  uint32_t need;  // cells that must be free: the 2x2 / 2x2x2 block the step sweeps (no cutting)
};

struct MoveTable {
  Move m[26];
  MoveTable() : m() {
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const int order = (dx != 0) + (dy != 0) + (dz != 0);
          uint32_t need = 0;
          for (int c = 0; c <= (dz != 0 ? 1 : 0); ++c)
            for (int b = 0; b <= (dy != 0 ? 1 : 0); ++b)
              for (int a = 0; a <= (dx != 0 ? 1 : 0); ++a)
                if (a != 0 || b != 0 || c != 0) need |= 1u << cell(a * dx, b * dy, c * dz);
          m[n++] = Move{dx, dy, dz, order == 1 ? 1.0 : order == 2 ? kSqrt2 : kSqrt3, need};
        }
  }
};
const MoveTable kMoves;

// std::priority_queue whose storage survives between queries (clear keeps the capacity).
template <class T, class Cmp>
class ReusableHeap : public std::priority_queue<T, std::vector<T>, Cmp> {
 public:
  explicit ReusableHeap(std::vector<T>& storage)
      : std::priority_queue<T, std::vector<T>, Cmp>(Cmp(), std::move(storage)), storage_(storage) {
    this->c.clear();
  }
  ~ReusableHeap() { storage_ = std::move(this->c); }
  ReusableHeap(const ReusableHeap&) = delete;
  ReusableHeap& operator=(const ReusableHeap&) = delete;

 private:
  std::vector<T>& storage_;
};

}  // namespace

TextbookAstar::TextbookAstar(int32_t nx, int32_t ny, int32_t nz, std::vector<uint8_t> blocked)
    : nx_(nx),
      ny_(ny),
      nz_(nz),
      sy_(nx),
      sz_(static_cast<int64_t>(nx) * ny),
      blocked_(std::move(blocked)) {
  const size_t n = static_cast<size_t>(nx) * static_cast<size_t>(ny) * static_cast<size_t>(nz);
  blocked_.resize(n, 1);
  g_.assign(n, 0.0);
  parent_.assign(n, 0);
  seen_.assign(n, 0);
  closed_.assign(n, 0);
}

bool TextbookAstar::is_free(int32_t x, int32_t y, int32_t z) const {
  if (x < 0 || y < 0 || z < 0 || x >= nx_ || y >= ny_ || z >= nz_) return false;
  return blocked_[static_cast<size_t>(x + y * sy_ + z * sz_)] == 0;
}

double TextbookAstar::octile(int32_t x, int32_t y, int32_t z) const {
  int32_t a = std::abs(x - gx_), b = std::abs(y - gy_), c = std::abs(z - gz_);
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  return static_cast<double>(a) + (kSqrt2 - 1.0) * static_cast<double>(b) +
         (kSqrt3 - kSqrt2) * static_cast<double>(c);
}

TextbookResult TextbookAstar::run(int32_t sx, int32_t sy, int32_t sz, int32_t gx, int32_t gy,
                                  int32_t gz) {
  TextbookResult r;
  if (!is_free(sx, sy, sz) || !is_free(gx, gy, gz)) return r;
  if (++gen_ == 0) {  // stamps wrapped: clear them once every 2^32 queries
    std::fill(seen_.begin(), seen_.end(), 0u);
    std::fill(closed_.begin(), closed_.end(), 0u);
    gen_ = 1;
  }
  gx_ = gx;
  gy_ = gy;
  gz_ = gz;
  const uint32_t start = static_cast<uint32_t>(sx + sy * sy_ + sz * sz_);
  const uint32_t goal = static_cast<uint32_t>(gx + gy * sy_ + gz * sz_);

  ReusableHeap<Entry, ByF> open(heap_storage_);
  g_[start] = 0.0;
  parent_[start] = start;
  seen_[start] = gen_;
  open.push(Entry{octile(sx, sy, sz), 0.0, start});

  while (!open.empty()) {
    const Entry e = open.top();
    open.pop();
    const uint32_t v = e.v;
    if (closed_[v] == gen_ || e.g > g_[v]) continue;  // stale duplicate (lazy deletion)
    if (v == goal) {
      r.found = true;
      r.cost = g_[v];
      uint32_t n = 1;
      for (uint32_t u = v; u != start; u = parent_[u]) ++n;
      r.path_voxels = n;
      return r;
    }
    closed_[v] = gen_;
    ++r.expansions;

    const int32_t z = static_cast<int32_t>(v / static_cast<uint64_t>(sz_));
    const uint32_t rem = v - static_cast<uint32_t>(z * sz_);
    const int32_t y = static_cast<int32_t>(rem / static_cast<uint32_t>(nx_));
    const int32_t x = static_cast<int32_t>(rem - static_cast<uint32_t>(y * nx_));

    // Which of the 27 cells around v are inside the grid and free (outside counts as blocked).
    uint32_t free27 = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (is_free(x + dx, y + dy, z + dz)) free27 |= 1u << cell(dx, dy, dz);

    const double gv = g_[v];
    for (const Move& m : kMoves.m) {
      if ((free27 & m.need) != m.need) continue;  // target blocked, or the step cuts a corner/edge
      const int32_t wx = x + m.dx, wy = y + m.dy, wz = z + m.dz;
      const uint32_t w = static_cast<uint32_t>(wx + wy * sy_ + wz * sz_);
      if (closed_[w] == gen_) continue;
      const double ng = gv + m.cost;
      if (seen_[w] == gen_ && !(ng < g_[w])) continue;
      g_[w] = ng;
      parent_[w] = v;
      seen_[w] = gen_;
      open.push(Entry{ng + octile(wx, wy, wz), ng, w});
    }
  }
  return r;  // goal unreachable
}

size_t TextbookAstar::memory_bytes() const {
  return blocked_.capacity() * sizeof(uint8_t) + g_.capacity() * sizeof(double) +
         parent_.capacity() * sizeof(uint32_t) + seen_.capacity() * sizeof(uint32_t) +
         closed_.capacity() * sizeof(uint32_t) + heap_storage_.capacity() * sizeof(Entry);
}

}  // namespace tdo_bench
