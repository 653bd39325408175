// The planner interface, the environment and the shared measuring code. See baselines.h.
#include "baselines.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

#include "planners_internal.h"
#include "tdo_samples/samples.h"

namespace tdo_baselines {
namespace {

constexpr uint32_t kMaxPolyline = 20000;    // points of a raw path measured by evaluate_polyline
constexpr uint32_t kMaxSamples = 1u << 19;  // trajectory samples (dt 0.01 s: 87 minutes)
constexpr double kClearanceCap = 10.0;      // m, metrics' clearance cap (as the pipeline)

}  // namespace

std::unique_ptr<Environment> Environment::create(const tdo_io::Map& map, double clearance,
                                                 uint32_t node_cap, std::string* error,
                                                 uint32_t headings) {
  std::unique_ptr<Environment> env(new Environment());
  env->map_ = map;
  env->clearance_ = clearance;
  const tdo_grid_desc& d = map.desc;
  env->lo_ = d.origin;
  env->hi_ =
      tdo_vec3{d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res, d.origin.z + d.nz * d.res};
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, headings, node_cap);
  const size_t bytes = tdo_planner_footprint(&cfg);
  env->planner_bytes_ = bytes;
  if (bytes == 0) {
    if (error) *error = "invalid planner configuration for " + map.path;
    return nullptr;
  }
  env->memory_.reset(new (std::nothrow) unsigned char[bytes]);
  if (!env->memory_) {
    if (error) *error = "cannot allocate " + std::to_string(bytes) + " bytes for " + map.path;
    return nullptr;
  }
  tdo_status st = tdo_planner_init(&env->planner_, env->memory_.get(), bytes, &cfg);
  if (st == TDO_OK) {
    env->grid_ = tdo_planner_grid(env->planner_);
    st = tdo_io::load_into(map, env->grid_, clearance);
  }
  if (st != TDO_OK) {
    if (error) *error = std::string(tdo_status_str(st)) + ": cannot load " + map.path;
    return nullptr;
  }

  // Contexts for measuring raw polylines: corner-free smoothing and an unrefined trajectory.
  const tdo_smooth_config sc{kMaxPolyline, 3u * kMaxPolyline + 7u, 0u};
  const uint32_t segs = 3u * kMaxPolyline + 7u;
  const tdo_traj_config tc{kMaxSamples, segs, TDO_TRAJ_PIECES_PER_SEGMENT * segs + 1u, 16u, 0u, 0u};
  const size_t extra = tdo_smooth_footprint(&sc) + tdo_traj_footprint(&tc);
  env->extra_.reset(new (std::nothrow) unsigned char[extra]);
  if (!env->extra_ || extra == 0) {
    if (error) *error = "cannot allocate the measuring contexts";
    return nullptr;
  }
  tdo_arena arena;
  tdo_arena_init(&arena, env->extra_.get(), extra);
  st = tdo_smooth_init(&env->smooth_, &arena, &sc);
  if (st == TDO_OK) st = tdo_traj_init(&env->traj_, &arena, &tc);
  if (st != TDO_OK) {
    if (error) *error = std::string(tdo_status_str(st)) + ": measuring contexts";
    return nullptr;
  }
  env->max_polyline_ = kMaxPolyline;
  return env;
}

Environment::~Environment() = default;

bool Environment::point_valid(const tdo_vec3& p) const {
  return tdo_collision_segment_clear(grid_, p, p, clearance_) == 1;
}

bool Environment::segment_valid(const tdo_vec3& a, const tdo_vec3& b) const {
  return tdo_collision_segment_clear(grid_, a, b, clearance_) == 1;
}

// ---- Planner base --------------------------------------------------------------------------

std::vector<std::string> Planner::param_names() const { return order_; }

bool Planner::set_param(const std::string& name, double value, std::string* error) {
  auto it = params_.find(name);
  if (it == params_.end()) {
    if (error) {
      std::string known;
      for (const std::string& n : order_) known += (known.empty() ? "" : ", ") + n;
      *error = this->name() + ": unknown parameter '" + name + "' (known: " + known + ")";
    }
    return false;
  }
  if (!std::isfinite(value) || value < it->second.min || value > it->second.max) {
    if (error) {
      *error = this->name() + ": parameter " + name + " must be in [" +
               std::to_string(it->second.min) + ", " + std::to_string(it->second.max) + "]";
    }
    return false;
  }
  it->second.value = value;
  return true;
}

double Planner::param(const std::string& name) const {
  auto it = params_.find(name);
  return it == params_.end() ? std::numeric_limits<double>::quiet_NaN() : it->second.value;
}

void Planner::add_param(const std::string& name, double value, double min, double max) {
  if (params_.find(name) == params_.end()) order_.push_back(name);
  params_[name] = Param{value, min, max};
}

