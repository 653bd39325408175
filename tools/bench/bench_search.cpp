// tdo-bench-search: time libtdo's A* and bidirectional A* against a plain textbook A* on the
// MovingAI 3D benchmarks, in one process, on the same queries, and check every cost.
//
// Usage: tdo-bench-search [--maps-dir DIR] [--map NAME]... [--limit N] [--repeat R] [--warmup W]
// See docs/performance.md for what is measured and how to read the table.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench_args.h"
#include "host_info.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"
#include "textbook_astar.h"

#ifndef TDO_BENCH_MAPS_DIR
#define TDO_BENCH_MAPS_DIR "maps/movingai"
#endif

namespace {

constexpr double kTolerance = 1e-4;  // voxel edges; the .3dscen costs have 8 decimals
constexpr int kPlanners = 3;
const char* const kPlannerName[kPlanners] = {"textbook", "astar", "bidir"};
enum { kTextbook = 0, kAstar = 1, kBidir = 2 };

struct Options {
  std::string maps_dir = TDO_BENCH_MAPS_DIR;
  std::vector<std::string> maps;  // map names without extension
  uint64_t limit = 0;             // 0 = all queries
  uint64_t repeat = 1;            // timings per query and planner; the minimum is kept
  uint64_t warmup = 20;           // untimed queries per map before timing
};

void usage(FILE* f) {
  std::fprintf(
      f,
      "usage: tdo-bench-search [--maps-dir DIR] [--map NAME]... [--limit N] [--repeat R]\n"
      "                        [--warmup W]\n"
      "  --maps-dir DIR  folder with NAME.3dmap and NAME.3dmap.3dscen (default %s)\n"
      "  --map NAME      map to run, repeatable (default: Simple and Complex)\n"
      "  --limit N       first N queries of each scenario (default: all)\n"
      "  --repeat R      time each query R times per planner, keep the minimum (default 1)\n"
      "  --warmup W      untimed queries per map before timing (default 20)\n"
      "Exit status: 0 all costs match, 1 a cost mismatch or failed query, 2 bad arguments\n"
      "or unreadable files.\n",
      TDO_BENCH_MAPS_DIR);
}

// Returns 0 on success, 2 after printing a message on a bad command line, 3 for --help.
int parse_args(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool takes_value =
        a == "--maps-dir" || a == "--map" || a == "--limit" || a == "--repeat" || a == "--warmup";
    int rc = 0;
    const char* v =
        tdo_bench::option_value("tdo-bench-search", argc, argv, &i, takes_value, usage, &rc);
    if (v == nullptr) return rc;
    bool ok = true;
    if (a == "--maps-dir") {
      o->maps_dir = v;
      ok = !o->maps_dir.empty();
    } else if (a == "--map") {
      o->maps.emplace_back(v);
      ok = !o->maps.back().empty();
    } else if (a == "--limit") {
      ok = tdo_bench::parse_count(v, 1, UINT64_MAX, &o->limit);
    } else if (a == "--repeat") {
      ok = tdo_bench::parse_count(v, 1, 1000, &o->repeat);
    } else {
      ok = tdo_bench::parse_count(v, 0, UINT64_MAX, &o->warmup);
    }
    if (!ok) {
      std::fprintf(stderr, "tdo-bench-search: bad value '%s' for %s\n", v, a.c_str());
      return 2;
    }
  }
  if (o->maps.empty()) o->maps = {"Simple", "Complex"};
  return 0;
}

// Timings and checks of one planner on one map.
struct Stats {
  std::vector<double> us;      // per query: time in microseconds (min over repeats)
  uint64_t expansions = 0;     // summed over queries
  uint64_t failed = 0;         // queries without a path or with an error status
  uint64_t mism_scen = 0;      // cost differs from the .3dscen cost (failures included)
  uint64_t mism_textbook = 0;  // cost differs from the textbook A* cost (failures included)
  size_t bytes_footprint = 0;  // arena bytes the configuration needs (libtdo)
  size_t bytes_used = 0;       // arena bytes carved (libtdo) / heap bytes held (textbook)
};

