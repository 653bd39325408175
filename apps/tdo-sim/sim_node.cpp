// tdo-sim's node: decode -> adapter -> tdo_sim_run -> encode (sim_node.h).
#include "sim_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <utility>

#include "tdo_io/map_io.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {
SimNode::SimNode(Bus* bus, SimConfig cfg) : bus_(bus), cfg_(std::move(cfg)) {
  started_ = std::chrono::steady_clock::now();
  next_status_ = started_;
  next_tick_ = started_;
  next_map_ = started_;
  setpoint_wall_ = started_;
}

bool SimNode::start(std::string* error) {
  const char* problem = start_problem(bus_, sim_ != nullptr, cfg_.rate_hz);
  if (problem[0] != '\0') return fail_start(error, problem);
  if (!(cfg_.map_clearance >= 0.0) || !std::isfinite(cfg_.map_clearance))
    return fail_start(error, "the map clearance must be finite and >= 0");
  if (cfg_.map_id < 0) return fail_start(error, "the map id must be >= 0");
  if (!std::isfinite(cfg_.brake_gain))
    return fail_start(error, "the brake gain must be finite (< 0: the follower's braking)");
  if (!(cfg_.setpoint_wait_s >= 0.0) || !std::isfinite(cfg_.setpoint_wait_s))
    return fail_start(error, "the setpoint wait must be finite and >= 0");
  if (!(cfg_.setpoint_max_age_steps >= 0.0) || !std::isfinite(cfg_.setpoint_max_age_steps))
    return fail_start(error, "the setpoint max age must be finite and >= 0");
  if (cfg_.has_goal) {
    has_goal_ = true;
    goal_ = cfg_.goal;
  }

  // The map file: geometry for the collision check and the message, movers, default start.
  tdo_io::Map map;
  std::vector<tdo_mover> movers;
  if (!cfg_.map_file.empty()) {
    tdo_io::LoadOptions lo;
    lo.resolution = cfg_.map_resolution;
    std::string why;
    if (!tdo_io::load_map(cfg_.map_file, lo, &map, &why)) return fail_start(error, why);
    const tdo_grid_desc& d = map.desc;
    if (!grid_.start(d.nx, d.ny, d.nz, static_cast<uint32_t>(map.boxes.size()),
                     cfg_.map_clearance / d.res, error))
      return false;
    const tdo_status st = tdo_io::load_into(map, grid_.grid(), cfg_.map_clearance);
    if (st != TDO_OK)
      return fail_start(error,
                        cfg_.map_file + ": the library refuses the map: " + tdo_status_str(st));
    const Check c = map_msg_from_map(map, cfg_.map_clearance, &map_msg_);
    if (!c.ok())
      return fail_start(error, cfg_.map_file + ": " + reason_str(c.reason) + ": " + c.detail);
    map_msg_.map_id = cfg_.map_id;
    map_msg_.vehicle_id = -1;
    map_id_ = cfg_.map_id;
    has_map_ = true;
    has_voxels_ = !map.voxels.empty();
    true_boxes_ = map.boxes;  // the static check's boxes (exact), hidden or not
    if (!cfg_.has_goal) {
      has_goal_ = map.has_goal;
      goal_ = map.goal;
    }
    if (cfg_.movers)
      for (const tdo_io::Mover& m : map.movers)
        movers.push_back(tdo_mover{static_cast<uint32_t>(m.id), m.pos, m.vel, m.radius});
  }
  tdo_box bounds{{0.0, 0.0, 0.0}, {50.0, 50.0, 20.0}};
  if (cfg_.has_bounds) {
    bounds = cfg_.bounds;
  } else if (has_map_) {
    const tdo_grid_desc& d = map.desc;
    bounds.min = d.origin;
    bounds.max =
        tdo_vec3{d.origin.x + d.nx * d.res, d.origin.y + d.ny * d.res, d.origin.z + d.nz * d.res};
  }
  tdo_vehicle_state s0{};
  if (cfg_.has_start)
    s0.p = cfg_.start;
  else if (has_map_ && map.has_start)
    s0.p = map.start;
  else
    s0.p = tdo_vec3{0.5 * (bounds.min.x + bounds.max.x), 0.5 * (bounds.min.y + bounds.max.y),
                    0.5 * (bounds.min.z + bounds.max.z)};
  if (movers.size() > cfg_.max_movers)
    return fail_start(error, std::to_string(movers.size()) + " movers, more than --max-movers " +
                                 std::to_string(cfg_.max_movers));

  tdo_sim_config scfg{};
  scfg.max_movers = cfg_.max_movers;
  arena_bytes_ = tdo_sim_footprint(&scfg);
  if (arena_bytes_ == 0) return fail_start(error, "invalid simulator capacity (movers >= 1)");
  const std::size_t allocated = alloc_node_arena(&arena_, arena_bytes_, error);
  if (allocated == 0) return false;
  tdo_arena arena;
  tdo_arena_init(&arena, arena_.get(), allocated);
  tdo_status st = tdo_sim_init(&sim_, &arena, &scfg);
  if (st != TDO_OK) {
    sim_ = nullptr;
    return fail_start(error, std::string("tdo_sim_init: ") + tdo_status_str(st));
  }
  tdo_sim_params sp;
  tdo_sim_params_default(&sp);
  sp.dt = 1.0 / cfg_.rate_hz;
  sp.v_max = cfg_.v_max;
  sp.a_max = cfg_.a_max;
  sp.j_max = cfg_.j_max;
  sp.bounds = bounds;
  sp.vehicle_radius = cfg_.vehicle_radius;
  sp.static_clearance = cfg_.static_clearance;
  // The true world's contact check, shared with tdo-sim-run: the file's boxes exactly
  // (tdo_sense_distance); the grid only for a file of voxels (.3dmap, OcTrees).
  sp.grid = has_voxels_ ? grid_.grid() : nullptr;
  sp.boxes = true_boxes_.data();
  sp.n_boxes = static_cast<uint32_t>(true_boxes_.size());
  sp.seed = cfg_.seed;
  sp.accel_noise = cfg_.accel_noise;
  // By default the braking the follower's safety filter rolls out (apf.h, brake_des): a_max
  // against v, proportional below v_lin = a_max^2 / (2 j_max), i.e. a = -(a_max / v_lin) v limited
  // to a_max: a late step brakes the way the last command's roll-out was checked to be safe.
  sp.brake_gain = cfg_.brake_gain >= 0.0 ? cfg_.brake_gain : 2.0 * cfg_.j_max / cfg_.a_max;
  // Lock-step waits for the follower: its setpoints cannot fall behind the clock.
  sp.setpoint_max_age = cfg_.lockstep ? 0.0 : cfg_.setpoint_max_age_steps / cfg_.rate_hz;
  st = tdo_sim_reset(sim_, &sp, &s0, movers.data(), static_cast<uint32_t>(movers.size()));
  if (st != TDO_OK)
    return fail_start(error,
                      std::string("the simulator refuses the set-up (rate, limits, bounds, start, "
                                  "movers): ") +
                          tdo_status_str(st));
  utime0_ = cfg_.start_utime != 0 ? cfg_.start_utime : wall_utime();
  const tdo_sim_output out = current();
  counters_.min_mover_gap = out.mover_gap;
  counters_.min_static_dist = out.static_dist;

  if (!start_sensing(map, error)) return false;  // the known part of the map as map_msg_
  const bool ok =
      bus_->subscribe(cfg_.setpoint_channel, [this](const void* d, std::size_t n,
                                                    const std::string&) { on_setpoint(d, n); }) &&
      (!sensing_ || bus_->subscribe(cfg_.map_request_channel,
                                    [this](const void* d, std::size_t n, const std::string&) {
                                      on_map_request(d, n);
                                    }));
  if (!ok) return fail_start(error, "cannot subscribe");
  if (cfg_.request_goal && !has_goal_)
    return fail_start(error, "a plan request needs a goal (--goal, or a map file with one)");
  publish_map();
  if (cfg_.request_goal && cfg_.lockstep) publish_request();
  publish_state();
  const auto now = std::chrono::steady_clock::now();
  next_tick_ = now + steady_seconds(1.0 / cfg_.rate_hz);
  next_map_ = now + steady_seconds(cfg_.map_period_s > 0.0 ? cfg_.map_period_s : 0.0);
  request_at_ = now + steady_seconds(cfg_.request_delay_s > 0.0 ? cfg_.request_delay_s : 0.0);
  return true;
}

