// One closed-loop episode with hidden columns, a range sensor, map updates and replanning.
#include "online.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>

#include "tdo_samples/samples.h"

namespace tdo_online {
namespace {

double dist(tdo_vec3 a, tdo_vec3 b) {
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// CPU time of this thread, ms (what the replanning itself costs, without waiting for a core).
double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

struct Arena {
  std::unique_ptr<unsigned char[]> mem;
  tdo_arena a{};
  explicit Arena(std::size_t n) : mem(new unsigned char[std::max<std::size_t>(n, 1)]) {
    tdo_arena_init(&a, mem.get(), n);
  }
};

/** The state of one online episode. */
struct Loop {
  const tdo_io::Map& map;
  const Options& o;
  Metrics* m;
  std::unique_ptr<unsigned char[]> planner_mem;
  tdo_planner* planner = nullptr;
  tdo_grid* grid = nullptr;  // the known map: the planner's and the follower's
  tdo_plan_params params{};
  std::vector<uint8_t> known;
  std::vector<uint32_t> revealed;
  std::vector<tdo_box> update_boxes;
  std::vector<tdo_sample> active, staged;
  bool pending = false;           // a switch is staged
  double pending_deadline = 0.0;  // s, vehicle time by which the staged switch must have happened
  double next_attempt = 0.0;      // s, vehicle time of the next allowed replanning attempt
  bool blocked = false;           // the last check found the active trajectory blocked
  tdo_replan_check_result mover_block{};  // the last check's mover conflict (blocked = 0: none)
  double next_mover_attempt = 0.0;        // s, vehicle time of the next mover replan allowed
  std::vector<tdo_voxel> mover_cells;     // temporary voxels of a mover's swept region
  double lookahead = 0.1;                 // s, the follower's reference lead over its clock
  Loop(const tdo_io::Map& mp, const Options& op, Metrics* me) : map(mp), o(op), m(me) {}
};

tdo_plan_params planner_params(Replanner r) {
  tdo_plan_params p;
  tdo_plan_params_default(&p);
  if (r == Replanner::MsfMtpo) {  // as tools/baselines' "msf-mtpo" preset
    tdo_plan_params_plain(&p);
    p.search = TDO_SEARCH_BIDIR;
    p.correction = TDO_CORRECT_GREEDY_LOS;
    p.smoothing = TDO_SMOOTHING_ARC;
    p.depth = TDO_PLAN_TRAJECTORY;
  }
  return p;
}

// The planner sized for the whole true map, loaded with the known boxes only.
bool setup_planner(Loop* L, std::string* error) {
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(L->map, L->o.clearance, 27u, 0u);
  if (L->o.stream_samples >= 0) cfg.cap.stream_samples = static_cast<uint32_t>(L->o.stream_samples);
  const std::size_t fp = tdo_planner_footprint(&cfg);
  if (fp == 0) {
    *error = "invalid planner configuration for this map";
    return false;
  }
  L->planner_mem.reset(new unsigned char[fp]);
  tdo_status st = tdo_planner_init(&L->planner, L->planner_mem.get(), fp, &cfg);
  if (st != TDO_OK) {
    *error = std::string("planner init: ") + tdo_status_str(st);
    return false;
  }
  L->grid = tdo_planner_grid(L->planner);
  tdo_io::Map known = L->map;
  known.boxes.clear();
  for (std::size_t i = 0; i < L->map.boxes.size(); ++i)
    if (L->known[i]) known.boxes.push_back(L->map.boxes[i]);
  st = tdo_io::load_into(known, L->grid, L->o.clearance);
  if (st != TDO_OK) {
    *error = std::string("map load: ") + tdo_status_str(st);
    return false;
  }
  L->params = planner_params(L->o.replanner);
  return true;
}

tdo_status plan(Loop* L, tdo_vec3 start, tdo_start_state state, std::vector<tdo_sample>* out) {
  tdo_plan_request req{};
  req.start = start;
  req.goal = L->map.goal;
  req.params = L->params;
  req.state = state;
  tdo_plan_result res{};
  const tdo_status st = tdo_planner_plan(L->planner, &req, &res);
  if (st != TDO_OK) return st;
  if (res.n_samples < 2u) return TDO_ERR_INFEASIBLE;
  return tdo_samples::plan_samples(L->planner, res, out);  // stored or regenerated
}

// Sense at p and apply what was revealed to the known grid. False with `error` when the update
// cannot be applied (capacity).
bool sense(Loop* L, tdo_vec3 p, uint32_t* n_revealed, std::string* error) {
  *n_revealed = 0;
  tdo_sense_input in{};
  in.p = p;
  in.range = L->o.sensor_range;
  in.boxes = L->map.boxes.data();
  in.n_boxes = static_cast<uint32_t>(L->map.boxes.size());
  in.known = L->known.data();
  in.revealed = L->revealed.data();
  in.max_revealed = static_cast<uint32_t>(L->revealed.size());
  tdo_sense_output so{};
  const tdo_status st = tdo_sense_run(&in, &so);
  if (st != TDO_OK) {  // the buffer holds every box: a full buffer is a bug here
    *error = std::string("sense: ") + tdo_status_str(st);
    return false;
  }
  if (so.n_revealed == 0u || L->grid == nullptr) {
    *n_revealed = so.n_revealed;
    return true;
  }
  tdo_grid_update up{};
  tdo_status us =
      tdo_sense_update(L->map.boxes.data(), in.n_boxes, L->revealed.data(), so.n_revealed,
                       L->update_boxes.data(), static_cast<uint32_t>(L->update_boxes.size()), &up);
  if (us == TDO_OK) us = tdo_grid_apply_update(L->grid, &up, nullptr);
  if (us != TDO_OK) {
    *error = std::string("map update: ") + tdo_status_str(us);
    return false;
  }
  *n_revealed = so.n_revealed;
  L->m->revealed += so.n_revealed;
  return true;
}

// Is the active trajectory blocked within the horizon from ref_time: on the known grid, or (when
// `movers` is given) by a mover's predicted position (constant velocity from `t_clock`)?
bool check_blocked(const Loop* L, double ref_time, const tdo_apf_input* movers = nullptr,
                   double t_clock = 0.0, tdo_replan_check_result* result = nullptr) {
  tdo_replan_check_input ci{};
  ci.grid = L->grid;
  ci.samples = L->active.data();
  ci.n_samples = static_cast<uint32_t>(L->active.size());
  ci.t = std::max(0.0, ref_time);
  ci.horizon = L->o.horizon;
  ci.clearance = std::max(0.0, L->o.clearance - L->o.check_slack);
  if (movers != nullptr) {
    ci.t = std::max(0.0, t_clock);
    ci.clearance = 0.0;  // the grid was checked at the clearance already
    ci.movers = movers->movers;
    ci.n_movers = movers->n_movers;
    ci.mover_clearance = L->o.vehicle_radius + L->o.mover_margin;
  }
  tdo_replan_check_result cr{};
  const bool blocked = tdo_replan_check(&ci, &cr) == TDO_OK && cr.blocked != 0 &&
                       (movers == nullptr || cr.cause == TDO_REPLAN_MOVER);
  if (result != nullptr) *result = cr;
  return blocked;
}

// A plan from the takeover state on the active trajectory (the switch at the takeover time). A
// refused one is counted by its status, and try_replan plans from the vehicle's state instead
// (which states the planner refuses: docs/design.md s.5, "Moving start").
tdo_status plan_takeover(Loop* L, const tdo_apf_output& out, double* t_switch) {
  tdo_replan_takeover_result tk{};
  tdo_status st = tdo_replan_takeover(L->active.data(), static_cast<uint32_t>(L->active.size()),
                                      std::max(0.0, out.ref_time), L->o.latency, &tk);
  *t_switch = tk.t;
  if (st == TDO_OK) st = plan(L, tk.p, tk.state, &L->staged);
  if (st != TDO_OK) L->m->failure_statuses.push_back(std::string("takeover:") + tdo_status_str(st));
  return st;
}

// A plan from the vehicle's own state (the switch at once). The simulator keeps it within the
// limits it can stop from (tdo_motion_limit); a state the planner still refuses (e.g.
// state_over_limits: its speed would have to rise above v_max while the acceleration is removed)
// is counted by its status and tried again retry_period later, like any failed replan.
tdo_status plan_from_vehicle(Loop* L, const tdo_apf_output& out, const tdo_vehicle_state& s,
                             double* t_switch) {
  *t_switch = std::max(0.0, out.ref_time);
  tdo_start_state vs{};
  vs.v = s.v;
  vs.a = s.a;
  const tdo_status st = plan(L, s.p, vs, &L->staged);
  if (st != TDO_OK) L->m->failure_statuses.push_back(std::string("vehicle:") + tdo_status_str(st));
  return st;
}

// One replanning attempt: from the takeover state, else (or with `vehicle_only`) from the
// vehicle's state. True when a plan is staged in the follower.
bool try_replan(Loop* L, tdo_apf* apf, const tdo_apf_output& out, const tdo_vehicle_state& s,
                bool vehicle_only) {
  const double t0 = now_ms(), c0 = cpu_ms();
  double t_switch = 0.0;
  tdo_status st = vehicle_only ? TDO_ERR_NOT_CONFIGURED : plan_takeover(L, out, &t_switch);
  if (st != TDO_OK) st = plan_from_vehicle(L, out, s, &t_switch);
  const double ms = now_ms() - t0, cpu = cpu_ms() - c0;
  if (st != TDO_OK) {
    ++L->m->replan_failures;
    return false;
  }
  tdo_apf_task task{};
  task.samples = L->staged.data();
  task.n_samples = static_cast<uint32_t>(L->staged.size());
  task.goal = L->map.goal;
  task.grid = L->grid;
  if (tdo_apf_switch(apf, &task, t_switch) != TDO_OK) {
    ++L->m->replan_failures;
    L->m->failure_statuses.push_back("switch_refused");
    return false;
  }
  L->pending = true;
  // The reference reaches the switch time after t_switch - ref_time of clock time; the clock
  // holds while the vehicle is pushed off, so a switch not taken half a second after that is
  // given up (the vehicle is replanned from its own state).
  L->pending_deadline = s.t + std::max(0.0, t_switch - out.ref_time) + 0.5;
  ++L->m->replans;
  L->m->replan_ms.push_back(ms);
  L->m->replan_cpu_ms.push_back(cpu);
  return true;
}

// A replan round a mover (docs/design.md s.4, "Replanning", movers): the region the blocking
// mover's sphere (radius + vehicle radius) sweeps over mover_window seconds around the time it
// blocks the trajectory is set as temporary voxels (only voxels that were free), a plan is made
// on that grid as for a blocked trajectory, and the same voxels are cleared again before the
// follower's next step: the grid is exactly as before. False with `error` only when the grid
// cannot be restored; *staged tells whether a plan was staged.
bool mover_replan(Loop* L, tdo_apf* apf, const tdo_apf_input& in, const tdo_apf_output& out,
                  bool* staged, std::string* error) {
  *staged = false;
  const double t0 = now_ms(), c0 = cpu_ms();
  const tdo_replan_check_result& cr = L->mover_block;
  const tdo_mover* mv = nullptr;
  for (uint32_t i = 0; i < in.n_movers; ++i)
    if (in.movers[i].id == cr.mover_id) mv = &in.movers[i];
  if (mv == nullptr) return true;
  // The movers are given at trajectory time t_clock (check_blocked); t_blocked is on that clock.
  const double t_clock = std::max(0.0, out.ref_time - L->lookahead);
  const double tc = std::max(0.0, cr.t_blocked - t_clock);
  tdo_replan_mover_region rg{};
  rg.mover = *mv;
  rg.t0 = std::max(0.0, tc - 0.5 * L->o.mover_window);
  rg.t1 = tc + 0.5 * L->o.mover_window;
  rg.pad = L->o.vehicle_radius;
  rg.keep_free = in.state.p;
  rg.keep_radius = L->o.mover_keep_free;
  uint32_t n = 0;
  if (tdo_replan_mover_voxels(L->grid, &rg, L->mover_cells.data(),
                              static_cast<uint32_t>(L->mover_cells.size()), &n) != TDO_OK ||
      n == 0u) {
    ++L->m->mover_skipped;
    return true;
  }
  tdo_grid_update up{};
  up.set = L->mover_cells.data();
  up.n_set = n;
  if (tdo_grid_apply_update(L->grid, &up, nullptr) != TDO_OK) {
    ++L->m->mover_skipped;
    return true;
  }
  *staged = try_replan(L, apf, out, in.state, false);
  up.set = nullptr;
  up.n_set = 0u;
  up.clear = L->mover_cells.data();
  up.n_clear = n;
  const tdo_status st = tdo_grid_apply_update(L->grid, &up, nullptr);
  if (st != TDO_OK) {
    *error = std::string("restoring the grid after a mover replan: ") + tdo_status_str(st);
    return false;
  }
  if (*staged) {  // the whole trigger-to-plan time: the region, the plan and the restore
    ++L->m->mover_replans;
    L->m->replan_ms.back() = now_ms() - t0;
    L->m->replan_cpu_ms.back() = cpu_ms() - c0;
  }
  return true;
}

// Sensing, checking and replanning of one step (before the follower's command is applied).
bool online_step(Loop* L, tdo_apf* apf, const tdo_apf_input& in, const tdo_apf_output& out,
                 bool sense_now, std::string* error) {
  const tdo_vehicle_state& s = in.state;
  if (sense_now) {
    uint32_t n = 0;
    if (!sense(L, s.p, &n, error)) return false;
    if (L->o.replanner != Replanner::None && !L->pending) {
      L->blocked = check_blocked(L, out.ref_time);
      if (L->blocked) ++L->m->triggers_blocked;
      // Movers over the same horizon: counted; with mover_window > 0 replanned round the
      // blocking mover's swept region (below), else left to the follower's evasion.
      L->mover_block = tdo_replan_check_result{};
      if (!L->blocked && in.n_movers > 0u &&
          check_blocked(L, out.ref_time, &in, out.ref_time - L->lookahead, &L->mover_block))
        ++L->m->mover_conflicts;
    }
  }
  if (sense_now && L->o.replanner != Replanner::None && L->o.mover_window > 0.0 && !L->pending &&
      !L->blocked && L->mover_block.blocked != 0 && s.t >= L->next_mover_attempt &&
      s.t >= L->next_attempt) {
    bool staged = false;
    if (!mover_replan(L, apf, in, out, &staged, error)) return false;
    L->mover_block = tdo_replan_check_result{};
    L->next_mover_attempt = s.t + L->o.mover_period;
    if (!staged) L->next_attempt = s.t + L->o.retry_period;
  }
  if (L->o.replanner == Replanner::None) return true;
  bool stale = false;
  if (L->pending) {
    if (s.t <= L->pending_deadline || s.t < L->next_attempt) return true;
    stale = true;
    ++L->m->stale_switches;
  }
  const bool stuck =
      (out.events & TDO_APF_EVENT_LM_DETECTED) != 0u || out.mode == TDO_APF_MODE_STUCK;
  if (stuck) ++L->m->triggers_stuck;
  if (stale || ((L->blocked || stuck) && s.t >= L->next_attempt)) {
    if (try_replan(L, apf, out, s, stale)) {
      L->blocked = false;
    } else {
      L->next_attempt = s.t + L->o.retry_period;
    }
  }
  return true;
}

struct Flight {
  Arena arena;
  tdo_apf* apf = nullptr;
  tdo_sim* sim = nullptr;
  explicit Flight(std::size_t bytes) : arena(bytes) {}
};

// Follower capacities: any plan the planner can return, the map's movers, room to switch.
tdo_apf_config follower_config(const Loop& L) {
  tdo_apf_config acfg{};
  acfg.max_samples =
      std::max<uint32_t>(tdo_io::capacity_for(L.map, L.o.clearance, 27u, 0u).max_samples, 2u);
  acfg.max_movers = std::max<uint32_t>(static_cast<uint32_t>(L.map.movers.size()), 1u);
  acfg.nearest_window = 200u;  // 2 s of 0.01 s samples either way
  acfg.switching = 1u;
  return acfg;
}

bool start_flight(Loop* L, Flight* f, const tdo_apf_config& acfg, const tdo_sim_config& scfg,
                  tdo_apf_params* prm, std::string* error) {
  tdo_status st;
  if ((st = tdo_apf_init(&f->apf, &f->arena.a, &acfg)) != TDO_OK ||
      (st = tdo_sim_init(&f->sim, &f->arena.a, &scfg)) != TDO_OK) {
    *error = std::string("follower/simulator init: ") + tdo_status_str(st);
    return false;
  }
  tdo_apf_params_default(prm, TDO_FOLLOWER_EAPF);
  prm->vehicle_radius = L->o.vehicle_radius;
  prm->v_max = L->params.v_max;
  prm->a_max = L->params.a_max;
  prm->j_max = L->params.j_max;
  prm->goal_tol = L->o.goal_tol;
  L->lookahead = prm->lookahead;
  tdo_apf_task task{};
  task.samples = L->active.data();
  task.n_samples = static_cast<uint32_t>(L->active.size());
  task.goal = L->map.goal;
  task.grid = L->grid;
  if ((st = tdo_apf_reset(f->apf, prm, &task)) != TDO_OK) {
    *error = std::string("follower reset: ") + tdo_status_str(st);
    return false;
  }
  std::vector<tdo_mover> movers;
  if (L->o.movers)
    for (const tdo_io::Mover& mv : L->map.movers)
      movers.push_back(tdo_mover{static_cast<uint32_t>(mv.id), mv.pos, mv.vel, mv.radius});
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.dt = prm->dt;
  sp.v_max = prm->v_max;
  sp.a_max = prm->a_max;
  sp.j_max = prm->j_max;
  const tdo_grid_desc& d = L->map.desc;
  sp.bounds.min = d.origin;
  sp.bounds.max =
      tdo_vec3{d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res, d.origin.z + d.nz * d.res};
  sp.vehicle_radius = L->o.vehicle_radius;
  sp.grid = nullptr;  // static contacts are measured against the true world: every box, exactly
  sp.boxes = L->map.boxes.data();
  sp.n_boxes = static_cast<uint32_t>(L->map.boxes.size());
  sp.static_clearance = L->o.static_clearance;
  tdo_vehicle_state s0{};
  s0.p = L->map.start;
  if ((st = tdo_sim_reset(f->sim, &sp, &s0, movers.data(), static_cast<uint32_t>(movers.size()))) !=
      TDO_OK) {
    *error = std::string("simulator reset: ") + tdo_status_str(st);
    return false;
  }
  return true;
}

bool fly(Loop* L, Flight* f, double dt, std::vector<tdo_vec3>* pos, std::string* error) {
  Metrics& m = *L->m;
  const double t_limit = L->o.time_factor * m.plan_duration + L->o.time_extra;
  const auto max_steps = static_cast<uint32_t>(std::ceil(t_limit / dt));
  const auto sense_every = static_cast<uint32_t>(std::max(1.0, std::round(L->o.sense_period / dt)));
  tdo_sim_output so{};
  tdo_sim_get(f->sim, &so);
  pos->assign(1, so.state.p);
  for (uint32_t k = 0; k < max_steps; ++k) {
    tdo_apf_input in{};
    in.state = so.state;
    in.movers = so.movers;
    in.n_movers = so.n_movers;
    tdo_apf_output ao;
    const tdo_status st = tdo_apf_run(f->apf, &in, &ao);
    if (st != TDO_OK && st != TDO_ERR_LOCAL_MINIMUM) {
      *error = std::string("follower step: ") + tdo_status_str(st);
      return false;
    }
    if ((ao.events & TDO_APF_EVENT_SWITCHED) != 0u) {
      L->active.swap(L->staged);
      L->pending = false;
      ++m.switches;
    }
    if ((ao.events & TDO_APF_EVENT_ESCAPE_FAILED) != 0u) m.escape_failed = true;
    if (!online_step(L, f->apf, in, ao, k % sense_every == 0u, error)) return false;
    tdo_sim_input si{};
    si.setpoint = ao.setpoint;
    tdo_sim_run(f->sim, &si, &so);
    ++m.steps;
    pos->push_back(so.state.p);
    m.min_true_static = std::min(m.min_true_static, so.static_dist);
    m.min_mover_gap = std::min(m.min_mover_gap, so.mover_gap);
    if (so.collision_static) m.collision_static = true;
    if (so.collision_mover) m.collision_mover = true;
    if (dist(so.state.p, L->map.goal) <= L->o.goal_tol) {
      m.success = true;
      break;
    }
  }
  m.time = so.state.t;
  return true;
}

}  // namespace

const char* replanner_name(Replanner r) {
  return r == Replanner::None ? "none" : (r == Replanner::MsfMtpo ? "msf-mtpo" : "tdo");
}

bool run(const tdo_io::Map& map, const Options& o, Metrics* out, std::string* error) {
  *out = Metrics{};
  if (!map.has_start || !map.has_goal) {
    *error = map.path + ": the map has no start or goal";
    return false;
  }
  Loop L(map, o, out);
  const auto n = static_cast<uint32_t>(map.boxes.size());
  L.known.assign(n, 1u);
  if (tdo_sense_hide(n, o.unknown, o.hide_seed, L.known.data()) != TDO_OK) {
    *error = "the unknown fraction must be in [0, 1]";
    return false;
  }
  for (uint8_t k : L.known) out->hidden += k == 0u;
  L.revealed.assign(std::max<uint32_t>(n, 1u), 0u);
  L.update_boxes.assign(std::max<uint32_t>(n, 1u), tdo_box{});
  L.mover_cells.assign(o.mover_window > 0.0 ? o.mover_cells : 0u, tdo_voxel{});
  if (!setup_planner(&L, error)) return false;
  uint32_t first_seen = 0;
  if (!sense(&L, map.start, &first_seen, error)) return false;  // what the start already sees
  const tdo_status st = plan(&L, map.start, tdo_start_state{}, &L.active);
  out->plan_status = static_cast<int>(st);
  if (st != TDO_OK) return true;
  out->planned = true;
  out->plan_duration = L.active.back().t;
  out->v_limit = L.params.v_max;
  out->a_limit = L.params.a_max;
  out->j_limit = L.params.j_max;
  const tdo_apf_config acfg = follower_config(L);
  tdo_sim_config scfg{};
  scfg.max_movers = acfg.max_movers;
  Flight f(tdo_apf_footprint(&acfg) + tdo_sim_footprint(&scfg));
  tdo_apf_params prm;
  if (!start_flight(&L, &f, acfg, scfg, &prm, error)) return false;
  std::vector<tdo_vec3> pos;
  if (!fly(&L, &f, prm.dt, &pos, error)) return false;
  out->collision = out->collision_static || out->collision_mover;
  tdo_episode::executed_vaj(pos, prm.dt, &out->max_speed, &out->max_acc, &out->max_jerk);
  return true;
}

}  // namespace tdo_online
