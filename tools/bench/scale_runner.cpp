// The planners of tdo-bench-scale on one map. See scale_runner.h.
#include "scale_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <new>
#include <sstream>
#include <utility>
#include <vector>

namespace tdo_bench {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool same_point(const tdo_vec3& a, const tdo_vec3& b) {
  return !(a.x < b.x) && !(a.x > b.x) && !(a.y < b.y) && !(a.y > b.y) && !(a.z < b.z) &&
         !(a.z > b.z);
}

// A /proc/self/status field in kB, as MB (0 when unreadable).
double status_mb(const std::string& field) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.compare(0, field.size() + 1, field + ":") != 0) continue;
    std::istringstream is(line.substr(field.size() + 1));
    double kb = 0.0;
    is >> kb;
    return kb / 1024.0;
  }
  return 0.0;
}

// The textbook A* on the voxels A*'s grid blocks at the clearance.
std::unique_ptr<TextbookAstar> make_textbook(const tdo_grid* grid) {
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  std::vector<uint8_t> blocked(static_cast<size_t>(d.nx) * d.ny * d.nz, 0);
  size_t i = 0;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t x = 0; x < d.nx; ++x, ++i)
        blocked[i] = tdo_grid_is_blocked(grid, tdo_voxel{x, j, k}) != 0 ? 1 : 0;
  return std::make_unique<TextbookAstar>(d.nx, d.ny, d.nz, std::move(blocked));
}

// One query planned `repeat` times: the status and result of the last call, the smallest time
// in o->ms, o->ran set.
tdo_status plan_best_of(tdo_planner* planner, const tdo_plan_request& req, uint64_t repeat,
                        tdo_plan_result* res, ScaleOutcome* o) {
  tdo_status st = TDO_OK;
  o->ran = true;
  o->ms = HUGE_VAL;
  for (uint64_t r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    st = tdo_planner_plan(planner, &req, res);
    o->ms = std::min(o->ms, ms_since(t0));
  }
  return st;
}

// A request from q's start to its goal with the library's default parameters.
tdo_plan_request default_request(const ScaleQuery& q) {
  tdo_plan_request req{};
  req.start = q.start;
  req.goal = q.goal;
  tdo_plan_params_default(&req.params);
  return req;
}

}  // namespace

const char* scale_planner_name(int planner) {
  static const char* const names[kScalePlanners] = {"tdo", "astar", "rrtconnect-simplify",
                                                    "textbook-astar"};
  return planner >= 0 && planner < kScalePlanners ? names[planner] : "?";
}

double rss_now_mb() { return status_mb("VmRSS"); }
double rss_peak_mb() { return status_mb("VmHWM"); }

bool rss_reset_peak() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5\n";
  f.flush();
  return static_cast<bool>(f);
}

ScaleMapRun::~ScaleMapRun() = default;

