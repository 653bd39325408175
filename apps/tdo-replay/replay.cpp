// tdo-replay's core (replay.h).
#include "replay.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <utility>

#include "tdo_lcm/bus.h"
#include "tdo_lcm/request_fields.h"
#include "tdo_lcm/wire.h"

namespace tdo_lcm {

namespace {

// A request field --override can set (request_fields.h). An integer field's setter casts the
// value, and a cast of a number outside its type's range (or of a fraction) would be undefined or
// silently truncated, so parse_override lets only whole numbers the LCM type holds through; values
// outside the library's ranges go through, for the planner to refuse.
using Field = tdo_lcm::RequestField;

const Field* find_field(const std::string& name) { return tdo_lcm::find_request_field(name); }

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/** Field-by-field comparison of one answer, collecting lines "FIELD: expected E, got G". */
class Differ {
 public:
  Differ(std::string prefix, double tol, int max_lines, std::vector<std::string>* out)
      : prefix_(std::move(prefix)), tol_(tol), max_lines_(max_lines), out_(out) {}
  ~Differ() {
    if (count_ > max_lines_)
      out_->push_back(prefix_ + "... and " + std::to_string(count_ - max_lines_) +
                      " more differing values");
  }
  int count() const { return count_; }

  void num(const std::string& field, double expected, double got) {
    if (same(expected, got)) return;
    add(field + ": expected " + fmt(expected) + ", got " + fmt(got));
  }
  void integer(const std::string& field, int64_t expected, int64_t got) {
    if (expected != got)
      add(field + ": expected " + std::to_string(expected) + ", got " + std::to_string(got));
  }
  void str(const std::string& field, const std::string& expected, const std::string& got) {
    if (expected != got) add(field + ": expected \"" + expected + "\", got \"" + got + "\"");
  }
  template <class Row>
  void rows(const std::string& field, const std::vector<Row>& expected,
            const std::vector<Row>& got) {
    const std::size_t n = std::min(expected.size(), got.size());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < expected[i].size() && j < got[i].size(); ++j)
        num(field + "[" + std::to_string(i) + "][" + std::to_string(j) + "]", expected[i][j],
            got[i][j]);
  }
  template <class T>
  void values(const std::string& field, const std::vector<T>& expected, const std::vector<T>& got) {
    const std::size_t n = std::min(expected.size(), got.size());
    for (std::size_t i = 0; i < n; ++i)
      num(field + "[" + std::to_string(i) + "]", static_cast<double>(expected[i]),
          static_cast<double>(got[i]));
  }

