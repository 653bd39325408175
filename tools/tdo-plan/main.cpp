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
#include "tdo_samples/samples.h"
#include "tool_cli.h"
#include "va_optimum.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitNoPlan = 1;
constexpr int kExitBadInput = 2;
constexpr double kScenTolerance = 1e-4;

/** Bad input: printed as one line "tdo-plan: error: ..." on stderr, exit status 2. */
using tdo_tool::BadInput;

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
  long long max_nodes = 4000000;
  long long max_open = 0; /**< open-list items per direction; 0 = max_nodes */
  std::string scen_path;
  long long limit = 0;
  std::string stop = "first-meet"; /**< tdo bidirectional stopping rule (first_meet) */
  std::string retry = "on";        /**< obstacle-aware retry of a flooding tdo search */
  std::string guide = "on";        /**< coarse guide of turn-penalised searches on large grids */
  std::string samples;             /**< stored | streamed | pieces (stream_samples); empty: the
                                        capacity's own (tdo_capacity_for_grid) */
  /** One option per row of tdo/params.h but depth, search, first_meet and grid_first (the
   *  planner, --stop and --retry set those), indexed by row; angles in degrees. */
  std::vector<double> real;
  std::vector<long long> whole;
  std::vector<std::string> named;
  std::vector<bool> given;
  tdo_plan_params params{}; /**< the parameters planned with (plan_params) */
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

constexpr double kDeg = 3.14159265358979323846 / 180.0;

bool is_angle(const tdo_param_info& r) { return std::string(r.unit) == "rad"; }

/** Rows tdo-plan sets through --planner, --stop and --retry, not by an option of their own. */
bool own_option(const tdo_param_info& r) {
  const std::string n = r.name;
  return n != "depth" && n != "search" && n != "first_meet" && n != "grid_first";
}

std::string option_name(const tdo_param_info& r) {
  std::string n = std::string("--") + r.name;
  std::replace(n.begin(), n.end(), '_', '-');
  return n;
}

/** A value of row r in tdo-plan's units (degrees for angles, 12 digits: 45, not 45.000000001). */
double shown(const tdo_param_info& r, double v) {
  return is_angle(r) ? std::stod(fmt(v / kDeg, 12)) : v;
}

/** Refuse a real option outside its row's range, in the option's units. */
void check_row(const tdo_param_info& r, double v) {
  const std::string name = option_name(r);
  const double scale = is_angle(r) ? 1.0 / kDeg : 1.0;
  check_finite(v, name.c_str());
  const double lo = r.min * scale;
  const double hi = r.max * scale;
  if (r.min_open ? !(v > lo) : !(v >= lo))
    throw BadInput{name + " must be " + (r.min_open ? "> " : ">= ") + fmt(lo) + ", got " + fmt(v)};
  if (r.max_open ? !(v < hi) : !(v <= hi))
    throw BadInput{name + " must be " + (r.max_open ? "below " : "at most ") + fmt(hi) +
                   (is_angle(r) ? " degrees" : "") + ", got " + fmt(v)};
}

void validate(const Options& o) {
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (!own_option(r) || !o.given[i]) continue;
    if (r.type == TDO_PARAM_REAL) check_row(r, o.real[i]);
    if (r.type == TDO_PARAM_UINT &&
        (static_cast<double>(o.whole[i]) < r.min || static_cast<double>(o.whole[i]) > r.max))
      throw BadInput{option_name(r) + " must be in [" + fmt(r.min, 12) + ", " + fmt(r.max, 12) +
                     "], got " + std::to_string(o.whole[i])};
  }
  if (o.clearance_given) check_nonneg(o.clearance, "--clearance");
  if (o.resolution_given) check_positive(o.resolution, "--resolution");
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

/** True when a turn-deviation row (has_plain) is not at its plain value. */
bool turn_terms_on(const tdo_plan_params& pp) {
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    const double v = tdo_param_get(&pp, i);
    if (r.has_plain != 0 && (v < r.plain || v > r.plain)) return true;
  }
  return false;
}