std::unique_ptr<ScaleMapRun> ScaleMapRun::create(const tdo_io::Map& map, double clearance,
                                                 uint32_t node_cap, int states, bool guide,
                                                 bool rrt, uint32_t samples, std::string* error) {
  std::unique_ptr<ScaleMapRun> r(new ScaleMapRun());
  r->clearance_ = clearance;
  r->states_ = states;

  // tdo: the library's footprint of the configuration with heading costs.
  double rss0 = rss_now_mb();
  auto t0 = Clock::now();
  tdo_planner_config cfg{};
  const bool voxel = states == TDO_STATES_VOXEL;
  cfg.cap = tdo_io::capacity_for(map, clearance, voxel ? 1u : 27u, node_cap);
  // The retry's tables and the coarse guide as tdo-plan sets them (tdo is turn-penalised, voxel
  // states included); without `guide` no guide.
  tdo_capacity_guide(&cfg.cap, map.desc.nx, map.desc.ny, map.desc.nz, 1);
  if (!guide) cfg.cap.guide_shift = 0u;
  if (samples != kScaleSamplesDefault) cfg.cap.stream_samples = samples;
  const size_t bytes = tdo_planner_footprint(&cfg);
  if (bytes == 0) {
    if (error) *error = map.path + ": invalid tdo planner configuration";
    return nullptr;
  }
  r->tdo_memory_.reset(new (std::nothrow) unsigned char[bytes]);
  if (!r->tdo_memory_) {
    if (error) *error = map.path + ": cannot allocate the tdo arena of " + std::to_string(bytes);
    return nullptr;
  }
  tdo_status st = tdo_planner_init(&r->tdo_, r->tdo_memory_.get(), bytes, &cfg);
  if (st == TDO_OK) st = tdo_io::load_into(map, tdo_planner_grid(r->tdo_), clearance);
  if (st != TDO_OK) {
    if (error) *error = map.path + ": tdo planner set-up: " + tdo_status_str(st);
    return nullptr;
  }
  r->setup_[kScaleTdo] = ScaleSetup{bytes, rss_now_mb() - rss0, ms_since(t0)};

  // astar: its own planner without heading costs, in a tools/baselines Environment.
  rss0 = rss_now_mb();
  t0 = Clock::now();
  r->env_ = tdo_baselines::Environment::create(map, clearance, node_cap, error, 1u);
  if (!r->env_) return nullptr;
  r->setup_[kScaleAstar] = ScaleSetup{r->env_->planner_bytes(), rss_now_mb() - rss0, ms_since(t0)};

  if (rrt) {
    r->rrt_ = tdo_baselines::make_planner("rrtconnect-simplify", error);
    if (!r->rrt_) return nullptr;
  }
  rss0 = rss_now_mb();
  t0 = Clock::now();
  r->textbook_ = make_textbook(r->env_->grid());
  r->setup_[kScaleTextbook] = ScaleSetup{0u, rss_now_mb() - rss0, ms_since(t0)};
  return r;
}

bool ScaleMapRun::has(int planner) const { return planner != kScaleRrt || rrt_ != nullptr; }

ScaleOutcome ScaleMapRun::run(int planner, const ScaleQuery& q, uint64_t seed, uint64_t repeat) {
  switch (planner) {
    case kScaleTdo:
      return run_tdo(q, repeat);
    case kScaleAstar:
      return run_astar(q, repeat);
    case kScaleRrt:
      return rrt_ ? run_rrt(q, seed, repeat) : ScaleOutcome{};
    default:
      return run_textbook(q, repeat);
  }
}

// A grid path of the libtdo planner measured and checked by tools/baselines' evaluate_polyline
// (as its "astar" planner).
ScaleOutcome ScaleMapRun::grid_outcome(const tdo_plan_result& res, const ScaleQuery& q,
                                       ScaleOutcome o) const {
  const std::vector<tdo_vec3> pts(res.grid_path, res.grid_path + res.n_grid_path);
  const tdo_baselines::PlanResult pr =
      tdo_baselines::evaluate_polyline(*env_, pts, q.start, q.goal);
  o.ok = pr.ok;
  o.status = pr.status;
  o.turns = pr.metrics.turns;
  o.length = pr.metrics.length_m;
  o.cost = res.search.cost;
  return o;
}

