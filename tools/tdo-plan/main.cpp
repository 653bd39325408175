// tdo-plan: plan on a map file with libtdo (docs/design.md s.10). Exit 0 planned, 1 no plan, 2 bad
// input.
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

#include "baselines.h"
#include "path_metrics.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"
#include "tdo_io/text.h"
#include "va_optimum.h"

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
  std::vector<double> start_vel; /**< m/s, the vehicle's velocity at the start (empty: 0) */
  std::vector<double> start_acc; /**< m/s^2, its acceleration at the start (empty: 0) */
  std::string planner = "tdo";
  bool json = false;
  bool optimum = false;   /**< print the v/a time optimum along the plan's own path */
  double clearance = 0.0; /**< m; default depends on the map kind */
  long long max_expansions = 0;
  long long max_nodes = 4000000;
  long long max_open = 0; /**< open-list items per direction; 0 = max_nodes */
  std::string scen_path;
  long long limit = 0;
  double lambda = 0.0;      /**< m of cost per (turn/pi)^2 */
  double mu = 0.0;          /**< m of f per unit deviation */
  double theta_max = 45.0;  /**< deg, direction constraint of the tdo search */
  double v_max = 3.0;       /**< m/s */
  double a_max = 3.0;       /**< m/s^2 */
  double j_max = 10.0;      /**< m/s^3 */
  double k = 1.0;           /**< corner radius scale */
  double dt = 0.01;         /**< s, trajectory sample period */
  double corner_time = 1.0; /**< G2 corner shapes for flight time (0 = Yang-Sukkarieh) */
  std::string smoothing = "g2";
  std::string correction = "multiscale";
  std::string shorten = "on";
  double h_weight = 1.0;           /**< heuristic weight of the turn-penalised search */
  std::string stop = "first-meet"; /**< tdo bidirectional stopping rule */
  std::string retry = "on";        /**< obstacle-aware retry of a flooding tdo search */
  std::string states = "heading";  /**< states of the tdo search: heading | voxel */
  double d_th = 0.0;               /**< deviation threshold, 0 = off */
  double a_lat_max = 0.0;          /**< m/s^2, 0 = a_max */
  double v_cruise = 0.0;           /**< m/s, 0 = v_max */
  double stop_angle = 150.0;       /**< deg */
  long long seed = 0;
  long long max_voxels = 100000000; /**< hidden: voxel capacity of the planner */
  long long arena_bytes = -1;       /**< hidden: arena size override (-1 = footprint) */
  bool clearance_given = false;
  double resolution = 0.0; /**< m, voxel edge of an OcTree map (when given) */
  bool resolution_given = false;
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
  check_nonneg(o.theta_max, "--theta-max");  // 0 (or 180): unconstrained, as in the library
  if (o.theta_max > 180.0)
    throw BadInput{"--theta-max must be at most 180 degrees, got " + fmt(o.theta_max)};
  if (o.clearance_given) check_nonneg(o.clearance, "--clearance");
  if (o.resolution_given) check_positive(o.resolution, "--resolution");
  check_positive(o.v_max, "--v-max");
  check_positive(o.a_max, "--a-max");
  check_positive(o.j_max, "--j-max");
  check_positive(o.k, "--k");
  check_positive(o.dt, "--dt");
  check_nonneg(o.corner_time, "--corner-time");
  if (o.corner_time > 1.0)
    throw BadInput{"--corner-time must be at most 1, got " + fmt(o.corner_time)};
  check_finite(o.h_weight, "--h-weight");
  if (o.h_weight < 1.0) throw BadInput{"--h-weight must be >= 1, got " + fmt(o.h_weight)};
  check_nonneg(o.d_th, "--d-th");
  if (o.d_th >= 1.0) throw BadInput{"--d-th must be below 1 (0 = off), got " + fmt(o.d_th)};
  check_nonneg(o.a_lat_max, "--a-lat-max");
  check_nonneg(o.v_cruise, "--v-cruise");
  check_positive(o.stop_angle, "--stop-angle");
  if (o.stop_angle > 180.0)
    throw BadInput{"--stop-angle must be at most 180 degrees, got " + fmt(o.stop_angle)};
  if (o.max_expansions < 0 || o.max_expansions > 0xFFFFFFFFLL) {
    throw BadInput{"--max-expansions must be in [0, 4294967295], got " +
                   std::to_string(o.max_expansions)};
  }
  if (o.max_nodes <= 0 || o.max_nodes > 0xFFFFFFF0LL) {
    throw BadInput{"--max-nodes must be in [1, 4294967280], got " + std::to_string(o.max_nodes)};
  }
  if (o.max_open < 0 || o.max_open > 0xFFFFFFF0LL) {
    throw BadInput{"--max-open must be in [0, 4294967280], got " + std::to_string(o.max_open)};
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
    case TDO_ERR_STATE_NOT_FINITE:
    case TDO_ERR_STATE_TOO_FAST:
    case TDO_ERR_STATE_OVER_LIMITS:
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
  // Voxel states need one state per voxel, as plain A* does (tdo_state_space).
  const bool penalised = o.lambda > 0.0 || o.mu > 0.0 || o.planner == "tdo";
  const uint32_t headings = penalised && o.states != "voxel" ? 27u : 1u;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, headings, static_cast<uint32_t>(o.max_nodes));
  cfg.cap.exact_heuristic = o.retry == "off" ? 0u : 1u;  // "first*" need the tables too
  cfg.cap.max_open = static_cast<uint32_t>(o.max_open);
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
    if (tdo_grid_is_blocked(grid, v) == 0) {  // the point itself (pipeline.h)
      return std::string(what) + " " + fmt_vec(p) + " is within the clearance of " +
             fmt(clearance) + " m of an obstacle (the point itself; its voxel " + fmt_voxel(v) +
             " is free)";
    }
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