tdo_sim_output SimNode::current() const {
  tdo_sim_output out{};
  if (sim_ != nullptr) tdo_sim_get(sim_, &out);
  return out;
}

bool SimNode::goal(tdo_vec3* out) const {
  if (!has_goal_) return false;
  *out = goal_;
  return true;
}

void SimNode::refuse(const std::string& what, const Check& c) {
  count_refusal(&counters_, what, c.reason, c.reason == Reason::other_vehicle);
}

void SimNode::on_setpoint(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::setpoint_t m{};
  Check c = decode(data, size, &m);
  tdo_setpoint sp{};
  if (c.ok()) c = setpoint_from_msg(m, cfg_.vehicle_id, utime0_, &sp);
  if (!c.ok()) {
    refuse("setpoint", c);
    return;
  }
  // An answer to a state already passed: never flown while steps wait for their answer.
  if (waits_for_answers() && m.utime < state_utime_) {
    ++counters_.late_setpoints;
    ++counters_.reasons["setpoint.late"];
  }
  setpoint_ = sp;
  setpoint_utime_ = m.utime;
  yaw_ = m.yaw;
  have_setpoint_ = true;
  setpoint_wall_ = std::chrono::steady_clock::now();
  ++counters_.setpoints;
  if (cfg_.lockstep) step();
}

