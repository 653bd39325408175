// Workloads of tdo-bench-scale. See scale_workloads.h.
#include "scale_workloads.h"

#include <fstream>

#include "bench.h"  // tdo_bench::load_forest_queries (tools/tdo-bench)

namespace tdo_bench {
namespace {

constexpr uint64_t kMovingAiDefault = 1000;  // queries per MovingAI scenario without --limit
constexpr double kMapClearance = 0.5;        // m, Map1-5 and the forests (tdo-plan's default)
constexpr double kGebClearance = 0.3;        // m, geb079 (maps/octomap/README.md)
constexpr double kGebResolution = 0.08;      // m, the tree's own resolution

bool readable(const std::string& path, std::string* error) {
  std::ifstream f(path);
  if (f.good()) return true;
  if (error) *error = path + ": cannot open";
  return false;
}

void cap(std::vector<ScaleQuery>* q, uint64_t limit) {
  if (limit > 0 && q->size() > limit) q->resize(static_cast<size_t>(limit));
}

// The five checked queries of maps/octomap/README.md, all at z = 1.2 m.
std::vector<ScaleQuery> geb079_queries() {
  struct Pair {
    const char* id;
    double sx, sy, gx, gy;
  };
  const Pair pairs[] = {{"G1", -5, 0, 27, 0},
                        {"G2", -5, 0, 10, 0},
                        {"G3", 13, 0, 27, 0},
                        {"G4", -5, 0, 24, -5},
                        {"G5", 6, 5, 11, -5}};
  std::vector<ScaleQuery> out;
  for (const Pair& p : pairs)
    out.push_back(ScaleQuery{tdo_vec3{p.sx, p.sy, 1.2}, tdo_vec3{p.gx, p.gy, 1.2}, p.id});
  return out;
}

bool movingai(const std::string& dir, const std::string& map, uint64_t limit, ScaleMap* m,
              std::string* error) {
  m->file = dir + "/movingai/" + map + ".3dmap";
  m->clearance = 0.0;
  if (!readable(m->file, error)) return false;
  std::vector<tdo_io::ScenQuery> scen;
  if (!tdo_io::load_scen(m->file + ".3dscen", &scen, error)) return false;
  for (const tdo_io::ScenQuery& q : scen)
    m->queries.push_back(ScaleQuery{q.start, q.goal, "line " + std::to_string(q.line)});
  cap(&m->queries, limit > 0 ? limit : kMovingAiDefault);
  return true;
}

bool forests(const std::string& dir, uint64_t limit, Workload* w, std::string* error) {
  const std::string csv = dir + "/forest_gen/start_and_end.csv";
  for (int id = 0; id < 3; ++id) {
    ScaleMap m;
    m.file = dir + "/forest_gen/forest" + std::to_string(id) + ".bt";
    m.clearance = kMapClearance;
    if (!readable(m.file, error)) return false;
    std::vector<Query> qs;
    if (!load_forest_queries(csv, id, &qs, error)) return false;
    for (const Query& q : qs)
      m.queries.push_back(ScaleQuery{q.start, q.goal, "trial " + std::to_string(q.index)});
    cap(&m.queries, limit);
    w->maps.push_back(m);
  }
  return true;
}

}  // namespace

const std::vector<std::string>& workload_names() {
  static const std::vector<std::string> names = {"geb079", "simple", "complex", "forest", "map1",
                                                 "map2",   "map3",   "map4",    "map5"};
  return names;
}

bool make_workload(const std::string& name, const std::string& maps_dir, uint64_t limit,
                   bool rrt_movingai, Workload* out, std::string* error) {
  *out = Workload{};
  out->name = name;
  if (name == "geb079") {
    ScaleMap m;
    m.file = maps_dir + "/octomap/geb079.bt";
    m.load.resolution = kGebResolution;
    m.clearance = kGebClearance;
    m.queries = geb079_queries();
    cap(&m.queries, limit);
    out->what = "geb079.bt at 0.08 m, clearance 0.3 m, queries G1-G5 of maps/octomap/README.md";
    out->maps.push_back(m);
    return readable(m.file, error);
  }
  if (name == "simple" || name == "complex") {
    ScaleMap m;
    const std::string file = name == "simple" ? "Simple" : "Complex";
    if (!movingai(maps_dir, file, limit, &m, error)) return false;
    out->what = "MovingAI " + file + ".3dmap, clearance 0, first " +
                std::to_string(m.queries.size()) + " queries of its .3dscen";
    out->rrt = rrt_movingai;
    out->maps.push_back(m);
    return true;
  }
  if (name == "forest") {
    out->what = "forest_gen forest0-2.bt at 0.1 m, clearance 0.5 m, start_and_end.csv pairs";
    return forests(maps_dir, limit, out, error);
  }
  for (int n = 1; n <= 5; ++n) {
    if (name != "map" + std::to_string(n)) continue;
    ScaleMap m;
    m.file = maps_dir + "/" + name + ".tdomap";
    m.clearance = kMapClearance;
    m.map_query = true;
    out->what = name + ".tdomap, clearance 0.5 m, the map's own start and goal";
    out->maps.push_back(m);
    return readable(m.file, error);
  }
  if (error) {
    std::string known;
    for (const std::string& n : workload_names()) known += (known.empty() ? "" : ", ") + n;
    *error = "unknown workload '" + name + "' (known: " + known + ")";
  }
  return false;
}

}  // namespace tdo_bench
