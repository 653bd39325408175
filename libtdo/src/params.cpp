// The table of plan parameters (params.h). One row per field of tdo_plan_params; everything
// else that lists parameters reads it.
#include "tdo/params.h"

#include <math.h>
#include <string.h>

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kInf = HUGE_VAL;

// Enums may be 1 byte (arm-none-eabi's short enums) or 4: each row records its field's size.

const char* const kDepth[] = {"search", "correct", "smooth", "trajectory"};
const char* const kSearch[] = {"astar", "bidir"};
const char* const kFirstMeet[] = {"optimal", "first-meet"};
const char* const kOnOff[] = {"off", "on"};
const char* const kCorrection[] = {"multiscale", "greedy", "none"};
const char* const kSmoothing[] = {"g2", "arc", "none"};
const char* const kGridFirst[] = {"off", "plain", "terms"};
const char* const kStates[] = {"heading", "voxel"};

#define TDO_OFF(field) offsetof(tdo_plan_params, field), sizeof(tdo_plan_params::field)
#define TDO_N(a) static_cast<uint32_t>(sizeof(a) / sizeof((a)[0]))

// Indices of the rows other rows refer to (default_of); checked below.
constexpr int32_t kAMax = 16;
constexpr int32_t kVMax = 15;

// name, type, unit, default, default_of, min, max, min_open, max_open, stage, values, n_values,
// has_plain, plain, tune_min, tune_max, offset, size, help
const tdo_param_info kTable[] = {
    {"depth", TDO_PARAM_ENUM, "", TDO_PLAN_TRAJECTORY, -1, 0, 3, 0, 0, TDO_PLAN_SEARCH, kDepth,
     TDO_N(kDepth), 0, 0, 0, 0, TDO_OFF(depth),
     "stages to run: search, correct, smooth, trajectory (docs/design.md)"},
    {"search", TDO_PARAM_ENUM, "", TDO_SEARCH_BIDIR, -1, 0, 1, 0, 0, TDO_PLAN_SEARCH, kSearch,
     TDO_N(kSearch), 0, 0, 0, 0, TDO_OFF(search), "astar or bidir (bidirectional, the paper's)"},
    {"lambda", TDO_PARAM_REAL, "m", 50.0, -1, 0.0, kInf, 0, 0, TDO_PLAN_SEARCH, nullptr, 0, 1, 0.0,
     0.0, 100.0, TDO_OFF(lambda), "turn penalty: cost per (turn/pi)^2 (docs/design.md s.1)"},
    {"mu", TDO_PARAM_REAL, "m", 20.0, -1, 0.0, kInf, 0, 0, TDO_PLAN_SEARCH, nullptr, 0, 1, 0.0, 0.0,
     50.0, TDO_OFF(mu), "deviation weight: f per unit deviation (docs/design.md s.1)"},
    {"theta_max", TDO_PARAM_REAL, "rad", 0.25 * kPi, -1, 0.0, kPi, 0, 0, TDO_PLAN_SEARCH, nullptr,
     0, 1, 0.0, 20.0 * kDeg, kPi, TDO_OFF(theta_max),
     "direction constraint of the turn-penalised search (0 or 180 deg: unconstrained)"},
    {"d_th", TDO_PARAM_REAL, "", 0.0, -1, 0.0, 1.0, 0, 1, TDO_PLAN_SEARCH, nullptr, 0, 0, 0.0, 0.0,
     0.0, TDO_OFF(d_th), "deviation threshold in (0,1) of the turn-penalised search (0 = off)"},
    {"h_weight", TDO_PARAM_REAL, "", 1.0, -1, 1.0, kInf, 0, 0, TDO_PLAN_SEARCH, nullptr, 0, 0, 0.0,
     0.0, 0.0, TDO_OFF(h_weight),
     "heuristic weight (>= 1) of the turn-penalised search: speed for optimality"},
    {"first_meet", TDO_PARAM_BOOL, "", 1.0, -1, 0.0, 1.0, 0, 0, TDO_PLAN_SEARCH, kFirstMeet,
     TDO_N(kFirstMeet), 1, 0.0, 0.0, 0.0, TDO_OFF(first_meet),
     "bidirectional stopping rule: first-meet (the paper) or optimal"},
    {"max_expansions", TDO_PARAM_UINT, "", 0.0, -1, 0.0, 4294967295.0, 0, 0, TDO_PLAN_SEARCH,
     nullptr, 0, 0, 0.0, 0.0, 0.0, TDO_OFF(max_expansions),
     "expansion budget of one search (0 = the configured default)"},
    {"correction", TDO_PARAM_ENUM, "", TDO_CORRECT_MULTISCALE, -1, 0, 2, 0, 0, TDO_PLAN_CORRECT,
     kCorrection, TDO_N(kCorrection), 0, 0.0, 0.0, 0.0, TDO_OFF(correction),
     "inflection correction: multiscale (TDO-MSF), greedy (line of sight), none"},
    {"shorten", TDO_PARAM_BOOL, "", 1.0, -1, 0.0, 1.0, 0, 0, TDO_PLAN_CORRECT, kOnOff,
     TDO_N(kOnOff), 0, 0.0, 0.0, 0.0, TDO_OFF(shorten),
     "partial shortcuts after the multiscale correction (off: the paper's correction alone)"},
    {"turn_threshold", TDO_PARAM_REAL, "rad", 10.0 * kDeg, -1, 0.0, kPi, 0, 0, TDO_PLAN_CORRECT,
     nullptr, 0, 0, 0.0, 0.0, 0.0, TDO_OFF(turn_threshold),
     "turns below this count as straight in the correction windows"},
    {"smoothing", TDO_PARAM_ENUM, "", TDO_SMOOTHING_G2, -1, 0, 2, 0, 0, TDO_PLAN_SMOOTH, kSmoothing,
     TDO_N(kSmoothing), 0, 0.0, 0.0, 0.0, TDO_OFF(smoothing),
     "corner smoothing: g2 (spiral corners), arc (the paper's eq. 8), none"},
    {"grid_first", TDO_PARAM_ENUM, "", TDO_GRID_FIRST_OFF, -1, 0, 2, 0, 0, TDO_PLAN_SEARCH,
     kGridFirst, TDO_N(kGridFirst), 0, 0.0, 0.0, 0.0, TDO_OFF(grid_first),
     "what the search starts with: off (the octile try), plain or terms (grid distances)"},
    {"k", TDO_PARAM_REAL, "", 1.0, -1, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0, 0.0, 0.3,
     3.0, TDO_OFF(k), "corner radius scale"},
    {"v_max", TDO_PARAM_REAL, "m/s", 3.0, -1, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0, 0.0,
     0.0, 0.0, TDO_OFF(v_max), "speed limit"},
    {"a_max", TDO_PARAM_REAL, "m/s^2", 3.0, -1, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0,
     0.0, 0.0, 0.0, TDO_OFF(a_max), "acceleration limit"},
    {"j_max", TDO_PARAM_REAL, "m/s^3", 10.0, -1, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0,
     0.0, 0.0, 0.0, TDO_OFF(j_max), "jerk limit"},
    {"a_lat_max", TDO_PARAM_REAL, "m/s^2", 3.0, kAMax, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0,
     0, 0.0, 0.0, 0.0, TDO_OFF(a_lat_max), "lateral acceleration limit of corners"},
    {"v_cruise", TDO_PARAM_REAL, "m/s", 3.0, kVMax, 0.0, kInf, 1, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0,
     0.0, 0.0, 0.0, TDO_OFF(v_cruise), "speed that sets R_min = v_cruise^2 / a_lat_max"},
    {"stop_angle", TDO_PARAM_REAL, "rad", 150.0 * kDeg, -1, 0.0, kPi, 1, 0, TDO_PLAN_SMOOTH,
     nullptr, 0, 0, 0.0, 0.0, 0.0, TDO_OFF(stop_angle),
     "corners sharper than this become stop points"},
    {"dt", TDO_PARAM_REAL, "s", 0.01, -1, 0.0, kInf, 1, 0, TDO_PLAN_TRAJECTORY, nullptr, 0, 0, 0.0,
     0.0, 0.0, TDO_OFF(dt), "trajectory sample period"},
    {"states", TDO_PARAM_ENUM, "", TDO_STATES_HEADING, -1, 0, 1, 0, 0, TDO_PLAN_SEARCH, kStates,
     TDO_N(kStates), 0, 0.0, 0.0, 0.0, TDO_OFF(states),
     "states of the turn-penalised search: heading (voxel, heading) or voxel (plain A*'s memory)"},
    {"corner_time", TDO_PARAM_REAL, "", 1.0, -1, 0.0, 1.0, 0, 0, TDO_PLAN_SMOOTH, nullptr, 0, 0,
     0.0, 0.0, 0.0, TDO_OFF(corner_time),
     "in [0, 1]: how far G2 corner shapes trade length for flight time (0 = Yang-Sukkarieh)"},
};

