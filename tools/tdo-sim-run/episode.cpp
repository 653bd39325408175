// One dynamic episode: plan, fly with the libtdo follower in the libtdo simulator, measure.
#include "episode.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>

#include "tdo_samples/samples.h"

namespace tdo_episode {
namespace {

double dist(tdo_vec3 a, tdo_vec3 b) {
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Distance from p to segment [a, b] (independent of libtdo's nearest-point search).
double seg_dist(tdo_vec3 p, tdo_vec3 a, tdo_vec3 b) {
  const double ex = b.x - a.x, ey = b.y - a.y, ez = b.z - a.z;
  const double l2 = ex * ex + ey * ey + ez * ez;
  double u = l2 > 0.0 ? ((p.x - a.x) * ex + (p.y - a.y) * ey + (p.z - a.z) * ez) / l2 : 0.0;
  u = std::min(1.0, std::max(0.0, u));
  return dist(p, tdo_vec3{a.x + u * ex, a.y + u * ey, a.z + u * ez});
}

// Distance from p to the planned polyline: every segment (brute force).
double path_dist(tdo_vec3 p, const std::vector<tdo_sample>& plan) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < plan.size(); ++i)
    best = std::min(best, seg_dist(p, plan[i].p, plan[i + 1].p));
  return best;
}

void event_lines(double t, uint32_t ev, std::vector<std::string>* out) {
  static const struct {
    uint32_t bit;
    const char* name;
  } kNames[] = {{TDO_APF_EVENT_LM_DETECTED, "local_minimum_detected"},
                {TDO_APF_EVENT_ESCAPE_START, "escape_start"},
                {TDO_APF_EVENT_ESCAPE_OK, "escape_ok"},
                {TDO_APF_EVENT_ESCAPE_FAILED, "escape_failed"},
                {TDO_APF_EVENT_GOAL_REACHED, "goal_reached"}};
  for (const auto& n : kNames) {
    if ((ev & n.bit) != 0u) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "t=%.2f: %s", t, n.name);
      out->push_back(buf);
    }
  }
}

struct Arena {
  std::unique_ptr<unsigned char[]> mem;
  tdo_arena a{};
  explicit Arena(std::size_t n) : mem(new unsigned char[std::max<std::size_t>(n, 1)]) {
    tdo_arena_init(&a, mem.get(), n);
  }
};

}  // namespace

bool set_param(tdo_apf_params* p, const std::string& name, double value) {
  struct Field {
    const char* name;
    double tdo_apf_params::*field;
  };
  static const Field kFields[] = {{"k_a", &tdo_apf_params::k_a},
                                  {"att_dist", &tdo_apf_params::att_dist},
                                  {"k_r", &tdo_apf_params::k_r},
                                  {"k_r_static", &tdo_apf_params::k_r_static},
                                  {"d_0", &tdo_apf_params::d_0},
                                  {"d_0_static", &tdo_apf_params::d_0_static},
                                  {"d_min", &tdo_apf_params::d_min},
                                  {"k_g", &tdo_apf_params::k_g},
                                  {"k_d", &tdo_apf_params::k_d},
                                  {"lookahead", &tdo_apf_params::lookahead},
                                  {"hold_dist", &tdo_apf_params::hold_dist},
                                  {"horizon", &tdo_apf_params::horizon},
                                  {"mover_margin", &tdo_apf_params::mover_margin},
                                  {"lm_window", &tdo_apf_params::lm_window},
                                  {"lm_progress", &tdo_apf_params::lm_progress},
                                  {"lm_force", &tdo_apf_params::lm_force},
                                  {"lm_speed", &tdo_apf_params::lm_speed},
                                  {"lm_goal_dist", &tdo_apf_params::lm_goal_dist},
                                  {"k_t", &tdo_apf_params::k_t},
                                  {"escape_time", &tdo_apf_params::escape_time},
                                  {"safety_margin", &tdo_apf_params::safety_margin}};
  for (const Field& f : kFields) {
    if (name == f.name) {
      p->*(f.field) = value;
      return true;
    }
  }
  if (name == "safety" && (value < 0.5 || value > 0.5) && value > -0.5 && value < 1.5) {
    p->safety = value > 0.5 ? 1u : 0u;
    return true;
  }
  if (name == "max_escapes" && value >= 0.0 && value < 1e6) {
    p->max_escapes = static_cast<uint32_t>(value);
    return true;
  }
  return false;
}

