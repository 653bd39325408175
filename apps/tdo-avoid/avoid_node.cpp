// tdo-avoid's node: decode -> adapter -> tdo_apf_run -> encode (avoid_node.h).
#include "avoid_node.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <utility>

#include "tdo_lcm/adapters.h"
#include "tdo_lcm/compact.h"
#include "tdo_lcm/map_update.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {
namespace {

bool valid_timeout(double s) { return s > 0.0 && s <= 1e6; }  // false for NaN

}  // namespace

AvoidNode::AvoidNode(Bus* bus, AvoidConfig cfg)
    : bus_(bus),
      cfg_(std::move(cfg)),
      watch_(steady_seconds(valid_timeout(cfg_.answer_timeout_s) ? cfg_.answer_timeout_s : 1.0)) {
  started_ = std::chrono::steady_clock::now();
  next_status_ = started_;
  next_tick_ = started_;
}

bool AvoidNode::start(std::string* error) {
  const char* problem = start_problem(bus_, apf_ != nullptr, cfg_.rate_hz);
  if (problem[0] != '\0') return fail_start(error, problem);
  if (!(cfg_.max_mover_shift_s >= 0.0)) return fail_start(error, "the mover shift must be >= 0");
  if (!valid_timeout(cfg_.answer_timeout_s))
    return fail_start(error, "the answer timeout must be in (0, 1e6] s");
  if (!(cfg_.replan_lead_s >= 0.0 && cfg_.replan_lead_s <= 60.0))
    return fail_start(error, "the replan lead must be in [0, 60] s");
  if (!(cfg_.replan_deviation_m > 0.0) || !std::isfinite(cfg_.replan_deviation_m) ||
      !(cfg_.replan_deviation_s >= 0.0) || !std::isfinite(cfg_.replan_deviation_s))
    return fail_start(error, "the replan deviation must be finite and > 0");
  if (!grid_.start(cfg_.max_nx, cfg_.max_ny, cfg_.max_nz, cfg_.max_boxes, cfg_.max_clearance_ratio,
                   error))
    return false;

  tdo_apf_params_default(&params_, cfg_.kind);
  params_.dt = 1.0 / cfg_.rate_hz;
  params_.v_max = cfg_.v_max;
  params_.a_max = cfg_.a_max;
  params_.j_max = cfg_.j_max;
  params_.vehicle_radius = cfg_.vehicle_radius;

  tdo_apf_config acfg{};
  acfg.max_samples = cfg_.max_samples;
  acfg.max_movers = cfg_.max_movers;
  acfg.nearest_window = cfg_.nearest_window;
  arena_bytes_ = tdo_apf_footprint(&acfg);
  if (arena_bytes_ == 0)
    return fail_start(error,
                      "invalid follower capacities (samples >= 2, movers >= 1, window >= 1)");
  const std::size_t allocated = alloc_node_arena(&arena_, arena_bytes_, error);
  if (allocated == 0) return false;
  tdo_arena arena;
  tdo_arena_init(&arena, arena_.get(), allocated);
  tdo_status st = tdo_apf_init(&apf_, &arena, &acfg);
  if (st != TDO_OK) {
    apf_ = nullptr;
    return fail_start(error, std::string("tdo_apf_init: ") + tdo_status_str(st));
  }
  // Let the library judge the parameters now (rate, limits) with a dummy straight task; the
  // follower stays unused until a real trajectory resets it.
  const tdo_sample probe[2] = {tdo_sample{0.0, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                               tdo_sample{1.0, {1, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
  tdo_apf_task task{};
  task.samples = probe;
  task.n_samples = 2;
  task.goal = probe[1].p;
  st = tdo_apf_reset(apf_, &params_, &task);
  if (st != TDO_OK)
    return fail_start(error,
                      std::string("the follower refuses the parameters (rate, limits, radius): ") +
                          tdo_status_str(st));

  const auto sub = [this](const std::string& ch, void (AvoidNode::*fn)(const void*, std::size_t)) {
    return bus_->subscribe(
        ch, [this, fn](const void* d, std::size_t n, const std::string&) { (this->*fn)(d, n); });
  };
  const bool ok = sub(cfg_.trajectory_channel, &AvoidNode::on_trajectory) &&
                  sub(cfg_.obstacles_channel, &AvoidNode::on_obstacles) &&
                  sub(cfg_.state_channel, &AvoidNode::on_state) &&
                  sub(cfg_.map_channel, &AvoidNode::on_map) &&
                  sub(cfg_.map_update_channel, &AvoidNode::on_map_update) &&
                  sub(cfg_.request_channel, &AvoidNode::on_request) &&
                  sub(cfg_.feasibility_channel, &AvoidNode::on_feasibility);
  return ok ? true : fail_start(error, "cannot subscribe");
}

void AvoidNode::refuse(const std::string& what, const Check& c) {
  count_refusal(&counters_, what, c.reason,
                c.reason == Reason::other_vehicle || c.reason == Reason::no_plan);
}

void AvoidNode::reset_task() {
  tdo_apf_task task{};
  task.samples = samples_.data();
  task.n_samples = static_cast<uint32_t>(samples_.size());
  task.goal = samples_.back().p;
  task.grid = have_map_ ? grid_.grid() : nullptr;
  task.t0 = task_t0_;
  const tdo_status st = tdo_apf_reset(apf_, &params_, &task);
  if (st == TDO_OK) {
    task_ready_ = true;
    return;
  }
  task_ready_ = false;
  have_task_ = false;
  refuse("trajectory",
         fail(Reason::library_error, std::string("tdo_apf_reset: ") + tdo_status_str(st) +
                                         " (request " + std::to_string(request_id_) + ")"));
}

void AvoidNode::on_trajectory(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::trajectory_t m{};
  Check c = decode(data, size, &m);
  if (c.ok() && m.vehicle_id != cfg_.vehicle_id)
    c = fail(Reason::other_vehicle, "trajectory for vehicle " + std::to_string(m.vehicle_id));
  if (c.ok()) watch_.arrived(m.request_id);  // delivered, whatever it holds
  if (c.ok() && replan_.phase == ReplanPhase::waiting && m.request_id == replan_.request_id) {
    on_replan_answer(m);  // the answer to this node's own replan (avoid_replan.cpp)
    return;
  }
  if (c.ok() && m.request_id >= cfg_.replan_id_base &&
      m.request_id < cfg_.replan_id_base + counters_.replans)
    c = fail(Reason::no_plan, "request " + std::to_string(m.request_id) +
                                  ": an answer to a replan given up (late, or superseded)");
  std::vector<tdo_sample> samples;
  if (c.ok()) c = trajectory_samples(m, &samples);
  if (!c.ok()) {
    refuse("trajectory", c);
    return;
  }
  // A plan from elsewhere (a ground station): followed from now, replanning starts afresh.
  replan_ = Replan{};
  template_set_ = false;
  for (const tdo::plan_request_t& r : requests_)
    if (r.request_id == m.request_id) {
      template_ = r;
      template_set_ = true;
    }
  samples_ = std::move(samples);
  near_idx_ = 0;
  request_id_ = m.request_id;
  have_task_ = true;
  task_ready_ = false;
  task_t0_set_ = have_state_;  // starts now, or at the first state
  task_t0_ = state_.t;
  if (task_t0_set_) reset_task();
  if (have_task_) ++counters_.trajectories;
  check_blocked();
}

// Checks of an answer and its samples: those it carries, else its compact form sampled at dt.
Check AvoidNode::trajectory_samples(const tdo::trajectory_t& m,
                                    std::vector<tdo_sample>* out) const {
  Check c = check_counts(m);
  const bool sampled = m.n_samples >= 2;
  if (c.ok() && (m.status_code != 0 || (!sampled && m.n_pieces == 0)))
    c = fail(Reason::no_plan, "request " + std::to_string(m.request_id) + ": status " + m.status +
                                  ", " + std::to_string(m.n_samples) + " samples, " +
                                  std::to_string(m.n_pieces) + " profile pieces");
  if (c.ok() && sampled && static_cast<uint64_t>(m.n_samples) > cfg_.max_samples)
    c = fail(Reason::over_capacity, std::to_string(m.n_samples) +
                                        " samples, more than the capacity of " +
                                        std::to_string(cfg_.max_samples));
  if (c.ok())
    c = sampled ? samples_from_msg(m, out) : samples_from_compact(m, cfg_.max_samples, out);
  return c;
}

void AvoidNode::on_request(const void* data, std::size_t size) {
  tdo::plan_request_t m{};
  if (!decode(data, size, &m).ok() || m.vehicle_id != cfg_.vehicle_id) return;
  watch_.promise(m.request_id, std::chrono::steady_clock::now());
  remember_request(m);
}

void AvoidNode::on_feasibility(const void* data, std::size_t size) {
  tdo::feasibility_t m{};
  if (!decode(data, size, &m).ok() || m.vehicle_id != cfg_.vehicle_id) return;
  watch_.promise(m.request_id, std::chrono::steady_clock::now());
}

void AvoidNode::on_obstacles(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::obstacles_t m{};
  Check c = decode(data, size, &m);
  std::vector<tdo_mover> movers;
  if (c.ok()) c = movers_from_msg(m, cfg_.vehicle_id, cfg_.max_movers, &movers);
  if (!c.ok()) {
    refuse("obstacles", c);
    return;
  }
  movers_ = std::move(movers);
  movers_utime_ = m.utime;
}

void AvoidNode::on_state(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::vehicle_state_t m{};
  Check c = decode(data, size, &m);
  tdo_vehicle_state s{};
  if (c.ok())
    c = vehicle_state_from_msg(m, cfg_.vehicle_id, utime_ref_set_ ? utime_ref_ : m.utime, &s);
  if (!c.ok()) {
    refuse("state", c);
    return;
  }
  if (!utime_ref_set_) {
    utime_ref_ = m.utime;
    utime_ref_set_ = true;
  }
  state_ = s;
  state_utime_ = m.utime;
  have_state_ = true;
  if (cfg_.lockstep) tick();
}

void AvoidNode::on_map(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::map_t m{};
  Check c = decode_map(data, size, cfg_.vehicle_id, &m);
  // The map in use, sent again (when stale: the whole map asked for, reloaded).
  if (c.ok() && have_map_ && m.map_id == map_id_ && !updates_.stale()) return;
  // Everything is checked before the grid is touched, so a bad map leaves the current one in place.
  if (c.ok()) c = map_check(m, grid_.capacity(), -1.0);
  if (!c.ok()) {
    refuse("map", c);
    return;
  }
  c = map_to_grid(m, grid_.capacity(), -1.0, grid_.grid());
  if (!c.ok()) {  // the grid was reset: no static repulsion until the next good map
    have_map_ = false;
    map_id_ = -1;
    updates_.clear();
    refuse("map", c);
  } else {
    have_map_ = true;
    map_id_ = m.map_id;
    updates_.on_map(m.map_id);
    ++counters_.maps_loaded;
  }
  // The follower must not step on a grid that changed under it: restart the task on the new one.
  if (task_ready_) reset_task();
  check_blocked();
  resume_after_map();
}

void AvoidNode::on_map_update(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::map_update_t u{};
  Check c = decode_map_update(data, size, cfg_.vehicle_id, &u);
  const bool was_stale = updates_.stale();
  if (c.ok()) c = updates_.order(u);
  if (c.ok()) {
    c = map_update_apply(u, grid_.grid(), nullptr);
    if (c.ok()) {
      updates_.applied(u.seq);
      ++counters_.updates_applied;
      if (task_ready_) reset_task();  // the follower's static repulsion sees the change
      check_blocked();
      resume_after_map();
      return;
    }
    updates_.mark_stale();
  }
  refuse("update", c);
  if (updates_.stale() && !was_stale)
    request_map(c.reason == Reason::gap ? "gap" : std::string("update_") + reason_str(c.reason));
}

void AvoidNode::request_map(const std::string& why) {
  bus_->publish(cfg_.map_request_channel,
                make_map_request("tdo-avoid", cfg_.vehicle_id, updates_, why, &map_request_seq_));
}

// The part of the task's samples that crosses a known obstacle (at the vehicle radius): exact
// segment queries between consecutive samples, bounded by the sample count.
void AvoidNode::check_blocked() {
  const double from = near_idx_ < samples_.size() ? samples_[near_idx_].t : 0.0;
  blocked_ = have_task_ && samples_blocked(samples_, from, &blocked_to_);
}

// Whether `samples` cross a known obstacle from trajectory time `from` on (tdo_replan_check over
// the rest of the trajectory, exact, at the vehicle radius; leaving the map's bounds counts);
// then the end time of the first piece that does in `blocked_to`. Samples the check refuses (not
// uniform in time) count as blocked.
bool AvoidNode::samples_blocked(const std::vector<tdo_sample>& samples, double from,
                                double* blocked_to) {
  if (!have_map_ || samples.size() < 2) return false;
  const tdo_grid* g = grid_.grid();
  if (tdo_grid_clearance(g) < 0.0) return false;  // no finished grid: nothing known
  tdo_replan_check_input in{};
  in.grid = g;
  in.samples = samples.data();
  in.n_samples = static_cast<uint32_t>(samples.size());
  in.t = std::max(0.0, from);
  in.horizon = std::max(0.0, samples.back().t - in.t);
  in.clearance = cfg_.vehicle_radius;
  tdo_replan_check_result r{};
  if (tdo_replan_check(&in, &r) != TDO_OK) {
    *blocked_to = samples.back().t;
    return true;
  }
  if (r.blocked == 0) return false;
  const std::size_t end = std::min<std::size_t>(r.index + 1, samples.size() - 1);
  *blocked_to = samples[end].t;
  return true;
}

bool AvoidNode::path_blocked() const {
  if (!blocked_ || !have_task_) return false;
  // Ahead when the vehicle's place on the trajectory (the sample nearest to it) has not passed
  // the blocked part: a vehicle held in front of it stays blocked however long it waits.
  return near_idx_ >= samples_.size() || samples_[near_idx_].t <= blocked_to_;
}

// The sample nearest to the vehicle, searched nearest_window samples each way from the last one
// (bounded; the vehicle moves less than that per step).
void AvoidNode::track_nearest() {
  if (!have_state_ || samples_.empty()) return;
  const std::size_t n = samples_.size(), w = cfg_.nearest_window;
  if (near_idx_ >= n) near_idx_ = 0;
  const std::size_t lo = near_idx_ > w ? near_idx_ - w : 0, hi = std::min(n - 1, near_idx_ + w);
  double best = HUGE_VAL;
  for (std::size_t k = lo; k <= hi; ++k) {
    const double dx = samples_[k].p.x - state_.p.x, dy = samples_[k].p.y - state_.p.y,
                 dz = samples_[k].p.z - state_.p.z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < best) {
      best = d2;
      near_idx_ = k;
    }
  }
}

void AvoidNode::publish_setpoint(const tdo_setpoint& sp, tdo_status st, int64_t request_id,
                                 Hold why) {
  yaw_ = heading_of(sp.v, yaw_);
  tdo::setpoint_t m{};
  const Check c =
      setpoint_to_msg(sp, state_utime_, cfg_.vehicle_id, setpoint_seq_, request_id, yaw_, st, &m);
  // Never "ok" while the trajectory ahead crosses a known obstacle, nor while stopped for a plan.
  static const struct {
    int32_t code;
    const char* name;
  } kHoldStatus[] = {{0, "ok"},
                     {kStatusPathBlocked, "path_blocked"},
                     {kStatusReplanning, "replanning"},
                     {kStatusNoWayThrough, "no_way_through"},
                     {kStatusReplanFailed, "replan_failed"}};
  if (why != Hold::idle) {
    m.status_code = kHoldStatus[static_cast<int>(why)].code;
    m.status = kHoldStatus[static_cast<int>(why)].name;
  }
  if (!c.ok()) {  // the library promises finite setpoints; count it rather than send garbage
    ++counters_.reasons[std::string("setpoint.") + reason_str(c.reason)];
    ++counters_.rejected;
    return;
  }
  bus_->publish(cfg_.setpoint_channel, m);
  ++setpoint_seq_;
  ++counters_.setpoints;
}

bool AvoidNode::tick() {
  if (apf_ == nullptr || !have_state_) return false;
  if (have_task_ && !task_ready_) {
    if (!task_t0_set_) {
      task_t0_ = state_.t;
      task_t0_set_ = true;
    }
    reset_task();
  }
  const auto t0 = std::chrono::steady_clock::now();
  track_nearest();
  movers_now_ = movers_;
  if (utime_ref_set_)
    movers_advance(&movers_now_, seconds_since(movers_utime_, utime_ref_), state_.t,
                   cfg_.max_mover_shift_s);
  if (blocked_ && !path_blocked()) check_blocked();  // past that piece: anything further on?
  if (replan_tick()) return true;  // a hover while a replan is in progress or after a stop
  if (task_ready_ && path_blocked()) {
    request_replan();
    hold(replan_.phase == ReplanPhase::stopped ? replan_.stop : Hold::blocked);
    return true;
  }
  if (task_ready_) {
    tdo_apf_input in{};
    in.state = state_;
    in.movers = movers_now_.empty() ? nullptr : movers_now_.data();
    in.n_movers = static_cast<uint32_t>(movers_now_.size());
    const tdo_status st = tdo_apf_run(apf_, &in, &last_out_);
    counters_.last_step_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (st == TDO_OK || st == TDO_ERR_LOCAL_MINIMUM) {
      if (st == TDO_OK)
        ++counters_.steps_ok;
      else
        ++counters_.steps_failed;
      if ((last_out_.events & TDO_APF_EVENT_GOAL_REACHED) != 0u) ++counters_.goal_reached;
      if ((last_out_.events & TDO_APF_EVENT_LM_DETECTED) != 0u) ++counters_.lm_detections;
      if (follower_wants_replan(st)) {  // brake from this state instead; the new plan takes over
        request_replan();
        hold(replan_.phase == ReplanPhase::stopped ? replan_.stop : Hold::replanning);
        return true;
      }
      publish_setpoint(last_out_.setpoint, st, request_id_);
      return true;
    }
    // Inputs are checked by the adapters, so this is unexpected: count it and hold.
    ++counters_.steps_failed;
    ++counters_.reasons[std::string("step.") + tdo_status_str(st)];
  }
  hold(Hold::idle);
  return true;
}

// One braking step from `s`: the hardest braking the limits allow (a_max above kBrakeSpeed, then
// proportional down to rest), through the library's motion rule.
tdo_setpoint AvoidNode::brake_step(const tdo_vehicle_state& s) const {
  constexpr double kBrakeSpeed = 0.5;  // m/s
  const double k = params_.a_max / kBrakeSpeed;
  const tdo_vec3 a_des{-k * s.v.x, -k * s.v.y, -k * s.v.z};
  tdo_setpoint sp{};
  tdo_motion_limit(&s, a_des, params_.v_max, params_.a_max, params_.j_max, params_.dt, &sp);
  return sp;
}

// Whether braking straight from the current state (brake_step until at rest, at most 5 s) keeps
// the vehicle centre more than its radius from the known geometry.
bool AvoidNode::brake_is_safe() {
  if (!have_map_) return true;
  const tdo_grid* g = grid_.grid();
  if (tdo_grid_clearance(g) < 0.0) return true;
  constexpr double kRest = 0.05, kMaxTime = 5.0;  // m/s, s
  tdo_vehicle_state s = state_;
  const int steps = static_cast<int>(kMaxTime / params_.dt);
  for (int k = 0; k < steps; ++k) {
    const tdo_setpoint sp = brake_step(s);
    s = tdo_vehicle_state{sp.t, sp.p, sp.v, sp.a};
    const double d = tdo_collision_point_distance(g, s.p, cfg_.vehicle_radius + 0.1);
    if (d >= 0.0 && d < cfg_.vehicle_radius + 0.02) return false;
    if (std::sqrt(s.v.x * s.v.x + s.v.y * s.v.y + s.v.z * s.v.z) < kRest) break;
  }
  return true;
}

// Brake to a hover with the library's motion rule: without a task (ok, the follower's damping),
// or, braking hard (brake_step), because the task ahead is blocked, a new plan is on its way or
// none could be had (a failed step with its named status).
void AvoidNode::hold(Hold why) {
  if (why != Hold::idle) {
    ++counters_.blocked_holds;
    ++counters_.steps_failed;
    tdo_setpoint sp = brake_step(state_);
    if (task_ready_ && !brake_is_safe()) {  // the follower's safety filter and wall terms instead
      tdo_apf_input in{};
      in.state = state_;
      in.movers = movers_now_.empty() ? nullptr : movers_now_.data();
      in.n_movers = static_cast<uint32_t>(movers_now_.size());
      const tdo_status st = tdo_apf_run(apf_, &in, &last_out_);
      if (st == TDO_OK || st == TDO_ERR_LOCAL_MINIMUM) sp = last_out_.setpoint;
      ++counters_.unsafe_brakes;
    }
    publish_setpoint(sp, TDO_OK, request_id_, why);
    return;
  }
  const double k = params_.k_d;
  const tdo_vec3 a_des{-k * state_.v.x, -k * state_.v.y, -k * state_.v.z};
  tdo_setpoint sp{};
  tdo_motion_limit(&state_, a_des, params_.v_max, params_.a_max, params_.j_max, params_.dt, &sp);
  ++counters_.holds;
  publish_setpoint(sp, TDO_OK, -1);
}

tdo::status_t AvoidNode::status_message() const {
  std::map<std::string, int64_t> reasons = counters_.reasons;
  if (updates_.stale()) reasons["state.map_stale"] = 1;  // outside the rejected + ignored sum
  if (path_blocked()) reasons["state.path_blocked"] = 1;
  if (const char* why = stop_status(); why[0] != '\0') reasons[std::string("state.") + why] = 1;
  StatusCounts c;
  c.map_id = map_id();
  c.received = counters_.received;
  c.maps_loaded = counters_.maps_loaded;
  c.answered = counters_.setpoints;
  c.succeeded = counters_.steps_ok;
  c.failed = counters_.steps_failed;
  c.rejected = counters_.rejected;
  c.ignored = counters_.ignored;
  c.last_plan_ms = counters_.last_step_ms;
  return make_status("tdo-avoid", status_seq_, cfg_.vehicle_id, started_, reasons, c);
}

void AvoidNode::publish_status() {
  send_status(bus_, cfg_.status_channel, status_message(), &status_seq_);
}

void AvoidNode::poll(std::chrono::steady_clock::time_point now) {
  if (const int64_t lost = watch_.expire(now); lost > 0) {
    counters_.missing += lost;
    counters_.rejected += lost;
    counters_.reasons["trajectory.missing"] += lost;
  }
  if (!cfg_.lockstep && now >= next_tick_) {
    tick();
    advance_deadline(&next_tick_, now, steady_seconds(1.0 / cfg_.rate_hz));
  }
  if (!(cfg_.heartbeat_period_s > 0.0) || now < next_status_) return;
  publish_status();
  advance_deadline(&next_status_, now, steady_seconds(cfg_.heartbeat_period_s));
}

std::chrono::steady_clock::time_point AvoidNode::next_due() const {
  auto t = std::chrono::steady_clock::time_point::max();
  if (cfg_.heartbeat_period_s > 0.0) t = next_status_;
  if (!cfg_.lockstep && next_tick_ < t) t = next_tick_;
  const auto deadline = watch_.next_deadline();
  if (deadline < t) t = deadline;
  return t;
}

}  // namespace tdo_lcm
