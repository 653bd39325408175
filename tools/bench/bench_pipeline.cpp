// tdo-bench-pipeline: the whole TDO-MSF static pipeline on the paper's maps, timed beside the raw
// A* grid path in the same process. Figures for docs/performance.md, not a timed test.
//
//   tdo-bench-pipeline [--maps-dir DIR] [--map NAME]... [--repeat R]
//
// For each map (default map1..map5): median and mean wall time of tdo_planner_plan with the default
// parameters (stages 1-3, 5 and the metrics), expansions, the arena footprint, and the quality
// columns of tdo (turns and length of the final path) against raw A* (turns and length of its grid
// path), then one "met" / "NOT met" line per goal of issue 3 (time: Map1-3 <= 1 ms, Map4-5 <= 5 ms
// median; quality: turns <= 10 % of A*'s, length <= A*'s). A last table times the variants of
// `grid_first` (tdo_grid_first: the search starts with grid distances instead of the octile try;
// TERMS also with h_weight 2) in the same process, each with its ratio to the default. Exit
// status 2 on bad arguments or unreadable maps, 1 when a plan fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "map_list.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace {

struct Stats {
  double median_ms = 0.0;
  double mean_ms = 0.0;
  double min_ms = 0.0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.median_ms = v[v.size() / 2];
  s.min_ms = v.front();
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean_ms = sum / static_cast<double>(v.size());
  return s;
}

// tdo with other parameters, timed beside the default.
struct Variant {
  const char* name;
  int grid_first;  // tdo_grid_first
  double h_weight;
};
const Variant kVariants[] = {{"grid_first plain", TDO_GRID_FIRST_PLAIN, 1.0},
                             {"grid_first terms", TDO_GRID_FIRST_TERMS, 1.0},
                             {"grid_first terms, h_weight 2", TDO_GRID_FIRST_TERMS, 2.0}};
constexpr size_t kNumVariants = sizeof(kVariants) / sizeof(kVariants[0]);

// One planner's figures on one map.
struct Figures {
  Stats t;
  uint32_t expansions = 0;
  uint32_t turns = 0;
  double length = 0.0;  // m
};

struct Row {
  std::string map;
  Figures tdo;
  Figures astar;
  Figures var[kNumVariants];
  size_t arena = 0;
  int feasible = 0;
};

int usage(const char* msg) {
  std::fprintf(stderr, "tdo-bench-pipeline: error: %s\n", msg);
  std::fprintf(stderr, "usage: tdo-bench-pipeline [--maps-dir DIR] [--map NAME]... [--repeat R]\n");
  return 2;
}

// Plan `req` R times; the result of the last run stays in `res`.
std::vector<double> timed(tdo_planner* pl, const tdo_plan_request& req, int repeat,
                          tdo_plan_result* res, tdo_status* st) {
  std::vector<double> ms;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    *st = tdo_planner_plan(pl, &req, res);
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return ms;
}

