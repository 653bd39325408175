// Shared helpers of the libtdo suites: a planner on a heap arena, and an independent reference
// model of the grid (brute-force occupancy and clearance, MovingAI movement rule, Dijkstra) written
// from docs/design.md s.0 without looking at libtdo's internals.
#ifndef TDO_TEST_LIBTDO_TEST_UTIL_H
#define TDO_TEST_LIBTDO_TEST_UTIL_H

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "arena_contexts.h"
#include "rng.h"
#include "tdo/tdo.h"

namespace tdo_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

/** Capacities spelled out by the test (not derived from tdo_capacity_for_grid). */
inline tdo_capacity make_cap(uint32_t voxels, uint32_t nodes, uint32_t path, uint32_t boxes = 64u,
                             uint32_t clear_cells = 20000u, uint32_t expansions = 1u << 30) {
  tdo_capacity cap{};
  cap.max_voxels = voxels;
  cap.max_boxes = boxes;
  cap.max_nodes = nodes;
  cap.max_path = path;
  cap.max_clear_cells = clear_cells;
  cap.max_expansions = expansions;
  return cap;
}

inline bool same_voxel(const tdo_voxel& a, const tdo_voxel& b) {
  return a.i == b.i && a.j == b.j && a.k == b.k;
}

inline std::string str(const tdo_voxel& v) {
  std::ostringstream os;
  os << "(" << v.i << "," << v.j << "," << v.k << ")";
  return os.str();
}

/** Independent model of a grid: geometry plus a blocked flag per voxel. */
struct VoxelMap {
  int32_t nx = 1, ny = 1, nz = 1;
  double res = 1.0;
  tdo_vec3 origin{0.0, 0.0, 0.0};
  std::vector<uint8_t> blocked;

  VoxelMap() = default;
  VoxelMap(int32_t x, int32_t y, int32_t z, double r, tdo_vec3 o)
      : nx(x), ny(y), nz(z), res(r), origin(o), blocked(static_cast<size_t>(x) * y * z, 0u) {}

  size_t size() const { return blocked.size(); }
  bool in(int64_t i, int64_t j, int64_t k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz;
  }
  size_t idx(int64_t i, int64_t j, int64_t k) const {
    return static_cast<size_t>(i + nx * (j + static_cast<int64_t>(ny) * k));
  }
  size_t idx(const tdo_voxel& v) const { return idx(v.i, v.j, v.k); }
  tdo_voxel voxel(size_t n) const {
    const int64_t s = static_cast<int64_t>(n);
    return tdo_voxel{static_cast<int32_t>(s % nx), static_cast<int32_t>((s / nx) % ny),
                     static_cast<int32_t>(s / (static_cast<int64_t>(nx) * ny))};
  }
  bool is_free(int64_t i, int64_t j, int64_t k) const {
    return in(i, j, k) && !blocked[idx(i, j, k)];
  }
  bool is_free(const tdo_voxel& v) const { return is_free(v.i, v.j, v.k); }
  void set(int32_t i, int32_t j, int32_t k, bool b = true) { blocked[idx(i, j, k)] = b ? 1u : 0u; }
  uint32_t free_count() const {
    uint32_t n = 0;
    for (uint8_t b : blocked) n += b ? 0u : 1u;
    return n;
  }
  tdo_grid_desc desc() const {
    tdo_grid_desc d{};
    d.nx = nx;
    d.ny = ny;
    d.nz = nz;
    d.res = res;
    d.origin = origin;
    return d;
  }
  /** docs/design.md s.0: the centre of voxel (i,j,k) is origin + (i + 0.5)*res. */
  tdo_vec3 center(const tdo_voxel& v) const {
    return tdo_vec3{origin.x + (v.i + 0.5) * res, origin.y + (v.j + 0.5) * res,
                    origin.z + (v.k + 0.5) * res};
  }
  /** A point strictly inside voxel v at fractions (fx, fy, fz) of its edge, fractions in (0, 1). */
  tdo_vec3 point_in(const tdo_voxel& v, double fx, double fy, double fz) const {
    return tdo_vec3{origin.x + (v.i + fx) * res, origin.y + (v.j + fy) * res,
                    origin.z + (v.k + fz) * res};
  }
};