std::string value_list(const tdo_param_info& r) {
  std::string s;
  for (uint32_t k = 0; k < r.n_values; ++k) s += (k ? " | " : "") + std::string(r.values[k]);
  return s;
}

/** One option per table row tdo-plan does not set itself, in the row's units (degrees). */
void add_param_options(CLI::App& app, Options& o) {
  const uint32_t n = tdo_param_count();
  o.real.assign(n, 0.0);
  o.whole.assign(n, 0);
  o.named.assign(n, std::string());
  o.given.assign(n, false);
  tdo_plan_params d;
  tdo_plan_params_default(&d);
  for (uint32_t i = 0; i < n; ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (!own_option(r)) continue;
    const double v = tdo_param_get(&d, i);
    std::string help = r.help;
    if (is_angle(r))
      help = "deg, " + help;
    else if (r.unit[0] != '\0')
      help = std::string(r.unit) + ", " + help;
    if (r.has_plain != 0)
      help += " (tdo: " + fmt(shown(r, v)) + ", other planners: " + fmt(shown(r, r.plain)) + ")";
    if (r.default_of >= 0) help += " (default: " + option_name(*tdo_param_at(r.default_of)) + ")";
    const std::string name = r.name;
    if (name == "correction") help += " (msf-mtpo: greedy)";
    if (name == "smoothing") help += " (msf-mtpo: arc)";
    if (r.type == TDO_PARAM_REAL) {
      o.real[i] = shown(r, v);
      auto* opt = app.add_option(option_name(r), o.real[i], help);
      if (r.has_plain == 0 && r.default_of < 0) opt->capture_default_str();
    } else if (r.type == TDO_PARAM_UINT) {
      o.whole[i] = static_cast<long long>(v);
      app.add_option(option_name(r), o.whole[i], help)->capture_default_str();
    } else {
      o.named[i] = r.values[static_cast<uint32_t>(v)];
      std::vector<std::string> values(r.values, r.values + r.n_values);
      app.add_option(option_name(r), o.named[i], value_list(r) + ": " + help)
          ->check(CLI::IsMember(values))
          ->capture_default_str();
    }
  }
}

/** --list-params: the table of tdo/params.h, one row per line. */
void print_params() {
  std::printf("%-16s %-6s %-6s %-12s %-24s %-10s %s\n", "name", "type", "unit", "default", "valid",
              "stage", "help");
  static const char* const kType[] = {"real", "uint", "bool", "enum"};
  static const char* const kStage[] = {"search", "correct", "smooth", "trajectory"};
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    std::string def = r.n_values > 0 ? r.values[static_cast<uint32_t>(r.def)] : fmt(r.def, 12);
    if (r.default_of >= 0) def = tdo_param_at(r.default_of)->name;
    std::string valid = r.n_values > 0 ? value_list(r)
                                       : std::string(r.min_open ? "(" : "[") + fmt(r.min, 12) +
                                             ", " + (std::isinf(r.max) ? "inf" : fmt(r.max, 12)) +
                                             (r.max_open || std::isinf(r.max) ? ")" : "]");
    std::printf("%-16s %-6s %-6s %-12s %-24s %-10s %s\n", r.name, kType[r.type],
                r.unit[0] != '\0' ? r.unit : "-", def.c_str(), valid.c_str(), kStage[r.stage],
                r.help);
  }
  std::fflush(stdout);
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

/** " (--samples MODE)" when --samples was given, for the messages that depend on it. */
std::string samples_note(const Options& o) {
  return o.samples.empty() ? "" : " (--samples " + o.samples + ")";
}

