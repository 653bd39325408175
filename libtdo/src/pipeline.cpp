// The TDO-MSF static pipeline: search -> correction -> smoothing -> trajectory -> metrics.
#include "tdo/pipeline.h"

#include <math.h>
#include <string.h>

#include "collision_internal.h"
#include "grid_internal.h"
#include "planner_internal.h"
#include "sample_energy.h"
#include "search_ends.h"
#include "search_headed.h"
#include "tdo/collision.h"
#include "tdo/params.h"
#include "vec3.h"

namespace tdo_internal {
uint32_t max_waypoints(const tdo_capacity& c);
namespace {

// m: the geometric stages verify at clearance - kClearanceTol, the allowance the feasibility report
// gives the clearance too (trajectory.h). Without it a grid path running exactly at the clearance
// (voxel centres next to cube faces, e.g. 0.3 m at 0.2 m voxels) fails the correction's check of
// its own input by a rounding error of ~1e-16 m, and the plan ends as TDO_ERR_NO_PATH although the
// search found a path.
constexpr double kClearanceTol = 1e-9;

double verify_clearance(double clearance) {
  return clearance > kClearanceTol ? clearance - kClearanceTol : clearance;
}

// Voxel centres of the search path, with the exact start and goal at the ends. An end point
// replaces its voxel's centre only when the segment from it to the next centre keeps the
// clearance; otherwise the centre stays too (start -> c0 -> c1 ...), as a segment from a point of
// a free voxel to that voxel's centre does (the voxel's centre and the point keep the clearance).
// Without this, a start off its voxel's centre could cut past an obstacle corner to the next
// centre and the correction stage would reject the whole path (TDO_ERR_NO_PATH) although the
// search found one.
// tdo_collision_segment_clear's answer for [a, b] at `clearance` (m), by segment_clear_steered:
// cheaper on voxel maps.
bool clear_at(const tdo_grid* g, tdo_vec3 a, tdo_vec3 b, double clearance) {
  return segment_clear_steered(g, a, b, clearance, nullptr, nullptr) != 0;
}

void world_path(tdo_planner* pl, const tdo_plan_request& req, const tdo_search_output& s,
                double clearance) {
  clearance = verify_clearance(clearance);
  tdo_vec3* w = pl->grid_path;
  const uint32_t n = s.n_path;
  uint32_t m = 0;
  w[m++] = req.start;
  if (n == 1) {  // start and goal share a voxel
    if (!clear_at(pl->grid, req.start, req.goal, clearance))
      w[m++] = tdo_grid_voxel_center(pl->grid, s.path[0]);
    w[m++] = req.goal;
    pl->n_grid_path = m;
    return;
  }
  const tdo_vec3 c1 = tdo_grid_voxel_center(pl->grid, s.path[1]);
  if (!clear_at(pl->grid, req.start, c1, clearance))
    w[m++] = tdo_grid_voxel_center(pl->grid, s.path[0]);
  for (uint32_t i = 1; i + 1 < n; ++i) w[m++] = tdo_grid_voxel_center(pl->grid, s.path[i]);
  const tdo_vec3 cl = tdo_grid_voxel_center(pl->grid, s.path[n - 2]);
  if (!clear_at(pl->grid, cl, req.goal, clearance))
    w[m++] = tdo_grid_voxel_center(pl->grid, s.path[n - 1]);
  w[m++] = req.goal;
  pl->n_grid_path = m;
}

// The direct route (docs/design.md s.1): when the straight segment from start to goal keeps the
// clearance, it is the shortest path and has no turn, so no search can better it for the
// turn-penalised planner; the search is skipped and the correction gets the segment itself.
// The search's own refusals (search_ends_ok: an end out of bounds or its voxel blocked by the
// centre rule, start equal to goal) are left to it: the same check, so the direct route never
// plans what the search refuses and the refusal's status is the search's.
bool direct_path(tdo_planner* pl, const tdo_plan_request& req, double clearance,
                 tdo_search_output* s) {
  const tdo_grid* g = pl->grid;
  tdo_voxel ends[2];
  if (search_ends_ok(g, req.start, req.goal, ends) != TDO_OK) return false;
  if (!clear_at(g, req.start, req.goal, verify_clearance(clearance))) return false;
  memset(s, 0, sizeof(*s));
  s->cost = s->penalized_cost = norm(sub(req.goal, req.start));
  s->direct = 1;
  pl->grid_path[0] = req.start;
  pl->grid_path[1] = req.goal;
  pl->n_grid_path = 2;
  return true;
}

// docs/design.md s.0: every point of the output keeps the clearance, the exact start and goal
// included. The search checks their voxels (the centre rule); this checks the points themselves,
// at every depth, so the raw searches and the full pipeline agree on what is plannable.
tdo_status check_end_points(const tdo_grid* grid, const tdo_plan_request& req, double clearance) {
  if (!(clearance > kClearanceTol)) return TDO_OK;
  tdo_voxel v;
  if (tdo_grid_world_to_voxel(grid, req.start, &v) && !tdo_grid_is_blocked(grid, v) &&
      tdo_collision_point_distance(grid, req.start, clearance) < verify_clearance(clearance))
    return TDO_ERR_START_BLOCKED;
  if (tdo_grid_world_to_voxel(grid, req.goal, &v) && !tdo_grid_is_blocked(grid, v) &&
      tdo_collision_point_distance(grid, req.goal, clearance) < verify_clearance(clearance))
    return TDO_ERR_GOAL_BLOCKED;
  return TDO_OK;
}

// ---------------------------------------------------------------------------------------------
// Moving start (docs/design.md s.5, "Moving start").

bool at_rest(const tdo_start_state& s) { return zero3(s.v) && zero3(s.a); }
bool finite_state(const tdo_start_state& s) { return finite3(s.v) && finite3(s.a); }
bool voxel_free(const tdo_grid* g, tdo_vec3 p) {
  tdo_voxel v;
  return tdo_grid_world_to_voxel(g, p, &v) && !tdo_grid_is_blocked(g, v);
}
tdo_vec3 along(tdo_vec3 p, tdo_vec3 d, double len) {
  return tdo_vec3{p.x + d.x * len, p.y + d.y * len, p.z + d.z * len};
}

/** The entry of a moving start: the ramp, the braking line, the points before the search start. */
struct Entry {
  tdo_traj_entry e;
  tdo_vec3 prefix[2];  // waypoints before the search start (the ramp's end, the braking line's)
  uint32_t n_prefix;
  tdo_vec3 search_start;  // where the search starts: the end of the braking line or its extension
};

constexpr int kExtensionTries = 4;      // extension lengths tried (halved each time)
constexpr double kBrakeStretch = 1e-9;  // relative: the braking line's point lies this far beyond
constexpr double kBrakeStretchAbs = 1e-11;  // m: at least this far (a short line's rounding)

/** Plans the entry of req's moving start: the start point in bounds and clear, the ramp (a cubic
 *  Bezier) and the braking line along the velocity clear, then an extension of the line, as long
 *  as a voxel edge or the braking distance, halved until clear (room for the corner that curves
 *  the vehicle into the path). */
tdo_status plan_entry(const tdo_grid* g, const tdo_plan_request& req, double clearance,
                      Entry* out) {
  const tdo_plan_params& p = req.params;
  tdo_status st = tdo_traj_entry_plan(req.start, &req.state, p.v_max, p.a_max, p.j_max, &out->e);
  if (st != TDO_OK) return st;
  tdo_voxel v;
  if (!tdo_grid_world_to_voxel(g, req.start, &v)) return TDO_ERR_START_OUT_OF_BOUNDS;
  const double c = verify_clearance(clearance);
  if (tdo_collision_point_distance(g, req.start, clearance) < c) return TDO_ERR_START_BLOCKED;
  const tdo_traj_entry& e = out->e;
  // Each ramp piece p + v t + a t^2 / 2 + j t^3 / 6 on [0, T] as a cubic Bezier: the first from
  // the start state to the knot, the second (if any) from the knot to the ramp's end.
  const tdo_vec3 from[2][3] = {{req.start, req.state.v, req.state.a},
                               {e.knot_p, e.knot_v, e.knot_a}};
  const double dur[2] = {e.knot, e.ramp - e.knot};
  const tdo_vec3 to[2] = {e.knot_p, e.p};
  for (int k = 0; k < 2; ++k) {
    const double t = dur[k];
    if (!(t > 0.0)) continue;
    const tdo_vec3 p0 = from[k][0], v0 = from[k][1], a0 = from[k][2];
    const tdo_vec3 b[4] = {p0, along(p0, v0, t / 3.0),
                           tdo_vec3{p0.x + (2.0 * v0.x * t + 0.5 * a0.x * t * t) / 3.0,
                                    p0.y + (2.0 * v0.y * t + 0.5 * a0.y * t * t) / 3.0,
                                    p0.z + (2.0 * v0.z * t + 0.5 * a0.z * t * t) / 3.0},
                           to[k]};
    if (!tdo_collision_bezier_clear(g, b, c, 0.0)) return TDO_ERR_STATE_CANNOT_STOP;
  }
  out->n_prefix = 0;
  out->prefix[out->n_prefix++] = e.p;
  out->search_start = e.p;
  if (!(e.speed > 0.0)) {  // the ramp ends at rest: the path starts there
    out->n_prefix = 0;
    return voxel_free(g, e.p) ? TDO_OK : TDO_ERR_STATE_CANNOT_STOP;
  }
  const tdo_vec3 d{e.v.x / e.speed, e.v.y / e.speed, e.v.z / e.speed};
  const double reach = e.brake * (1.0 + kBrakeStretch);
  const tdo_vec3 stop =
      along(e.p, d, reach > e.brake + kBrakeStretchAbs ? reach : e.brake + kBrakeStretchAbs);
  if (!tdo_collision_segment_clear(g, e.p, stop, c)) return TDO_ERR_STATE_CANNOT_STOP;
  const double res = tdo_grid_get_desc(g).res;
  double ext = e.brake > res ? e.brake : res;
  for (int k = 0; k < kExtensionTries; ++k, ext *= 0.5) {
    const tdo_vec3 end = along(stop, d, ext);
    if (tdo_collision_segment_clear(g, stop, end, c) && voxel_free(g, end)) {
      out->prefix[out->n_prefix++] = stop;
      out->search_start = end;
      return TDO_OK;
    }
  }
  out->search_start = stop;
  return voxel_free(g, stop) ? TDO_OK : TDO_ERR_STATE_CANNOT_STOP;
}

/** The entry's points, then the corrected path from the search start, into pl->waypoints. */
tdo_status entry_waypoints(tdo_planner* pl, const Entry& en, tdo_plan_result* out) {
  const uint32_t n = en.n_prefix + out->n_waypoints;
  if (n > max_waypoints(pl->cfg.cap)) return TDO_ERR_PATH_CAPACITY;
  for (uint32_t i = 0; i < en.n_prefix; ++i) pl->waypoints[i] = en.prefix[i];
  for (uint32_t i = 0; i < out->n_waypoints; ++i)
    pl->waypoints[en.n_prefix + i] = out->waypoints[i];
  out->waypoints = pl->waypoints;
  out->n_waypoints = n;
  return TDO_OK;
}

/** Whether the smoothed path still begins with the whole braking line (a corner may take it). */
bool keeps_braking_line(const tdo_path& path, const Entry& en) {
  if (!(en.e.speed > 0.0)) return true;
  return path.n > 0 && path.seg[0].kind == TDO_SEGMENT_LINE && path.seg[0].length >= en.e.brake;
}

// True when the trajectory stage's energy is the one tdo_metrics_compute would sum over its stored
// samples (the same steps in the same order) and those are samples it accepts (sample_energy.h).
bool energy_known(const tdo_traj_output* traj, double dt) {
  if (traj == nullptr || traj->samples == nullptr || traj->n_samples < 2u) return false;
  return isfinite(traj->energy) && samples_accepted(traj->samples, traj->n_samples, dt);
}

// `traj`: the trajectory stage's output: when its samples were streamed (not stored), or stored
// and energy_known, the energy and flight time come from its pass (the same sums over the same
// samples) instead of a second pass in tdo_metrics_compute.
void metrics_of(tdo_planner* pl, tdo_plan_result* r, const tdo_path* path, const tdo_plan_params& p,
                const tdo_traj_output* traj = nullptr) {
  tdo_metrics_input mi;
  memset(&mi, 0, sizeof(mi));
  if (r->reached >= TDO_PLAN_CORRECT) {
    mi.waypoints = r->waypoints;
    mi.n_waypoints = r->n_waypoints;
  } else {
    mi.waypoints = r->grid_path;
    mi.n_waypoints = r->n_grid_path;
  }
  mi.path = path;
  const bool known = energy_known(traj, p.dt);
  mi.samples = r->n_samples > 0 && !known ? r->samples : nullptr;
  mi.n_samples = r->n_samples;
  mi.dt = p.dt;
  mi.grid = pl->grid;
  mi.clearance_cap = 10.0;
  // The samples lie on the path, so its minimum is at most theirs (uncapped below the trajectory
  // report's cap): a tight hint (tdo_metrics_input.clearance_hint).
  const double seen = r->feasibility.min_clearance;
  const double cap = tdo_grid_clearance(pl->grid) + TDO_TRAJ_CLEARANCE_CAP_EXTRA;
  const bool near = r->reached == TDO_PLAN_TRAJECTORY && seen >= 0.0 && seen < cap;
  if (near) mi.clearance_hint = seen + 1e-9;
  // A round that pieces mode accepted measured the path itself as tdo_metrics_compute does
  // (trajectory.h, tdo_traj_output.report): below its cap that is this metric, taken as it is.
  const bool path_measured = near && traj != nullptr && traj->samples == nullptr &&
                             traj->report.ok && traj->sample_passes == traj->refinements;
  if (path_measured) mi.grid = nullptr;
  tdo_metrics_compute(&mi, &r->metrics);
  if (path_measured) r->metrics.min_clearance_m = seen;
  if (traj != nullptr && traj->n_samples >= 2u && (traj->samples == nullptr || known)) {
    r->metrics.energy = traj->energy;
    r->metrics.flight_time_s = traj->samples != nullptr
                                   ? traj->samples[traj->n_samples - 1u].t - traj->samples[0].t
                                   : traj->duration;  // last t - first t, the first t being 0
  }
}

}  // namespace

// Stages past the search exist only when their capacities are set: correction and smoothing need
// max_checks, the trajectory stage max_samples and max_profile. A search-only planner stays small.
bool has_geometry(const tdo_capacity& c) { return c.max_checks > 0; }
bool has_trajectory(const tdo_capacity& c) {
  return has_geometry(c) && c.max_samples > 0 && c.max_profile > 0;
}

tdo_correct_config correct_cfg(const tdo_capacity& c) {
  return tdo_correct_config{c.max_path + 2u, c.max_checks};
}
// Waypoints the smoothing takes: the correction's output, at most the grid path's points (its
// voxels with the exact start and goal) unless max_waypoints says fewer.
uint32_t max_waypoints(const tdo_capacity& c) {
  return c.max_waypoints != 0u && c.max_waypoints < c.max_path + 2u ? c.max_waypoints
                                                                    : c.max_path + 2u;
}
// Path segments: a line per waypoint gap and at most two curves per corner (g2).
uint32_t max_segments(const tdo_capacity& c) { return 3u * max_waypoints(c) + 1u; }
tdo_smooth_config smooth_cfg(const tdo_capacity& c) {
  return tdo_smooth_config{max_waypoints(c), max_segments(c), c.max_shrinks};
}
tdo_traj_config traj_cfg(const tdo_capacity& c) {
  return tdo_traj_config{c.max_samples,    max_segments(c),   c.max_profile,
                         c.max_violations, c.max_refinements, c.stream_samples};
}

size_t pipeline_footprint(const tdo_planner_config* cfg) {
  const tdo_capacity& c = cfg->cap;
  size_t bytes = tdo_arena_round(static_cast<size_t>(c.max_path + 2u) * sizeof(tdo_vec3));
  if (has_geometry(c)) {
    bytes += tdo_arena_round(static_cast<size_t>(max_waypoints(c)) * sizeof(tdo_vec3));
    const tdo_correct_config cc = correct_cfg(c);
    const tdo_smooth_config sc = smooth_cfg(c);
    bytes += tdo_correct_footprint(&cc) + tdo_smooth_footprint(&sc);
  }
  if (has_trajectory(c)) {
    const tdo_traj_config tc = traj_cfg(c);
    bytes += tdo_traj_footprint(&tc);
  }
  return bytes;
}

tdo_status pipeline_init(tdo_planner* pl, tdo_arena* arena) {
  const tdo_capacity& c = pl->cfg.cap;
  pl->grid_path =
      static_cast<tdo_vec3*>(tdo_arena_alloc(arena, (c.max_path + 2u) * sizeof(tdo_vec3)));
  if (pl->grid_path == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  pl->correct = nullptr;
  pl->smooth = nullptr;
  pl->traj = nullptr;
  pl->waypoints = nullptr;
  tdo_status st = TDO_OK;
  if (has_geometry(c)) {
    pl->waypoints =
        static_cast<tdo_vec3*>(tdo_arena_alloc(arena, max_waypoints(c) * sizeof(tdo_vec3)));
    if (pl->waypoints == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    const tdo_correct_config cc = correct_cfg(c);
    const tdo_smooth_config sc = smooth_cfg(c);
    st = tdo_correct_init(&pl->correct, arena, &cc);
    if (st == TDO_OK) st = tdo_smooth_init(&pl->smooth, arena, &sc);
  }
  if (st == TDO_OK && has_trajectory(c)) {
    const tdo_traj_config tc = traj_cfg(c);
    st = tdo_traj_init(&pl->traj, arena, &tc);
  }
  return st;
}

}  // namespace tdo_internal

using namespace tdo_internal;

extern "C" void tdo_plan_search_input(const tdo_plan_params* p, tdo_search_input* in) {
  if (p == nullptr || in == nullptr) return;
  in->kind = p->search;
  in->lambda = p->lambda;
  in->mu = p->mu;
  in->theta_max = p->theta_max;
  in->d_th = p->d_th;
  in->h_weight = p->h_weight;
  in->first_meet = p->first_meet;
  in->grid_first = p->grid_first;
  in->states = p->states;
  in->max_expansions = p->max_expansions;
}

extern "C" void tdo_plan_correct_input(const tdo_plan_params* p, tdo_correct_input* in) {
  if (p == nullptr || in == nullptr) return;
  in->mode = p->correction;
  in->turn_threshold = p->turn_threshold;
  in->shorten = p->shorten;
}

extern "C" void tdo_plan_smooth_input(const tdo_plan_params* p, tdo_smooth_input* in) {
  if (p == nullptr || in == nullptr) return;
  in->mode = p->smoothing;
  in->k = p->k;
  in->v_cruise = p->v_cruise;
  in->v_max = p->v_max;
  in->a_lat_max = p->a_lat_max;
  in->j_max = p->j_max;
  in->stop_angle = p->stop_angle;
  in->corner_time = p->corner_time;
}

extern "C" void tdo_plan_traj_input(const tdo_plan_params* p, tdo_traj_input* in) {
  if (p == nullptr || in == nullptr) return;
  in->v_max = p->v_max;
  in->a_max = p->a_max;
  in->j_max = p->j_max;
  in->a_lat_max = p->a_lat_max;
  in->dt = p->dt;
}

namespace {

struct MetricField {
  const char* name;
  double tdo_metrics::*value;
};
constexpr MetricField kMetricFields[] = {{"length_m", &tdo_metrics::length_m},
                                         {"total_turn_deg", &tdo_metrics::total_turn_deg},
                                         {"min_clearance_m", &tdo_metrics::min_clearance_m},
                                         {"avg_curvature", &tdo_metrics::avg_curvature},
                                         {"smoothness", &tdo_metrics::smoothness},
                                         {"energy", &tdo_metrics::energy},
                                         {"flight_time_s", &tdo_metrics::flight_time_s}};
constexpr uint32_t kMetricCount = sizeof(kMetricFields) / sizeof(kMetricFields[0]);

}  // namespace

extern "C" uint32_t tdo_metric_count(void) { return kMetricCount; }

extern "C" const char* tdo_metric_name(uint32_t i) {
  return i < kMetricCount ? kMetricFields[i].name : nullptr;
}

extern "C" double tdo_metric_value(const tdo_metrics* m, uint32_t i) {
  if (m == nullptr || i >= kMetricCount) return static_cast<double>(NAN);
  return m->*kMetricFields[i].value;
}

extern "C" tdo_status tdo_planner_plan(tdo_planner* pl, const tdo_plan_request* req,
                                       tdo_plan_result* out) {
  if (pl == nullptr || req == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  pl->have_samples = 0;
  const tdo_plan_params& p = req->params;
  out->status = tdo_plan_params_check(&p, nullptr);
  if (out->status != TDO_OK) return out->status;
  const double clearance = tdo_grid_clearance(pl->grid);
  if (clearance < 0.0) return out->status = TDO_ERR_MAP_NOT_READY;
  if ((p.depth >= TDO_PLAN_CORRECT && pl->correct == nullptr) ||
      (p.depth >= TDO_PLAN_TRAJECTORY && pl->traj == nullptr))
    return out->status = TDO_ERR_NOT_CONFIGURED;

  // A moving start: the entry first; the search starts where it ends (docs/design.md s.5).
  const bool moving = !at_rest(req->state);
  if (!finite_state(req->state)) return out->status = TDO_ERR_STATE_NOT_FINITE;
  if (moving && p.depth != TDO_PLAN_TRAJECTORY) return out->status = TDO_ERR_INVALID_ARGUMENT;
  Entry entry;
  memset(&entry, 0, sizeof(entry));
  tdo_plan_request sreq = *req;
  if (moving) {
    out->status = plan_entry(pl->grid, *req, clearance, &entry);
    if (out->status != TDO_OK) return out->status;
    sreq.start = entry.search_start;
  }

  // Stage 1: search.
  tdo_search_input si;
  memset(&si, 0, sizeof(si));
  si.grid = pl->grid;
  si.start = sreq.start;
  si.goal = req->goal;
  tdo_plan_search_input(&p, &si);
  if (p.depth >= TDO_PLAN_CORRECT && search_headed(&si) &&
      direct_path(pl, sreq, clearance, &out->search)) {
    out->status = TDO_OK;
  } else {
    GuideReport guide;
    out->status = guide_search(pl->guide, pl->search, &si, &out->search, &guide);
    out->search.guide = guide.used;
    out->search.guide_expansions = guide.expansions;
    if (out->status == TDO_OK) out->status = check_end_points(pl->grid, sreq, clearance);
    if (out->status != TDO_OK) return out->status;
    world_path(pl, sreq, out->search, clearance);
  }
  out->grid_path = pl->grid_path;
  out->n_grid_path = pl->n_grid_path;
  out->reached = TDO_PLAN_SEARCH;
  if (p.depth == TDO_PLAN_SEARCH) {
    metrics_of(pl, out, nullptr, p);
    return out->status;
  }

  // Stage 2: inflection correction.
  tdo_correct_input ci;
  memset(&ci, 0, sizeof(ci));
  ci.grid = pl->grid;
  ci.points = out->grid_path;
  ci.n_points = out->n_grid_path;
  ci.clearance = verify_clearance(clearance);
  tdo_plan_correct_input(&p, &ci);
  // At clearance 0 a grid step is clear by MovingAI's rule (s.0: every voxel it sweeps is free,
  // so it stays half a voxel edge from every other voxel); the points between the ends are
  // voxel centres joined by steps, or the direct route's two ends (no step).
  ci.steps_proven = !(clearance > 0.0) && out->search.direct == 0 ? 1 : 0;
  tdo_correct_output co;
  out->status = tdo_correct_run(pl->correct, &ci, &co);
  if (out->status != TDO_OK) return out->status;
  out->waypoints = co.waypoints;
  out->n_waypoints = co.n_waypoints;
  out->n_safety_critical = co.n_safety_critical;
  if (moving) {
    out->status = entry_waypoints(pl, entry, out);
    if (out->status != TDO_OK) return out->status;
  }
  out->reached = TDO_PLAN_CORRECT;
  if (p.depth == TDO_PLAN_CORRECT) {
    metrics_of(pl, out, nullptr, p);
    return out->status;
  }

  // Stage 3: smoothing; stage 5: time parameterisation with feasibility refinement. When the
  // trajectory stays infeasible, the corners are enlarged where there is room (k x 1.5) and the
  // whole check runs again, a bounded number of times.
  tdo_smooth_input mi;
  memset(&mi, 0, sizeof(mi));
  mi.grid = pl->grid;
  mi.waypoints = out->waypoints;
  mi.n_waypoints = out->n_waypoints;
  mi.clearance = verify_clearance(clearance);
  tdo_plan_smooth_input(&p, &mi);
  const uint32_t rounds = p.depth == TDO_PLAN_TRAJECTORY ? 3u : 1u;
  tdo_traj_output to;
  memset(&to, 0, sizeof(to));
  for (uint32_t round = 0; round < rounds; ++round) {
    tdo_smooth_output so;
    out->status = tdo_smooth_run(pl->smooth, &mi, &so);
    // A corner that took part of a moving start's braking line: the polyline with a stop at
    // every corner instead (lines only), on which the vehicle can always brake.
    if (out->status == TDO_OK && moving && !keeps_braking_line(so.path, entry)) {
      mi.mode = TDO_SMOOTHING_NONE;
      out->status = tdo_smooth_run(pl->smooth, &mi, &so);
    }
    if (out->status != TDO_OK) return out->status;
    out->path = so.path;
    out->reached = TDO_PLAN_SMOOTH;
    if (p.depth == TDO_PLAN_SMOOTH) break;
    tdo_traj_input ti;
    memset(&ti, 0, sizeof(ti));
    ti.path = so.path;
    ti.grid = pl->grid;
    ti.clearance = clearance;
    tdo_plan_traj_input(&p, &ti);
    ti.start_p = req->start;
    ti.start = req->state;
    // Every line of the path lies on a segment the correction checked, every curve passed the
    // smoothing's check, both at verify_clearance: the pieces mode need not measure it again.
    ti.clearance_proven = moving ? 0 : 1;
    out->status = tdo_traj_run(pl->traj, &ti, &to);
    out->feasibility = to.report;
    out->refinements += to.refinements;
    out->sample_passes += to.sample_passes;
    out->samples = to.samples;
    out->n_samples = to.n_samples;
    out->reached = TDO_PLAN_TRAJECTORY;
    if (out->status != TDO_ERR_INFEASIBLE) break;
    mi.k *= 1.5;
  }
  if (out->status != TDO_OK && out->status != TDO_ERR_INFEASIBLE) return out->status;
  metrics_of(pl, out, &out->path, p, out->reached == TDO_PLAN_TRAJECTORY ? &to : nullptr);
  if (out->status == TDO_ERR_INFEASIBLE) {  // never hand out a violating trajectory as usable
    out->samples = nullptr;
    out->n_samples = 0;
  }
  pl->have_samples = out->status == TDO_OK && out->n_samples > 0u ? 1 : 0;
  return out->status;
}

extern "C" tdo_status tdo_planner_each_sample(const tdo_planner* pl, tdo_sample_fn fn, void* user) {
  if (pl == nullptr || fn == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (pl->traj == nullptr) return TDO_ERR_NOT_CONFIGURED;
  if (!pl->have_samples) return TDO_ERR_INVALID_ARGUMENT;
  return tdo_traj_each_sample(pl->traj, fn, user);
}
