// Map sets and aggregation for tdo-bench and tdo-tune. See bench.h.
#include "bench.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "mapgen.h"

namespace tdo_bench {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool load_case(const std::string& set, const std::string& name, const std::string& file,
               double clearance, uint32_t node_cap, MapCase* out, std::string* error) {
  out->set = set;
  out->name = name;
  out->file = file;
  if (!tdo_io::load_map(file, &out->map, error)) return false;
  out->env = tdo_baselines::Environment::create(out->map, clearance, node_cap, error);
  if (!out->env) return false;
  out->queries.clear();
  if (out->map.has_start && out->map.has_goal) {
    Query q;
    q.set = set;
    q.map = name;
    q.start = out->map.start;
    q.goal = out->map.goal;
    out->queries.push_back(q);
  }
  return true;
}

bool make_random_case(const RandomSpec& spec, int index, const std::string& dir, double clearance,
                      MapCase* out, std::string* error) {
  tdo_mapgen::Params p;
  p.layout = tdo_mapgen::Layout::Columns;
  for (int a = 0; a < 3; ++a) p.size[a] = spec.size[a];
  p.columns = spec.columns;
  p.footprint_dm[0] = 10;
  p.footprint_dm[1] = 30;
  p.seed = spec.seed0 + static_cast<uint64_t>(index);
  const double start[3] = {2.0, 2.0, 3.0};
  const double goal[3] = {spec.size[0] - 1.0, spec.size[1] - 1.0, spec.size[2] / 2.0};
  for (int a = 0; a < 3; ++a) {
    p.start[a] = std::llround(start[a] * 1e4);
    p.goal[a] = std::llround(goal[a] * 1e4);
  }
  const std::string msg = tdo_mapgen::validate(p);
  if (!msg.empty()) {
    if (error) *error = "random map: " + msg;
    return false;
  }
  const std::string name = "random_" + std::to_string(index);
  const std::string file = dir + "/" + name + ".tdomap";
  tdo_mapgen::Result res;
  if (!tdo_mapgen::generate(p, dir + "/" + name + ".scratch", &res, error)) return false;
  std::ofstream f(file);
  f << res.text;
  if (!f) {
    if (error) *error = "cannot write " + file;
    return false;
  }
  f.close();
  return load_case("random", name, file, clearance, 0, out, error);
}

bool load_forest_queries(const std::string& csv, int map_id, std::vector<Query>* out,
                         std::string* error) {
  std::ifstream f(csv);
  if (!f) {
    if (error) *error = csv + ": cannot open";
    return false;
  }
  out->clear();
  std::string line;
  int lineno = 0;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream is(line);
    int trial = 0;
    int id = 0;
    double v[6];
    if (!(is >> trial >> id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5])) {
      if (error) *error = csv + ":" + std::to_string(lineno) + ": expected 8 numbers";
      return false;
    }
    if (id != map_id) continue;
    Query q;
    q.set = "forest";
    q.map = "forest" + std::to_string(map_id);
    q.index = trial;
    q.start = tdo_vec3{v[0], v[1], v[2]};
    q.goal = tdo_vec3{v[3], v[4], v[5]};
    out->push_back(q);
  }
  return true;
}

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  std::size_t n = 0;
  for (double x : v) {
    if (std::isnan(x)) continue;
    s += x;
    ++n;
  }
  return n == 0 ? kNaN : s / static_cast<double>(n);
}

const std::vector<Column>& metric_columns() {
  static const std::vector<Column> cols = {
      {"turns", "turns", "%.1f"},
      {"total_turn_deg", "total turn (deg)", "%.1f"},
      {"length_m", "length (m)", "%.2f"},
      {"min_clearance_m", "min clearance (m)", "%.3f"},
      {"avg_curvature", "avg curvature (1/m)", "%.4f"},
      {"smoothness", "smoothness", "%.3f"},
      {"energy", "energy (m^2/s^3)", "%.2f"},
      {"flight_time_s", "flight time (s)", "%.2f"},
      {"smooth", "smooth", "%.2f"},
      {"expansions", "expansions", "%.0f"},
  };
  return cols;
}

double metric(const tdo_baselines::PlanResult& r, const std::string& key) {
  const tdo_metrics& m = r.metrics;
  if (key == "turns") return m.turns;
  if (key == "total_turn_deg") return m.total_turn_deg;
  if (key == "length_m") return m.length_m;
  if (key == "min_clearance_m") return m.min_clearance_m;
  if (key == "avg_curvature") return m.avg_curvature;
  if (key == "smoothness") return m.smoothness;
  if (key == "energy") return r.has_trajectory ? m.energy : kNaN;
  if (key == "flight_time_s") return r.has_trajectory ? m.flight_time_s : kNaN;
  if (key == "smooth") return r.smooth ? 1.0 : 0.0;
  if (key == "expansions") return static_cast<double>(r.expansions);
  if (key == "plan_time_ms") return r.plan_time_ms;
  return kNaN;
}

Agg aggregate(const std::vector<const Run*>& runs) {
  Agg a;
  std::vector<double> times;
  std::map<std::string, std::vector<double>> vals;
  for (const Run* run : runs) {
    ++a.runs;
    times.push_back(run->r.plan_time_ms);
    if (!run->r.ok) continue;
    ++a.ok;
    if (run->r.feasible) ++a.feasible;
    for (const Column& c : metric_columns()) vals[c.key].push_back(metric(run->r, c.key));
  }
  a.success = a.runs > 0 ? static_cast<double>(a.ok) / a.runs : 0.0;
  for (const Column& c : metric_columns()) a.med[c.key] = median(vals[c.key]);
  a.time_ms = median(times);
  return a;
}

}  // namespace tdo_bench
