// Planners that are configurations of libtdo's pipeline (tdo_planner_plan): the full TDO-MSF,
// the MSF-MTPO baseline, raw A*, and the ablation models A-E of the paper's Table 8.
//
// Ablation mapping (docs/results.md repeats it):
//   model-a  bidirectional A*, no turn/deviation terms, raw grid path
//   model-b  + turn-deviation cost (the library's defaults, first meeting), raw path
//   model-c  + multi-scale inflection correction (P2 polyline)
//   model-d  + curvature-constrained adaptive-radius smoothing: the paper's circular arcs of eq. 8
//            (smoothing = arc), time-parameterised once by stage 5 without any refinement
//   model-e  + trajectory-guided E-APF: the E-APF is the online tracker (docs/design.md s.4), it
//   does
//            not change a static plan, so model-e plans exactly like model-d
//   full     + dynamic feasibility verification and refinement = `tdo` (G2 corners, stage 5 with
//            refinement rounds)
#include <chrono>
#include <cmath>
#include <cstring>

#include "planners_internal.h"

namespace tdo_baselines {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

enum class Stage { Search, Correct, SmoothOnce, Trajectory };
// The library depth of each Stage (SmoothOnce: stage 5 then runs here, without refinement).
constexpr tdo_plan_depth kStageDepth[] = {TDO_PLAN_SEARCH, TDO_PLAN_CORRECT, TDO_PLAN_SMOOTH,
                                          TDO_PLAN_TRAJECTORY};

struct Preset {
  const char* name;
  const char* description;
  tdo_search_kind kind;
  bool penalties;  // the turn-deviation rows at their defaults (else tdo_plan_params_plain)
  tdo_correct_mode correction;
  tdo_smoothing smoothing;
  Stage stage;
};

const Preset kPresets[] = {
    {"tdo", "TDO-MSF: turn-deviation bidir A*, multi-scale correction, G2 corners, feasibility",
     TDO_SEARCH_BIDIR, true, TDO_CORRECT_MULTISCALE, TDO_SMOOTHING_G2, Stage::Trajectory},
    {"msf-mtpo",
     "MSF-MTPO baseline: bidir A* without penalties, greedy line of sight, fixed-rule arc corners",
     TDO_SEARCH_BIDIR, false, TDO_CORRECT_GREEDY_LOS, TDO_SMOOTHING_ARC, Stage::Trajectory},
    {"astar", "original A*: 26-connected grid path, no penalties (raw)", TDO_SEARCH_ASTAR, false,
     TDO_CORRECT_NONE, TDO_SMOOTHING_NONE, Stage::Search},
    {"model-a", "ablation A: bidirectional A*, raw grid path", TDO_SEARCH_BIDIR, false,
     TDO_CORRECT_NONE, TDO_SMOOTHING_NONE, Stage::Search},
    {"model-b", "ablation B: A + turn-deviation cost, raw grid path", TDO_SEARCH_BIDIR, true,
     TDO_CORRECT_NONE, TDO_SMOOTHING_NONE, Stage::Search},
    {"model-c", "ablation C: B + multi-scale inflection correction (polyline P2)", TDO_SEARCH_BIDIR,
     true, TDO_CORRECT_MULTISCALE, TDO_SMOOTHING_NONE, Stage::Correct},
    {"model-d", "ablation D: C + adaptive-radius arc corners, one unrefined time parameterisation",
     TDO_SEARCH_BIDIR, true, TDO_CORRECT_MULTISCALE, TDO_SMOOTHING_ARC, Stage::SmoothOnce},
    {"model-e", "ablation E: D + E-APF (online tracker; no effect on the static plan, = D)",
     TDO_SEARCH_BIDIR, true, TDO_CORRECT_MULTISCALE, TDO_SMOOTHING_ARC, Stage::SmoothOnce},
};

bool same_point(const tdo_vec3& a, const tdo_vec3& b) {
  return !(a.x < b.x) && !(a.x > b.x) && !(a.y < b.y) && !(a.y > b.y) && !(a.z < b.z) &&
         !(a.z > b.z);
}

tdo_vec3 segment_end(const tdo_path_segment& s) {
  return s.kind == TDO_SEGMENT_BEZIER ? s.p[3] : s.p[1];
}

// Points along the path every `step` m (at most max_points), both ends included.
std::vector<tdo_vec3> sample_path(const tdo_path& path, double step, std::size_t max_points) {
  std::vector<tdo_vec3> out;
  if (path.n == 0 || !(path.length > 0.0)) return out;
  const double n = std::min(static_cast<double>(max_points - 1), std::ceil(path.length / step));
  const auto count = static_cast<std::size_t>(std::max(1.0, n));
  for (std::size_t i = 0; i <= count; ++i) {
    const double s = path.length * static_cast<double>(i) / static_cast<double>(count);
    double local = 0.0;
    const uint32_t k = tdo_path_locate(&path, s, &local);
    if (k == UINT32_MAX) break;
    out.push_back(tdo_segment_point(&path.seg[k], local));
  }
  // The ends exactly (arclength rounding may leave the last evaluation a few ulp short).
  if (!out.empty()) {
    out.front() = path.seg[0].p[0];
    out.back() = segment_end(path.seg[path.n - 1]);
  }
  return out;
}

bool angle(const tdo_param_info& r) { return std::strcmp(r.unit, "rad") == 0; }

/** A row's planner parameter name: the row's name, "_deg" appended for angles. */
std::string key(const tdo_param_info& r) { return std::string(r.name) + (angle(r) ? "_deg" : ""); }

class PipelinePlanner : public Planner {
 public:
  // One planner parameter per real or integer row of tdo/params.h (angles in degrees, "_deg");
  // a row with default_of follows its source (a_lat_max = a_max).
  explicit PipelinePlanner(const Preset& preset) : preset_(preset) {
    tdo_plan_params d = default_params();
    if (!preset.penalties) tdo_plan_params_plain(&d);
    for (uint32_t i = 0; i < tdo_param_count(); ++i) {
      const tdo_param_info& r = *tdo_param_at(i);
      if ((r.type != TDO_PARAM_REAL && r.type != TDO_PARAM_UINT) || r.default_of >= 0) continue;
      const double scale = angle(r) ? 1.0 / kDeg : 1.0;
      const double lo = r.min_open ? std::nextafter(r.min, HUGE_VAL) : r.min;
      const double hi = std::isinf(r.max) ? 1e300 : r.max_open ? std::nextafter(r.max, 0.0) : r.max;
      add_param(key(r), tdo_param_get(&d, i) * scale, lo * scale, hi * scale);
    }
  }
  std::string name() const override { return preset_.name; }
  std::string description() const override { return preset_.description; }