/** Load the model's blocked voxels as voxel cubes into a library grid and finish it. */
inline tdo_status load_voxels(tdo_grid* grid, const VoxelMap& m, double clearance = 0.0) {
  const tdo_grid_desc d = m.desc();
  tdo_status st = tdo_grid_reset(grid, &d);
  if (st != TDO_OK) return st;
  for (size_t n = 0; n < m.size(); ++n) {
    if (!m.blocked[n]) continue;
    const tdo_voxel v = m.voxel(n);
    st = tdo_grid_add_voxel(grid, v.i, v.j, v.k);
    if (st != TDO_OK) return st;
  }
  return tdo_grid_finish(grid, clearance);
}

/** Random voxel map: each voxel blocked with probability `density`. */
inline VoxelMap random_voxel_map(Rng& rng, int32_t nx, int32_t ny, int32_t nz, double res,
                                 double density) {
  VoxelMap m(nx, ny, nz, res,
             tdo_vec3{rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0)});
  for (size_t n = 0; n < m.size(); ++n) m.blocked[n] = rng.uniform() < density ? 1u : 0u;
  return m;
}

// ---------------------------------------------------------------------------------------------
// Obstacle geometry and the brute-force blocked rule of docs/design.md s.0.

struct Obstacles {
  std::vector<tdo_box> boxes;
  std::vector<tdo_voxel> cubes;
};

inline double axis_gap(double p, double lo, double hi) {
  if (p < lo) return lo - p;
  if (p > hi) return p - hi;
  return 0.0;
}

/** Exact Euclidean distance from point p to the closed box b. */
inline double distance_to_box(const tdo_vec3& p, const tdo_box& b) {
  const double gx = axis_gap(p.x, b.min.x, b.max.x);
  const double gy = axis_gap(p.y, b.min.y, b.max.y);
  const double gz = axis_gap(p.z, b.min.z, b.max.z);
  return std::sqrt(gx * gx + gy * gy + gz * gz);
}

/** The cube of voxel v as a box: [origin + i*res, origin + (i+1)*res] on each axis. */
inline tdo_box cube_box(const VoxelMap& g, const tdo_voxel& v) {
  tdo_box b{};
  b.min = tdo_vec3{g.origin.x + v.i * g.res, g.origin.y + v.j * g.res, g.origin.z + v.k * g.res};
  b.max = tdo_vec3{g.origin.x + (v.i + 1) * g.res, g.origin.y + (v.j + 1) * g.res,
                   g.origin.z + (v.k + 1) * g.res};
  return b;
}

/** Voxel v, spanning [lo, hi) per axis, meets the open interior of box b. */
inline bool voxel_meets_box_interior(const VoxelMap& g, const tdo_voxel& v, const tdo_box& b) {
  const auto axis = [&](double o, int32_t i, double lo, double hi) {
    const double v0 = o + i * g.res;
    const double v1 = o + (i + 1) * g.res;
    return v0 < hi && v1 > lo;
  };
  return axis(g.origin.x, v.i, b.min.x, b.max.x) && axis(g.origin.y, v.j, b.min.y, b.max.y) &&
         axis(g.origin.z, v.k, b.min.z, b.max.z);
}

/** Brute force: occupied[v] = v intersects a box interior or is a cube. */
inline std::vector<uint8_t> brute_occupied(const VoxelMap& g, const Obstacles& obs) {
  std::vector<uint8_t> occ(g.size(), 0u);
  for (size_t n = 0; n < g.size(); ++n) {
    const tdo_voxel v = g.voxel(n);
    for (const tdo_box& b : obs.boxes)
      if (voxel_meets_box_interior(g, v, b)) occ[n] = 1u;
  }
  for (const tdo_voxel& c : obs.cubes) occ[g.idx(c)] = 1u;
  return occ;
}

/** Brute force: blocked[v] = occupied, or centre strictly closer than c to any obstacle. */
inline std::vector<uint8_t> brute_blocked(const VoxelMap& g, const Obstacles& obs, double c) {
  std::vector<uint8_t> blk = brute_occupied(g, obs);
  if (!(c > 0.0)) return blk;
  for (size_t n = 0; n < g.size(); ++n) {
    if (blk[n]) continue;
    const tdo_vec3 p = g.center(g.voxel(n));
    for (const tdo_box& b : obs.boxes)
      if (distance_to_box(p, b) < c) blk[n] = 1u;
    for (const tdo_voxel& cube : obs.cubes)
      if (distance_to_box(p, cube_box(g, cube)) < c) blk[n] = 1u;
  }
  return blk;
}

