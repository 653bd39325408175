/**
 * @file request_fields.h
 * @brief The parameter fields of plan_request_t, each bound to its row of libtdo's parameter
 *        table (tdo/params.h): LCM name, use_defaults bit, what the LCM type can hold, and access
 *        as a double. The adapters, tdo-request's --param and tdo-replay's --override read it.
 */
#ifndef TDO_LCM_REQUEST_FIELDS_H
#define TDO_LCM_REQUEST_FIELDS_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** One parameter field of plan_request_t. */
struct RequestField {
  const char* name;        /**< LCM field name (lambda is "lambda_turn": a Python keyword) */
  int32_t param;           /**< row in tdo/params.h; -1: not a tdo_plan_params field (clearance) */
  int32_t use_default_bit; /**< plan_request_t::USE_DEFAULT_* */
  bool integer;            /**< an integer or boolean LCM type: values are whole numbers */
  double lo, hi;           /**< integer fields: what the LCM type holds (boolean: 0, 1) */
  double own_default;      /**< param == -1: the value use_defaults stands for */
  double (*get)(const tdo::plan_request_t&);
  void (*set)(tdo::plan_request_t&, double); /**< integers: v whole and in [lo, hi] */
};

/** Every parameter field of plan_request_t (every row of tdo/params.h once, plus clearance). */
const std::vector<RequestField>& request_fields();

/** The field named `name` (its LCM name, or the library's name: "lambda"), or nullptr. */
const RequestField* find_request_field(const std::string& name);

/** The library's name of a field (its params.h row), or its LCM name when it has no row. */
const char* request_field_param_name(const RequestField& f);

}  // namespace tdo_lcm

#endif  // TDO_LCM_REQUEST_FIELDS_H