// ---- Measuring -----------------------------------------------------------------------------

tdo_plan_params default_params() {
  tdo_plan_params p;
  tdo_plan_params_default(&p);
  return p;
}

static bool same_point(const tdo_vec3& a, const tdo_vec3& b) {
  return !(a.x < b.x) && !(a.x > b.x) && !(a.y < b.y) && !(a.y > b.y) && !(a.z < b.z) &&
         !(a.z > b.z);
}

bool metrics_with_trajectory(tdo_metrics_input mi, tdo_status ts, const tdo_traj* traj,
                             const tdo_traj_output& to, double dt, PlanResult* r) {
  std::vector<tdo_sample> samples;  // stored or regenerated: the same samples
  if ((ts == TDO_OK || ts == TDO_ERR_INFEASIBLE) && to.n_samples >= 2) {
    const tdo_status st = tdo_samples::traj_samples(traj, to, &samples);
    if (st != TDO_OK) {
      r->status = tdo_status_str(st);
      return false;
    }
    mi.samples = samples.data();
    mi.n_samples = static_cast<uint32_t>(samples.size());
    mi.dt = dt;
    r->has_trajectory = true;
    r->feasible = ts == TDO_OK;
  }
  const tdo_status st = tdo_metrics_compute(&mi, &r->metrics);
  if (st != TDO_OK) r->status = tdo_status_str(st);
  return st == TDO_OK;
}

PlanResult evaluate_polyline(Environment& env, const std::vector<tdo_vec3>& pts,
                             const tdo_vec3& start, const tdo_vec3& goal) {
  PlanResult r;
  r.path = pts;
  r.curve = pts;
  if (pts.size() < 2 || !same_point(pts.front(), start) || !same_point(pts.back(), goal)) {
    r.status = "endpoints";
    return r;
  }
  if (pts.size() > env.max_polyline()) {
    r.status = "path_capacity";
    return r;
  }
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (!env.segment_valid(pts[i - 1], pts[i])) {
      r.status = "collides";
      return r;
    }
  }
  const tdo_plan_params dp = default_params();
  tdo_metrics_input mi{};
  mi.waypoints = pts.data();
  mi.n_waypoints = static_cast<uint32_t>(pts.size());
  mi.path = nullptr;  // the polyline itself, discrete curvature
  mi.grid = env.grid();
  mi.clearance_cap = kClearanceCap;

  // Stop-and-go trajectory: libtdo's smoothing = none, then stage 5 without refinement.
  tdo_smooth_input si{};
  si.grid = env.grid();
  si.waypoints = pts.data();
  si.n_waypoints = static_cast<uint32_t>(pts.size());
  si.clearance = env.clearance();
  tdo_plan_smooth_input(&dp, &si);
  si.mode = TDO_SMOOTHING_NONE;
  tdo_smooth_output so{};
  tdo_traj_output to{};
  tdo_status ts = TDO_ERR_INVALID_ARGUMENT;
  if (tdo_smooth_run(env.smoother(), &si, &so) == TDO_OK) {
    tdo_traj_input ti{};
    ti.path = so.path;
    ti.grid = env.grid();
    ti.clearance = env.clearance();
    tdo_plan_traj_input(&dp, &ti);
    ts = tdo_traj_run(env.traj(), &ti, &to);
  }
  if (!metrics_with_trajectory(mi, ts, env.traj(), to, dp.dt, &r)) return r;
  if (r.metrics.min_clearance_m < env.clearance() - 1e-9) {  // cannot happen after the checks
    r.status = "collides";
    return r;
  }
  r.smooth = r.metrics.curvature_continuous != 0 && r.feasible;
  r.ok = true;
  r.status = "ok";
  return r;
}

// ---- Registry ------------------------------------------------------------------------------

const std::vector<std::string>& planner_names() {
  static const std::vector<std::string> names = {
      "tdo",     "msf-mtpo",         "astar",   "model-a",    "model-b",
      "model-c", "model-d",          "model-e", "rrtconnect", "rrtconnect-simplify",
      "rrtstar", "rrtstar-simplify", "pso",     "gwo"};
  return names;
}

std::unique_ptr<Planner> make_planner(const std::string& name, std::string* error) {
  std::unique_ptr<Planner> p = make_pipeline_planner(name);
  if (!p) p = make_ompl_planner(name);
  if (!p) p = make_swarm_planner(name);
  if (!p && error) {
    std::string known;
    for (const std::string& n : planner_names()) known += (known.empty() ? "" : ", ") + n;
    *error = "unknown planner '" + name + "' (known: " + known + ")";
  }
  return p;
}

}  // namespace tdo_baselines