constexpr uint32_t kCount = TDO_N(kTable);

#undef TDO_OFF
#undef TDO_N

bool whole(double v) { return !(trunc(v) < v) && !(trunc(v) > v); }

// The table holds every field of the struct exactly once (checked by test_params.cpp too).
static_assert(sizeof(kTable) / sizeof(kTable[0]) == 24, "one row per tdo_plan_params field");

extern "C" uint32_t tdo_param_count(void) { return kCount; }

extern "C" const tdo_param_info* tdo_param_at(uint32_t i) {
  return i < kCount ? &kTable[i] : nullptr;
}

extern "C" int32_t tdo_param_find(const char* name) {
  if (name == nullptr) return -1;
  for (uint32_t i = 0; i < kCount; ++i)
    if (strcmp(kTable[i].name, name) == 0) return static_cast<int32_t>(i);
  return -1;
}

extern "C" int tdo_param_valid(uint32_t i, double v) {
  if (i >= kCount || !isfinite(v)) return 0;
  const tdo_param_info& r = kTable[i];
  if (r.type != TDO_PARAM_REAL && !whole(v)) return 0;
  if (r.min_open ? !(v > r.min) : !(v >= r.min)) return 0;
  if (r.max_open ? !(v < r.max) : !(v <= r.max)) return 0;
  return 1;
}

