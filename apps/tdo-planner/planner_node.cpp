// tdo-planner's node: decode -> adapter -> tdo_planner_plan -> encode (planner_node.h).
#include "planner_node.h"

#include <cmath>
#include <new>
#include <utility>

#include "tdo/pipeline.h"
#include "tdo/traj_profile.h"
#include "tdo_lcm/compact.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/wire.h"
#if TDO_LCM_HAVE_OCTOMAP
#include "tdo_lcm/map_file.h"
#endif

namespace tdo_lcm {

PlannerNode::PlannerNode(Bus* bus, PlannerConfig cfg) : bus_(bus), cfg_(std::move(cfg)) {
  started_ = std::chrono::steady_clock::now();
  next_status_ = started_;
}

bool PlannerNode::start(std::string* error) {
  const char* problem = start_problem(bus_, false, 1.0);
  if (problem[0] != '\0') return fail_start(error, problem);
  if (cfg_.max_nx <= 0 || cfg_.max_ny <= 0 || cfg_.max_nz <= 0)
    return fail_start(error, "the capacity sizes must be > 0");
  if (!(cfg_.max_clearance_ratio >= 0.0) || !std::isfinite(cfg_.max_clearance_ratio))
    return fail_start(error, "the clearance ratio must be finite and >= 0");
  tdo_capacity_for_grid(&cfg_tdo_.cap, cfg_.max_nx, cfg_.max_ny, cfg_.max_nz,
                        cfg_.max_clearance_ratio, 27u, cfg_.max_nodes);
  cfg_tdo_.cap.max_boxes = cfg_.max_boxes > 0 ? cfg_.max_boxes : 1u;
  if (cfg_.stream_samples >= 0)
    cfg_tdo_.cap.stream_samples = static_cast<uint32_t>(cfg_.stream_samples);
  arena_bytes_ = tdo_planner_footprint(&cfg_tdo_);
  if (arena_bytes_ == 0) {  // the library names what it refuses
    unsigned char byte = 0;
    tdo_planner* none = nullptr;
    return fail_start(error, std::string("tdo_planner_init: ") +
                                 tdo_status_str(tdo_planner_init(&none, &byte, 1u, &cfg_tdo_)) +
                                 ": invalid planner configuration");
  }
  if (alloc_node_arena(&arena_, arena_bytes_, error) == 0) return false;
  const tdo_status st = tdo_planner_init(&planner_, arena_.get(), arena_bytes_, &cfg_tdo_);
  if (st != TDO_OK)
    return fail_start(error, std::string("tdo_planner_init: ") + tdo_status_str(st));
  const bool ok =
      bus_->subscribe(cfg_.map_channel,
                      [this](const void* d, std::size_t n, const std::string&) { on_map(d, n); }) &&
      bus_->subscribe(cfg_.request_channel, [this](const void* d, std::size_t n,
                                                   const std::string&) { on_request(d, n); }) &&
      bus_->subscribe(cfg_.map_update_channel, [this](const void* d, std::size_t n,
                                                      const std::string&) { on_map_update(d, n); });
  return ok ? true : fail_start(error, "cannot subscribe");
}

void PlannerNode::refuse(const std::string& what, const Check& c) {
  count_refusal(&counters_, what, c.reason, c.reason == Reason::other_vehicle);
  // Refused requests also by the field at fault ("field.v_max"; outside the rejected sum).
  if (what == "request" && !c.field.empty()) ++counters_.reasons["field." + c.field];
}

void PlannerNode::answer(const tdo::trajectory_t& traj, const tdo::feasibility_t& feas) {
  // The generated encoders trust the counts; the adapters keep them right, this makes sure.
  if (!check_counts(traj).ok() || !check_counts(feas).ok()) return;
  bus_->publish(cfg_.trajectory_channel, traj);
  bus_->publish(cfg_.feasibility_channel, feas);
  ++counters_.answered;
}

void PlannerNode::answer_error(const AnswerIds& ids, const std::string& what, const Check& c) {
  refuse(what, c);
  tdo::trajectory_t traj{};
  tdo::feasibility_t feas{};
  error_answer(ids, tdo::trajectory_t::STATUS_REJECTED, reason_str(c.reason), c.detail, &traj,
               &feas);
  feas.refused_field = c.field;
  feas.refused_reason = c.detail;
  answer(traj, feas);
}

void PlannerNode::on_map(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::map_t m{};
  Check c = decode_map(data, size, cfg_.vehicle_id, &m);
  // The map in use, sent again (a publisher repeats it for late starters): the updates applied
  // on top of it stay. A stale map is reloaded (the whole map was asked for).
  if (c.ok() && have_map_ && m.map_id == map_id_ && !updates_.stale()) return;
#if TDO_LCM_HAVE_OCTOMAP
  // An OctoMap binary stream is rasterised onto the message's grid first (capacity checked before).
  if (c.ok() && m.encoding == tdo::map_t::ENCODING_OCTOMAP_BT) {
    tdo::map_t rle{};
    c = octomap_to_rle(m, cfg_tdo_.cap.max_voxels, &rle);
    if (c.ok()) m = std::move(rle);
  }
#endif
  // Everything is checked before the grid is touched, so a bad map leaves the current one in place.
  if (c.ok()) c = map_check(m, cfg_tdo_.cap, -1.0);
  if (!c.ok()) {
    refuse("map", c);
    return;
  }
  c = map_to_grid(m, cfg_tdo_.cap, -1.0, tdo_planner_grid(planner_));
  if (!c.ok()) {  // the library refused after the reset: no map until the next good one
    have_map_ = false;
    map_id_ = -1;
    updates_.clear();
    refuse("map", c);
    return;
  }
  // The grid's one-off work (legal steps, distance field) now, on map arrival, not in the first
  // request's plan. It cannot fail on the grid map_to_grid just finished.
  (void)tdo_grid_prepare(tdo_planner_grid(planner_));
  updates_.on_map(m.map_id);
  stale_why_.clear();
  have_map_ = true;
  map_id_ = m.map_id;
  map_res_ = m.resolution;
  map_clearance_ = m.clearance;
  ++counters_.maps_loaded;
}

bool PlannerNode::set_clearance(double clearance, Check* why) {
  tdo_grid* grid = tdo_planner_grid(planner_);
  // Bit-exact: the grid was finished with this very clearance.
  if (!(std::fabs(tdo_grid_clearance(grid) - clearance) > 0.0)) return true;
  *why = clearance_check(clearance, map_res_, cfg_tdo_.cap);
  if (!why->ok()) return false;
  const double previous = tdo_grid_clearance(grid);
  tdo_status st = tdo_grid_finish(grid, clearance);
  if (st == TDO_OK) return true;
  *why = fail(Reason::grid_error, std::string("tdo_grid_finish: ") + tdo_status_str(st));
  if (previous < 0.0 || tdo_grid_finish(grid, previous) != TDO_OK) {
    have_map_ = false;
    map_id_ = -1;
    updates_.clear();
  }
  return false;
}

void PlannerNode::on_request(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::plan_request_t m{};
  Check c = decode(data, size, &m);
  if (!c.ok()) {  // no request id to answer to
    refuse("request", c);
    return;
  }
  AnswerIds ids;
  ids.utime = wall_utime();
  ids.request_id = m.request_id;
  ids.request_seq = m.seq;
  ids.vehicle_id = m.vehicle_id;
  ids.map_id = map_id();

  tdo_plan_request req{};
  double clearance = -1.0;
  c = plan_request_from_msg(m, cfg_.vehicle_id, &req, &clearance);
  if (c.reason == Reason::other_vehicle) {
    refuse("request", c);
    return;
  }
  if (c.ok() && !have_map_) c = fail(Reason::no_map, "no map received yet on " + cfg_.map_channel);
  if (c.ok() && updates_.stale())
    c = fail(Reason::map_stale, "map " + std::to_string(map_id_) + " is stale (" + stale_why_ +
                                    "): waiting for the whole map on " + cfg_.map_channel);
  if (c.ok() && m.map_id >= 0 && m.map_id != map_id_)
    c = fail(Reason::unknown_map, "request for map " + std::to_string(m.map_id) +
                                      ", the planner has map " + std::to_string(map_id_));
  if (c.ok()) {
    if (clearance < 0.0) clearance = map_clearance_;
    set_clearance(clearance, &c);
  }
  if (!c.ok()) {
    ids.map_id = map_id();
    answer_error(ids, "request", c);
    return;
  }

  tdo_plan_result result{};
  const auto t0 = std::chrono::steady_clock::now();
  const tdo_status st = tdo_planner_plan(planner_, &req, &result);
  const auto t1 = std::chrono::steady_clock::now();
  const double plan_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  counters_.last_plan_ms = plan_ms;

  tdo::trajectory_t traj{};
  tdo::feasibility_t feas{};
  ids.utime = wall_utime();
  // A usable trajectory also travels in its compact form (compact.h), unless it begins with a
  // moving start's acceleration ramp, which is not a piece on the path (its first piece starts
  // after it): that one travels as samples.
  const tdo_traj* traj_ctx = tdo_planner_trajectory(planner_);
  tdo_traj_piece first{};
  const bool compact = st == TDO_OK && traj_ctx != nullptr &&
                       tdo_traj_piece_at(traj_ctx, 0u, &first) == TDO_OK && !(first.t0 > 0.0);
  const bool with_samples =
      m.samples == tdo::plan_request_t::SAMPLES_ON || (st == TDO_OK && !compact);
  c = trajectory_to_msg(result, req, ids, plan_ms, &traj, with_samples, planner_);
  if (c.ok() && compact) c = compact_to_msg(result.path, traj_ctx, &traj);
  if (c.ok()) c = feasibility_to_msg(result, req, clearance, ids, &feas);
  if (!c.ok()) {
    answer_error(ids, "result", c);
    return;
  }
  if (st == TDO_OK)
    ++counters_.succeeded;
  else
    ++counters_.failed;
  answer(traj, feas);
}

void PlannerNode::on_map_update(const void* data, std::size_t size) {
  ++counters_.received;
  tdo::map_update_t u{};
  Check c = decode_map_update(data, size, cfg_.vehicle_id, &u);
  if (c.ok()) c = updates_.order(u);  // a gap makes the map stale
  if (c.ok()) {
    // Applied at the clearance of the grid's last finish; a request with another clearance
    // re-finishes the grid with every update in it.
    c = map_update_apply(u, tdo_planner_grid(planner_), nullptr);
    if (c.ok()) {
      updates_.applied(u.seq);
      ++counters_.updates_applied;
      return;
    }
    updates_.mark_stale();  // the map lacks an update it was sent
  }
  refuse("update", c);
  if (updates_.stale() && stale_why_.empty()) {
    stale_why_ = c.reason == Reason::gap ? "gap" : std::string("update_") + reason_str(c.reason);
    request_map(stale_why_.c_str());
  }
}

void PlannerNode::request_map(const char* why) {
  bus_->publish(cfg_.map_request_channel,
                make_map_request("tdo-planner", cfg_.vehicle_id, updates_, why, &map_request_seq_));
  ++counters_.map_requests;
  next_map_request_ = std::chrono::steady_clock::now() + steady_seconds(1.0);
}

tdo::status_t PlannerNode::status_message() const {
  std::map<std::string, int64_t> reasons = counters_.reasons;
  if (updates_.stale()) reasons["state.map_stale"] = 1;  // outside the rejected + ignored sum
  const StatusCounts c{map_id(),           counters_.received,  counters_.maps_loaded,
                       counters_.answered, counters_.succeeded, counters_.failed,
                       counters_.rejected, counters_.ignored,   counters_.last_plan_ms};
  return make_status("tdo-planner", status_seq_, cfg_.vehicle_id, started_, reasons, c);
}

void PlannerNode::publish_status() {
  send_status(bus_, cfg_.status_channel, status_message(), &status_seq_);
}

void PlannerNode::poll(std::chrono::steady_clock::time_point now) {
  if (updates_.stale() && !(now < next_map_request_)) request_map(stale_why_.c_str());
  if (!(cfg_.heartbeat_period_s > 0.0) || now < next_status_) return;
  publish_status();
  advance_deadline(&next_status_, now, steady_seconds(cfg_.heartbeat_period_s));
}

}  // namespace tdo_lcm
