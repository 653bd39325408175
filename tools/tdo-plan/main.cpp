// tdo-plan: plan on a map file with libtdo (interfaces.md). Exit 0 planned, 1 no plan, 2 bad input.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "path_metrics.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitNoPlan = 1;
constexpr int kExitBadInput = 2;
constexpr double kScenTolerance = 1e-4;

/** Bad input: printed as one line "tdo-plan: error: ..." on stderr, exit status 2. */
struct BadInput {
  std::string message;
};

/** Everything the command line sets. */
struct Options {
  std::string map_path;
  std::vector<double> start;
  std::vector<double> goal;
  std::string planner = "bidir";
  bool json = false;
  double clearance = 0.0; /**< m; default depends on the map kind */
  long long max_expansions = 0;
  long long max_nodes = 4000000;
  std::string scen_path;
  long long limit = 0;
  double lambda = 0.0;     /**< m of cost per (turn/pi)^2 */
  double mu = 0.0;         /**< m of f per unit deviation */
  double theta_max = 45.0; /**< deg, direction constraint of the tdo search */
  double v_max = 3.0;      /**< m/s */
  double a_max = 3.0;      /**< m/s^2 */
  double j_max = 10.0;     /**< m/s^3 */
  double k = 1.0;          /**< corner radius scale */
  double dt = 0.01;        /**< s, trajectory sample period */
  std::string smoothing = "g2";
  long long seed = 0;
  long long max_voxels = 100000000; /**< hidden: voxel capacity of the planner */
  long long arena_bytes = -1;       /**< hidden: arena size override (-1 = footprint) */
  bool clearance_given = false;
};

