// Timing of the collision queries and the correction on a Map5-like world (50 x 50 x 20 m, 1 m
// voxels, 500 random columns with 1-3 m footprints), as boxes and as voxel cubes. Not a CTest
// test: prints medians. Build by hand against the library, e.g.
//   g++ -O2 -std=c++17 -Ilibtdo/include test/libtdo/bench_collision.cpp \
//       /work/build-collide/libtdo/libtdo.a -o /tmp/bench_collision && /tmp/bench_collision
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rng.h"
#include "tdo/collision.h"
#include "tdo/correct.h"
#include "tdo/tdo.h"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct World {
  tdo_grid_desc desc{50, 50, 20, 1.0, tdo_vec3{0, 0, 0}};
  std::vector<tdo_box> boxes;
};

World map5(uint64_t seed) {
  tdo_test::Rng rng(seed);
  World w;
  for (int b = 0; b < 500; ++b) {
    const double x = rng.uniform(0, 50), y = rng.uniform(0, 50);
    const double fx = rng.uniform(1, 3), fy = rng.uniform(1, 3), h = rng.uniform(1, 20);
    // keep start (2,2,3) and goal (49,49,15) free
    if ((x < 5 && y < 5) || (x > 45 && y > 45)) continue;
    w.boxes.push_back(tdo_box{tdo_vec3{x, y, 0}, tdo_vec3{x + fx, y + fy, h}});
  }
  return w;
}

template <class F>
double time_us(F&& f, int reps) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  return median(t);
}