/** Size, allocate and initialise the planner, then load the map. Throws BadInput. */
void build_planner(const Options& o, const tdo_io::Map& map, double clearance, Planner* p) {
  // Voxel states need one state per voxel, as plain A* does (tdo_state_space).
  const bool penalised = o.planner == "tdo" || turn_terms_on(o.params);
  const uint32_t headings = penalised && o.params.states != TDO_STATES_VOXEL ? 27u : 1u;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, headings, static_cast<uint32_t>(o.max_nodes));
  // The retry's tables and the coarse guide (docs/design.md s.1) as the library sizes them for a
  // turn-penalised search, voxel states included; --guide off drops the guide.
  tdo_capacity_guide(&cfg.cap, map.desc.nx, map.desc.ny, map.desc.nz, penalised ? 1 : 0);
  if (o.guide != "on") cfg.cap.guide_shift = 0u;
  cfg.cap.exact_heuristic = o.retry == "off" ? 0u : 1u;  // "first*" need the tables too
  cfg.cap.max_open = static_cast<uint32_t>(o.max_open);
  if (!o.samples.empty()) (void)tdo_samples::mode_parse(o.samples.c_str(), &cfg.cap.stream_samples);
  const double nvox = voxel_count(map.desc);
  const std::size_t fit_bytes = tdo_planner_footprint(&cfg);  // the arena this map needs
  const auto vcap = static_cast<uint32_t>(o.max_voxels);
  if (nvox > static_cast<double>(vcap) || cfg.cap.max_voxels > vcap) {
    // The map does not fit: let the library name the overflow, in a planner of one voxel (one of
    // --max-voxels would be carved and cleared for nothing: the search's slots alone are 8 bytes
    // per voxel).
    cfg.cap.max_voxels = 1u;
    const uint64_t nodes = headings;
    cfg.cap.max_nodes =
        static_cast<uint32_t>(std::min<uint64_t>({nodes, cfg.cap.max_nodes, 0xFFFFFFF0u}));
    if (cfg.cap.max_nodes == 0) cfg.cap.max_nodes = 1;
    cfg.cap.max_path = 1u;
    cfg.cap.max_expansions = cfg.cap.max_nodes;
  }
  p->footprint = tdo_planner_footprint(&cfg);
  if (p->footprint == 0) {  // the library names what it refuses
    unsigned char byte = 0;
    tdo_planner* none = nullptr;
    const tdo_status why = tdo_planner_init(&none, &byte, 1u, &cfg);
    throw BadInput{std::string(tdo_status_str(why)) +
                   ": invalid planner configuration for this map" + samples_note(o)};
  }
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
    throw BadInput{std::string(tdo_status_str(st)) + ": planner initialisation failed" +
                   samples_note(o)};
  p->grid = tdo_planner_grid(p->planner);
  p->search = tdo_planner_search(p->planner);
  st = tdo_io::load_into(map, p->grid, clearance);
  if (st == TDO_ERR_MAP_CAPACITY) {
    throw BadInput{std::string(tdo_status_str(st)) + ": map " + map.path + " has " +
                   std::to_string(map.desc.nx) + " x " + std::to_string(map.desc.ny) + " x " +
                   std::to_string(map.desc.nz) + " = " + fmt(nvox, 15) +
                   " voxels, more than the capacity of " + std::to_string(vcap) +
                   " (--max-voxels); planning on it needs an arena of " +
                   std::to_string(fit_bytes) + " bytes"};
  }
  if (st == TDO_ERR_CLEARANCE_CAPACITY) {
    throw BadInput{std::string(tdo_status_str(st)) + ": clearance " + fmt(clearance) +
                   " m reaches further than the configured stencil"};
  }
  if (st != TDO_OK)
    throw BadInput{std::string(tdo_status_str(st)) + ": cannot load map " + map.path};
  // The grid's one-off work (legal steps, distance field) belongs to the load, not to the plan
  // timed below.
  st = tdo_grid_prepare(p->grid);
  if (st != TDO_OK)
    throw BadInput{std::string(tdo_status_str(st)) + ": cannot prepare map " + map.path};
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

/** Every option of a table row with the value planned with (angles in degrees). */
nlohmann::json params_json(const Options& o, double clearance, double resolution) {
  nlohmann::json p;
  p["resolution"] = resolution;
  p["stop"] = o.stop;
  p["retry"] = o.retry;
  p["clearance"] = clearance;
  p["seed"] = o.seed;
  p["max_nodes"] = o.max_nodes;
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (!own_option(r)) continue;
    const double v = tdo_param_get(&o.params, i);
    const std::string key = std::string(r.name) + (is_angle(r) ? "_deg" : "");
    if (r.type == TDO_PARAM_REAL)
      p[key] = o.given[i] ? o.real[i] : shown(r, v);
    else if (r.type == TDO_PARAM_UINT)
      p[key] = static_cast<long long>(v);
    else
      p[key] = r.values[static_cast<uint32_t>(v)];
  }
  return p;
}