void SimNode::step() { step_at(std::chrono::steady_clock::now()); }

bool SimNode::follower_alive(std::chrono::steady_clock::time_point now) const {
  return have_setpoint_ &&
         (cfg_.lockstep || now - setpoint_wall_ <= steady_seconds(cfg_.setpoint_timeout_s));
}

void SimNode::step_at(std::chrono::steady_clock::time_point now) {
  if (sim_ == nullptr) return;
  tdo_sim_input in{};
  in.setpoint = setpoint_;  // the library judges its age against the simulated clock
  const bool came = follower_alive(now);
  // Timed steps that wait for their answer fly nothing else: without it the step is late.
  const bool late = came && waits_for_answers() && !answered();
  tdo_sim_output out{};
  const auto t0 = std::chrono::steady_clock::now();
  // None came lately, or not the answer to this state: brake.
  const tdo_status st = came && !late ? tdo_sim_run(sim_, &in, &out) : tdo_sim_hold(sim_, &out);
  counters_.last_step_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (st != TDO_OK && st != TDO_ERR_SETPOINT_STALE) {  // not after a good reset; count it
    ++counters_.reasons[std::string("step.") + tdo_status_str(st)];
    return;
  }
  note_stale(st == TDO_ERR_SETPOINT_STALE, out);
  note_late(late, out);
  if (out.braked != 0) ++counters_.brakes;
  ++counters_.steps;
  if (out.collision_mover != 0) ++counters_.mover_collisions;
  if (out.collision_static != 0) ++counters_.static_collisions;
  if (out.collision_mover != 0 || out.collision_static != 0) ++counters_.collision_steps;
  counters_.min_mover_gap = std::min(counters_.min_mover_gap, out.mover_gap);
  counters_.min_static_dist = std::min(counters_.min_static_dist, out.static_dist);
  if (sensing_) sense();  // before the state: a lock-step follower steps as soon as it arrives
  publish_state();
}

void SimNode::note_stale(bool stale, const tdo_sim_output& out) {
  if (stale) {
    ++counters_.stale_steps;
    ++counters_.reasons[std::string("step.") + tdo_status_str(TDO_ERR_SETPOINT_STALE)];
  }
  if (cfg_.log && stale != stale_)
    std::fprintf(stderr,
                 stale ? "tdo-sim: %s at t = %.2f s: the setpoint is %.3f s old (more than %g "
                         "steps): braking to a hover\n"
                       : "tdo-sim: %s ended at t = %.2f s (setpoint %.3f s old, bound %g "
                         "steps): flying the setpoints again\n",
                 tdo_status_str(TDO_ERR_SETPOINT_STALE), out.state.t, out.setpoint_age,
                 cfg_.setpoint_max_age_steps);
  stale_ = stale;
}

void SimNode::note_late(bool late, const tdo_sim_output& out) {
  if (late) {
    ++counters_.late_steps;
    ++counters_.reasons["step.setpoint_late"];
  }
  if (cfg_.log && late != late_)
    std::fprintf(stderr,
                 late ? "tdo-sim: setpoint_late at t = %.2f s: no answer to the state within %g s: "
                        "braking\n"
                      : "tdo-sim: setpoint_late ended at t = %.2f s (wait %g s): flying the "
                        "answers again\n",
                 out.state.t, cfg_.setpoint_wait_s);
  late_ = late;
}