const char* follower_name(tdo_follower_kind k) { return k == TDO_FOLLOWER_APF ? "apf" : "eapf"; }

namespace {

/** The planner's memory, kept for the flight: the follower and the simulator use its grid. */
struct PlannerBox {
  std::unique_ptr<unsigned char[]> mem;
  tdo_grid* grid = nullptr;
  tdo_plan_params params{};
};

// Step 1: plan the map's query with the default parameters into out->plan. False with `error`
// when the map cannot be loaded into a planner; an unplannable query leaves m.planned false.
bool plan_episode(const tdo_io::Map& map, const Options& o, PlannerBox* box, Episode* out,
                  std::string* error) {
  Metrics& m = out->m;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, o.clearance, 27u, 0u);
  if (o.stream_samples >= 0) cfg.cap.stream_samples = static_cast<uint32_t>(o.stream_samples);
  const std::size_t fp = tdo_planner_footprint(&cfg);
  if (fp == 0) {
    *error = "invalid planner configuration for this map";
    return false;
  }
  box->mem.reset(new unsigned char[fp]);
  tdo_planner* planner = nullptr;
  tdo_status st = tdo_planner_init(&planner, box->mem.get(), fp, &cfg);
  if (st != TDO_OK) {
    *error = std::string("planner init: ") + tdo_status_str(st);
    return false;
  }
  box->grid = tdo_planner_grid(planner);
  st = tdo_io::load_into(map, box->grid, o.clearance);
  if (st != TDO_OK) {
    *error = std::string("map load: ") + tdo_status_str(st);
    return false;
  }
  tdo_plan_request req{};
  req.start = map.start;
  req.goal = map.goal;
  tdo_plan_params_default(&req.params);
  box->params = req.params;
  tdo_plan_result res{};
  st = tdo_planner_plan(planner, &req, &res);
  m.plan_status = static_cast<int>(st);
  m.movers = o.movers ? static_cast<uint32_t>(map.movers.size()) : 0u;
  if (st != TDO_OK || res.n_samples < 2u) return true;
  st = tdo_samples::plan_samples(planner, res, &out->plan);  // stored or regenerated
  if (st != TDO_OK) {
    *error = std::string("plan samples: ") + tdo_status_str(st);
    return false;
  }
  m.planned = true;
  m.plan_duration = out->plan.back().t;
  m.v_limit = req.params.v_max;
  m.a_limit = req.params.a_max;
  m.j_limit = req.params.j_max;
  return true;
}

// Step 2: the follower's parameters (the options' overrides applied) and its reset on the plan.
bool start_follower(const tdo_io::Map& map, const Options& o, const PlannerBox& box, tdo_apf* apf,
                    Episode* out, std::string* error) {
  tdo_apf_params prm;
  tdo_apf_params_default(&prm, o.follower);
  prm.vehicle_radius = o.vehicle_radius;
  prm.v_max = box.params.v_max;
  prm.a_max = box.params.a_max;
  prm.j_max = box.params.j_max;
  prm.goal_tol = o.goal_tol;
  for (const auto& kv : o.params) {
    if (!set_param(&prm, kv.first, kv.second)) {
      *error = "unknown follower parameter '" + kv.first + "'";
      return false;
    }
  }
  out->params = prm;
  tdo_apf_task task{};
  task.samples = out->plan.data();
  task.n_samples = static_cast<uint32_t>(out->plan.size());
  task.goal = map.goal;
  task.grid = box.grid;
  task.t0 = 0.0;
  const tdo_status st = tdo_apf_reset(apf, &prm, &task);
  if (st != TDO_OK) {
    *error = std::string("follower reset: ") + tdo_status_str(st) +
             (st == TDO_ERR_INVALID_ARGUMENT ? " (a follower parameter out of range)" : "");
    return false;
  }
  return true;
}