/** The turn-deviation rows (has_plain) with their values, e.g. "lambda 50, mu 20, ...". */
std::string turn_terms_text(const tdo_plan_params& pp) {
  std::string s;
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (r.has_plain == 0 || r.type != TDO_PARAM_REAL) continue;
    s += (s.empty() ? "" : ", ") + std::string(r.name) + " " +
         fmt(shown(r, tdo_param_get(&pp, i))) + (is_angle(r) ? " deg" : "");
  }
  return s;
}

/** The pipeline parameters of a planner preset, with the command line's values: the library's
 *  defaults for tdo, the plain search (tdo_plan_params_plain) for the others, then every option
 *  given; a row with default_of follows its source unless given. */
tdo_plan_params plan_params(const Options& o, tdo_search_kind kind) {
  tdo_plan_params pp;
  tdo_plan_params_default(&pp);
  const bool tdo = o.planner == "tdo";
  if (!tdo) tdo_plan_params_plain(&pp);
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (!own_option(r)) continue;
    double v = tdo_param_get(&pp, i);
    if (r.type == TDO_PARAM_BOOL || r.type == TDO_PARAM_ENUM) {
      for (uint32_t k = 0; k < r.n_values; ++k)
        if (o.named[i] == r.values[k]) v = k;
    } else if (o.given[i]) {
      v = r.type == TDO_PARAM_UINT ? static_cast<double>(o.whole[i])
                                   : o.real[i] * (is_angle(r) ? kDeg : 1.0);
    } else if (r.default_of >= 0) {
      v = tdo_param_get(&pp, static_cast<uint32_t>(r.default_of));
    }
    if (tdo_param_set(&pp, i, v) != TDO_OK)
      throw BadInput{option_name(r) + ": " + fmt(v) + " cannot be held"};
  }
  pp.search = kind;
  pp.first_meet = tdo ? (o.stop == "first-meet" ? 1 : 0) : 0;
  pp.grid_first = o.retry == "first"         ? TDO_GRID_FIRST_PLAIN
                  : o.retry == "first-terms" ? TDO_GRID_FIRST_TERMS
                                             : TDO_GRID_FIRST_OFF;
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