inline tdo_status load_obstacles(tdo_grid* grid, const VoxelMap& g, const Obstacles& obs,
                                 double clearance) {
  const tdo_grid_desc d = g.desc();
  tdo_status st = tdo_grid_reset(grid, &d);
  if (st != TDO_OK) return st;
  for (const tdo_box& b : obs.boxes) {
    st = tdo_grid_add_box(grid, &b);
    if (st != TDO_OK) return st;
  }
  for (const tdo_voxel& v : obs.cubes) {
    st = tdo_grid_add_voxel(grid, v.i, v.j, v.k);
    if (st != TDO_OK) return st;
  }
  return tdo_grid_finish(grid, clearance);
}

// ---------------------------------------------------------------------------------------------
// MovingAI movement rule and a reference Dijkstra.

/** Number of changed axes of a step, 0 when a and b are not 26-neighbours (or equal). */
inline int step_order(const tdo_voxel& a, const tdo_voxel& b) {
  const int32_t dx = b.i - a.i, dy = b.j - a.j, dz = b.k - a.k;
  if (dx < -1 || dx > 1 || dy < -1 || dy > 1 || dz < -1 || dz > 1) return 0;
  return (dx != 0) + (dy != 0) + (dz != 0);
}

/**
 * A step a -> b is legal when a and b are 26-neighbours and every voxel of the axis-aligned block
 * spanned by them (the 2x2 square of an edge diagonal, the 2x2x2 cube of a corner diagonal) is
 * free.
 */
inline bool legal_step(const VoxelMap& m, const tdo_voxel& a, const tdo_voxel& b) {
  if (step_order(a, b) == 0) return false;
  const int32_t dx = b.i - a.i, dy = b.j - a.j, dz = b.k - a.k;
  for (int32_t ex = 0; ex <= (dx != 0 ? 1 : 0); ++ex)
    for (int32_t ey = 0; ey <= (dy != 0 ? 1 : 0); ++ey)
      for (int32_t ez = 0; ez <= (dz != 0 ? 1 : 0); ++ez)
        if (!m.is_free(a.i + ex * dx, a.j + ey * dy, a.k + ez * dz)) return false;
  return true;
}

/** Length of a legal step: res * {1, sqrt2, sqrt3}. */
inline double step_length(double res, const tdo_voxel& a, const tdo_voxel& b) {
  return res * std::sqrt(static_cast<double>(step_order(a, b)));
}

/**
 * Optimal turn-penalised cost from s to g: Dijkstra over (voxel, last step) states, every legal
 * step allowed (no direction constraint), cost = length + lambda * (angle between consecutive
 * steps / pi)^2 summed over the path's turns (docs/design.md s.1); +inf when unreachable.
 */
inline double reference_penalised_cost(const VoxelMap& m, const tdo_voxel& s, const tdo_voxel& g,
                                       double lambda) {
  if (!m.is_free(s) || !m.is_free(g)) return kInf;
  const double pi = std::acos(-1.0);
  constexpr int kNone = 27;  // start state: no step yet; steps are (dx+1) + 3 (dy+1) + 9 (dz+1)
  std::vector<double> dist(m.size() * 28u, kInf);
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  const size_t start = m.idx(s) * 28u + kNone;
  dist[start] = 0.0;
  open.push(Item{0.0, start});
  const size_t goal = m.idx(g);
  while (!open.empty()) {
    const Item top = open.top();
    open.pop();
    if (top.first > dist[top.second]) continue;
    if (top.second / 28u == goal) return top.first;
    const tdo_voxel u = m.voxel(top.second / 28u);
    const int last = static_cast<int>(top.second % 28u);
    for (int32_t dz = -1; dz <= 1; ++dz)
      for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx) {
          const tdo_voxel w{u.i + dx, u.j + dy, u.k + dz};
          if (!legal_step(m, u, w)) continue;
          double turn = 0.0;
          if (last != kNone) {
            const double a[3] = {double(last % 3 - 1), double(last / 3 % 3 - 1),
                                 double(last / 9 - 1)};
            const double c = (a[0] * dx + a[1] * dy + a[2] * dz) /
                             std::sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) *
                                       double(dx * dx + dy * dy + dz * dz));
            const double angle = std::acos(std::fmax(-1.0, std::fmin(1.0, c)));
            turn = lambda * (angle / pi) * (angle / pi);
          }
          const double nd = top.first + step_length(m.res, u, w) + turn;
          const size_t wi =
              m.idx(w) * 28u + static_cast<size_t>((dx + 1) + 3 * (dy + 1) + 9 * (dz + 1));
          if (nd < dist[wi]) {
            dist[wi] = nd;
            open.push(Item{nd, wi});
          }
        }
  }
  return kInf;
}

