/**
 * @file params.h
 * @brief The one table of plan parameters: every field of tdo_plan_params with its name, type,
 *        unit, default, valid range, help text and place in the struct.
 *
 * The library's validation (tdo_planner_plan), tdo-plan's options and JSON, the LCM adapters,
 * tdo-request's --param, replay's overrides, the bench planners and tdo-tune all read this table;
 * adding a parameter means adding its field to tdo_plan_params, a row to the table
 * (libtdo/src/params.cpp) and the code that uses it (plus its field in plan_request_t.lcm).
 * `tdo-plan --list-params` prints it. Plain C, static data, no allocation.
 */
#ifndef TDO_PARAMS_H
#define TDO_PARAMS_H

#include <stddef.h>
#include <stdint.h>

#include "tdo/pipeline.h"
#include "tdo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How a parameter is stored in tdo_plan_params. */
typedef enum tdo_param_type {
  TDO_PARAM_REAL = 0, /**< double */
  TDO_PARAM_UINT = 1, /**< uint32_t */
  TDO_PARAM_BOOL = 2, /**< int, 0 or 1; `values` names both */
  TDO_PARAM_ENUM = 3  /**< an enum or int holding 0 .. n_values - 1; `values` names each */
} tdo_param_type;

/** One row of the table. Angles are radians here (tools print and read them in degrees). */
typedef struct tdo_param_info {
  const char* name;     /**< field name in tdo_plan_params, e.g. "lambda" */
  tdo_param_type type;  /**< storage and meaning of the value */
  const char* unit;     /**< "m", "rad", "m/s", "m/s^2", "m/s^3", "s" or "" (a number) */
  double def;           /**< default (tdo_plan_params_default) */
  int32_t default_of;   /**< >= 0: index of the parameter whose value is this one's default when
                             a caller leaves it to the defaults (a_lat_max follows a_max); -1 */
  double min;           /**< smallest valid value (-HUGE_VAL: none) */
  double max;           /**< largest valid value (HUGE_VAL: none) */
  int min_open;         /**< 1: min itself is invalid (value > min) */
  int max_open;         /**< 1: max itself is invalid (value < max) */
  tdo_plan_depth stage; /**< checked when tdo_plan_params.depth >= stage (the stage using it) */
  const char* const* values; /**< BOOL and ENUM: the name of each value 0 .. n_values - 1 */
  uint32_t n_values;         /**< BOOL: 2; ENUM: the count; else 0 */
  int has_plain;   /**< 1: the plain search (no turn-deviation terms) sets it to `plain` */
  double plain;    /**< its value in the plain search (tdo_plan_params_plain) */
  double tune_min; /**< tune_min < tune_max: the range a tuner searches (tdo-tune) */
  double tune_max;
  size_t offset;    /**< offsetof(tdo_plan_params, field) */
  size_t size;      /**< sizeof the field (enums are 1 byte with short enums, e.g. arm-none-eabi) */
  const char* help; /**< one line: what it does */
} tdo_param_info;

/** Number of rows: one per field of tdo_plan_params, in the struct's order. */
uint32_t tdo_param_count(void);

/** Row `i`, or NULL when i >= tdo_param_count(). */
const tdo_param_info* tdo_param_at(uint32_t i);

/** Index of the row named `name`, or -1 (also for NULL). */
int32_t tdo_param_find(const char* name);

/** 1 when `v` is a valid value of row `i` (finite, in range, whole for UINT/BOOL/ENUM), else 0. */
int tdo_param_valid(uint32_t i, double v);

/** The value of row `i` in `p` as a double (enums and flags as their integer); NaN for a bad
 *  index or a NULL pointer. */
double tdo_param_get(const tdo_plan_params* p, uint32_t i);

/**
 * @brief Store `v` in row `i` of `p` when the field can hold it: any double for REAL (also one
 *        outside the valid range: tdo_plan_params_check judges it), a whole number in
 *        [0, 2^32 - 1] for UINT, one of the values for BOOL and ENUM.
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT (p unchanged) for a NULL pointer, a bad index or a
 *         value the field cannot hold.
 */
tdo_status tdo_param_set(tdo_plan_params* p, uint32_t i, double v);

/**
 * @brief The validation of tdo_planner_plan: `depth` first, then every row whose stage `depth`
 *        runs, in table order.
 * @param bad when not NULL, receives the index of the first invalid row (unchanged on TDO_OK)
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for NULL `p` (bad untouched) or an invalid value.
 */
tdo_status tdo_plan_params_check(const tdo_plan_params* p, uint32_t* bad);

/** Switch the turn-deviation terms off: every row with has_plain gets its plain value (lambda =
 *  mu = 0, no direction constraint, the optimal stop). The baselines' search. */
void tdo_plan_params_plain(tdo_plan_params* p);

#ifdef __cplusplus
}
#endif

#endif /* TDO_PARAMS_H */