// Step 3: the simulator on the map's bounds with the first m.movers movers, vehicle at the start.
bool start_sim(const tdo_io::Map& map, const Options& o, const PlannerBox& box, tdo_sim* sim,
               tdo_sim_params* sp, Episode* out, std::string* error) {
  const tdo_apf_params& prm = out->params;
  const uint32_t n_movers = out->m.movers;
  std::vector<tdo_mover> movers;
  for (uint32_t i = 0; i < n_movers; ++i) {
    const tdo_io::Mover& mv = map.movers[i];
    movers.push_back(tdo_mover{static_cast<uint32_t>(mv.id), mv.pos, mv.vel, mv.radius});
    out->radii.push_back(mv.radius);
  }
  out->tracks.assign(n_movers, {});
  tdo_sim_params_default(sp);
  sp->dt = prm.dt;
  sp->v_max = prm.v_max;
  sp->a_max = prm.a_max;
  sp->j_max = prm.j_max;
  sp->bounds.min = map.desc.origin;
  sp->bounds.max = tdo_vec3{map.desc.origin.x + map.desc.nx * map.desc.res,
                            map.desc.origin.y + map.desc.ny * map.desc.res,
                            map.desc.origin.z + map.desc.nz * map.desc.res};
  sp->vehicle_radius = o.vehicle_radius;
  sp->static_clearance = o.static_clearance;
  sp->grid = box.grid;
  sp->seed = o.seed;
  sp->accel_noise = o.accel_noise;
  tdo_vehicle_state s0{};
  s0.p = map.start;
  const tdo_status st = tdo_sim_reset(sim, sp, &s0, movers.data(), n_movers);
  if (st != TDO_OK) {
    *error = std::string("simulator reset: ") + tdo_status_str(st);
    return false;
  }
  return true;
}

// Step 4: fly until the goal is within goal_tol or the time limit; positions into `pos`.
bool fly(const tdo_io::Map& map, const Options& o, double dt, tdo_apf* apf, tdo_sim* sim,
         Episode* out, std::vector<tdo_vec3>* pos, std::string* error) {
  Metrics& m = out->m;
  const double t_limit = o.time_factor * m.plan_duration + o.time_extra;
  const auto max_steps = static_cast<uint32_t>(std::ceil(t_limit / dt));
  tdo_sim_output so{};
  tdo_sim_get(sim, &so);
  m.min_mover_sep = so.mover_gap;
  m.min_static_dist = so.static_dist;
  pos->assign(1, so.state.p);
  double dev_sum = 0.0;
  uint32_t dev_n = 0;
  bool arrived = false;
  for (uint32_t k = 0; k < max_steps && !arrived; ++k) {
    tdo_apf_input in{};
    in.state = so.state;
    in.movers = so.movers;
    in.n_movers = so.n_movers;
    tdo_apf_output ao;
    const tdo_status st = tdo_apf_run(apf, &in, &ao);
    if (st != TDO_OK && st != TDO_ERR_LOCAL_MINIMUM) {
      *error = std::string("follower step: ") + tdo_status_str(st);
      return false;
    }
    if ((ao.events & TDO_APF_EVENT_ESCAPE_FAILED) != 0u) m.escape_failed = true;
    if ((ao.events & TDO_APF_EVENT_SAFETY) != 0u) ++m.safety_steps;
    if ((ao.events & TDO_APF_EVENT_EVADE) != 0u) ++m.evade_steps;
    event_lines(so.state.t, ao.events, &out->events);
    m.lm_events = ao.lm_detections;
    m.escapes = ao.escapes;
    tdo_sim_input si{};
    si.setpoint = ao.setpoint;
    tdo_sim_run(sim, &si, &so);
    ++m.steps;
    pos->push_back(so.state.p);
    m.min_mover_sep = std::min(m.min_mover_sep, so.mover_gap);
    m.min_static_dist = std::min(m.min_static_dist, so.static_dist);
    if (so.collision_mover) m.collision_mover = true;
    if (so.collision_static) m.collision_static = true;
    const double dev = path_dist(so.state.p, out->plan);
    m.max_deviation = std::max(m.max_deviation, dev);
    dev_sum += dev;
    ++dev_n;
    if (dist(so.state.p, map.goal) <= o.goal_tol) arrived = true;
    if (o.keep_samples) {
      out->steps.push_back(Step{so.state.t, so.state.p, so.state.v, so.state.a, so.mover_gap,
                                so.static_dist, dev, ao.events, static_cast<int>(ao.mode),
                                ao.a_des});
      for (uint32_t i = 0; i < so.n_movers; ++i) out->tracks[i].push_back(so.movers[i].p);
    }
  }
  m.success = arrived;
  m.collision = m.collision_mover || m.collision_static;
  m.mean_deviation = dev_n > 0 ? dev_sum / dev_n : 0.0;
  m.time = so.state.t;
  m.time_overhead = arrived ? m.time - m.plan_duration : 0.0;
  return true;
}

}  // namespace