void run(const char* name, tdo_planner* pl, const World& w, bool as_cubes) {
  tdo_grid* g = tdo_planner_grid(pl);
  const double clearance = 0.5;
  auto load = [&]() {
    tdo_grid_reset(g, &w.desc);
    if (!as_cubes) {
      for (const tdo_box& b : w.boxes) tdo_grid_add_box(g, &b);
    } else {
      for (const tdo_box& b : w.boxes)
        for (int k = 0; k < static_cast<int>(std::ceil(b.max.z)); ++k)
          for (int j = static_cast<int>(b.min.y);
               j < static_cast<int>(std::ceil(b.max.y)) && j < 50; ++j)
            for (int i = static_cast<int>(b.min.x);
                 i < static_cast<int>(std::ceil(b.max.x)) && i < 50; ++i)
              tdo_grid_add_voxel(g, i, j, k);
    }
    return tdo_grid_finish(g, clearance);
  };
  if (load() != TDO_OK) {
    std::printf("%s: load failed\n", name);
    return;
  }
  const double t_finish = time_us(load, 9);

  // Random segments inside the bounds: short (<= 3 m) and long (across the map).
  tdo_test::Rng rng(5);
  std::vector<tdo_vec3> a, b_short, b_long;
  for (int i = 0; i < 4000; ++i) {
    const tdo_vec3 p{rng.uniform(0, 50), rng.uniform(0, 50), rng.uniform(0, 20)};
    a.push_back(p);
    b_short.push_back(tdo_vec3{std::min(50.0, std::max(0.0, p.x + rng.uniform(-2, 2))),
                               std::min(50.0, std::max(0.0, p.y + rng.uniform(-2, 2))),
                               std::min(20.0, std::max(0.0, p.z + rng.uniform(-1, 1)))});
    b_long.push_back(tdo_vec3{rng.uniform(0, 50), rng.uniform(0, 50), rng.uniform(0, 20)});
  }
  int clear_short = 0, clear_long = 0, clear_bz = 0;
  std::vector<double> ts, tl, tp, td, tb;
  // Corner-like cubic Beziers (a 2-4 m corner) at clearance 0.5 m, tolerance 5 mm.
  std::vector<tdo_vec3> bz;
  for (int i = 0; i < 1000; ++i) {
    const tdo_vec3 p{rng.uniform(4, 46), rng.uniform(4, 46), rng.uniform(2, 18)};
    const double r = rng.uniform(2, 4), th = rng.uniform(0, 6.283);
    const tdo_vec3 u{std::cos(th), std::sin(th), 0}, v{-std::sin(th), std::cos(th), 0};
    bz.push_back(tdo_vec3{p.x - r * u.x, p.y - r * u.y, p.z});
    bz.push_back(tdo_vec3{p.x - 0.4 * r * u.x, p.y - 0.4 * r * u.y, p.z});
    bz.push_back(tdo_vec3{p.x + 0.4 * r * v.x, p.y + 0.4 * r * v.y, p.z});
    bz.push_back(tdo_vec3{p.x + r * v.x, p.y + r * v.y, p.z});
  }
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = Clock::now();
    for (size_t i = 0; i < a.size(); ++i)
      clear_short += tdo_collision_segment_clear(g, a[i], b_short[i], clearance);
    ts.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / a.size());
    t0 = Clock::now();
    for (size_t i = 0; i < a.size(); ++i)
      clear_long += tdo_collision_segment_clear(g, a[i], b_long[i], clearance);
    tl.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / a.size());
    t0 = Clock::now();
    double sink = 0;
    for (size_t i = 0; i < a.size(); ++i)
      sink += tdo_collision_point_distance(g, a[i], clearance + 1.0);
    tp.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / a.size());
    t0 = Clock::now();
    for (size_t i = 0; i < a.size(); ++i)
      sink += tdo_collision_segment_distance(g, a[i], b_short[i], 10.0);
    td.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / a.size());
    if (sink < -1.0) std::printf("?");
    t0 = Clock::now();
    for (size_t i = 0; i < bz.size(); i += 4)
      clear_bz += tdo_collision_bezier_clear(g, &bz[i], clearance, 0.005);
    tb.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() /
                 (bz.size() / 4));
  }

  // The correction of an A* grid path from (2,2,3) to (49,49,15), as the pipeline builds it.
  tdo_search* s = tdo_planner_search(pl);
  tdo_search_input si{};
  si.grid = g;
  si.start = tdo_vec3{2, 2, 3};
  si.goal = tdo_vec3{49, 49, 15};
  si.kind = TDO_SEARCH_BIDIR;
  si.lambda = 50;
  si.mu = 20;
  si.theta_max = 3.14159265358979 / 4;
  tdo_search_output so{};
  const tdo_status sst = tdo_search_run(s, &si, &so);
  std::vector<tdo_vec3> pts;
  for (uint32_t i = 0; i < so.n_path; ++i) pts.push_back(tdo_grid_voxel_center(g, so.path[i]));
  if (pts.size() >= 2) {
    pts.front() = si.start;
    pts.back() = si.goal;
  }
  // and a raw A* path (many more turns)
  tdo_search_input sa = si;
  sa.kind = TDO_SEARCH_ASTAR;
  sa.lambda = sa.mu = sa.theta_max = 0;
  tdo_search_output soa{};
  tdo_search_run(s, &sa, &soa);
  std::vector<tdo_vec3> pts_a;
  for (uint32_t i = 0; i < soa.n_path; ++i) pts_a.push_back(tdo_grid_voxel_center(g, soa.path[i]));
  if (pts_a.size() >= 2) {
    pts_a.front() = si.start;
    pts_a.back() = si.goal;
  }
  static unsigned char mem[1 << 22];
  tdo_arena arena;
  tdo_arena_init(&arena, mem, sizeof mem);
  tdo_correct_config cc{4096, 100000};
  tdo_correct* corr = nullptr;
  tdo_correct_init(&corr, &arena, &cc);

  std::printf("%s: %zu boxes, finish (df + buckets + blocked) %.0f us\n", name, w.boxes.size(),
              t_finish);
  std::printf("  segment_clear short (<=3 m): %.2f us/check median (%d%% clear)\n", median(ts),
              clear_short * 100 / (5 * static_cast<int>(a.size())));
  std::printf("  segment_clear long (random, across the map): %.2f us/check (%d%% clear)\n",
              median(tl), clear_long * 100 / (5 * static_cast<int>(a.size())));
  std::printf("  point_distance cap 1.5 m: %.3f us/query\n", median(tp));
  std::printf("  segment_distance short, cap 10 m: %.2f us/query\n", median(td));
  std::printf("  bezier_clear 2-4 m corners, tol 5 mm: %.2f us/query (%d%% clear)\n", median(tb),
              clear_bz * 100 / (5 * static_cast<int>(bz.size() / 4)));
  const std::vector<tdo_vec3>* paths[2] = {&pts, &pts_a};
  const char* pnames[2] = {"tdo bidir path", "raw A* path"};
  for (int p = 0; p < 2; ++p) {
    if (paths[p]->size() < 2) {
      std::printf("  %s: search failed (%s)\n", pnames[p], tdo_status_str(sst));
      continue;
    }
    for (tdo_correct_mode mode :
         {TDO_CORRECT_MULTISCALE, TDO_CORRECT_GREEDY_LOS, TDO_CORRECT_NONE}) {
      tdo_correct_input ci{};
      ci.grid = g;
      ci.points = paths[p]->data();
      ci.n_points = static_cast<uint32_t>(paths[p]->size());
      ci.mode = mode;
      ci.clearance = clearance;
      ci.turn_threshold = 10.0 * 3.14159265358979 / 180.0;
      tdo_correct_output co{};
      tdo_status st = TDO_OK;
      const double t = time_us([&]() { st = tdo_correct_run(corr, &ci, &co); }, 21);
      std::printf(
          "  correct %-10s on %s (%u pts): %s, %u waypoints, %u checks, %.0f us (%.2f us/check)\n",
          mode == TDO_CORRECT_MULTISCALE   ? "multiscale"
          : mode == TDO_CORRECT_GREEDY_LOS ? "greedy"
                                           : "none",
          pnames[p], ci.n_points, tdo_status_str(st), co.n_waypoints, co.checks, t,
          co.checks ? t / co.checks : 0.0);
    }
  }
}

}  // namespace

int main() {
  const World w = map5(2024);
  tdo_planner_config cfg{};
  tdo_capacity_for_grid(&cfg.cap, 50, 50, 20, 0.5, 27u, 0u);
  cfg.cap.max_boxes = 600;
  std::vector<unsigned char> mem(tdo_planner_footprint(&cfg));
  tdo_planner* pl = nullptr;
  if (tdo_planner_init(&pl, mem.data(), mem.size(), &cfg) != TDO_OK) return 1;
  run("map5 boxes", pl, w, false);
  run("map5 as voxel cubes", pl, w, true);
  return 0;
}