/** Optimal MovingAI cost from s to g (the Dijkstra above without turn costs); +inf when
 *  unreachable. */
inline double reference_cost(const VoxelMap& m, const tdo_voxel& s, const tdo_voxel& g) {
  return reference_penalised_cost(m, s, g, 0.0);
}

inline bool near_rel(double a, double b, double rel = 1e-9) {
  return std::fabs(a - b) <= rel * std::fmax(1.0, std::fmax(std::fabs(a), std::fabs(b)));
}

/** Sum over interior path points of lambda * (angle between consecutive steps / pi)^2. */
inline double turn_penalty(const tdo_search_output& out, double lambda) {
  const double pi = std::acos(-1.0);
  double sum = 0.0;
  for (uint32_t n = 2; n < out.n_path; ++n) {
    const tdo_voxel& a = out.path[n - 2];
    const tdo_voxel& b = out.path[n - 1];
    const tdo_voxel& c = out.path[n];
    const double u[3] = {double(b.i - a.i), double(b.j - a.j), double(b.k - a.k)};
    const double w[3] = {double(c.i - b.i), double(c.j - b.j), double(c.k - b.k)};
    const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double nw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double cosang = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / (nu * nw);
    cosang = std::fmin(1.0, std::fmax(-1.0, cosang));
    const double t = std::acos(cosang) / pi;
    sum += lambda * t * t;
  }
  return sum;
}

/**
 * The returned path starts at s, ends at g, every step is legal per the MovingAI rule on `m`, and
 * the sum of its step lengths equals out.cost.
 */
inline ::testing::AssertionResult valid_path(const VoxelMap& m, const tdo_search_output& out,
                                             const tdo_voxel& s, const tdo_voxel& g) {
  if (out.n_path == 0 || out.path == nullptr)
    return ::testing::AssertionFailure() << "empty path (n_path=" << out.n_path << ")";
  if (!same_voxel(out.path[0], s))
    return ::testing::AssertionFailure()
           << "path starts at " << str(out.path[0]) << ", start voxel is " << str(s);
  if (!same_voxel(out.path[out.n_path - 1], g))
    return ::testing::AssertionFailure()
           << "path ends at " << str(out.path[out.n_path - 1]) << ", goal voxel is " << str(g);
  double length = 0.0;
  for (uint32_t n = 0; n < out.n_path; ++n) {
    if (!m.is_free(out.path[n]))
      return ::testing::AssertionFailure()
             << "path voxel " << n << " " << str(out.path[n]) << " is blocked or outside";
    if (n == 0) continue;
    if (!legal_step(m, out.path[n - 1], out.path[n]))
      return ::testing::AssertionFailure()
             << "illegal step " << n << ": " << str(out.path[n - 1]) << " -> " << str(out.path[n]);
    length += step_length(m.res, out.path[n - 1], out.path[n]);
  }
  if (!near_rel(length, out.cost))
    return ::testing::AssertionFailure()
           << "sum of step lengths " << length << " != out.cost " << out.cost;
  return ::testing::AssertionSuccess();
}

/** Search input with no penalties and a generous explicit budget. */
inline tdo_search_input make_input(const tdo_grid* grid, tdo_vec3 start, tdo_vec3 goal,
                                   tdo_search_kind kind, double lambda = 0.0, double mu = 0.0,
                                   uint32_t max_expansions = 0u) {
  tdo_search_input in{};
  in.grid = grid;
  in.start = start;
  in.goal = goal;
  in.kind = kind;
  in.lambda = lambda;
  in.mu = mu;
  in.max_expansions = max_expansions;
  return in;
}

inline const char* kind_name(tdo_search_kind k) {
  return k == TDO_SEARCH_ASTAR ? "astar" : "bidir";
}

}  // namespace tdo_test

#endif  // TDO_TEST_LIBTDO_TEST_UTIL_H