// The full pipeline with the library's defaults; measured by its own stage 6 (tdo_metrics_compute
// on the final path), checked as tools/baselines checks its "tdo": exact ends and the clearance.
// With depth_ TDO_PLAN_SEARCH the search alone, its grid path measured as A*'s (grid_outcome).
ScaleOutcome ScaleMapRun::run_tdo(const ScaleQuery& q, uint64_t repeat) {
  tdo_plan_request req = default_request(q);
  req.params.states = states_;
  req.params.depth = depth_;
  tdo_plan_result res{};
  ScaleOutcome o;
  const tdo_status st = plan_best_of(tdo_, req, repeat, &res, &o);
  if (depth_ == TDO_PLAN_SEARCH) {
    if (st != TDO_OK) {
      o.status = tdo_status_str(st);
      return o;
    }
    return grid_outcome(res, q, o);
  }
  if (res.reached == TDO_PLAN_TRAJECTORY) {
    ++tdo_trajectories_;
    if (res.sample_passes > 0u) ++tdo_sampled_;
  }
  if (st != TDO_OK && st != TDO_ERR_INFEASIBLE) {
    o.status = tdo_status_str(st);
    return o;
  }
  const tdo_path& p = res.path;
  const tdo_path_segment* last = p.n > 0 ? &p.seg[p.n - 1] : nullptr;
  const bool ends = last != nullptr && same_point(p.seg[0].p[0], q.start) &&
                    same_point(last->kind == TDO_SEGMENT_BEZIER ? last->p[3] : last->p[1], q.goal);
  if (!ends) {
    o.status = "endpoints";
    return o;
  }
  if (!(res.metrics.min_clearance_m >= clearance_ - 1e-9)) {
    o.status = "collides";
    return o;
  }
  o.ok = true;
  o.status = st == TDO_OK ? "ok" : "ok_infeasible";
  o.turns = res.metrics.turns;
  o.length = res.metrics.length_m;
  o.cost = res.search.cost;
  return o;
}

// Plain A*: the same one-call API, depth search, the plain search's parameters; its grid path is
// measured and checked by tools/baselines' evaluate_polyline (as its "astar" planner).
ScaleOutcome ScaleMapRun::run_astar(const ScaleQuery& q, uint64_t repeat) {
  tdo_plan_request req = default_request(q);
  req.params.depth = TDO_PLAN_SEARCH;
  req.params.search = TDO_SEARCH_ASTAR;
  tdo_plan_params_plain(&req.params);  // no turn-deviation terms (first_meet: bidir only)
  tdo_plan_result res{};
  ScaleOutcome o;
  const tdo_status st = plan_best_of(env_->planner(), req, repeat, &res, &o);
  if (st != TDO_OK) {
    o.status = tdo_status_str(st);
    return o;
  }
  return grid_outcome(res, q, o);
}

ScaleOutcome ScaleMapRun::run_rrt(const ScaleQuery& q, uint64_t seed, uint64_t repeat) {
  ScaleOutcome o;
  o.ran = true;
  o.ms = HUGE_VAL;
  tdo_baselines::PlanResult pr;
  for (uint64_t r = 0; r < repeat; ++r) {
    pr = rrt_->plan(*env_, q.start, q.goal, seed);  // same seed: the same plan every repeat
    o.ms = std::min(o.ms, pr.plan_time_ms);
  }
  o.ok = pr.ok;
  o.status = pr.status;
  o.turns = pr.metrics.turns;
  o.length = pr.metrics.length_m;
  return o;
}

// Voxel to voxel, as the library's search snaps the start and goal; cost between voxel centres.
ScaleOutcome ScaleMapRun::run_textbook(const ScaleQuery& q, uint64_t repeat) {
  ScaleOutcome o;
  o.ran = true;
  const tdo_grid* grid = env_->grid();
  tdo_voxel s{};
  tdo_voxel g{};
  if (!tdo_grid_world_to_voxel(grid, q.start, &s) || !tdo_grid_world_to_voxel(grid, q.goal, &g)) {
    o.status = "outside";
    return o;
  }
  o.ms = HUGE_VAL;
  TextbookResult tr;
  for (uint64_t r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    tr = textbook_->run(s.i, s.j, s.k, g.i, g.j, g.k);
    o.ms = std::min(o.ms, ms_since(t0));
  }
  o.ok = tr.found;
  o.status = tr.found ? "ok" : "no_path";
  o.cost = tr.cost * tdo_grid_get_desc(grid).res;
  return o;
}

}  // namespace tdo_bench