std::string fmt(double v, int precision = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string fmt_vec(const tdo_vec3& p) {
  return "(" + fmt(p.x, 10) + ", " + fmt(p.y, 10) + ", " + fmt(p.z, 10) + ")";
}

std::string fmt_voxel(const tdo_voxel& v) {
  return "(" + std::to_string(v.i) + ", " + std::to_string(v.j) + ", " + std::to_string(v.k) + ")";
}

void check_finite(double v, const char* name) {
  if (!std::isfinite(v)) throw BadInput{std::string(name) + " must be finite, got " + fmt(v)};
}

void check_nonneg(double v, const char* name) {
  check_finite(v, name);
  if (v < 0.0) throw BadInput{std::string(name) + " must be >= 0, got " + fmt(v)};
}

void check_positive(double v, const char* name) {
  check_finite(v, name);
  if (!(v > 0.0)) throw BadInput{std::string(name) + " must be > 0, got " + fmt(v)};
}

tdo_vec3 to_vec(const std::vector<double>& v, const char* name) {
  if (v.size() != 3) throw BadInput{std::string(name) + " needs 3 numbers X Y Z"};
  for (double c : v) check_finite(c, name);
  return tdo_vec3{v[0], v[1], v[2]};
}

void validate(const Options& o) {
  check_nonneg(o.lambda, "--lambda");
  check_nonneg(o.mu, "--mu");
  check_positive(o.theta_max, "--theta-max");
  if (o.theta_max > 180.0)
    throw BadInput{"--theta-max must be at most 180 degrees, got " + fmt(o.theta_max)};
  if (o.clearance_given) check_nonneg(o.clearance, "--clearance");
  check_positive(o.v_max, "--v-max");
  check_positive(o.a_max, "--a-max");
  check_positive(o.j_max, "--j-max");
  check_positive(o.k, "--k");
  check_positive(o.dt, "--dt");
  if (o.max_expansions < 0 || o.max_expansions > 0xFFFFFFFFLL) {
    throw BadInput{"--max-expansions must be in [0, 4294967295], got " +
                   std::to_string(o.max_expansions)};
  }
  if (o.max_nodes <= 0 || o.max_nodes > 0xFFFFFFF0LL) {
    throw BadInput{"--max-nodes must be in [1, 4294967280], got " + std::to_string(o.max_nodes)};
  }
  if (o.max_voxels <= 0 || o.max_voxels > 0xFFFFFFF0LL) {
    throw BadInput{"--max-voxels must be in [1, 4294967280], got " + std::to_string(o.max_voxels)};
  }
  if (o.limit < 0) throw BadInput{"--limit must be >= 0, got " + std::to_string(o.limit)};
  if (o.seed < 0) throw BadInput{"--seed must be >= 0, got " + std::to_string(o.seed)};
  if (o.arena_bytes < -1) throw BadInput{"--arena-bytes must be >= 0"};
}

bool is_bad_input(tdo_status st) {
  switch (st) {
    case TDO_ERR_INVALID_ARGUMENT:
    case TDO_ERR_ARENA_TOO_SMALL:
    case TDO_ERR_MAP_CAPACITY:
    case TDO_ERR_BOX_CAPACITY:
    case TDO_ERR_INVALID_BOX:
    case TDO_ERR_MAP_NOT_READY:
    case TDO_ERR_START_OUT_OF_BOUNDS:
    case TDO_ERR_GOAL_OUT_OF_BOUNDS:
    case TDO_ERR_START_BLOCKED:
    case TDO_ERR_GOAL_BLOCKED:
    case TDO_ERR_START_EQUALS_GOAL:
    case TDO_ERR_OBSTACLE_CAPACITY:
    case TDO_ERR_CLEARANCE_CAPACITY:
      return true;
    default:
      return false;
  }
}

/** The planner and the arena it lives in. */
struct Planner {
  std::unique_ptr<unsigned char[]> memory;
  std::size_t bytes = 0;
  std::size_t footprint = 0;
  tdo_planner* planner = nullptr;
  tdo_grid* grid = nullptr;
  tdo_search* search = nullptr;
};

double voxel_count(const tdo_grid_desc& d) {
  return static_cast<double>(d.nx) * static_cast<double>(d.ny) * static_cast<double>(d.nz);
}

/** Size, allocate and initialise the planner, then load the map. Throws BadInput. */
void build_planner(const Options& o, const tdo_io::Map& map, double clearance, Planner* p) {
  const uint32_t headings = (o.lambda > 0.0 || o.mu > 0.0) ? 27u : 1u;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, headings, static_cast<uint32_t>(o.max_nodes));
  const double nvox = voxel_count(map.desc);
  const auto vcap = static_cast<uint32_t>(o.max_voxels);
  if (nvox > static_cast<double>(vcap) || cfg.cap.max_voxels > vcap) {
    // The map does not fit: configure the capacity anyway and let the library name the overflow.
    cfg.cap.max_voxels = vcap;
    const uint64_t nodes = static_cast<uint64_t>(vcap) * headings;
    cfg.cap.max_nodes =
        static_cast<uint32_t>(std::min<uint64_t>({nodes, cfg.cap.max_nodes, 0xFFFFFFF0u}));
    if (cfg.cap.max_nodes == 0) cfg.cap.max_nodes = 1;
    cfg.cap.max_path = std::min<uint32_t>(cfg.cap.max_path == 0 ? vcap : cfg.cap.max_path, vcap);
    if (cfg.cap.max_path == 0) cfg.cap.max_path = 1;
    cfg.cap.max_expansions = cfg.cap.max_nodes;
  }
  p->footprint = tdo_planner_footprint(&cfg);
  if (p->footprint == 0) throw BadInput{"invalid planner configuration for this map"};
  p->bytes = o.arena_bytes >= 0 ? static_cast<std::size_t>(o.arena_bytes) : p->footprint;
  p->memory.reset(new (std::nothrow) unsigned char[std::max<std::size_t>(p->bytes, 1u)]);
  if (!p->memory)
    throw BadInput{"cannot allocate an arena of " + std::to_string(p->bytes) + " bytes"};
  tdo_status st = tdo_planner_init(&p->planner, p->memory.get(), p->bytes, &cfg);
  if (st == TDO_ERR_ARENA_TOO_SMALL) {
    throw BadInput{std::string(tdo_status_str(st)) + ": arena of " + std::to_string(p->bytes) +
                   " bytes, this configuration needs " + std::to_string(p->footprint)};
  }
  if (st != TDO_OK)
    throw BadInput{std::string(tdo_status_str(st)) + ": planner initialisation failed"};
  p->grid = tdo_planner_grid(p->planner);
  p->search = tdo_planner_search(p->planner);
  st = tdo_io::load_into(map, p->grid, clearance);
  if (st == TDO_ERR_MAP_CAPACITY) {
    throw BadInput{std::string(tdo_status_str(st)) + ": map " + map.path + " has " +
                   std::to_string(map.desc.nx) + " x " + std::to_string(map.desc.ny) + " x " +
                   std::to_string(map.desc.nz) + " = " + fmt(nvox, 15) +
                   " voxels, more than the capacity of " + std::to_string(cfg.cap.max_voxels) +
                   " (--max-voxels)"};
  }
  if (st == TDO_ERR_CLEARANCE_CAPACITY) {
    throw BadInput{std::string(tdo_status_str(st)) + ": clearance " + fmt(clearance) +
                   " m reaches further than the configured stencil"};
  }
  if (st != TDO_OK)
    throw BadInput{std::string(tdo_status_str(st)) + ": cannot load map " + map.path};
}