void executed_vaj(const std::vector<tdo_vec3>& pos, double dt, double* max_v, double* max_a,
                  double* max_j) {
  std::vector<tdo_vec3> v, a;
  for (std::size_t i = 0; i + 1 < pos.size(); ++i)
    v.push_back(tdo_vec3{(pos[i + 1].x - pos[i].x) / dt, (pos[i + 1].y - pos[i].y) / dt,
                         (pos[i + 1].z - pos[i].z) / dt});
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    a.push_back(tdo_vec3{(v[i + 1].x - v[i].x) / dt, (v[i + 1].y - v[i].y) / dt,
                         (v[i + 1].z - v[i].z) / dt});
  const tdo_vec3 zero{0.0, 0.0, 0.0};
  for (const auto& x : v) *max_v = std::max(*max_v, dist(x, zero));
  for (const auto& x : a) *max_a = std::max(*max_a, dist(x, zero));
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    *max_j = std::max(*max_j, dist(a[i + 1], a[i]) / dt);
}

namespace {

// Step 5: executed v, a, j maxima by finite differences of the positions (paper eq. 15-17).
void executed_limits(const std::vector<tdo_vec3>& pos, double dt, Metrics* m) {
  executed_vaj(pos, dt, &m->max_speed, &m->max_acc, &m->max_jerk);
}

}  // namespace

bool run(const tdo_io::Map& map, const Options& o, Episode* out, std::string* error) {
  *out = Episode{};
  if (!map.has_start || !map.has_goal) {
    *error = map.path + ": the map has no start or goal";
    return false;
  }
  PlannerBox box;
  if (!plan_episode(map, o, &box, out, error)) return false;
  if (!out->m.planned) return true;

  tdo_apf_config acfg{};
  acfg.max_samples = static_cast<uint32_t>(out->plan.size());
  acfg.max_movers = std::max<uint32_t>(out->m.movers, 1u);
  acfg.nearest_window = 200u;  // 2 s of 0.01 s samples either way
  tdo_sim_config scfg{};
  scfg.max_movers = acfg.max_movers;
  Arena arena(tdo_apf_footprint(&acfg) + tdo_sim_footprint(&scfg));
  tdo_apf* apf = nullptr;
  tdo_sim* sim = nullptr;
  tdo_status st;
  if ((st = tdo_apf_init(&apf, &arena.a, &acfg)) != TDO_OK ||
      (st = tdo_sim_init(&sim, &arena.a, &scfg)) != TDO_OK) {
    *error = std::string("follower/simulator init: ") + tdo_status_str(st);
    return false;
  }
  if (!start_follower(map, o, box, apf, out, error)) return false;
  tdo_sim_params sp;
  if (!start_sim(map, o, box, sim, &sp, out, error)) return false;
  std::vector<tdo_vec3> pos;
  if (!fly(map, o, sp.dt, apf, sim, out, &pos, error)) return false;
  executed_limits(pos, sp.dt, &out->m);
  return true;
}