 private:
  bool same(double a, double b) const {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    if (tol_ <= 0.0) return std::memcmp(&a, &b, sizeof a) == 0;
    if (!(a < b) && !(a > b)) return true;  // also equal infinities
    return std::fabs(a - b) <= tol_ * std::max(1.0, std::fabs(a));
  }
  void add(const std::string& line) {
    if (count_ < max_lines_) out_->push_back(prefix_ + line);
    ++count_;
  }
  std::string prefix_;
  double tol_;
  int max_lines_;
  int count_ = 0;
  std::vector<std::string>* out_;
};

void compare(const tdo::trajectory_t& e, const tdo::trajectory_t& g, Differ* d) {
  d->integer("map_id", e.map_id, g.map_id);
  d->integer("status_code", e.status_code, g.status_code);
  d->str("status", e.status, g.status);
  d->str("detail", e.detail, g.detail);
  d->integer("reached", e.reached, g.reached);
  d->integer("n_grid_path", e.n_grid_path, g.n_grid_path);
  d->rows("grid_path", e.grid_path, g.grid_path);
  d->integer("n_waypoints", e.n_waypoints, g.n_waypoints);
  d->rows("waypoints", e.waypoints, g.waypoints);
  d->num("dt", e.dt, g.dt);
  d->integer("n_samples", e.n_samples, g.n_samples);
  d->rows("samples", e.samples, g.samples);
  d->num("length_m", e.length_m, g.length_m);
  d->integer("turns", e.turns, g.turns);
  d->num("total_turn_deg", e.total_turn_deg, g.total_turn_deg);
  d->num("min_clearance_m", e.min_clearance_m, g.min_clearance_m);
  d->num("avg_curvature", e.avg_curvature, g.avg_curvature);
  d->num("smoothness", e.smoothness, g.smoothness);
  d->num("energy", e.energy, g.energy);
  d->num("flight_time_s", e.flight_time_s, g.flight_time_s);
  d->integer("expansions", e.expansions, g.expansions);
  d->num("search_cost", e.search_cost, g.search_cost);
  d->integer("request_seq", e.request_seq, g.request_seq);
  d->integer("n_segments", e.n_segments, g.n_segments);
  d->values("segment_kind", e.segment_kind, g.segment_kind);
  d->values("segment_s0", e.segment_s0, g.segment_s0);
  d->values("segment_length", e.segment_length, g.segment_length);
  d->values("segment_points", e.segment_points, g.segment_points);
  d->integer("n_pieces", e.n_pieces, g.n_pieces);
  d->values("piece_t0", e.piece_t0, g.piece_t0);
  d->values("piece_dur", e.piece_dur, g.piece_dur);
  d->values("piece_s0", e.piece_s0, g.piece_s0);
  d->values("piece_v0", e.piece_v0, g.piece_v0);
  d->values("piece_a0", e.piece_a0, g.piece_a0);
  d->values("piece_j", e.piece_j, g.piece_j);
  d->num("duration_s", e.duration_s, g.duration_s);
  d->num("path_length_m", e.path_length_m, g.path_length_m);
  d->integer("sample_count", e.sample_count, g.sample_count);
}

void compare(const tdo::feasibility_t& e, const tdo::feasibility_t& g, Differ* d) {
  d->integer("status_code", e.status_code, g.status_code);
  d->str("status", e.status, g.status);
  d->integer("checked", e.checked, g.checked);
  d->integer("ok", e.ok, g.ok);
  d->num("max_speed", e.max_speed, g.max_speed);
  d->num("max_acc", e.max_acc, g.max_acc);
  d->num("max_jerk", e.max_jerk, g.max_jerk);
  d->num("min_turn_radius", e.min_turn_radius, g.min_turn_radius);
  d->num("min_clearance", e.min_clearance, g.min_clearance);
  d->integer("refinements", e.refinements, g.refinements);
  d->num("v_max", e.v_max, g.v_max);
  d->num("a_max", e.a_max, g.a_max);
  d->num("j_max", e.j_max, g.j_max);
  d->num("clearance", e.clearance, g.clearance);
  d->integer("n_violations_total", e.n_violations_total, g.n_violations_total);
  d->integer("n_violations", e.n_violations, g.n_violations);
  d->values("violation_t", e.violation_t, g.violation_t);
  d->values("violation_what", e.violation_what, g.violation_what);
  d->values("violation_value", e.violation_value, g.violation_value);
  d->values("violation_limit", e.violation_limit, g.violation_limit);
  d->integer("request_seq", e.request_seq, g.request_seq);
  d->str("refused_field", e.refused_field, g.refused_field);
  d->str("refused_reason", e.refused_reason, g.refused_reason);
}

using Key = std::pair<int32_t, int64_t>;  // vehicle_id, request_id

std::string key_str(const Key& k) {
  return "request " + std::to_string(k.second) + " (vehicle " + std::to_string(k.first) + ")";
}

/** Recorded answers of one kind, by key, in log order; and the comparison of replayed ones. */
template <class Msg>
struct Answers {
  std::string channel;
  std::map<Key, std::deque<Msg>> recorded;

  void check(const Msg& got, const ReplayOptions& opt, ReplayReport* r) {
    const Key key{got.vehicle_id, got.request_id};
    auto it = recorded.find(key);
    if (it == recorded.end() || it->second.empty()) {
      ++r->not_recorded;
      r->diffs.push_back(key_str(key) + " " + channel + ": answered by the replay (status \"" +
                         got.status + "\") but not in the log");
      return;
    }
    const Msg expected = std::move(it->second.front());
    it->second.pop_front();
    ++r->compared;
    Differ d(key_str(key) + " " + channel + ": ", opt.tolerance, opt.max_diffs_per_answer,
             &r->diffs);
    compare(expected, got, &d);
    if (d.count() == 0)
      ++r->matched;
    else
      ++r->differed;
  }
  void leftovers(ReplayReport* r) {
    for (auto& kv : recorded)
      for (const Msg& m : kv.second) {
        ++r->not_replayed;
        r->diffs.push_back(key_str(kv.first) + " " + channel + ": in the log (status \"" +
                           m.status + "\") but not answered by the replay");
      }
  }
};

}  // namespace

std::string override_names() {
  std::string s;
  for (const Field& f : tdo_lcm::request_fields()) {
    s += (s.empty() ? "" : ", ") + std::string(f.name);
    const std::string lib = tdo_lcm::request_field_param_name(f);
    if (lib != f.name) s += ", " + lib;
  }
  return s;
}

bool parse_override(const std::string& text, Override* out, std::string* error) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    *error = "--override '" + text + "': expected NAME=VALUE";
    return false;
  }
  out->name = text.substr(0, eq);
  const Field* field = find_field(out->name);
  if (field == nullptr) {
    *error = "--override '" + text + "': unknown field '" + out->name +
             "' (known: " + override_names() + ")";
    return false;
  }
  const std::string v = text.substr(eq + 1);
  char* end = nullptr;
  out->value = std::strtod(v.c_str(), &end);
  if (v.empty() || end == nullptr || *end != '\0') {
    *error = "--override '" + text + "': '" + v + "' is not a number";
    return false;
  }
  const double whole = std::trunc(out->value);
  if (field->integer && (!(out->value >= field->lo && out->value <= field->hi) ||
                         whole < out->value || whole > out->value)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%.0f, %.0f]", field->lo, field->hi);
    *error = "--override '" + text + "': " + out->name + " takes an integer in " + range;
    return false;
  }
  return true;
}

