// tdo-request's core (request_cli.h).
#include "request_cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tdo/params.h"
#include "tdo_lcm/request_fields.h"

namespace tdo_lcm {
namespace {

using R = tdo::plan_request_t;

/** The values --param lets through for an integer field: what the LCM type holds and the
 *  library's valid range of its row (an enum's values; max_expansions >= 0). */
void integer_range(const RequestField& f, double* lo, double* hi) {
  *lo = f.lo;
  *hi = f.hi;
  const tdo_param_info* row = f.param >= 0 ? tdo_param_at(static_cast<uint32_t>(f.param)) : nullptr;
  if (row == nullptr) return;
  *lo = std::max(*lo, row->min);
  *hi = std::min(*hi, row->max);
}

std::string fmt(const char* f, double a) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

std::string line(const char* key, const std::string& value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%-17s", key);
  return buf + value + "\n";
}

std::string vec(const double* v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v[0], v[1], v[2]);
  return buf;
}

}  // namespace

std::string request_param_names() {
  std::string s;
  for (const RequestField& f : request_fields()) {
    s += (s.empty() ? "" : ", ") + std::string(f.name);
    const std::string lib = request_field_param_name(f);
    if (lib != f.name) s += ", " + lib;
  }
  return s;
}

bool apply_request_param(const std::string& text, R* m, std::string* error) {
  const std::size_t eq = text.find('=');
  const std::string name = eq == std::string::npos ? text : text.substr(0, eq);
  if (eq == std::string::npos || eq == 0) {
    *error = "--param '" + text + "': expected NAME=VALUE";
    return false;
  }
  const RequestField* found = find_request_field(name);
  if (found == nullptr) {
    *error = "--param '" + text + "': unknown parameter '" + name +
             "' (known: " + request_param_names() + ")";
    return false;
  }
  const std::string v = text.substr(eq + 1);
  char* end = nullptr;
  const double value = std::strtod(v.c_str(), &end);
  if (v.empty() || end == nullptr || *end != '\0' || !std::isfinite(value)) {
    *error = "--param '" + text + "': '" + v + "' is not a finite number";
    return false;
  }
  const bool whole = !(std::trunc(value) < value) && !(std::trunc(value) > value);
  double lo = 0.0;
  double hi = 0.0;
  integer_range(*found, &lo, &hi);
  if (found->integer && (!whole || value < lo || value > hi)) {
    *error = "--param '" + text + "': " + name + " takes a whole number in [" + fmt("%.17g", lo) +
             ", " + fmt("%.17g", hi) + "]";
    return false;
  }
  found->set(*m, value);
  m->use_defaults &= ~found->use_default_bit;
  return true;
}

bool build_request(const double start[3], const double goal[3],
                   const std::vector<std::string>& list, R* m, std::string* error) {
  *m = R{};
  m->map_id = -1;
  for (int a = 0; a < 3; ++a) {
    m->start[a] = start[a];
    m->goal[a] = goal[a];
  }
  m->use_defaults = R::USE_DEFAULT_ALL;
  for (const std::string& p : list)
    if (!apply_request_param(p, m, error)) return false;
  return true;
}

std::string answer_summary(const R& req, const tdo::trajectory_t& t, const tdo::feasibility_t& f,
                           std::size_t traj_bytes) {
  std::string s;
  s += line("request", std::to_string(t.request_id) + " (seq " + std::to_string(t.request_seq) +
                           "), vehicle " + std::to_string(t.vehicle_id) + ", map " +
                           std::to_string(t.map_id));
  s += line("start -> goal", vec(req.start) + " -> " + vec(req.goal));
  s += line("status", t.status);
  if (!t.detail.empty()) s += line("detail", t.detail);
  if (!f.refused_field.empty()) s += line("refused field", f.refused_field);
  if (t.n_grid_path > 0) {
    s += line("grid path", std::to_string(t.n_grid_path) + " voxels, search cost " +
                               fmt("%.6f m", t.search_cost));
    if (t.reached >= R::DEPTH_CORRECT) s += line("waypoints", std::to_string(t.n_waypoints));
    s += line("length_m", fmt("%.3f", t.length_m));
    s += line("turns", std::to_string(t.turns) + fmt(" (%.1f deg in total)", t.total_turn_deg));
    s += line("min_clearance_m", fmt("%.3f", t.min_clearance_m));
    s += line("avg_curvature", fmt("%.4f 1/m", t.avg_curvature));
    s += line("smoothness", fmt("%.4f", t.smoothness));
    if (t.reached == R::DEPTH_TRAJECTORY) {
      s += line("energy", fmt("%.3f m^2/s^3", t.energy));
      s += line("flight_time_s", fmt("%.2f", t.flight_time_s));
      s +=
          line("feasible", std::string(f.ok ? "yes" : "no") + fmt(" (max speed %.3f", f.max_speed) +
                               fmt(", acc %.3f", f.max_acc) + fmt(", jerk %.3f", f.max_jerk) +
                               "; " + std::to_string(f.n_violations_total) + " violations)");
    }
    s += line("expansions", std::to_string(t.expansions));
  }
  s += line("plan_time_ms", fmt("%.3f", t.plan_time_ms));
  s +=
      line("trajectory", std::to_string(t.n_segments) + " segments, " + std::to_string(t.n_pieces) +
                             " profile pieces, " + std::to_string(t.n_samples) + " samples, " +
                             std::to_string(traj_bytes) + " bytes");
  return s;
}

}  // namespace tdo_lcm
