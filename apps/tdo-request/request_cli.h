/**
 * @file request_cli.h
 * @brief tdo-request minus its main(): a plan request from start, goal and NAME=VALUE parameters
 *        (every other parameter left to libtdo's defaults through use_defaults), and the answer
 *        printed as tdo-plan's summary table.
 */
#ifndef TDO_REQUEST_CLI_H
#define TDO_REQUEST_CLI_H

#include <string>
#include <vector>

#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** @return the names --param accepts, comma-separated. */
std::string request_param_names();

/**
 * @brief Set one parameter of `m` from "NAME=VALUE" and clear its use_defaults bit. Names are the
 *        plan_request_t fields (lambda for lambda_turn); integer and boolean fields take whole
 *        numbers in their range (enums: their constants' values, e.g. smoothing=1 for ARC).
 * @return false with `error` for an unknown name, a value that is no number or out of range.
 */
bool apply_request_param(const std::string& text, tdo::plan_request_t* m, std::string* error);

/**
 * @brief A request from start to goal with every parameter left to the defaults, then `params`.
 * @return false with `error` when a parameter is refused (apply_request_param).
 */
bool build_request(const double start[3], const double goal[3],
                   const std::vector<std::string>& params, tdo::plan_request_t* m,
                   std::string* error);

/** @return the answer as tdo-plan's summary table (plus the request, refusal and message size). */
std::string answer_summary(const tdo::plan_request_t& req, const tdo::trajectory_t& t,
                           const tdo::feasibility_t& f, std::size_t traj_bytes);

}  // namespace tdo_lcm

#endif  // TDO_REQUEST_CLI_H