namespace {
nlohmann::json vec(tdo_vec3 p) { return nlohmann::json::array({p.x, p.y, p.z}); }
nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }
}  // namespace

std::string to_json(const Episode& e, const tdo_io::Map& map, const Options& o) {
  using nlohmann::json;
  const Metrics& m = e.m;
  json j;
  j["map"] = map.path;
  j["follower"] = follower_name(o.follower);
  j["start"] = vec(map.start);
  j["goal"] = vec(map.goal);
  j["plan_status"] = tdo_status_str(static_cast<tdo_status>(m.plan_status));
  const tdo_grid_desc& d = map.desc;
  j["bounds"] =
      json::array({vec(d.origin), vec(tdo_vec3{d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res,
                                               d.origin.z + d.nz * d.res})});
  json boxes = json::array();
  for (const auto& b : map.boxes) boxes.push_back(json::array({vec(b.min), vec(b.max)}));
  j["boxes"] = boxes;
  json mj;
  mj["success"] = m.success;
  mj["collision"] = m.collision;
  mj["collision_mover"] = m.collision_mover;
  mj["collision_static"] = m.collision_static;
  mj["min_mover_separation_m"] = num(m.min_mover_sep);
  mj["min_static_distance_m"] = num(m.min_static_dist);
  mj["max_deviation_m"] = m.max_deviation;
  mj["mean_deviation_m"] = m.mean_deviation;
  mj["plan_duration_s"] = m.plan_duration;
  mj["time_s"] = m.time;
  mj["time_overhead_s"] = m.time_overhead;
  mj["local_minimum_events"] = m.lm_events;
  mj["escapes"] = m.escapes;
  mj["escape_failed"] = m.escape_failed;
  mj["max_speed"] = m.max_speed;
  mj["max_acc"] = m.max_acc;
  mj["max_jerk"] = m.max_jerk;
  mj["steps"] = m.steps;
  mj["safety_filter_steps"] = m.safety_steps;
  mj["evasion_steps"] = m.evade_steps;
  mj["movers"] = m.movers;
  j["metrics"] = mj;
  json pj;
  pj["dt"] = e.params.dt;
  pj["k_a"] = e.params.k_a;
  pj["k_r"] = e.params.k_r;
  pj["k_r_static"] = e.params.k_r_static;
  pj["d_0_static"] = e.params.d_0_static;
  pj["d_0"] = e.params.d_0;
  pj["k_g"] = e.params.k_g;
  pj["k_d"] = e.params.k_d;
  pj["v_max"] = e.params.v_max;
  pj["a_max"] = e.params.a_max;
  pj["j_max"] = e.params.j_max;
  pj["vehicle_radius"] = o.vehicle_radius;
  pj["static_clearance"] = o.static_clearance;
  pj["goal_tol"] = o.goal_tol;
  j["params"] = pj;
  json plan = json::array();
  for (const auto& s : e.plan) plan.push_back(vec(s.p));
  j["plan"] = plan;
  json steps = json::array();
  for (const auto& s : e.steps) {
    steps.push_back(json{{"t", s.t},
                         {"p", vec(s.p)},
                         {"v", vec(s.v)},
                         {"a", vec(s.a)},
                         {"mover_gap", num(s.mover_gap)},
                         {"static_dist", num(s.static_dist)},
                         {"deviation", s.deviation},
                         {"events", s.events},
                         {"mode", s.mode},
                         {"a_des", vec(s.a_des)}});
  }
  j["steps"] = steps;
  json movers = json::array();
  for (std::size_t i = 0; i < e.tracks.size(); ++i) {
    json tr = json::array();
    for (const auto& p : e.tracks[i]) tr.push_back(vec(p));
    movers.push_back(json{{"radius", e.radii[i]}, {"track", tr}});
  }
  j["movers"] = movers;
  j["events"] = e.events;
  return j.dump(1);
}

}  // namespace tdo_episode
