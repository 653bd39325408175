// tdo-avoid's replanning (avoid_node.h, docs/lcm.md "Replanning"): when the trajectory followed is
// blocked, or the follower finds a local minimum or stays off the path, the node brakes, asks the
// planner for a new plan from the state the braking will have reached at the takeover time, and
// follows that plan from then on; no way through, or no usable answer after max_replans requests,
// is a safe stop with a named status.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "avoid_node.h"
#include "tdo_lcm/node_status.h"

namespace tdo_lcm {
namespace {

constexpr double kRetryAfterS = 1.0;  // s at rest after replan_failed before asking again

}  // namespace

void AvoidNode::remember_request(const tdo::plan_request_t& m) {
  requests_.push_back(m);
  if (requests_.size() > kMaxTemplates) requests_.erase(requests_.begin());
}

bool AvoidNode::have_template() const { return cfg_.replan && template_set_; }

const char* AvoidNode::stop_status() const {
  switch (replan_.phase) {
    case ReplanPhase::stopped:
      return replan_.stop == Hold::no_way_through ? "no_way_through" : "replan_failed";
    case ReplanPhase::waiting:
    case ReplanPhase::pending:
      return "replanning";
    case ReplanPhase::idle:
      break;
  }
  return "";
}

// The follower asks for a new plan: a local minimum (detected, or the escape failed), or off the
// path by more than replan_deviation_m for replan_deviation_s.
bool AvoidNode::follower_wants_replan(tdo_status st) {
  if (!have_template()) return false;
  if (replan_.wanted) return true;
  bool want = st == TDO_ERR_LOCAL_MINIMUM || (last_out_.events & TDO_APF_EVENT_LM_DETECTED) != 0u;
  if (last_out_.terms.deviation > cfg_.replan_deviation_m) {
    if (replan_.off_since < 0.0) replan_.off_since = state_.t;
    if (state_.t - replan_.off_since >= cfg_.replan_deviation_s) want = true;
  } else {
    replan_.off_since = -1.0;
  }
  replan_.wanted = want;
  return want;
}

// Ask for a new plan from the state the braking (brake_step, the rule hold() applies) reaches at
// the takeover time, replan_lead_s from now, rounded up to whole steps.
void AvoidNode::request_replan() {
  if (!have_template() || replan_.phase != ReplanPhase::idle) return;
  if (replan_.attempts >= cfg_.max_replans ||
      counters_.replans >= static_cast<int64_t>(cfg_.max_replans_total)) {
    replan_stop(Hold::replan_failed);
    return;
  }
  const double lead = cfg_.replan_lead_s > 0.0 ? cfg_.replan_lead_s : 0.0;
  const int steps = std::max(1, static_cast<int>(std::ceil(lead / params_.dt - 1e-9)));
  tdo_vehicle_state s = state_;
  for (int k = 0; k < steps && k < 100000; ++k) {
    const tdo_setpoint sp = brake_step(s);
    s = tdo_vehicle_state{state_.t + (k + 1) * params_.dt, sp.p, sp.v, sp.a};
  }
  tdo::plan_request_t m = template_;
  m.utime = wall_utime();
  m.request_id = cfg_.replan_id_base + counters_.replans;
  m.seq = replan_seq_++;
  m.vehicle_id = cfg_.vehicle_id;
  m.map_id = -1;  // the planner's latest map
  if (replan_.clearance >= 0.0) {
    m.clearance = replan_.clearance;
    m.use_defaults &= ~tdo::plan_request_t::USE_DEFAULT_CLEARANCE;
  }
  const tdo_vec3* v3[3] = {&s.p, &s.v, &s.a};
  double* out[3] = {m.start, m.start_vel, m.start_acc};
  for (int i = 0; i < 3; ++i) {
    out[i][0] = v3[i]->x;
    out[i][1] = v3[i]->y;
    out[i][2] = v3[i]->z;
  }
  replan_.phase = ReplanPhase::waiting;
  replan_.request_id = m.request_id;
  replan_.t_take = s.t;
  replan_.start_speed = std::sqrt(s.v.x * s.v.x + s.v.y * s.v.y + s.v.z * s.v.z);
  ++replan_.attempts;
  ++counters_.replans;
  bus_->publish(cfg_.request_channel, m);  // comes back to on_request: promised, remembered
}

// The answer to the replan waited for: taken over at its time when it is a plan that is clear of
// the known obstacles and came before the takeover time.
void AvoidNode::on_replan_answer(const tdo::trajectory_t& m) {
  std::vector<tdo_sample> samples;
  const Check c = trajectory_samples(m, &samples);
  if (!c.ok()) {
    if (m.status_code == TDO_ERR_NO_PATH) {
      ++counters_.replan_refused;
      replan_stop(Hold::no_way_through);
      return;
    }
    // Still braking: a start the planner cannot continue from (state_*) is asked again from a
    // slower one without counting (bounded: the braking ends). A start within the clearance
    // (the vehicle was pushed near an obstacle): asked again at the vehicle radius.
    constexpr double kMoving = 0.05;  // m/s
    if (m.status_code >= TDO_ERR_STATE_NOT_FINITE && m.status_code <= TDO_ERR_STATE_CANNOT_STOP &&
        replan_.start_speed > kMoving && replan_.attempts > 0)
      --replan_.attempts;
    if (m.status_code == TDO_ERR_START_BLOCKED) replan_.clearance = cfg_.vehicle_radius;
    replan_refused(c.reason == Reason::no_plan ? m.status : reason_str(c.reason));
    return;
  }
  double blocked_to = 0.0;
  if (samples_blocked(samples, 0.0, &blocked_to)) {
    replan_refused("blocked");  // planned on a map without the obstacle: ask again
    return;
  }
  if (state_.t > replan_.t_take + 0.5 * params_.dt) {
    replan_refused("late");  // the predicted state is past: ask again from the current one
    return;
  }
  replan_.samples = std::move(samples);
  replan_.phase = ReplanPhase::pending;
}

void AvoidNode::replan_refused(const std::string& why) {
  ++counters_.replan_refused;
  ++counters_.ignored;
  ++counters_.reasons["replan." + why];
  replan_.phase = ReplanPhase::idle;
  replan_.samples.clear();
}

// Whether the vehicle has been at rest (below 0.05 m/s) for `s` seconds since the stop.
bool AvoidNode::at_rest_since(double s) {
  constexpr double kRest = 0.05;  // m/s
  const double speed =
      std::sqrt(state_.v.x * state_.v.x + state_.v.y * state_.v.y + state_.v.z * state_.v.z);
  if (speed > kRest)
    replan_.rest_since = -1.0;
  else if (replan_.rest_since < 0.0)
    replan_.rest_since = state_.t;
  return replan_.rest_since >= 0.0 && state_.t - replan_.rest_since >= s;
}

void AvoidNode::replan_stop(Hold why) {
  replan_.phase = ReplanPhase::stopped;
  replan_.stop = why;
  replan_.rest_since = -1.0;
  replan_.samples.clear();
  ++counters_.safe_stops;
}

// A map or an update changed what is known: a safe stop is reconsidered (a new trigger may ask
// again, max_replans more times).
void AvoidNode::resume_after_map() {
  if (replan_.phase == ReplanPhase::stopped) replan_ = Replan{};
}

// Per step, before the follower: take a pending plan over at its time; otherwise, while a replan
// is in progress or after a stop, brake with the named status. @return true when it published.
bool AvoidNode::replan_tick() {
  switch (replan_.phase) {
    case ReplanPhase::idle:
      return false;
    case ReplanPhase::stopped:
      if (replan_.stop == Hold::replan_failed && at_rest_since(kRetryAfterS)) {
        replan_ = Replan{};  // at rest, where the predicted start is the state itself: ask again
        replan_.wanted = true;
        request_replan();
      }
      hold(replan_.phase == ReplanPhase::stopped ? replan_.stop : Hold::replanning);
      return true;
    case ReplanPhase::pending:
      if (state_.t + 0.5 * params_.dt >= replan_.t_take) {
        switch_to_pending();
        return false;  // this step already follows the new plan
      }
      break;
    case ReplanPhase::waiting:
      if (state_.t > replan_.t_take + 0.5 * params_.dt) {
        replan_refused("late");
        if (path_blocked() || replan_.wanted) request_replan();
        if (replan_.phase == ReplanPhase::stopped) {
          hold(replan_.stop);
          return true;
        }
      }
      break;
  }
  hold(path_blocked() ? Hold::blocked : Hold::replanning);
  return true;
}

void AvoidNode::switch_to_pending() {
  samples_ = std::move(replan_.samples);
  near_idx_ = 0;
  request_id_ = replan_.request_id;
  have_task_ = true;
  task_t0_ = replan_.t_take;  // trajectory t = 0 is the takeover time it was planned for
  task_t0_set_ = true;
  replan_ = Replan{};
  reset_task();
  if (have_task_) {
    ++counters_.trajectories;
    ++counters_.replan_switches;
  }
  check_blocked();
}

}  // namespace tdo_lcm