/** One-line explanation of a search status that means bad input. */
std::string explain(tdo_status st, const tdo_grid* grid, const tdo_vec3& start,
                    const tdo_vec3& goal, double clearance) {
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  const tdo_vec3 hi{d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res,
                    d.origin.z + d.nz * d.res};
  const std::string bounds = "[" + fmt(d.origin.x) + ", " + fmt(hi.x) + ") x [" + fmt(d.origin.y) +
                             ", " + fmt(hi.y) + ") x [" + fmt(d.origin.z) + ", " + fmt(hi.z) + ")";
  const auto blocked = [&](const char* what, const tdo_vec3& p) {
    tdo_voxel v{};
    tdo_grid_world_to_voxel(grid, p, &v);
    const bool occ = tdo_grid_is_occupied(grid, v) != 0;
    return std::string(what) + " " + fmt_vec(p) + " is blocked: voxel " + fmt_voxel(v) +
           (occ ? " intersects an obstacle"
                : " is within the clearance of " + fmt(clearance) + " m of an obstacle");
  };
  const std::string name = tdo_status_str(st);
  switch (st) {
    case TDO_ERR_START_OUT_OF_BOUNDS:
      return name + ": start " + fmt_vec(start) + " is outside the map bounds " + bounds;
    case TDO_ERR_GOAL_OUT_OF_BOUNDS:
      return name + ": goal " + fmt_vec(goal) + " is outside the map bounds " + bounds;
    case TDO_ERR_START_BLOCKED:
      return name + ": " + blocked("start", start);
    case TDO_ERR_GOAL_BLOCKED:
      return name + ": " + blocked("goal", goal);
    case TDO_ERR_START_EQUALS_GOAL:
      return name + ": start " + fmt_vec(start) + " and goal " + fmt_vec(goal) +
             " are the same point (voxel)";
    default:
      return name + ": the search rejected the query";
  }
}

std::string explain_no_plan(tdo_status st, uint32_t budget) {
  const std::string name = tdo_status_str(st);
  switch (st) {
    case TDO_ERR_NO_PATH:
      return name + ": the goal is unreachable";
    case TDO_ERR_BUDGET:
      return name + ": expansion budget" +
             (budget > 0 ? " of " + std::to_string(budget) : std::string()) +
             " exhausted (--max-expansions)";
    case TDO_ERR_NODE_CAPACITY:
      return name + ": search node pool full (--max-nodes)";
    case TDO_ERR_PATH_CAPACITY:
      return name + ": path longer than the path buffer";
    default:
      return name;
  }
}

const char* kind_name(tdo_io::MapKind k) {
  switch (k) {
    case tdo_io::MapKind::TdoMap:
      return "tdomap";
    case tdo_io::MapKind::MovingAI:
      return "3dmap";
    case tdo_io::MapKind::OctoMap:
      return "octomap";
  }
  return "?";
}

