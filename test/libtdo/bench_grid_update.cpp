// Map updates against a rebuild on a Map6-sized world (50 x 50 x 20 m at 0.25 m: 3.2 M voxels,
// clearance 0.5 m, 500 random columns as boxes): the voxel visits (tdo_grid_update_result
// .cells_touched) and the wall time of tdo_grid_apply_update for a wall box, ten boxes, 100 voxel
// cubes set and 100 cleared, beside the time of tdo_grid_finish, which a rebuild needs. Not a
// CTest test: prints figures and ratios measured in the same process. Build by hand:
//   g++ -O2 -std=c++17 -Ilibtdo/include test/libtdo/bench_grid_update.cpp \
//       build/libtdo/libtdo.a -o /tmp/bench_grid_update && /tmp/bench_grid_update
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "rng.h"
#include "tdo/tdo.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Planner {
  std::vector<unsigned char> mem;
  tdo_planner* p = nullptr;
  explicit Planner(uint32_t voxels) {
    tdo_planner_config cfg{};
    cfg.cap.max_voxels = voxels;
    cfg.cap.max_boxes = 2048;
    cfg.cap.max_nodes = 16;
    cfg.cap.max_path = 16;
    cfg.cap.max_clear_cells = 20000;
    cfg.cap.max_expansions = 16;
    mem.assign(tdo_planner_footprint(&cfg), 0u);
    if (tdo_planner_init(&p, mem.data(), mem.size(), &cfg) != TDO_OK) std::abort();
  }
  tdo_grid* grid() { return tdo_planner_grid(p); }
};

void row(const char* what, const tdo_grid_update& u, tdo_grid* g, double finish_ms) {
  tdo_grid_update_result r{};
  const auto t0 = Clock::now();
  if (tdo_grid_apply_update(g, &u, &r) != TDO_OK) std::abort();
  const double ms = ms_since(t0);
  std::printf("%-22s %12llu %10.3f %10.0fx\n", what,
              static_cast<unsigned long long>(r.cells_touched), ms,
              finish_ms / (ms > 1e-6 ? ms : 1e-6));
}

}  // namespace

int main() {
  const tdo_grid_desc d{200, 200, 80, 0.25, tdo_vec3{0, 0, 0}};
  Planner pl(200u * 200u * 80u);
  tdo_test::Rng rng(6);
  std::vector<tdo_box> columns;
  for (int c = 0; c < 500; ++c) {
    const double x = rng.uniform(0, 48), y = rng.uniform(0, 48), w = rng.uniform(1, 3);
    columns.push_back(tdo_box{{x, y, 0}, {x + w, y + w, rng.uniform(1, 20)}});
  }
  auto rebuild = [&]() {
    if (tdo_grid_reset(pl.grid(), &d) != TDO_OK) std::abort();
    for (const tdo_box& b : columns) tdo_grid_add_box(pl.grid(), &b);
    const auto t0 = Clock::now();
    if (tdo_grid_finish(pl.grid(), 0.5) != TDO_OK) std::abort();
    return ms_since(t0);
  };
  double finish_ms = rebuild();
  for (int k = 0; k < 2; ++k) finish_ms = std::min(finish_ms, rebuild());
  std::printf("world: 200 x 200 x 80 voxels (3.2 M) at 0.25 m, clearance 0.5 m, 500 columns\n");
  std::printf("tdo_grid_finish (a rebuild): %.1f ms (best of 3)\n\n", finish_ms);
  std::printf("%-22s %12s %10s %11s\n", "update", "cells", "ms", "finish/upd");
  const tdo_box wall{{24, 0, 0}, {26, 40, 20}};
  row("wall 2 x 40 x 20 m", tdo_grid_update{nullptr, 0, nullptr, 0, &wall, 1, 0}, pl.grid(),
      finish_ms);
  std::vector<tdo_box> ten;
  for (int k = 0; k < 10; ++k) {
    const double x = rng.uniform(0, 48), y = rng.uniform(0, 48);
    ten.push_back(tdo_box{{x, y, 0}, {x + 1, y + 1, 10}});
  }
  row("10 boxes 1 x 1 x 10 m", tdo_grid_update{nullptr, 0, nullptr, 0, ten.data(), 10, 0},
      pl.grid(), finish_ms);
  std::vector<tdo_voxel> vox;
  for (int k = 0; k < 100; ++k)
    vox.push_back(tdo_voxel{rng.range(0, 199), rng.range(0, 199), rng.range(0, 79)});
  row("100 cubes set", tdo_grid_update{vox.data(), 100, nullptr, 0, nullptr, 0, 0}, pl.grid(),
      finish_ms);
  row("100 cubes cleared", tdo_grid_update{nullptr, 0, vox.data(), 100, nullptr, 0, 0}, pl.grid(),
      finish_ms);
  return 0;
}