  PlanResult plan(Environment& env, const tdo_vec3& start, const tdo_vec3& goal,
                  uint64_t /*seed*/) override {
    tdo_plan_request req{};
    req.start = start;
    req.goal = goal;
    tdo_plan_params& pp = req.params;
    pp = default_params();
    if (!preset_.penalties) tdo_plan_params_plain(&pp);
    for (uint32_t i = 0; i < tdo_param_count(); ++i) {
      const tdo_param_info& r = *tdo_param_at(i);
      if (r.type != TDO_PARAM_REAL && r.type != TDO_PARAM_UINT) continue;
      const double v = r.default_of >= 0 ? tdo_param_get(&pp, static_cast<uint32_t>(r.default_of))
                       : r.type == TDO_PARAM_UINT ? std::round(p(key(r)))
                                                  : p(key(r)) * (angle(r) ? kDeg : 1.0);
      (void)tdo_param_set(&pp, i, v);  // in range: set_param checked it
    }
    pp.search = preset_.kind;
    pp.correction = preset_.correction;
    pp.smoothing = preset_.smoothing;
    pp.depth = kStageDepth[static_cast<int>(preset_.stage)];

    tdo_plan_result res{};
    tdo_traj_output to{};
    tdo_status traj_status = TDO_ERR_INVALID_ARGUMENT;
    const auto t0 = std::chrono::steady_clock::now();
    const tdo_status st = tdo_planner_plan(env.planner(), &req, &res);
    if (st == TDO_OK && preset_.stage == Stage::SmoothOnce) {
      tdo_traj_input ti{};
      ti.path = res.path;
      ti.grid = env.grid();
      ti.clearance = env.clearance();
      tdo_plan_traj_input(&pp, &ti);
      traj_status = tdo_traj_run(env.traj(), &ti, &to);  // no refinement rounds (config 0)
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();

    PlanResult r;
    if (preset_.stage == Stage::Search || preset_.stage == Stage::Correct) {
      if (st != TDO_OK) {
        r.status = tdo_status_str(st);
      } else {
        std::vector<tdo_vec3> pts;
        if (preset_.stage == Stage::Search)
          pts.assign(res.grid_path, res.grid_path + res.n_grid_path);
        else
          pts.assign(res.waypoints, res.waypoints + res.n_waypoints);
        r = evaluate_polyline(env, pts, start, goal);
      }
      r.plan_time_ms = ms;
      r.expansions = res.search.expansions;
      return r;
    }

    r.plan_time_ms = ms;
    r.expansions = res.search.expansions;
    if (st != TDO_OK && st != TDO_ERR_INFEASIBLE) {
      r.status = tdo_status_str(st);
      return r;
    }
    r.path.assign(res.waypoints, res.waypoints + res.n_waypoints);
    if (preset_.stage == Stage::Trajectory) {
      r.metrics = res.metrics;
      r.has_trajectory = res.reached == TDO_PLAN_TRAJECTORY;
      r.feasible = st == TDO_OK;
    } else {
      tdo_metrics_input mi{};
      mi.waypoints = res.waypoints;
      mi.n_waypoints = res.n_waypoints;
      mi.path = &res.path;
      mi.grid = env.grid();
      mi.clearance_cap = 10.0;
      if (!metrics_with_trajectory(mi, traj_status, env.traj(), to, pp.dt, &r)) return r;
    }
    r.curve = sample_path(res.path, 0.1, 20000);
    // Independent of what the stages claim: exact ends and the clearance of the final path.
    if (res.path.n == 0 || !same_point(res.path.seg[0].p[0], start) ||
        !same_point(segment_end(res.path.seg[res.path.n - 1]), goal)) {
      r.status = "endpoints";
      return r;
    }
    if (!(r.metrics.min_clearance_m >= env.clearance() - 1e-9)) {
      r.status = "collides";
      return r;
    }
    r.smooth = r.metrics.curvature_continuous != 0 && r.feasible;
    r.ok = true;
    r.status = st == TDO_OK ? "ok" : "ok_infeasible";
    if (preset_.stage == Stage::SmoothOnce && !r.feasible) r.status = "ok_infeasible";
    return r;
  }

 private:
  Preset preset_;
};

}  // namespace

std::unique_ptr<Planner> make_pipeline_planner(const std::string& name) {
  for (const Preset& p : kPresets) {
    if (name == p.name) return std::make_unique<PipelinePlanner>(p);
  }
  return nullptr;
}

}  // namespace tdo_baselines