nlohmann::json params_json(const Options& o, double clearance, long long max_expansions) {
  nlohmann::json p;
  p["lambda"] = o.lambda;
  p["mu"] = o.mu;
  p["theta_max_deg"] = o.theta_max;
  p["clearance"] = clearance;
  p["v_max"] = o.v_max;
  p["a_max"] = o.a_max;
  p["j_max"] = o.j_max;
  p["k"] = o.k;
  p["dt"] = o.dt;
  p["smoothing"] = o.smoothing;
  p["seed"] = o.seed;
  p["max_expansions"] = max_expansions;
  p["max_nodes"] = o.max_nodes;
  return p;
}

/** --scen mode: every query (or the first --limit) with the search only, costs against the file. */
int run_scen(const Options& o, const tdo_io::Map& map, double clearance, tdo_search_kind kind) {
  std::vector<tdo_io::ScenQuery> queries;
  std::string err;
  if (!tdo_io::load_scen(o.scen_path, &queries, &err)) throw BadInput{err};
  if (o.limit > 0 && static_cast<std::size_t>(o.limit) < queries.size())
    queries.resize(static_cast<std::size_t>(o.limit));
  Planner p;
  build_planner(o, map, clearance, &p);

  std::vector<double> times_ms;
  times_ms.reserve(queries.size());
  uint64_t expansions = 0;
  std::size_t passed = 0;
  std::size_t failed = 0;
  for (const tdo_io::ScenQuery& q : queries) {
    tdo_search_input in{};
    in.grid = p.grid;
    in.start = q.start;
    in.goal = q.goal;
    in.kind = kind;
    in.lambda = o.lambda;
    in.mu = o.mu;
    in.max_expansions = static_cast<uint32_t>(o.max_expansions);
    tdo_search_output out{};
    const auto t0 = std::chrono::steady_clock::now();
    const tdo_status st = tdo_search_run(p.search, &in, &out);
    const auto t1 = std::chrono::steady_clock::now();
    times_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    expansions += out.expansions;
    if (st == TDO_OK && std::fabs(out.cost - q.cost) <= kScenTolerance) {
      ++passed;
    } else {
      ++failed;
      std::printf("line %d: expected %.8f, got %s (status %s)\n", q.line, q.cost,
                  st == TDO_OK ? fmt(out.cost, 12).c_str() : "-", tdo_status_str(st));
    }
  }
  if (!times_ms.empty()) {
    double total = 0.0;
    for (double t : times_ms) total += t;
    std::vector<double> sorted = times_ms;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    const double median = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    std::printf(
        "%s on %s: %zu queries, median %.4f ms, mean %.4f ms, %.0f expansions/s, arena %zu bytes\n",
        o.planner.c_str(), map.path.c_str(), n, median, total / static_cast<double>(n),
        total > 0.0 ? static_cast<double>(expansions) / (total / 1000.0) : 0.0, p.bytes);
  }
  std::printf("%zu passed, %zu failed\n", passed, failed);
  std::fflush(stdout);
  return failed == 0 ? kExitOk : kExitNoPlan;
}