bool apply_overrides(const std::vector<Override>& overrides, tdo::plan_request_t* m,
                     std::string* error) {
  for (const Override& o : overrides) {
    const Field* f = find_field(o.name);
    if (f == nullptr) {
      *error = "unknown override field '" + o.name + "'";
      return false;
    }
    f->set(*m, o.value);
  }
  return true;
}

int replay_log(const std::string& log_path, const ReplayOptions& options, ReplayReport* report,
               std::string* error) {
  *report = ReplayReport{};
  const PlannerConfig& pc = options.planner;
  Answers<tdo::trajectory_t> traj{pc.trajectory_channel, {}};
  Answers<tdo::feasibility_t> feas{pc.feasibility_channel, {}};

  // Pass 1: the recorded answers.
  {
    lcm::LogFile log(log_path, "r");
    if (!log.good()) {
      *error = log_path + ": cannot open the LCM log";
      return 2;
    }
    int64_t requests = 0;
    for (const lcm::LogEvent* ev = log.readNextEvent(); ev != nullptr; ev = log.readNextEvent()) {
      ++report->events;
      const std::size_t n = static_cast<std::size_t>(ev->datalen);
      if (ev->channel == pc.request_channel) ++requests;
      if (ev->channel == traj.channel || ev->channel == feas.channel) {
        Check c;
        Key key;
        if (ev->channel == traj.channel) {
          tdo::trajectory_t m{};
          c = decode(ev->data, n, &m);
          key = Key{m.vehicle_id, m.request_id};
          if (c.ok() && m.vehicle_id == pc.vehicle_id) traj.recorded[key].push_back(std::move(m));
        } else {
          tdo::feasibility_t m{};
          c = decode(ev->data, n, &m);
          key = Key{m.vehicle_id, m.request_id};
          if (c.ok() && m.vehicle_id == pc.vehicle_id) feas.recorded[key].push_back(std::move(m));
        }
        if (!c.ok()) {
          *error = log_path + ": event " + std::to_string(ev->eventnum) + " on " + ev->channel +
                   " cannot be decoded: " + reason_str(c.reason) + ": " + c.detail;
          return 2;
        }
        if (key.first == pc.vehicle_id)
          ++report->recorded;
        else
          ++report->other_vehicles;
      }
    }
    if (requests == 0) {
      *error = log_path + ": no event on " + pc.request_channel + ": nothing to replay";
      return 2;
    }
  }

  // Pass 2: feed the inputs to the node, compare what it answers.
  Bus bus("memq://");
  if (!bus.good()) {
    *error = "cannot start LCM on memq://";
    return 2;
  }
  PlannerConfig cfg = pc;
  cfg.heartbeat_period_s = 0.0;
  PlannerNode node(&bus, cfg);
  std::string why;
  if (!node.start(&why)) {
    *error = "planner: " + why;
    return 2;
  }
  std::vector<tdo::trajectory_t> got_traj;
  std::vector<tdo::feasibility_t> got_feas;
  bus.subscribe(cfg.trajectory_channel, [&](const void* d, std::size_t n, const std::string&) {
    tdo::trajectory_t m{};
    if (decode(d, n, &m).ok()) got_traj.push_back(std::move(m));
  });
  bus.subscribe(cfg.feasibility_channel, [&](const void* d, std::size_t n, const std::string&) {
    tdo::feasibility_t m{};
    if (decode(d, n, &m).ok()) got_feas.push_back(std::move(m));
  });

  lcm::LogFile log(log_path, "r");
  if (!log.good()) {
    *error = log_path + ": cannot open the LCM log";
    return 2;
  }
  std::vector<uint8_t> buf;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev != nullptr; ev = log.readNextEvent()) {
    const std::size_t n = static_cast<std::size_t>(ev->datalen);
    if (ev->channel == cfg.map_channel) {
      ++report->maps;
      node.on_map(ev->data, n);
    } else if (ev->channel == cfg.map_update_channel) {
      node.on_map_update(ev->data, n);  // in log order, like the maps
    } else if (ev->channel == cfg.request_channel) {
      ++report->requests;
      tdo::plan_request_t m{};
      if (!options.overrides.empty() && decode(ev->data, n, &m).ok()) {
        if (!apply_overrides(options.overrides, &m, error)) return 2;
        buf.resize(static_cast<std::size_t>(m.getEncodedSize()));
        m.encode(buf.data(), 0, static_cast<int>(buf.size()));
        node.on_request(buf.data(), buf.size());
      } else {
        node.on_request(ev->data, n);  // as recorded, also when it is malformed
      }
    } else {
      continue;
    }
    for (int i = 0; i < 1000 && bus.handle_timeout(0) > 0; ++i) {
    }
    for (const auto& m : got_traj) traj.check(m, options, report);
    for (const auto& m : got_feas) feas.check(m, options, report);
    got_traj.clear();
    got_feas.clear();
  }
  traj.leftovers(report);
  feas.leftovers(report);
  return (report->differed == 0 && report->not_recorded == 0 && report->not_replayed == 0) ? 0 : 1;
}

}  // namespace tdo_lcm