struct Summary {
  double median = 0, mean = 0, p90 = 0, total = 0;  // us
};

Summary summarize(std::vector<double> v) {
  Summary s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.median = n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  const size_t r90 = static_cast<size_t>(std::ceil(0.9 * static_cast<double>(n)));  // nearest rank
  s.p90 = v[r90 > 0 ? r90 - 1 : 0];
  for (double x : v) s.total += x;
  s.mean = s.total / static_cast<double>(n);
  return s;
}

bool file_exists(const std::string& p) {
  std::ifstream f(p);
  return f.good();
}

struct MapResult {
  std::string name;
  uint64_t queries = 0;
  Stats st[kPlanners];
};

// Runs one map. Returns 0, or 2 after printing a message when a file or the planner set-up fails.
int run_map(const Options& o, const std::string& name, MapResult* res) {
  res->name = name;
  const std::string map_path = o.maps_dir + "/" + name + ".3dmap";
  const std::string scen_path = map_path + ".3dscen";
  tdo_io::Map map;
  std::string err;
  if (!tdo_io::load_map(map_path, &map, &err)) {
    std::fprintf(stderr, "tdo-bench-search: %s\n", err.c_str());
    return 2;
  }
  std::vector<tdo_io::ScenQuery> queries;
  if (!tdo_io::load_scen(scen_path, &queries, &err)) {
    std::fprintf(stderr, "tdo-bench-search: %s\n", err.c_str());
    return 2;
  }
  if (o.limit > 0 && queries.size() > o.limit) queries.resize(o.limit);
  res->queries = queries.size();

  // libtdo: one planner in a caller-owned arena, sized for this map without heading costs.
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, 0.0, 1, 0);
  const size_t footprint = tdo_planner_footprint(&cfg);
  if (footprint == 0) {
    std::fprintf(stderr, "tdo-bench-search: %s: invalid planner capacities\n", map_path.c_str());
    return 2;
  }
  std::unique_ptr<unsigned char[]> arena(new unsigned char[footprint]);
  // Touch every page now, as the textbook's std::vector::assign does for its arrays, so first-touch
  // page faults land in neither planner's timings.
  std::memset(arena.get(), 0, footprint);
  tdo_planner* planner = nullptr;
  tdo_status s = tdo_planner_init(&planner, arena.get(), footprint, &cfg);
  if (s == TDO_OK) s = tdo_io::load_into(map, tdo_planner_grid(planner), 0.0);
  if (s != TDO_OK) {
    std::fprintf(stderr, "tdo-bench-search: %s: planner set-up failed: %s\n", map_path.c_str(),
                 tdo_status_str(s));
    return 2;
  }
  const tdo_grid* grid = tdo_planner_grid(planner);
  tdo_search* search = tdo_planner_search(planner);
  const tdo_grid_desc desc = tdo_grid_get_desc(grid);

  // Textbook A*: its own blocked-voxel array, straight from the file's voxel list.
  const int64_t nvox = static_cast<int64_t>(desc.nx) * desc.ny * desc.nz;
  std::vector<uint8_t> blocked(static_cast<size_t>(nvox), 0);
  for (const tdo_voxel& v : map.voxels) {
    if (v.i < 0 || v.j < 0 || v.k < 0 || v.i >= desc.nx || v.j >= desc.ny || v.k >= desc.nz)
      continue;
    blocked[static_cast<size_t>(v.i + static_cast<int64_t>(v.j) * desc.nx +
                                static_cast<int64_t>(v.k) * desc.nx * desc.ny)] = 1;
  }
  tdo_bench::TextbookAstar textbook(desc.nx, desc.ny, desc.nz, std::move(blocked));
  auto to_voxel = [&](double p, double origin) {
    return static_cast<int32_t>(std::floor((p - origin) / desc.res));
  };

  struct Outcome {
    bool ok;
    double cost;  // voxel edges
    uint64_t expansions;
  };
  // One query on one planner; returns its outcome and adds its time (us) to *us.
  auto run_one = [&](int planner_id, const tdo_io::ScenQuery& q, double* us) -> Outcome {
    Outcome out{false, 0.0, 0};
    if (planner_id == kTextbook) {
      const int32_t sx = to_voxel(q.start.x, desc.origin.x),
                    sy = to_voxel(q.start.y, desc.origin.y),
                    sz = to_voxel(q.start.z, desc.origin.z), gx = to_voxel(q.goal.x, desc.origin.x),
                    gy = to_voxel(q.goal.y, desc.origin.y), gz = to_voxel(q.goal.z, desc.origin.z);
      const auto t0 = std::chrono::steady_clock::now();
      const tdo_bench::TextbookResult r = textbook.run(sx, sy, sz, gx, gy, gz);
      const auto t1 = std::chrono::steady_clock::now();
      *us = std::chrono::duration<double, std::micro>(t1 - t0).count();
      out = Outcome{r.found, r.cost, r.expansions};
    } else {
      tdo_search_input in{};
      in.grid = grid;
      in.start = q.start;
      in.goal = q.goal;
      in.kind = planner_id == kAstar ? TDO_SEARCH_ASTAR : TDO_SEARCH_BIDIR;
      in.lambda = 0.0;
      in.mu = 0.0;
      in.max_expansions = 0;
      tdo_search_output so{};
      const auto t0 = std::chrono::steady_clock::now();
      const tdo_status st = tdo_search_run(search, &in, &so);
      const auto t1 = std::chrono::steady_clock::now();
      *us = std::chrono::duration<double, std::micro>(t1 - t0).count();
      out = Outcome{st == TDO_OK, so.cost / desc.res, so.expansions};
      if (st != TDO_OK && st != TDO_ERR_NO_PATH)
        std::fprintf(stderr, "tdo-bench-search: %s line %d: %s: %s\n", scen_path.c_str(), q.line,
                     kPlannerName[planner_id], tdo_status_str(st));
    }
    return out;
  };

  // Warm caches and branch predictors on a few queries, untimed.
  for (uint64_t i = 0; i < o.warmup && i < queries.size(); ++i)
    for (int p = 0; p < kPlanners; ++p) {
      double us = 0;
      (void)run_one(p, queries[i], &us);
    }

  for (Stats& st : res->st) st.us.reserve(queries.size());
  // Interleaved: every query runs on all three planners before the next query, the order rotating
  // per query, so drifts in machine speed hit all planners alike.
  for (size_t qi = 0; qi < queries.size(); ++qi) {
    const tdo_io::ScenQuery& q = queries[qi];
    Outcome oc[kPlanners];
    for (int k = 0; k < kPlanners; ++k) {
      const int p = static_cast<int>((qi + static_cast<size_t>(k)) % kPlanners);
      double best = HUGE_VAL;
      for (uint64_t r = 0; r < o.repeat; ++r) {
        double us = 0;
        oc[p] = run_one(p, q, &us);
        best = std::min(best, us);
      }
      res->st[p].us.push_back(best);
    }
    for (int p = 0; p < kPlanners; ++p) {
      Stats& st = res->st[p];
      st.expansions += oc[p].expansions;
      if (!oc[p].ok) {
        ++st.failed;
        ++st.mism_scen;
        if (p != kTextbook) ++st.mism_textbook;
        continue;
      }
      if (std::fabs(oc[p].cost - q.cost) > kTolerance) {
        ++st.mism_scen;
        if (st.mism_scen <= 5)
          std::fprintf(stderr, "tdo-bench-search: %s line %d: %s cost %.8f, scen %.8f\n",
                       scen_path.c_str(), q.line, kPlannerName[p], oc[p].cost, q.cost);
      }
      if (p != kTextbook &&
          (!oc[kTextbook].ok || std::fabs(oc[p].cost - oc[kTextbook].cost) > kTolerance))
        ++st.mism_textbook;
    }
  }
  for (int p = kAstar; p <= kBidir; ++p) {
    res->st[p].bytes_footprint = footprint;
    res->st[p].bytes_used = tdo_planner_arena_used(planner);
  }
  res->st[kTextbook].bytes_used = textbook.memory_bytes();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const int pa = parse_args(argc, argv, &o);
  if (pa == 3) return 0;
  if (pa != 0) return 2;

  // Every file must be there before the first (long) run starts.
  for (const std::string& name : o.maps) {
    const std::string map_path = o.maps_dir + "/" + name + ".3dmap";
    for (const std::string& p : {map_path, map_path + ".3dscen"}) {
      if (!file_exists(p)) {
        std::fprintf(stderr, "tdo-bench-search: cannot open '%s' (use --maps-dir)\n", p.c_str());
        return 2;
      }
    }
  }

  const std::string load_before = tdo_bench::load_average();
  std::vector<MapResult> results;
  for (const std::string& name : o.maps) {
    results.emplace_back();
    const int rc = run_map(o, name, &results.back());
    if (rc != 0) return rc;
  }

  std::printf("# tdo-bench-search\n\n");
  std::printf("command:");
  for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
  std::printf("\nmachine: %u hardware threads, CPU %s; load average %s before, %s after\n",
              std::thread::hardware_concurrency(), tdo_bench::cpu_model().c_str(),
              load_before.c_str(), tdo_bench::load_average().c_str());
  std::printf("queries per map: %s, repeat %llu (min kept), warm-up %llu, tolerance %g\n\n",
              o.limit > 0 ? std::to_string(o.limit).c_str() : "all",
              static_cast<unsigned long long>(o.repeat), static_cast<unsigned long long>(o.warmup),
              kTolerance);
  std::printf(
      "| map | planner | queries | median us | mean us | p90 us | Mexp/s | mean exp/query | "
      "failed | cost mism. vs scen | cost mism. vs textbook | arena footprint B | arena used B "
      "|\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  uint64_t mismatches = 0;
  for (const MapResult& m : results) {
    for (int p = 0; p < kPlanners; ++p) {
      const Stats& st = m.st[p];
      const Summary s = summarize(st.us);
      const double mexps = s.total > 0 ? static_cast<double>(st.expansions) / s.total : 0.0;
      const double mean_exp =
          m.queries > 0 ? static_cast<double>(st.expansions) / static_cast<double>(m.queries) : 0.0;
      mismatches += st.mism_scen + st.mism_textbook;
      std::printf("| %s | %s | %llu | %.1f | %.1f | %.1f | %.2f | %.0f | %llu | %llu | ",
                  m.name.c_str(), kPlannerName[p], static_cast<unsigned long long>(m.queries),
                  s.median, s.mean, s.p90, mexps, mean_exp,
                  static_cast<unsigned long long>(st.failed),
                  static_cast<unsigned long long>(st.mism_scen));
      if (p == kTextbook)
        std::printf("- | - | %zu (heap) |\n", st.bytes_used);
      else
        std::printf("%llu | %zu | %zu |\n", static_cast<unsigned long long>(st.mism_textbook),
                    st.bytes_footprint, st.bytes_used);
    }
  }

  std::printf(
      "\n| map | textbook/astar median | textbook/astar mean | textbook/bidir median | "
      "textbook/bidir mean |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  for (const MapResult& m : results) {
    const Summary t = summarize(m.st[kTextbook].us);
    const Summary a = summarize(m.st[kAstar].us);
    const Summary b = summarize(m.st[kBidir].us);
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f |\n", m.name.c_str(), t.median / a.median,
                t.mean / a.mean, t.median / b.median, t.mean / b.mean);
  }
  std::printf("\n");
  for (const MapResult& m : results) {
    if (m.name != "Complex") continue;
    const Summary t = summarize(m.st[kTextbook].us);
    const Summary a = summarize(m.st[kAstar].us);
    const bool met = t.median >= 2.0 * a.median && t.mean >= 2.0 * a.mean &&
                     m.st[kAstar].mism_scen == 0 && m.st[kAstar].mism_textbook == 0;
    std::printf(
        "goal (Complex: astar >= 2x faster than textbook in median and mean, same costs): "
        "%s\n",
        met ? "met" : "NOT met");
  }
  std::printf("mismatches: %llu\n", static_cast<unsigned long long>(mismatches));
  return mismatches == 0 ? 0 : 1;
}