/** One query: plan, print JSON or a summary. */
int run_single(const Options& o, const tdo_io::Map& map, double clearance, tdo_search_kind kind) {
  tdo_vec3 start{};
  tdo_vec3 goal{};
  if (!o.start.empty()) {
    start = to_vec(o.start, "--start");
  } else if (map.has_start) {
    start = map.start;
  } else {
    throw BadInput{"no start: give --start X Y Z or a 'start' line in " + map.path};
  }
  if (!o.goal.empty()) {
    goal = to_vec(o.goal, "--goal");
  } else if (map.has_goal) {
    goal = map.goal;
  } else {
    throw BadInput{"no goal: give --goal X Y Z or a 'goal' line in " + map.path};
  }

  Planner p;
  build_planner(o, map, clearance, &p);

  tdo_search_input in{};
  in.grid = p.grid;
  in.start = start;
  in.goal = goal;
  in.kind = kind;
  in.lambda = o.lambda;
  in.mu = o.mu;
  in.max_expansions = static_cast<uint32_t>(o.max_expansions);
  tdo_search_output out{};
  const auto t0 = std::chrono::steady_clock::now();
  const tdo_status st = tdo_search_run(p.search, &in, &out);
  const auto t1 = std::chrono::steady_clock::now();
  const double plan_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();

  std::vector<tdo_vec3> path;
  if (st == TDO_OK && out.path != nullptr && out.n_path > 0) {
    path.reserve(out.n_path + 1u);
    for (uint32_t i = 0; i < out.n_path; ++i)
      path.push_back(tdo_grid_voxel_center(p.grid, out.path[i]));
    if (path.size() == 1) {
      path[0] = start;
      path.push_back(goal);
    } else {
      path.front() = start;
      path.back() = goal;
    }
  }
  const double length = tdo_tools::polyline_length(path);
  const tdo_tools::TurnStats turns = tdo_tools::turn_stats(path);

  if (o.json) {
    nlohmann::json j;
    j["status"] = tdo_status_str(st);
    j["planner"] = o.planner;
    j["params"] = params_json(o, clearance, o.max_expansions);
    nlohmann::json gp = nlohmann::json::array();
    for (const tdo_vec3& q : path) gp.push_back({q.x, q.y, q.z});
    j["grid_path"] = gp;
    j["metrics"] = {{"length_m", length},
                    {"turns", turns.turns},
                    {"total_turn_deg", turns.total_turn_deg},
                    {"plan_time_ms", plan_ms},
                    {"expansions", out.expansions}};
    if (st == TDO_OK) j["search_cost"] = out.cost;
    j["arena_bytes"] = p.bytes;
    std::cout << j.dump() << std::endl;
  } else {
    const tdo_grid_desc& d = map.desc;
    std::printf("map             %s (%s, %d x %d x %d voxels, res %s m)\n", map.path.c_str(),
                kind_name(map.kind), d.nx, d.ny, d.nz, fmt(d.res).c_str());
    std::printf("planner         %s (lambda %s, mu %s, clearance %s m)\n", o.planner.c_str(),
                fmt(o.lambda).c_str(), fmt(o.mu).c_str(), fmt(clearance).c_str());
    std::printf("start           %s\n", fmt_vec(start).c_str());
    std::printf("goal            %s\n", fmt_vec(goal).c_str());
    std::printf("status          %s\n", tdo_status_str(st));
    if (st == TDO_OK) {
      std::printf("search_cost     %.8f\n", out.cost);
      std::printf("length_m        %.6f\n", length);
      std::printf("grid_path       %zu points\n", path.size());
      std::printf("turns           %d\n", turns.turns);
      std::printf("total_turn_deg  %.3f\n", turns.total_turn_deg);
    }
    std::printf("expansions      %" PRIu32 "\n", out.expansions);
    std::printf("plan_time_ms    %.3f\n", plan_ms);
    std::printf("arena_bytes     %zu\n", p.bytes);
    std::fflush(stdout);
  }

  if (st == TDO_OK) return kExitOk;
  if (is_bad_input(st)) throw BadInput{explain(st, p.grid, start, goal, clearance)};
  std::fprintf(stderr, "tdo-plan: no plan: %s\n", explain_no_plan(st, in.max_expansions).c_str());
  return kExitNoPlan;
}