void SimNode::publish_state() {
  if (sim_ == nullptr) return;
  const tdo_sim_output out = current();
  const double yaw = have_setpoint_ ? yaw_ : heading_of(out.state.v, 0.0);
  tdo::vehicle_state_t s{};
  Check c = vehicle_state_to_msg(out.state, utime0_, cfg_.vehicle_id, state_seq_, yaw, &s);
  tdo::obstacles_t o{};
  if (c.ok()) c = movers_to_msg(out.movers, out.n_movers, s.utime, -1, obstacles_seq_, &o);
  if (!c.ok()) {
    ++counters_.reasons[std::string("state.") + reason_str(c.reason)];
    return;
  }
  // Movers first: a lock-step follower steps as soon as the state arrives.
  bus_->publish(cfg_.obstacles_channel, o);
  bus_->publish(cfg_.state_channel, s);
  state_utime_ = s.utime;
  ++obstacles_seq_;
  ++state_seq_;
}

void SimNode::publish_map() {
  if (!has_map_) return;
  map_msg_.utime = wall_utime();
  if (!check_counts(map_msg_).ok()) return;
  bus_->publish(cfg_.map_channel, map_msg_);
  ++counters_.maps_published;
}

bool SimNode::publish_request() {
  if (sim_ == nullptr || !has_goal_) return false;
  tdo_plan_request req{};
  tdo_plan_params_default(&req.params);
  req.start = current().state.p;
  req.goal = goal_;
  tdo::plan_request_t m{};
  plan_request_to_msg(req, -1.0, &m);  // clearance: the map's hint
  m.utime = wall_utime();
  m.request_id = 1;
  m.vehicle_id = cfg_.vehicle_id;
  m.map_id = has_map_ ? map_id_ : -1;
  bus_->publish(cfg_.request_channel, m);
  requested_ = true;
  return true;
}

tdo::status_t SimNode::status_message() const {
  StatusCounts c;
  c.map_id = has_map_ ? map_id_ : -1;
  c.received = counters_.received;
  c.maps_loaded = has_map_ ? 1 : 0;
  c.answered = counters_.steps;
  c.succeeded = counters_.steps - counters_.collision_steps;
  c.failed = counters_.collision_steps;
  c.rejected = counters_.rejected;
  c.ignored = counters_.ignored;
  c.last_plan_ms = counters_.last_step_ms;
  return make_status("tdo-sim", status_seq_, cfg_.vehicle_id, started_, counters_.reasons, c);
}

void SimNode::publish_status() {
  send_status(bus_, cfg_.status_channel, status_message(), &status_seq_);
}

void SimNode::poll(std::chrono::steady_clock::time_point now) {
  if (!cfg_.lockstep && now >= next_tick_) {
    // Wait (bounded by setpoint_wait_s) for the answer to the current state while the follower
    // is alive; then step with it, or late.
    if (!waiting_) wait_until_ = next_tick_ + steady_seconds(cfg_.setpoint_wait_s);
    const bool wait =
        waits_for_answers() && follower_alive(now) && !answered() && now < wait_until_;
    if (wait && !waiting_) ++counters_.waits;  // once per tick
    waiting_ = wait;
    if (!waiting_) {
      step_at(now);
      advance_deadline(&next_tick_, now, steady_seconds(1.0 / cfg_.rate_hz));
    }
  }
  if (!cfg_.lockstep && has_map_ && cfg_.map_period_s > 0.0 && now >= next_map_) {
    publish_map();
    next_map_ = now + steady_seconds(cfg_.map_period_s);
  }
  if (cfg_.request_goal && !requested_ && now >= request_at_) publish_request();
  if (!(cfg_.heartbeat_period_s > 0.0) || now < next_status_) return;
  publish_status();
  advance_deadline(&next_status_, now, steady_seconds(cfg_.heartbeat_period_s));
}

std::chrono::steady_clock::time_point SimNode::next_due() const {
  auto t = std::chrono::steady_clock::time_point::max();
  if (cfg_.heartbeat_period_s > 0.0) t = next_status_;
  if (!cfg_.lockstep) t = std::min(t, waiting_ ? wait_until_ : next_tick_);
  if (!cfg_.lockstep && has_map_ && cfg_.map_period_s > 0.0) t = std::min(t, next_map_);
  if (cfg_.request_goal && !requested_) t = std::min(t, request_at_);
  return t;
}

}  // namespace tdo_lcm
