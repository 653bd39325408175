// plan_request_t's parameter fields bound to libtdo's parameter table (request_fields.h). This is
// the one place in apps/ that names each parameter: the LCM struct has a member per parameter.
#include "tdo_lcm/request_fields.h"

#include <cstring>
#include <limits>
#include <type_traits>

#include "tdo/params.h"

namespace tdo_lcm {
namespace {

using R = tdo::plan_request_t;

template <class T>
constexpr double type_lo() {
  return std::is_same<T, double>::value ? 0.0
         : sizeof(T) == 1               ? -128.0
                                        : static_cast<double>(std::numeric_limits<T>::min());
}
template <class T>
constexpr double type_hi() {
  return std::is_same<T, double>::value ? 0.0 : static_cast<double>(std::numeric_limits<T>::max());
}

// LCM_NAME: the member of plan_request_t; PARAM: the row's name in tdo/params.h ("" = none);
// BIT: its use_defaults bit.
#define TDO_REQUEST_FIELD(LCM_NAME, PARAM, BIT)                                                \
  RequestField {                                                                               \
#LCM_NAME, tdo_param_find(PARAM), R::BIT,                                                    \
        !std::is_same<decltype(R::LCM_NAME), double>::value,                                     \
        type_lo<decltype(R::LCM_NAME)>(), type_hi<decltype(R::LCM_NAME)>(), -1.0,                \
        [](const R& m) { return static_cast<double>(m.LCM_NAME); },                              \
        [](R& m, double v) { m.LCM_NAME = static_cast<decltype(R::LCM_NAME)>(v); } \
  }

std::vector<RequestField> make_fields() {
  std::vector<RequestField> f = {
      TDO_REQUEST_FIELD(clearance, "", USE_DEFAULT_CLEARANCE),
      TDO_REQUEST_FIELD(depth, "depth", USE_DEFAULT_DEPTH),
      TDO_REQUEST_FIELD(search, "search", USE_DEFAULT_SEARCH),
      TDO_REQUEST_FIELD(lambda_turn, "lambda", USE_DEFAULT_LAMBDA_TURN),
      TDO_REQUEST_FIELD(mu, "mu", USE_DEFAULT_MU),
      TDO_REQUEST_FIELD(theta_max, "theta_max", USE_DEFAULT_THETA_MAX),
      TDO_REQUEST_FIELD(d_th, "d_th", USE_DEFAULT_D_TH),
      TDO_REQUEST_FIELD(h_weight, "h_weight", USE_DEFAULT_H_WEIGHT),
      TDO_REQUEST_FIELD(first_meet, "first_meet", USE_DEFAULT_FIRST_MEET),
      TDO_REQUEST_FIELD(grid_first, "grid_first", USE_DEFAULT_GRID_FIRST),
      TDO_REQUEST_FIELD(states, "states", USE_DEFAULT_STATES),
      TDO_REQUEST_FIELD(max_expansions, "max_expansions", USE_DEFAULT_MAX_EXPANSIONS),
      TDO_REQUEST_FIELD(correction, "correction", USE_DEFAULT_CORRECTION),
      TDO_REQUEST_FIELD(shorten, "shorten", USE_DEFAULT_SHORTEN),
      TDO_REQUEST_FIELD(turn_threshold, "turn_threshold", USE_DEFAULT_TURN_THRESHOLD),
      TDO_REQUEST_FIELD(smoothing, "smoothing", USE_DEFAULT_SMOOTHING),
      TDO_REQUEST_FIELD(k, "k", USE_DEFAULT_K),
      TDO_REQUEST_FIELD(v_max, "v_max", USE_DEFAULT_V_MAX),
      TDO_REQUEST_FIELD(a_max, "a_max", USE_DEFAULT_A_MAX),
      TDO_REQUEST_FIELD(j_max, "j_max", USE_DEFAULT_J_MAX),
      TDO_REQUEST_FIELD(a_lat_max, "a_lat_max", USE_DEFAULT_A_LAT_MAX),
      TDO_REQUEST_FIELD(v_cruise, "v_cruise", USE_DEFAULT_V_CRUISE),
      TDO_REQUEST_FIELD(stop_angle, "stop_angle", USE_DEFAULT_STOP_ANGLE),
      TDO_REQUEST_FIELD(dt, "dt", USE_DEFAULT_DT),
      TDO_REQUEST_FIELD(corner_time, "corner_time", USE_DEFAULT_CORNER_TIME),
  };
  for (RequestField& x : f) {  // LCM booleans are int8_t on the wire; their values are 0 and 1
    const tdo_param_info* row =
        x.param >= 0 ? tdo_param_at(static_cast<uint32_t>(x.param)) : nullptr;
    if (row != nullptr && row->type == TDO_PARAM_BOOL) {
      x.lo = 0.0;
      x.hi = 1.0;
    }
  }
  return f;
}

#undef TDO_REQUEST_FIELD

}  // namespace

const std::vector<RequestField>& request_fields() {
  static const std::vector<RequestField> f = make_fields();
  return f;
}

const char* request_field_param_name(const RequestField& f) {
  const tdo_param_info* row = f.param >= 0 ? tdo_param_at(static_cast<uint32_t>(f.param)) : nullptr;
  return row != nullptr ? row->name : f.name;
}

const RequestField* find_request_field(const std::string& name) {
  for (const RequestField& f : request_fields())
    if (name == f.name || name == request_field_param_name(f)) return &f;
  return nullptr;
}

}  // namespace tdo_lcm