int run(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Plan a path on a voxel map with libtdo.\n"
      "Exit status: 0 planned, 1 no plan (status printed), 2 bad input.",
      "tdo-plan"};
  app.add_option("--map", o.map_path, "map file: .tdomap, MovingAI .3dmap (OctoMap .bt/.ot later)")
      ->required();
  app.add_option("--start", o.start, "start X Y Z in m (default: the map's 'start')")->expected(3);
  app.add_option("--goal", o.goal, "goal X Y Z in m (default: the map's 'goal')")->expected(3);
  app.add_option(
         "--planner", o.planner,
         "astar | bidir (default bidir for now; tdo and msf-mtpo arrive with the pipeline issue)")
      ->capture_default_str();
  app.add_flag("--json", o.json, "print one JSON object on stdout");
  app.add_option(
      "--clearance", o.clearance,
      "m kept from obstacles (default 0.5 for .tdomap, 0 for .3dmap: MovingAI grid rules alone)");
  app.add_option("--max-expansions", o.max_expansions,
                 "expansion budget of one search (0 = the default, 2 x --max-nodes)")
      ->capture_default_str();
  app.add_option("--max-nodes", o.max_nodes, "search states per direction (sizes the arena)")
      ->capture_default_str();
  auto* scen = app.add_option("--scen", o.scen_path,
                              "MovingAI .3dscen: plan its queries, compare costs (1e-4)");
  app.add_option("--limit", o.limit, "with --scen: only the first N queries (0 = all)")
      ->capture_default_str();
  app.add_option("--lambda", o.lambda,
                 "turn penalty, m of cost per (turn/pi)^2 (default 0 for astar/bidir)")
      ->capture_default_str();
  app.add_option("--mu", o.mu, "deviation weight, m of f (default 0 for astar/bidir)")
      ->capture_default_str();
  app.add_option("--theta-max", o.theta_max,
                 "deg, direction constraint (tdo; accepted, unused for now)")
      ->capture_default_str();
  app.add_option("--v-max", o.v_max, "m/s (accepted, unused for now)")->capture_default_str();
  app.add_option("--a-max", o.a_max, "m/s^2 (accepted, unused for now)")->capture_default_str();
  app.add_option("--j-max", o.j_max, "m/s^3 (accepted, unused for now)")->capture_default_str();
  app.add_option("--k", o.k, "corner radius scale (accepted, unused for now)")
      ->capture_default_str();
  app.add_option("--dt", o.dt, "s, trajectory sample period (accepted, unused for now)")
      ->capture_default_str();
  app.add_option("--smoothing", o.smoothing, "arc | g2 (accepted, unused for now)")
      ->check(CLI::IsMember({"arc", "g2"}))
      ->capture_default_str();
  app.add_option("--seed", o.seed, "random seed (accepted, unused for now)")->capture_default_str();
  // Advanced, hidden from --help: capacities for tests of the overflow paths.
  app.add_option("--max-voxels", o.max_voxels, "voxel capacity of the planner")->group("");
  app.add_option("--arena-bytes", o.arena_bytes, "arena size in bytes (default: the footprint)")
      ->group("");
  scen->excludes(app.get_option("--start"));
  scen->excludes(app.get_option("--goal"));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    throw BadInput{e.what()};
  }
  o.clearance_given = app.count("--clearance") > 0;
  validate(o);

  tdo_search_kind kind = TDO_SEARCH_BIDIR;
  if (o.planner == "astar") {
    kind = TDO_SEARCH_ASTAR;
  } else if (o.planner == "bidir") {
    kind = TDO_SEARCH_BIDIR;
  } else if (o.planner == "tdo" || o.planner == "msf-mtpo") {
    throw BadInput{"planner '" + o.planner + "' arrives with the pipeline issue"};
  } else {
    throw BadInput{"unknown planner '" + o.planner + "' (expected astar or bidir)"};
  }

  tdo_io::Map map;
  std::string err;
  if (!tdo_io::load_map(o.map_path, &map, &err)) throw BadInput{err};
  const double clearance =
      o.clearance_given ? o.clearance : (map.kind == tdo_io::MapKind::MovingAI ? 0.0 : 0.5);

  if (!o.scen_path.empty()) return run_scen(o, map, clearance, kind);
  return run_single(o, map, clearance, kind);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const BadInput& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "tdo-plan: error: %s\n", e.message.c_str());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "tdo-plan: error: out of memory\n");
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tdo-plan: error: %s\n", e.what());
    return kExitBadInput;
  }
}