// The path metrics every planner reports (tdo_metric_name's names, and turns).
nlohmann::json metrics_json(const tdo_metrics& m) {
  nlohmann::json j = {{"turns", m.turns}};
  for (uint32_t i = 0; i < tdo_metric_count(); ++i) j[tdo_metric_name(i)] = tdo_metric_value(&m, i);
  return j;
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
    tdo_plan_search_input(&pp, &in);  // pp.search is kind
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

/** The v/a time optimum along a plan's samples (va_optimum.h); time 0 without samples. */
tdo_tools::VaOptimum plan_optimum(const std::vector<tdo_sample>& samples, const Options& o) {
  std::vector<tdo_vec3> pts;
  pts.reserve(samples.size());
  for (const tdo_sample& q : samples) pts.push_back(q.p);
  return tdo_tools::va_optimum(pts, o.params.v_max, o.params.a_max, 0.02, o.params.j_max);
}

/** One query: plan, print JSON or a summary. */
/** The text output's lines about the search: work, memory, retry and guide (search.h). */
void print_search(const Options& o, const tdo_search_output& sr) {
  std::printf("expansions       %" PRIu32 "\n", sr.expansions);
  std::printf("states           %" PRIu32 " (both directions; at most %" PRIu32
              " in one: --max-nodes)\n",
              sr.states, sr.peak_nodes);
  std::printf("open_list_peak   %" PRIu32 " (per direction; --max-open)\n", sr.peak_open);
  if (sr.fallback == 3)  // tdo_search_output.fallback (search.h): the heading pool ran out
    std::printf("search_try       voxel states (the heading states filled --max-nodes)\n");
  else if (sr.fallback > 0)  // tdo_search_output.fallback (search.h: the retries' weights)
    std::printf("search_try       retry %" PRIu32 " (%s: grid-distance heuristic)\n", sr.fallback,
                o.retry == "first"         ? "no octile try, --retry first"
                : o.retry == "first-terms" ? "after the first try, --retry first-terms"
                                           : "after the octile try");
  else if (o.retry == "first-terms")
    std::printf(
        "search_try       first (grid distances and the deviation term, --retry "
        "first-terms)\n");
  if (sr.direct != 0)  // tdo_search_output.direct (search.h: the direct route)
    std::printf(
        "search_direct    the straight start-goal segment keeps the clearance: no search\n");
  if (sr.guide > 0) {  // tdo_search_output.guide (search.h: the coarse guide)
    const char* how = sr.guide == 1   ? "corridor"
                      : sr.guide == 2 ? "corridor empty, whole grid"
                                      : "short query, whole grid";
    std::printf("search_guide     %s (%" PRIu32 " expansions of the guide's other tries)\n", how,
                sr.guide_expansions);
  }
}

// The start or goal (`name`): --NAME when given, else the map file's line; bad input without both.
tdo_vec3 end_point(const std::vector<double>& given, const std::string& name, bool in_map,
                   const tdo_vec3& from_map, const std::string& path) {
  const std::string option = "--" + name;
  if (!given.empty()) return to_vec(given, option.c_str());
  if (in_map) return from_map;
  throw BadInput{"no " + name + ": give " + option + " X Y Z or a '" + name + "' line in " + path};
}

int run_single(const Options& o, const tdo_io::Map& map, double clearance, tdo_search_kind kind) {
  const tdo_vec3 start = end_point(o.start, "start", map.has_start, map.start, map.path);
  const tdo_vec3 goal = end_point(o.goal, "goal", map.has_goal, map.goal, map.path);

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
  // Stored or regenerated (--samples): the same samples; read only for the outputs that use them.
  std::vector<tdo_sample> samples;
  const tdo_status sst =
      o.json || o.optimum ? tdo_samples::plan_samples(p.planner, res, &samples) : TDO_OK;
  if (sst != TDO_OK)
    throw BadInput{std::string(tdo_status_str(sst)) + ": cannot read the plan's " +
                   std::to_string(res.n_samples) + " samples" + samples_note(o)};
  const bool optimum = o.optimum && planned && samples.size() > 1;
  const tdo_tools::VaOptimum opt = optimum ? plan_optimum(samples, o) : tdo_tools::VaOptimum{};
  const double ratio = opt.time_s > 0.0 ? m.flight_time_s / opt.time_s : 0.0;

  if (o.json) {
    nlohmann::json j;
    j["status"] = tdo_status_str(st);
    j["planner"] = o.planner;
    j["params"] = params_json(o, clearance, map.desc.res);
    j["grid_path"] = points_json(res.grid_path, res.n_grid_path);
    if (res.reached >= TDO_PLAN_CORRECT)
      j["waypoints"] = points_json(res.waypoints, res.n_waypoints);
    if (!samples.empty()) {
      nlohmann::json rows = nlohmann::json::array();
      for (const tdo_sample& q : samples)
        rows.push_back({q.t, q.p.x, q.p.y, q.p.z, q.v.x, q.v.y, q.v.z, q.a.x, q.a.y, q.a.z});
      j["trajectory"] = {{"dt", req.params.dt}, {"samples", rows}};
    }
    if (planned) {
      j["metrics"] = metrics_json(m);
      j["metrics"].update({{"plan_time_ms", plan_ms},
                           {"expansions", res.search.expansions},
                           {"smooth", m.curvature_continuous != 0 && st == TDO_OK &&
                                          res.reached == TDO_PLAN_TRAJECTORY}});
    } else {
      j["metrics"] = {{"plan_time_ms", plan_ms}, {"expansions", res.search.expansions}};
    }
    if (res.reached == TDO_PLAN_TRAJECTORY) j["feasibility"] = feasibility_json(res.feasibility);
    if (optimum)
      j["va_optimum"] = {{"time_s", opt.time_s},
                         {"ratio", ratio},
                         {"jerk_bound_s", opt.jerk_bound_s},
                         {"length_m", opt.length_m},
                         {"refinements", res.refinements}};
    if (st == TDO_OK || planned) j["search_cost"] = res.search.cost;
    j["arena_bytes"] = p.bytes;
    std::cout << j.dump() << std::endl;
  } else {
    const tdo_grid_desc& d = map.desc;
    std::printf("map              %s (%s, %d x %d x %d voxels, res %s m)\n", map.path.c_str(),
                kind_name(map.kind), d.nx, d.ny, d.nz, fmt(d.res).c_str());
    std::printf("planner          %s (%s, clearance %s m)\n", o.planner.c_str(),
                turn_terms_text(req.params).c_str(), fmt(clearance).c_str());
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
        if (optimum && opt.time_s > 0.0)
          std::printf(
              "jerk_bound_s     %.2f (no flight within j_max is faster; bound/optimum %.3f)\n",
              opt.jerk_bound_s, opt.jerk_bound_s / opt.time_s);
      }
    }
    print_search(o, res.search);
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
      j["metrics"].update(metrics_json(m));
      j["metrics"]["smooth"] = r.smooth;
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
  bool list_params = false;
  app.add_option("--map", o.map_path,
                 "map file: .tdomap, MovingAI .3dmap, OctoMap OcTree .bt/.ot (required)");
  app.add_flag("--list-params", list_params,
               "print the table of plan parameters (libtdo's tdo/params.h) and exit");
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
  add_param_options(app, o);
  app.add_option("--retry", o.retry,
                 "on: a tdo search whose octile-guided try floods restarts with grid distances "
                 "(24 bytes per voxel more; docs/performance.md) | first: it starts with them "
                 "(maps whose walls make the octile try flood) | first-terms: its first try "
                 "keeps the deviation term and the turn bound with grid distances in h | off")
      ->check(CLI::IsMember({"on", "off", "first", "first-terms"}));
  app.add_option("--guide", o.guide,
                 "on: a turn-penalised search on a grid of 2^19 voxels or more first plans on "
                 "4^3-voxel cells and searches a corridor around that plan (docs/design.md s.1) "
                 "| off: the whole grid")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--samples", o.samples,
                 "stored | streamed | pieces: the trajectory samples kept in the arena, or "
                 "regenerated on demand (tdo_capacity.stream_samples 0 / 1 / 2; the same samples; "
                 "pieces verifies each profile piece in closed form, so its feasibility maxima "
                 "are bounds and its energy the integral). Default: as tdo_capacity_for_grid sets "
                 "it")
      ->check(CLI::IsMember({"stored", "streamed", "pieces"}));
  app.add_option("--stop", o.stop, "tdo search stopping rule: first-meet (the paper) | optimal")
      ->check(CLI::IsMember({"first-meet", "optimal"}))
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

  const int help = tdo_tool::parse_args(app, argc, argv);
  if (help >= 0) return help;

  if (list_params) {
    print_params();
    return kExitOk;
  }
  if (o.map_path.empty()) throw BadInput{"--map is required"};
  o.clearance_given = app.count("--clearance") > 0;
  o.resolution_given = app.count("--resolution") > 0;
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (own_option(r)) o.given[i] = app.count(option_name(r)) > 0;
  }
  // Planner presets; options given on the command line win.
  if (o.planner == "msf-mtpo") {
    const auto preset = [&o](const char* row, const char* value) {
      const int32_t i = tdo_param_find(row);
      if (i >= 0 && !o.given[static_cast<uint32_t>(i)]) o.named[static_cast<uint32_t>(i)] = value;
    };
    preset("correction", "greedy");
    preset("smoothing", "arc");
  }
  validate(o);
  const tdo_search_kind kind = o.planner == "astar" ? TDO_SEARCH_ASTAR : TDO_SEARCH_BIDIR;
  o.params = plan_params(o, kind);

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