// `repeat` timed plans of `req` (the last result in *res) into *out; false after a message naming
// the map and the planner when the plan fails.
bool measure(tdo_planner* pl, const tdo_plan_request& req, int repeat, const std::string& map,
             const std::string& planner, tdo_plan_result* res, Figures* out) {
  tdo_status st = TDO_OK;
  const std::vector<double> ms = timed(pl, req, repeat, res, &st);
  if (st != TDO_OK) {
    std::fprintf(stderr, "tdo-bench-pipeline: %s: %s: %s\n", map.c_str(), planner.c_str(),
                 tdo_status_str(st));
    return false;
  }
  out->t = stats(ms);
  out->expansions = res->search.expansions;
  out->turns = res->metrics.turns;
  out->length = res->metrics.length_m;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  tdo_bench::MapList maps{TDO_BENCH_PIPELINE_MAPS_DIR, {}};
  int repeat = 21;
  const std::string bad = maps.parse(argc, argv, [&](const std::string& a, const std::string& v) {
    if (a != "--repeat") return "unknown option " + a;
    char* end = nullptr;
    const long r = std::strtol(v.c_str(), &end, 10);
    if (end == v.c_str() || *end != '\0' || r < 1 || r > 100000)
      return std::string("--repeat needs an integer in [1, 100000]");
    repeat = static_cast<int>(r);
    return std::string();
  });
  if (!bad.empty()) return usage(bad.c_str());
  const std::vector<std::string> names = maps.chosen();
  const std::string& dir = maps.dir;

  std::vector<Row> rows;
  for (const std::string& name : names) {
    tdo_io::Map map;
    std::string err;
    if (!tdo_io::load_map(dir + "/" + name + ".tdomap", &map, &err)) return usage(err.c_str());
    if (!map.has_start || !map.has_goal) return usage((name + ": no start/goal").c_str());
    const double clearance = 0.5;
    tdo_planner_config cfg{};
    cfg.cap = tdo_io::capacity_for(map, clearance, 27u, 0u);
    cfg.cap.exact_heuristic = 1u;  // the obstacle-aware retry (docs/performance.md)
    const size_t bytes = tdo_planner_footprint(&cfg);
    std::unique_ptr<unsigned char[]> arena(new unsigned char[bytes]);
    std::fill(arena.get(), arena.get() + bytes, 0);  // touch every page before timing
    tdo_planner* pl = nullptr;
    if (tdo_planner_init(&pl, arena.get(), bytes, &cfg) != TDO_OK ||
        tdo_io::load_into(map, tdo_planner_grid(pl), clearance) != TDO_OK)
      return usage((name + ": planner set-up failed").c_str());

    Row row;
    row.map = name;
    row.arena = bytes;
    tdo_plan_request req{};
    req.start = map.start;
    req.goal = map.goal;
    tdo_plan_params_default(&req.params);
    tdo_plan_result res{};
    if (!measure(pl, req, repeat, name, "tdo", &res, &row.tdo)) return 1;
    row.feasible = res.feasibility.ok;

    for (size_t k = 0; k < kNumVariants; ++k) {
      tdo_plan_params_default(&req.params);
      req.params.grid_first = kVariants[k].grid_first;
      req.params.h_weight = kVariants[k].h_weight;
      const std::string planner = std::string("tdo ") + kVariants[k].name;
      if (!measure(pl, req, repeat, name, planner, &res, &row.var[k])) return 1;
    }

    tdo_plan_params_default(&req.params);
    req.params.depth = TDO_PLAN_SEARCH;
    req.params.search = TDO_SEARCH_ASTAR;
    tdo_plan_params_plain(&req.params);  // no turn-deviation terms (first_meet: bidir only)
    if (!measure(pl, req, repeat, name, "astar", &res, &row.astar)) return 1;
    rows.push_back(row);
  }

  std::printf("repeat %d per planner and map; clearance 0.5 m; tdo = default parameters\n\n",
              repeat);
  std::printf(
      "| map | tdo median ms | tdo mean ms | tdo min ms | tdo expansions | astar median ms | "
      "astar expansions | arena bytes | feasible "
      "|\n|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %.3f | %.3f | %.3f | %u | %.3f | %u | %zu | %s |\n", r.map.c_str(),
                r.tdo.t.median_ms, r.tdo.t.mean_ms, r.tdo.t.min_ms, r.tdo.expansions,
                r.astar.t.median_ms, r.astar.expansions, r.arena, r.feasible ? "yes" : "no");
  std::printf(
      "\n| map | tdo turns | astar turns | turns ratio | tdo length m | astar length m | "
      "length ratio |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows)
    std::printf("| %s | %u | %u | %.3f | %.3f | %.3f | %.3f |\n", r.map.c_str(), r.tdo.turns,
                r.astar.turns,
                r.astar.turns > 0 ? static_cast<double>(r.tdo.turns) / r.astar.turns : 0.0,
                r.tdo.length, r.astar.length, r.tdo.length / r.astar.length);
  std::printf(
      "\n| map | tdo variant | median ms | ratio to tdo | expansions | turns | length m "
      "| length ratio to astar |\n|---|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows)
    for (size_t k = 0; k < kNumVariants; ++k) {
      const Figures& v = r.var[k];
      std::printf("| %s | %s | %.3f | %.3f | %u | %u | %.3f | %.3f |\n", r.map.c_str(),
                  kVariants[k].name, v.t.median_ms, v.t.median_ms / r.tdo.t.median_ms, v.expansions,
                  v.turns, v.length, v.length / r.astar.length);
    }
  // The goals of issue 3 (docs/performance.md), one line each.
  std::printf("\n");
  for (const Row& r : rows) {
    double limit = 0.0;
    if (r.map == "map1" || r.map == "map2" || r.map == "map3") limit = 1.0;
    if (r.map == "map4" || r.map == "map5") limit = 5.0;
    if (limit > 0.0)
      std::printf("goal %s: median plan time %.3f ms <= %.0f ms: %s\n", r.map.c_str(),
                  r.tdo.t.median_ms, limit, r.tdo.t.median_ms <= limit ? "met" : "NOT met");
    const double turns_ratio =
        r.astar.turns > 0 ? static_cast<double>(r.tdo.turns) / r.astar.turns : 0.0;
    std::printf("goal %s: tdo turns %u <= 10%% of astar turns %u (ratio %.3f): %s\n", r.map.c_str(),
                r.tdo.turns, r.astar.turns, turns_ratio,
                10u * r.tdo.turns <= r.astar.turns ? "met" : "NOT met");
    std::printf("goal %s: tdo length %.3f m <= astar length %.3f m: %s\n", r.map.c_str(),
                r.tdo.length, r.astar.length, r.tdo.length <= r.astar.length ? "met" : "NOT met");
  }
  std::printf("\nmaps: %zu\n", rows.size());
  return 0;
}
