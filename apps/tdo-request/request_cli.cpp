// tdo-request's core (request_cli.h).
#include "request_cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

namespace tdo_lcm {
namespace {

using R = tdo::plan_request_t;

/** A --param: its use_defaults bit, how it is set, and for integer fields the allowed range. */
struct Param {
  const char* name;
  int32_t bit;
  std::function<void(R*, double)> set;
  bool integer;
  double lo, hi;
};

Param real(const char* name, int32_t bit, double R::*member) {
  return {name, bit, [member](R* m, double v) { m->*member = v; }, false, 0.0, 0.0};
}
Param int8(const char* name, int32_t bit, int8_t R::*member, double lo, double hi) {
  return {name, bit, [member](R* m, double v) { m->*member = static_cast<int8_t>(v); },
          true, lo,  hi};
}
Param flag(const char* name, int32_t bit, int8_t R::*member) {  // LCM booleans are int8_t
  return {name, bit, [member](R* m, double v) { m->*member = v > 0.5 ? 1 : 0; }, true, 0.0, 1.0};
}

const std::vector<Param>& params() {
  static const std::vector<Param> p = {
      int8("depth", R::USE_DEFAULT_DEPTH, &R::depth, R::DEPTH_SEARCH, R::DEPTH_TRAJECTORY),
      int8("search", R::USE_DEFAULT_SEARCH, &R::search, R::SEARCH_ASTAR, R::SEARCH_BIDIR),
      real("lambda", R::USE_DEFAULT_LAMBDA_TURN, &R::lambda_turn),
      real("lambda_turn", R::USE_DEFAULT_LAMBDA_TURN, &R::lambda_turn),
      real("mu", R::USE_DEFAULT_MU, &R::mu),
      real("theta_max", R::USE_DEFAULT_THETA_MAX, &R::theta_max),
      real("d_th", R::USE_DEFAULT_D_TH, &R::d_th),
      real("h_weight", R::USE_DEFAULT_H_WEIGHT, &R::h_weight),
      flag("first_meet", R::USE_DEFAULT_FIRST_MEET, &R::first_meet),
      int8("grid_first", R::USE_DEFAULT_GRID_FIRST, &R::grid_first, R::GRID_FIRST_OFF,
           R::GRID_FIRST_TERMS),
      {"max_expansions", R::USE_DEFAULT_MAX_EXPANSIONS,
       [](R* m, double v) { m->max_expansions = static_cast<int32_t>(v); }, true, 0.0,
       2147483647.0},
      int8("correction", R::USE_DEFAULT_CORRECTION, &R::correction, R::CORRECT_MULTISCALE,
           R::CORRECT_NONE),
      flag("shorten", R::USE_DEFAULT_SHORTEN, &R::shorten),
      real("turn_threshold", R::USE_DEFAULT_TURN_THRESHOLD, &R::turn_threshold),
      int8("smoothing", R::USE_DEFAULT_SMOOTHING, &R::smoothing, R::SMOOTHING_G2,
           R::SMOOTHING_NONE),
      real("k", R::USE_DEFAULT_K, &R::k),
      real("v_max", R::USE_DEFAULT_V_MAX, &R::v_max),
      real("a_max", R::USE_DEFAULT_A_MAX, &R::a_max),
      real("j_max", R::USE_DEFAULT_J_MAX, &R::j_max),
      real("a_lat_max", R::USE_DEFAULT_A_LAT_MAX, &R::a_lat_max),
      real("v_cruise", R::USE_DEFAULT_V_CRUISE, &R::v_cruise),
      real("stop_angle", R::USE_DEFAULT_STOP_ANGLE, &R::stop_angle),
      real("dt", R::USE_DEFAULT_DT, &R::dt),
      real("clearance", R::USE_DEFAULT_CLEARANCE, &R::clearance),
      int8("states", R::USE_DEFAULT_STATES, &R::states, R::STATES_HEADING, R::STATES_VOXEL),
      real("corner_time", R::USE_DEFAULT_CORNER_TIME, &R::corner_time),
  };
  return p;
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
  for (const Param& p : params()) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}

bool apply_request_param(const std::string& text, R* m, std::string* error) {
  const std::size_t eq = text.find('=');
  const std::string name = eq == std::string::npos ? text : text.substr(0, eq);
  if (eq == std::string::npos || eq == 0) {
    *error = "--param '" + text + "': expected NAME=VALUE";
    return false;
  }
  const Param* found = nullptr;
  for (const Param& p : params())
    if (name == p.name) found = &p;
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
  if (found->integer && (!whole || value < found->lo || value > found->hi)) {
    *error = "--param '" + text + "': " + name + " takes a whole number in [" +
             fmt("%.17g", found->lo) + ", " + fmt("%.17g", found->hi) + "]";
    return false;
  }
  found->set(m, value);
  m->use_defaults &= ~found->bit;
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
