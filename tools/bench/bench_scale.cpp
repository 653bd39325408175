// tdo-bench-scale: the full tdo pipeline, plain A* and OMPL RRTConnect + simplify in one process on
// real maps (geb079, MovingAI Simple and Complex, the forest_gen forests, Map1-5), interleaved per
// query so drifts in machine speed hit all planners alike; a textbook A* checks A*'s costs. Prints
// the tables and the goals of issue 19 (docs/performance.md, "Real maps: the scale benchmark").
// Figures, not a timed test.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench_args.h"
#include "host_info.h"
#include "scale_load.h"
#include "scale_report.h"
#include "scale_runner.h"
#include "scale_workloads.h"
#include "tdo_samples/samples.h"

#ifndef TDO_BENCH_SCALE_MAPS_DIR
#define TDO_BENCH_SCALE_MAPS_DIR "maps"
#endif

namespace {

using tdo_bench::kScalePlanners;

struct Options {
  std::string maps_dir = TDO_BENCH_SCALE_MAPS_DIR;
  std::vector<std::string> workloads;  // default: all
  uint64_t limit = 0;                  // queries per map; 0 = MovingAI 1000, others all
  uint64_t repeat = 1;                 // best of R per query and planner
  uint64_t warmup = 3;                 // untimed queries per map before timing
  uint64_t seed = 1;                   // RRTConnect: query i of a workload has seed + i
  bool rrt_movingai = true;            // RRTConnect + simplify on MovingAI too
  bool load = false;                   // --load: map loading only (scale_load.h)
  uint64_t max_nodes = 4000000;        // search states per direction (tdo-plan's default)
  std::string states = "heading";      // tdo's state space: heading | voxel
  std::string guide = "on";            // tdo's coarse guide on grids of 2^19 voxels or more
  std::string depth = "trajectory";    // tdo's stages: trajectory (all) | search
  std::string samples = "default";     // tdo's trajectory samples: default | a mode name
  uint32_t stream_samples = tdo_bench::kScaleSamplesDefault;  // `samples` parsed (samples_mode)
  uint64_t trajectories = 0;  // timed tdo plans that reached the trajectory stage
  uint64_t sampled = 0;       // of them: verified a round over the samples
};

// --samples as ScaleMapRun::create takes it: "default" (tdo_bench::kScaleSamplesDefault, the
// library's choice) or a mode name of tdo_samples::mode_parse; false for another name.
bool samples_mode(const std::string& s, uint32_t* mode) {
  if (s != "default") return tdo_samples::mode_parse(s.c_str(), mode);
  *mode = tdo_bench::kScaleSamplesDefault;
  return true;
}

void usage(FILE* f) {
  std::fprintf(
      f,
      "usage: tdo-bench-scale [--workload NAME]... [--limit N] [--repeat R] [--warmup W]\n"
      "                       [--seed S] [--no-rrt-movingai] [--max-nodes N] [--states S]\n"
      "                       [--guide on|off] [--samples default|stored|streamed|pieces]\n"
      "                       [--depth trajectory|search]\n"
      "                       [--maps-dir DIR] [--load]\n"
      "  --workload NAME  geb079, simple, complex, forest, map1 .. map5; repeatable\n"
      "                   (default: all, in that order)\n"
      "  --limit N        at most N queries per map (default: 1000 on MovingAI, all elsewhere)\n"
      "  --repeat R       time each query R times per planner, keep the best (default 1)\n"
      "  --warmup W       untimed queries per map before timing (default 3)\n"
      "  --seed S         RRTConnect seed of a workload's first query (default 1)\n"
      "  --no-rrt-movingai  skip RRTConnect + simplify on the MovingAI maps ('-' rows)\n"
      "  --max-nodes N    search states per direction of the tdo and A* planners, as\n"
      "                   tdo-plan --max-nodes (default 4000000; 0 = voxels x headings)\n"
      "  --states S       tdo's search states: heading (the library's default) or voxel\n"
      "                   (tdo_plan_params.states; tdo sized without headings, as tdo-plan)\n"
      "  --guide on|off   tdo's coarse guide on grids of 2^19 voxels or more (design s.1;\n"
      "                   default on, as tdo-plan)\n"
      "  --samples M      tdo's trajectory samples (tdo_capacity.stream_samples): default (the\n"
      "                   library's: pieces on grids of 2^19 voxels or more, else stored),\n"
      "                   stored, streamed, or pieces (closed-form check per profile piece;\n"
      "                   the header counts the plans that fell back to the samples)\n"
      "  --depth D        tdo's stages (tdo_plan_params.depth): trajectory (default, the full\n"
      "                   pipeline) or search (the search alone, no direct-route check; its\n"
      "                   grid path measured and checked as A*'s)\n"
      "  --maps-dir DIR   the repository's maps/ folder (default %s)\n"
      "  --load           time map loading instead of planning: tdo's load of each OcTree and\n"
      "                   .3dmap map against the OctoMap library's read / the .3dmap parse\n"
      "                   (median of --repeat runs; default workloads geb079 simple complex\n"
      "                   forest)\n"
      "Exit status: 0 done, 1 tdo missed a query A* solved or A*'s cost differs from the\n"
      "textbook A*'s, 2 bad arguments, missing files or a failed set-up.\n",
      TDO_BENCH_SCALE_MAPS_DIR);
}

// 0 on success, 2 after a message for a bad command line, 3 for --help.
int parse_args(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-rrt-movingai") {
      o->rrt_movingai = false;
      continue;
    }
    if (a == "--load") {
      o->load = true;
      continue;
    }
    const bool takes_value = a == "--workload" || a == "--limit" || a == "--repeat" ||
                             a == "--warmup" || a == "--seed" || a == "--maps-dir" ||
                             a == "--max-nodes" || a == "--states" || a == "--guide" ||
                             a == "--samples" || a == "--depth";
    int rc = 0;
    const char* v =
        tdo_bench::option_value("tdo-bench-scale", argc, argv, &i, takes_value, usage, &rc);
    if (v == nullptr) return rc;
    bool ok = *v != '\0';
    if (a == "--workload") {
      if (std::find(o->workloads.begin(), o->workloads.end(), v) != o->workloads.end()) {
        std::fprintf(stderr, "tdo-bench-scale: workload '%s' given twice\n", v);
        return 2;
      }
      o->workloads.emplace_back(v);  // an unknown name is refused with the known ones listed
    } else if (a == "--maps-dir") {
      o->maps_dir = v;
    } else if (a == "--guide") {
      o->guide = v;
      ok = o->guide == "on" || o->guide == "off";
    } else if (a == "--samples") {
      o->samples = v;
      ok = samples_mode(o->samples, &o->stream_samples);
    } else if (a == "--depth") {
      o->depth = v;
      ok = o->depth == "trajectory" || o->depth == "search";
    } else if (a == "--states") {
      o->states = v;
      ok = o->states == "heading" || o->states == "voxel";
    } else if (a == "--limit") {
      ok = tdo_bench::parse_count(v, 1, UINT32_MAX, &o->limit);
    } else if (a == "--repeat") {
      ok = tdo_bench::parse_count(v, 1, 1000, &o->repeat);
    } else if (a == "--warmup") {
      ok = tdo_bench::parse_count(v, 0, 1000, &o->warmup);
    } else if (a == "--max-nodes") {
      ok = tdo_bench::parse_count(v, 0, 0xFFFFFFF0u, &o->max_nodes);
    } else {
      ok = tdo_bench::parse_count(v, 0, UINT32_MAX, &o->seed);
    }
    if (!ok) {
      std::fprintf(stderr, "tdo-bench-scale: bad value '%s' for %s\n", v, a.c_str());
      return 2;
    }
  }
  if (o->workloads.empty() && o->load) o->workloads = {"geb079", "simple", "complex", "forest"};
  if (o->workloads.empty()) o->workloads = tdo_bench::workload_names();
  return 0;
}