/** One-line explanation of a refused start state (--start-vel, --start-acc). */
std::string explain_state(tdo_status st, const tdo_plan_request& req) {
  const std::string name = tdo_status_str(st);
  const tdo_vec3 v = req.state.v, a = req.state.a;
  const double speed = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  const double acc = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
  if (st == TDO_ERR_STATE_TOO_FAST)
    return name + ": start speed " + fmt(speed) + " m/s is above v_max " + fmt(req.params.v_max);
  if (acc > req.params.a_max)
    return name + ": start acceleration " + fmt(acc) + " m/s^2 is above a_max " +
           fmt(req.params.a_max);
  return name +
         ": removing the start acceleration (jerk 0.95 j_max) would take the speed above "
         "v_max " +
         fmt(req.params.v_max);
}

std::string explain_no_plan(tdo_status st, uint32_t budget) {
  const std::string name = tdo_status_str(st);
  switch (st) {
    case TDO_ERR_STATE_CANNOT_STOP:
      return name +
             ": an obstacle or the map bound lies within the stopping distance along the "
             "start velocity (--start-vel)";
    case TDO_ERR_NO_PATH:
      return name + ": the goal is unreachable";
    case TDO_ERR_BUDGET:
      return name + ": expansion budget" +
             (budget > 0 ? " of " + std::to_string(budget) : std::string()) +
             " exhausted (--max-expansions)";
    case TDO_ERR_NODE_CAPACITY:
      return name + ": search node pool full (--max-nodes)";
    case TDO_ERR_OPEN_CAPACITY:
      return name + ": search open list full (--max-open)";
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

nlohmann::json params_json(const Options& o, double clearance, long long max_expansions,
                           double resolution) {
  nlohmann::json p;
  p["resolution"] = resolution;
  p["lambda"] = o.lambda;
  p["mu"] = o.mu;
  p["theta_max_deg"] = o.theta_max;
  p["h_weight"] = o.h_weight;
  p["d_th"] = o.d_th;
  p["stop"] = o.stop;
  p["correction"] = o.correction;
  p["shorten"] = o.shorten;
  p["retry"] = o.retry;
  p["states"] = o.states;
  p["a_lat_max"] = o.a_lat_max > 0.0 ? o.a_lat_max : o.a_max;
  p["v_cruise"] = o.v_cruise > 0.0 ? o.v_cruise : o.v_max;
  p["stop_angle_deg"] = o.stop_angle;
  p["clearance"] = clearance;
  p["v_max"] = o.v_max;
  p["a_max"] = o.a_max;
  p["j_max"] = o.j_max;
  p["k"] = o.k;
  p["dt"] = o.dt;
  p["corner_time"] = o.corner_time;
  p["smoothing"] = o.smoothing;
  p["seed"] = o.seed;
  p["max_expansions"] = max_expansions;
  p["max_nodes"] = o.max_nodes;
  return p;
}

/** The pipeline parameters of a planner preset, with the command line's values. */
tdo_plan_params plan_params(const Options& o, tdo_search_kind kind) {
  tdo_plan_params pp;
  tdo_plan_params_default(&pp);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  pp.search = kind;
  pp.lambda = o.lambda;
  pp.mu = o.mu;
  pp.theta_max = o.planner == "tdo" ? o.theta_max * kDeg : 0.0;
  pp.h_weight = o.h_weight;
  pp.first_meet = o.planner == "tdo" ? (o.stop == "first-meet" ? 1 : 0) : 0;
  pp.grid_first = o.retry == "first"         ? TDO_GRID_FIRST_PLAIN
                  : o.retry == "first-terms" ? TDO_GRID_FIRST_TERMS
                                             : TDO_GRID_FIRST_OFF;
  pp.states = o.states == "voxel" ? TDO_STATES_VOXEL : TDO_STATES_HEADING;
  pp.d_th = o.d_th;
  pp.max_expansions = static_cast<uint32_t>(o.max_expansions);
  pp.correction = o.correction == "greedy" ? TDO_CORRECT_GREEDY_LOS
                  : o.correction == "none" ? TDO_CORRECT_NONE
                                           : TDO_CORRECT_MULTISCALE;
  pp.shorten = o.shorten == "on" ? 1 : 0;
  pp.smoothing = o.smoothing == "arc"    ? TDO_SMOOTHING_ARC
                 : o.smoothing == "none" ? TDO_SMOOTHING_NONE
                                         : TDO_SMOOTHING_G2;
  pp.k = o.k;
  pp.v_max = o.v_max;
  pp.a_max = o.a_max;
  pp.j_max = o.j_max;
  pp.a_lat_max = o.a_lat_max > 0.0 ? o.a_lat_max : o.a_max;
  pp.v_cruise = o.v_cruise > 0.0 ? o.v_cruise : o.v_max;
  pp.stop_angle = o.stop_angle * kDeg;
  pp.dt = o.dt;
  pp.corner_time = o.corner_time;
  pp.depth = (o.planner == "astar" || o.planner == "bidir") ? TDO_PLAN_SEARCH : TDO_PLAN_TRAJECTORY;
  return pp;
}

nlohmann::json points_json(const tdo_vec3* pts, uint32_t n) {
  nlohmann::json a = nlohmann::json::array();
  for (uint32_t i = 0; i < n; ++i) a.push_back({pts[i].x, pts[i].y, pts[i].z});
  return a;
}

const char* quantity_name(tdo_quantity q) {
  switch (q) {
    case TDO_QUANTITY_SPEED:
      return "speed";
    case TDO_QUANTITY_ACCELERATION:
      return "acceleration";
    case TDO_QUANTITY_JERK:
      return "jerk";
    case TDO_QUANTITY_TURN_RADIUS:
      return "turn_radius";
    case TDO_QUANTITY_CLEARANCE:
      return "clearance";
  }
  return "?";
}

nlohmann::json feasibility_json(const tdo_feasibility& f) {
  nlohmann::json v = nlohmann::json::array();
  for (uint32_t i = 0; i < f.n_violations; ++i) {
    const tdo_violation& x = f.violations[i];
    v.push_back(
        {{"t", x.t}, {"quantity", quantity_name(x.what)}, {"value", x.value}, {"limit", x.limit}});
  }
  return {{"ok", f.ok != 0},
          {"max_speed", f.max_speed},
          {"max_acc", f.max_acc},
          {"max_jerk", f.max_jerk},
          {"min_turn_radius", std::isfinite(f.min_turn_radius) ? f.min_turn_radius : -1.0},
          {"min_clearance_m", f.min_clearance},
          {"violations", v},
          {"violations_total", f.n_violations_total}};
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
  // The search as the pipeline runs it for this planner (plan_params): for tdo its direction
  // constraint, stopping rule, retry and states too.
  const tdo_plan_params pp = plan_params(o, kind);
  for (const tdo_io::ScenQuery& q : queries) {
    tdo_search_input in{};
    in.grid = p.grid;
    in.start = q.start;
    in.goal = q.goal;
    in.kind = kind;
    in.lambda = pp.lambda;
    in.mu = pp.mu;
    in.theta_max = pp.theta_max;
    in.d_th = pp.d_th;
    in.h_weight = pp.h_weight;
    in.first_meet = pp.first_meet;
    in.grid_first = pp.grid_first;
    in.states = pp.states;
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

/** The v/a time optimum along the samples of a plan (va_optimum.h); time 0 without samples. */
tdo_tools::VaOptimum plan_optimum(const tdo_plan_result& res, const Options& o) {
  std::vector<tdo_vec3> pts;
  pts.reserve(res.n_samples);
  for (uint32_t i = 0; i < res.n_samples; ++i) pts.push_back(res.samples[i].p);
  return tdo_tools::va_optimum(pts, o.v_max, o.a_max);
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

  tdo_plan_request req{};
  req.start = start;
  req.goal = goal;
  req.params = plan_params(o, kind);
  if (!o.start_vel.empty()) req.state.v = to_vec(o.start_vel, "--start-vel");
  if (!o.start_acc.empty()) req.state.a = to_vec(o.start_acc, "--start-acc");
  const tdo_vec3 sv = req.state.v, sa = req.state.a;
  const auto nonzero = [](const tdo_vec3& q) {
    return std::fabs(q.x) > 0.0 || std::fabs(q.y) > 0.0 || std::fabs(q.z) > 0.0;
  };
  const bool moving = nonzero(sv) || nonzero(sa);
  if (moving && req.params.depth != TDO_PLAN_TRAJECTORY)
    throw BadInput{"--start-vel / --start-acc need a planner with a trajectory (--planner tdo)"};
  tdo_plan_result res{};
  const auto t0 = std::chrono::steady_clock::now();
  const tdo_status st = tdo_planner_plan(p.planner, &req, &res);
  const auto t1 = std::chrono::steady_clock::now();
  const double plan_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  const bool planned = st == TDO_OK || st == TDO_ERR_INFEASIBLE;
  const tdo_metrics& m = res.metrics;
  const bool optimum = o.optimum && planned && res.n_samples > 1;
  const tdo_tools::VaOptimum opt = optimum ? plan_optimum(res, o) : tdo_tools::VaOptimum{};
  const double ratio = opt.time_s > 0.0 ? m.flight_time_s / opt.time_s : 0.0;

  if (o.json) {
    nlohmann::json j;
    j["status"] = tdo_status_str(st);
    j["planner"] = o.planner;
    j["params"] = params_json(o, clearance, o.max_expansions, map.desc.res);
    j["grid_path"] = points_json(res.grid_path, res.n_grid_path);
    if (res.reached >= TDO_PLAN_CORRECT)
      j["waypoints"] = points_json(res.waypoints, res.n_waypoints);
    if (res.n_samples > 0) {
      nlohmann::json samples = nlohmann::json::array();
      for (uint32_t i = 0; i < res.n_samples; ++i) {
        const tdo_sample& q = res.samples[i];
        samples.push_back({q.t, q.p.x, q.p.y, q.p.z, q.v.x, q.v.y, q.v.z, q.a.x, q.a.y, q.a.z});
      }
      j["trajectory"] = {{"dt", req.params.dt}, {"samples", samples}};
    }
    if (planned) {
      j["metrics"] = {{"length_m", m.length_m},
                      {"turns", m.turns},
                      {"total_turn_deg", m.total_turn_deg},
                      {"min_clearance_m", m.min_clearance_m},
                      {"avg_curvature", m.avg_curvature},
                      {"smoothness", m.smoothness},
                      {"energy", m.energy},
                      {"flight_time_s", m.flight_time_s},
                      {"plan_time_ms", plan_ms},
                      {"expansions", res.search.expansions},
                      {"smooth", m.curvature_continuous != 0 && st == TDO_OK &&
                                     res.reached == TDO_PLAN_TRAJECTORY}};
    } else {
      j["metrics"] = {{"plan_time_ms", plan_ms}, {"expansions", res.search.expansions}};
    }
    if (res.reached == TDO_PLAN_TRAJECTORY) j["feasibility"] = feasibility_json(res.feasibility);
    if (optimum)
      j["va_optimum"] = {{"time_s", opt.time_s},
                         {"ratio", ratio},
                         {"length_m", opt.length_m},
                         {"refinements", res.refinements}};
    if (st == TDO_OK || planned) j["search_cost"] = res.search.cost;
    j["arena_bytes"] = p.bytes;
    std::cout << j.dump() << std::endl;
  } else {
    const tdo_grid_desc& d = map.desc;
    std::printf("map              %s (%s, %d x %d x %d voxels, res %s m)\n", map.path.c_str(),
                kind_name(map.kind), d.nx, d.ny, d.nz, fmt(d.res).c_str());
    std::printf("planner          %s (lambda %s, mu %s, theta_max %s deg, clearance %s m)\n",
                o.planner.c_str(), fmt(o.lambda).c_str(), fmt(o.mu).c_str(),
                fmt(o.theta_max).c_str(), fmt(clearance).c_str());
    std::printf("start -> goal    %s -> %s\n", fmt_vec(start).c_str(), fmt_vec(goal).c_str());
    if (moving)
      std::printf("start_state      v %s m/s, a %s m/s^2\n", fmt_vec(sv).c_str(),
                  fmt_vec(sa).c_str());
    std::printf("status           %s\n", tdo_status_str(st));
    if (planned) {
      std::printf("grid path        %u voxels, search cost %.6f m\n", res.n_grid_path,
                  res.search.cost);
      if (res.reached >= TDO_PLAN_CORRECT)
        std::printf("waypoints        %u (%u kept for clearance)\n", res.n_waypoints,
                    res.n_safety_critical);
      std::printf("length_m         %.3f\n", m.length_m);
      std::printf("turns            %u (%.1f deg in total)\n", m.turns, m.total_turn_deg);
      std::printf("min_clearance_m  %.3f\n", m.min_clearance_m);
      std::printf("avg_curvature    %.4f 1/m\n", m.avg_curvature);
      std::printf("smoothness       %.4f\n", m.smoothness);
      if (res.reached == TDO_PLAN_TRAJECTORY) {
        const tdo_feasibility& f = res.feasibility;
        std::printf("energy           %.3f m^2/s^3\n", m.energy);
        std::printf("flight_time_s    %.2f\n", m.flight_time_s);
        std::printf("feasible         %s (max speed %.3f, acc %.3f, jerk %.3f; %u violations)\n",
                    f.ok ? "yes" : "no", f.max_speed, f.max_acc, f.max_jerk, f.n_violations_total);
        if (optimum)
          std::printf("va_optimum_s     %.2f (v/a optimum along this path; flight/optimum %.3f)\n",
                      opt.time_s, ratio);
      }
    }
    std::printf("expansions       %" PRIu32 "\n", res.search.expansions);
    std::printf("states           %" PRIu32 " (both directions; at most %" PRIu32
                " in one: --max-nodes)\n",
                res.search.states, res.search.peak_nodes);
    std::printf("open_list_peak   %" PRIu32 " (per direction; --max-open)\n", res.search.peak_open);
    if (res.search.fallback > 0)  // tdo_search_output.fallback (search.h: the retries' weights)
      std::printf("search_try       retry %" PRIu32 " (%s: grid-distance heuristic)\n",
                  res.search.fallback,
                  o.retry == "first"         ? "no octile try, --retry first"
                  : o.retry == "first-terms" ? "after the first try, --retry first-terms"
                                             : "after the octile try");
    else if (o.retry == "first-terms")
      std::printf(
          "search_try       first (grid distances and the deviation term, --retry "
          "first-terms)\n");
    std::printf("plan_time_ms     %.3f\n", plan_ms);
    std::printf("arena_bytes      %zu\n", p.bytes);
    std::fflush(stdout);
  }

  if (st == TDO_OK) return kExitOk;
  if (st == TDO_ERR_STATE_TOO_FAST || st == TDO_ERR_STATE_OVER_LIMITS)
    throw BadInput{explain_state(st, req)};
  if (is_bad_input(st)) throw BadInput{explain(st, p.grid, start, goal, clearance)};
  std::fprintf(stderr, "tdo-plan: no plan: %s\n",
               explain_no_plan(st, req.params.max_expansions).c_str());
  return kExitNoPlan;
}

/** tdo-plan's own planners plus those of tools/baselines (ablation models, OMPL, pagmo). */
std::vector<std::string> planner_choices() {
  std::vector<std::string> v = {"tdo", "astar", "bidir", "msf-mtpo"};
  for (const std::string& n : tdo_baselines::planner_names())
    if (std::find(v.begin(), v.end(), n) == v.end()) v.push_back(n);
  return v;
}

bool is_bench_planner(const std::string& name) {
  return name != "tdo" && name != "astar" && name != "bidir" && name != "msf-mtpo";
}

/** A planner of tools/baselines (the bench's interface): summary or JSON without a trajectory. */
int run_bench_planner(const Options& o, const tdo_io::Map& map, double clearance) {
  if (!o.start_vel.empty() || !o.start_acc.empty())
    throw BadInput{"--start-vel / --start-acc need a planner with a trajectory (--planner tdo)"};
  if (o.start.empty() && !map.has_start) throw BadInput{"no start: give --start X Y Z"};
  if (o.goal.empty() && !map.has_goal) throw BadInput{"no goal: give --goal X Y Z"};
  const tdo_vec3 start = o.start.empty() ? map.start : to_vec(o.start, "--start");
  const tdo_vec3 goal = o.goal.empty() ? map.goal : to_vec(o.goal, "--goal");
  std::string err;
  auto env =
      tdo_baselines::Environment::create(map, clearance, static_cast<uint32_t>(o.max_nodes), &err);
  if (!env) throw BadInput{err};
  auto planner = tdo_baselines::make_planner(o.planner, &err);
  if (!planner) throw BadInput{err};
  const tdo_baselines::PlanResult r =
      planner->plan(*env, start, goal, static_cast<uint64_t>(o.seed));
  const tdo_metrics& m = r.metrics;
  if (o.json) {
    nlohmann::json j;
    j["status"] = r.status;
    j["planner"] = o.planner;
    j["params"] = {{"clearance", clearance}, {"seed", o.seed}};
    for (const std::string& n : planner->param_names()) j["params"][n] = planner->param(n);
    j["waypoints"] = nlohmann::json::array();
    for (const tdo_vec3& q : r.path) j["waypoints"].push_back({q.x, q.y, q.z});
    j["metrics"] = {{"plan_time_ms", r.plan_time_ms}, {"expansions", r.expansions}};
    if (r.ok) {
      j["metrics"].update({{"length_m", m.length_m},
                           {"turns", m.turns},
                           {"total_turn_deg", m.total_turn_deg},
                           {"min_clearance_m", m.min_clearance_m},
                           {"avg_curvature", m.avg_curvature},
                           {"smoothness", m.smoothness},
                           {"energy", m.energy},
                           {"flight_time_s", m.flight_time_s},
                           {"smooth", r.smooth}});
    }
    std::cout << j.dump() << std::endl;
  } else {
    std::printf("planner          %s (%s)\n", o.planner.c_str(), planner->description().c_str());
    std::printf("status           %s\n", r.status.c_str());
    if (r.ok) {
      std::printf("waypoints        %zu\n", r.path.size());
      std::printf("length_m         %.3f\n", m.length_m);
      std::printf("turns            %u (%.1f deg in total)\n", m.turns, m.total_turn_deg);
      std::printf("min_clearance_m  %.3f\n", m.min_clearance_m);
    }
    std::printf("plan_time_ms     %.3f\n", r.plan_time_ms);
    std::fflush(stdout);
  }
  if (r.ok) return kExitOk;
  std::fprintf(stderr, "tdo-plan: no plan: %s\n", r.status.c_str());
  return kExitNoPlan;
}

int run(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Plan a path on a voxel map with libtdo.\n"
      "Exit status: 0 planned, 1 no plan (status printed), 2 bad input.",
      "tdo-plan"};
  app.add_option("--map", o.map_path, "map file: .tdomap, MovingAI .3dmap, OctoMap OcTree .bt/.ot")
      ->required();
  app.add_option("--resolution", o.resolution,
                 "m, voxel edge an OcTree map (.bt/.ot) is voxelized at (default: the tree's)");
  app.add_option("--start", o.start, "start X Y Z in m (default: the map's 'start')")->expected(3);
  app.add_option("--goal", o.goal, "goal X Y Z in m (default: the map's 'goal')")->expected(3);
  app.add_option("--start-vel", o.start_vel,
                 "velocity VX VY VZ in m/s at the start (default 0 0 0: at rest; a moving start, "
                 "docs/design.md s.5)")
      ->expected(3);
  app.add_option("--start-acc", o.start_acc,
                 "acceleration AX AY AZ in m/s^2 at the start (default 0 0 0)")
      ->expected(3);
  app.add_option("--planner", o.planner,
                 "tdo (the full TDO-MSF pipeline) | astar | bidir (raw grid paths, no penalties) | "
                 "msf-mtpo (the paper's baseline) | the bench's planners: model-a..model-e "
                 "(ablation), rrtconnect[-simplify], rrtstar[-simplify], pso, gwo (--seed)")
      ->check(CLI::IsMember(planner_choices()))
      ->capture_default_str();
  app.add_flag("--json", o.json, "print one JSON object on stdout");
  app.add_flag("--optimum", o.optimum,
               "also print the v/a time optimum along the plan's own sampled path (|v| <= v-max, "
               "total |a| <= a-max, rest to rest, no jerk limit) and flight_time / optimum");
  app.add_option(
      "--clearance", o.clearance,
      "m kept from obstacles (default 0.5 for .tdomap, 0 for .3dmap: MovingAI grid rules alone)");
  app.add_option("--max-expansions", o.max_expansions,
                 "expansion budget of one search (0 = the default, 2 x --max-nodes)")
      ->capture_default_str();
  app.add_option("--max-nodes", o.max_nodes, "search states per direction (sizes the arena)")
      ->capture_default_str();
  app.add_option("--max-open", o.max_open,
                 "open-list items per direction (0 = --max-nodes); the text output's "
                 "open_list_peak is a query's need")
      ->capture_default_str();
  auto* scen = app.add_option("--scen", o.scen_path,
                              "MovingAI .3dscen: plan its queries, compare costs (1e-4)");
  app.add_option("--limit", o.limit, "with --scen: only the first N queries (0 = all)")
      ->capture_default_str();
  app.add_option("--lambda", o.lambda, "turn penalty, m of cost per (turn/pi)^2 (tdo: 50, else 0)");
  app.add_option("--mu", o.mu, "deviation weight, m of f (tdo: 20, else 0)");
  app.add_option("--theta-max", o.theta_max,
                 "deg, direction constraint of the tdo search (0 or 180: unconstrained)")
      ->capture_default_str();
  app.add_option("--h-weight", o.h_weight,
                 "heuristic weight (>= 1) of the turn-penalised search: speed for optimality")
      ->capture_default_str();
  app.add_option("--retry", o.retry,
                 "on: a tdo search whose octile-guided try floods restarts with grid distances "
                 "(24 bytes per voxel more; docs/performance.md) | first: it starts with them "
                 "(maps whose walls make the octile try flood) | first-terms: its first try "
                 "keeps the deviation term and the turn bound with grid distances in h | off")
      ->check(CLI::IsMember({"on", "off", "first", "first-terms"}));
  app.add_option("--states", o.states,
                 "heading: (voxel, heading) states of the tdo search | voxel: one state per voxel, "
                 "its heading the step it was reached by (plain A*'s memory)")
      ->check(CLI::IsMember({"heading", "voxel"}))
      ->capture_default_str();
  app.add_option("--stop", o.stop, "tdo search stopping rule: first-meet (the paper) | optimal")
      ->check(CLI::IsMember({"first-meet", "optimal"}))
      ->capture_default_str();
  app.add_option("--d-th", o.d_th, "deviation threshold in (0,1) of the tdo search (0 = off)")
      ->capture_default_str();
  app.add_option("--correction", o.correction, "multiscale | greedy | none (msf-mtpo: greedy)")
      ->check(CLI::IsMember({"multiscale", "greedy", "none"}));
  app.add_option(
         "--shorten", o.shorten,
         "on | off: partial shortcuts after the multiscale correction (docs/performance.md)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--smoothing", o.smoothing, "g2 | arc | none (msf-mtpo: arc)")
      ->check(CLI::IsMember({"g2", "arc", "none"}));
  app.add_option("--k", o.k, "corner radius scale")->capture_default_str();
  app.add_option("--v-max", o.v_max, "m/s")->capture_default_str();
  app.add_option("--a-max", o.a_max, "m/s^2")->capture_default_str();
  app.add_option("--j-max", o.j_max, "m/s^3")->capture_default_str();
  app.add_option("--a-lat-max", o.a_lat_max, "m/s^2, lateral limit of corners (default a-max)");
  app.add_option("--v-cruise", o.v_cruise,
                 "m/s, sets R_min = v_cruise^2/a_lat_max (default v-max)");
  app.add_option("--stop-angle", o.stop_angle, "deg, sharper corners become stop points")
      ->capture_default_str();
  app.add_option("--dt", o.dt, "s, trajectory sample period")->capture_default_str();
  app.add_option("--corner-time", o.corner_time,
                 "in [0, 1]: how far G2 corner shapes trade the Yang-Sukkarieh shape for flight "
                 "time (0 = Yang-Sukkarieh)")
      ->capture_default_str();
  app.add_option("--seed", o.seed, "random seed (stochastic planners; unused by tdo)")
      ->capture_default_str();
  // Advanced, hidden from --help: capacities for tests of the overflow paths.
  app.add_option("--max-voxels", o.max_voxels, "voxel capacity of the planner")->group("");
  app.add_option("--arena-bytes", o.arena_bytes, "arena size in bytes (default: the footprint)")
      ->group("");
  scen->excludes(app.get_option("--start"));
  scen->excludes(app.get_option("--goal"));
  scen->excludes(app.get_option("--start-vel"));
  scen->excludes(app.get_option("--start-acc"));

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
  o.resolution_given = app.count("--resolution") > 0;

  // Planner presets; options given on the command line win.
  const bool tdo = o.planner == "tdo";
  if (app.count("--lambda") == 0) o.lambda = tdo ? 50.0 : 0.0;
  if (app.count("--mu") == 0) o.mu = tdo ? 20.0 : 0.0;
  if (o.planner == "msf-mtpo") {
    if (app.count("--correction") == 0) o.correction = "greedy";
    if (app.count("--smoothing") == 0) o.smoothing = "arc";
  }
  validate(o);
  const tdo_search_kind kind = o.planner == "astar" ? TDO_SEARCH_ASTAR : TDO_SEARCH_BIDIR;

  tdo_io::Map map;
  std::string err;
  tdo_io::LoadOptions load;
  load.resolution = o.resolution_given ? o.resolution : 0.0;  // 0: the tree's
  load.max_voxels = static_cast<uint64_t>(o.max_voxels);
  if (!tdo_io::load_map(o.map_path, load, &map, &err)) throw BadInput{err};
  if (o.resolution_given && map.kind != tdo_io::MapKind::OctoMap)
    throw BadInput{"--resolution applies to OcTree maps (.bt/.ot) only; " + o.map_path +
                   " gives its own grid"};
  const double clearance =
      o.clearance_given ? o.clearance : (map.kind == tdo_io::MapKind::MovingAI ? 0.0 : 0.5);

  if (!o.scen_path.empty()) return run_scen(o, map, clearance, kind);
  if (is_bench_planner(o.planner)) return run_bench_planner(o, map, clearance);
  return run_single(o, map, clearance, kind);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const BadInput& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "tdo-plan: error: %s\n", tdo_io::one_line(e.message).c_str());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "tdo-plan: error: out of memory\n");
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tdo-plan: error: %s\n", tdo_io::one_line(e.what()).c_str());
    return kExitBadInput;
  }
}