// A BOOL or ENUM field: an int or an enum of 1, 2 or 4 bytes holding a small non-negative value.
int64_t read_int(const unsigned char* at, size_t size) {
  switch (size) {
    case 1: {
      int8_t v;
      memcpy(&v, at, 1);
      return v;
    }
    case 2: {
      int16_t v;
      memcpy(&v, at, 2);
      return v;
    }
    default: {
      int32_t v;
      memcpy(&v, at, 4);
      return v;
    }
  }
}

void write_int(unsigned char* at, size_t size, int32_t n) {
  switch (size) {
    case 1: {
      const int8_t v = static_cast<int8_t>(n);
      memcpy(at, &v, 1);
      break;
    }
    case 2: {
      const int16_t v = static_cast<int16_t>(n);
      memcpy(at, &v, 2);
      break;
    }
    default:
      memcpy(at, &n, 4);
      break;
  }
}

}  // namespace

extern "C" double tdo_param_get(const tdo_plan_params* p, uint32_t i) {
  if (p == nullptr || i >= kCount) return static_cast<double>(NAN);
  const tdo_param_info& r = kTable[i];
  const unsigned char* at = reinterpret_cast<const unsigned char*>(p) + r.offset;
  switch (r.type) {
    case TDO_PARAM_REAL: {
      double v;
      memcpy(&v, at, sizeof v);
      return v;
    }
    case TDO_PARAM_UINT: {
      uint32_t v;
      memcpy(&v, at, sizeof v);
      return static_cast<double>(v);
    }
    case TDO_PARAM_BOOL:
    case TDO_PARAM_ENUM:
      return static_cast<double>(read_int(at, r.size));
  }
  return static_cast<double>(NAN);
}

extern "C" tdo_status tdo_param_set(tdo_plan_params* p, uint32_t i, double v) {
  if (p == nullptr || i >= kCount) return TDO_ERR_INVALID_ARGUMENT;
  const tdo_param_info& r = kTable[i];
  // What the field can hold: any double; a whole uint32_t; an enum's or a flag's values.
  if (r.type != TDO_PARAM_REAL) {
    const double hi = r.type == TDO_PARAM_UINT ? 4294967295.0 : r.max;
    if (!isfinite(v) || !whole(v) || v < r.min || v > hi) return TDO_ERR_INVALID_ARGUMENT;
  }
  unsigned char* at = reinterpret_cast<unsigned char*>(p) + r.offset;
  switch (r.type) {
    case TDO_PARAM_REAL:
      memcpy(at, &v, sizeof v);
      break;
    case TDO_PARAM_UINT: {
      const uint32_t u = static_cast<uint32_t>(v);
      memcpy(at, &u, sizeof u);
      break;
    }
    case TDO_PARAM_BOOL:
    case TDO_PARAM_ENUM:
      write_int(at, r.size, static_cast<int32_t>(v));
      break;
  }
  return TDO_OK;
}

extern "C" tdo_status tdo_plan_params_check(const tdo_plan_params* p, uint32_t* bad) {
  if (p == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  const uint32_t depth_row = 0;  // "depth": decides which other rows are checked
  if (tdo_param_valid(depth_row, tdo_param_get(p, depth_row)) == 0) {
    if (bad != nullptr) *bad = depth_row;
    return TDO_ERR_INVALID_ARGUMENT;
  }
  for (uint32_t i = 1; i < kCount; ++i) {
    if (p->depth < kTable[i].stage) continue;
    if (tdo_param_valid(i, tdo_param_get(p, i)) == 0) {
      if (bad != nullptr) *bad = i;
      return TDO_ERR_INVALID_ARGUMENT;
    }
  }
  return TDO_OK;
}

extern "C" void tdo_plan_params_plain(tdo_plan_params* p) {
  if (p == nullptr) return;
  for (uint32_t i = 0; i < kCount; ++i)
    if (kTable[i].has_plain != 0) (void)tdo_param_set(p, i, kTable[i].plain);
}

extern "C" void tdo_plan_params_default(tdo_plan_params* p) {
  if (p == nullptr) return;
  memset(p, 0, sizeof(*p));
  for (uint32_t i = 0; i < kCount; ++i) (void)tdo_param_set(p, i, kTable[i].def);
}