// One map of a workload: load it, set the planners up, warm up, then every query on every planner
// in a rotating order. Returns 0, or 2 after a message.
int run_map(Options& o, const tdo_bench::Workload& w, const tdo_bench::ScaleMap& sm,
            tdo_bench::WorkloadRecord* rec) {
  tdo_io::Map map;
  std::string err;
  const auto t0 = std::chrono::steady_clock::now();
  if (!tdo_io::load_map(sm.file, sm.load, &map, &err)) {
    std::fprintf(stderr, "tdo-bench-scale: %s\n", err.c_str());
    return 2;
  }
  rec->load_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<tdo_bench::ScaleQuery> queries = sm.queries;
  if (sm.map_query) {
    if (!map.has_start || !map.has_goal) {
      std::fprintf(stderr, "tdo-bench-scale: %s: no start and goal in the file\n", sm.file.c_str());
      return 2;
    }
    queries.push_back(tdo_bench::ScaleQuery{map.start, map.goal, "map"});
  }
  std::unique_ptr<tdo_bench::ScaleMapRun> run =
      tdo_bench::ScaleMapRun::create(map, sm.clearance, static_cast<uint32_t>(o.max_nodes),
                                     o.states == "voxel" ? TDO_STATES_VOXEL : TDO_STATES_HEADING,
                                     o.guide == "on", w.rrt, o.stream_samples, &err);
  if (!run) {
    std::fprintf(stderr, "tdo-bench-scale: %s\n", err.c_str());
    return 2;
  }
  run->set_tdo_depth(o.depth == "search" ? TDO_PLAN_SEARCH : TDO_PLAN_TRAJECTORY);
  for (int p = 0; p < kScalePlanners; ++p) {
    tdo_bench::ScaleSetup& s = rec->p[p].setup;
    const tdo_bench::ScaleSetup& m = run->setup(p);
    s = tdo_bench::ScaleSetup{std::max(s.arena_bytes, m.arena_bytes), std::max(s.rss_mb, m.rss_mb),
                              std::max(s.ms, m.ms)};
  }
  const uint64_t base = rec->labels.size();  // workload-wide query index of this map's first
  for (uint64_t i = 0; i < o.warmup && i < queries.size(); ++i)
    for (int p = 0; p < kScalePlanners; ++p)
      if (run->has(p)) (void)run->run(p, queries[i], o.seed + base + i, 1);
  const uint64_t traj0 = run->tdo_trajectories(), sampled0 = run->tdo_sampled();
  for (size_t qi = 0; qi < queries.size(); ++qi) {
    tdo_bench::ScaleOutcome oc[kScalePlanners];
    for (int k = 0; k < kScalePlanners; ++k) {
      const int p = static_cast<int>((qi + static_cast<size_t>(k)) % kScalePlanners);
      if (run->has(p)) oc[p] = run->run(p, queries[qi], o.seed + base + qi, o.repeat);
    }
    for (int p = 0; p < kScalePlanners; ++p) rec->p[p].q.push_back(oc[p]);
    rec->labels.push_back(queries[qi].label);
    if ((qi + 1) % 100 == 0)
      std::fprintf(stderr, "tdo-bench-scale: %s: %zu of %zu queries\n", sm.file.c_str(), qi + 1,
                   queries.size());
  }
  o.trajectories += run->tdo_trajectories() - traj0;
  o.sampled += run->tdo_sampled() - sampled0;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const int pa = parse_args(argc, argv, &o);
  if (pa == 3) return 0;
  if (pa != 0) return pa;
  // Every workload is described (query files read, map files checked) before anything runs.
  std::vector<tdo_bench::Workload> workloads;
  for (const std::string& name : o.workloads) {
    tdo_bench::Workload w;
    std::string err;
    if (!tdo_bench::make_workload(name, o.maps_dir, o.limit, o.rrt_movingai, &w, &err)) {
      std::fprintf(stderr, "tdo-bench-scale: %s\n", err.c_str());
      return 2;
    }
    workloads.push_back(w);
  }
  if (o.load) {
    std::printf("tdo-bench-scale --load: repeat %llu\ncpu: %s; load average before %s\n",
                static_cast<unsigned long long>(o.repeat), tdo_bench::cpu_model().c_str(),
                tdo_bench::load_average().c_str());
    const int st = tdo_bench::run_load_bench(workloads, o.repeat);
    std::printf("load average after %s\n", tdo_bench::load_average().c_str());
    return st;
  }
  const std::string load_before = tdo_bench::load_average();
  std::vector<tdo_bench::WorkloadRecord> records;
  for (const tdo_bench::Workload& w : workloads) {
    tdo_bench::WorkloadRecord rec;
    rec.name = w.name;
    rec.what = w.what;
    rec.start_rss_mb = tdo_bench::rss_now_mb();
    rec.peak_reset = tdo_bench::rss_reset_peak();
    std::fprintf(stderr, "tdo-bench-scale: %s: %s\n", w.name.c_str(), w.what.c_str());
    for (const tdo_bench::ScaleMap& sm : w.maps) {
      const int st = run_map(o, w, sm, &rec);
      if (st != 0) return st;
    }
    rec.peak_rss_mb = tdo_bench::rss_peak_mb();
    records.push_back(rec);
  }
  std::printf(
      "tdo-bench-scale: repeat %llu (best of), warmup %llu, seed %llu, max-nodes %llu, states "
      "%s, guide %s, samples %s (%llu of %llu tdo trajectories verified over the samples), depth "
      "%s%s\n",
      static_cast<unsigned long long>(o.repeat), static_cast<unsigned long long>(o.warmup),
      static_cast<unsigned long long>(o.seed), static_cast<unsigned long long>(o.max_nodes),
      o.states.c_str(), o.guide.c_str(), o.samples.c_str(),
      static_cast<unsigned long long>(o.sampled), static_cast<unsigned long long>(o.trajectories),
      o.depth.c_str(), o.rrt_movingai ? "" : ", no rrtconnect-simplify on MovingAI");
  std::printf("command:");
  for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
  std::printf("\ncpu: %s; load average before %s, after %s\n", tdo_bench::cpu_model().c_str(),
              load_before.c_str(), tdo_bench::load_average().c_str());
  for (const tdo_bench::WorkloadRecord& r : records)
    std::printf("workload %s: %s\n", r.name.c_str(), r.what.c_str());
  std::printf("\n");
  tdo_bench::print_tables(records);
  return tdo_bench::print_goals(records) ? 0 : 1;
}
