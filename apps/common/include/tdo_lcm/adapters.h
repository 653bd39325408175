/**
 * @file adapters.h
 * @brief Messages <-> libtdo structs. Every function validates counts, finiteness, ranges and
 *        capacities and says why it refused (check.h); none throws on bad content.
 *
 * Incoming direction (message -> library): map_check / map_to_grid, plan_request_from_msg,
 * samples_from_msg. Outgoing (library -> message): trajectory_to_msg, feasibility_to_msg,
 * reject_answer, map_from_occupancy, plan_request_to_msg. check_counts guards every message the
 * apps build before it is encoded: the generated encoders trust the count fields.
 */
#ifndef TDO_LCM_ADAPTERS_H
#define TDO_LCM_ADAPTERS_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo/config.h"
#include "tdo/grid.h"
#include "tdo/pipeline.h"
#include "tdo/types.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

// ---- maps ------------------------------------------------------------------------------------

/**
 * @brief Validate a map message against the planner's capacities without touching a grid.
 * @param cap the planner's capacities (max_voxels, max_boxes, max_clear_cells are checked)
 * @param clearance m, the clearance the grid will be finished with; < 0: the map's hint
 * @return ok; count_mismatch; non_finite (resolution, origin, clearance, boxes); out_of_range
 *         (resolution <= 0, a size <= 0, negative clearance, inverted box, negative run, map_id
 *         < 0); map_capacity (voxels, boxes or clearance stencil); bad_encoding;
 *         unsupported_encoding (OctoMap, not decoded by this build); rle_mismatch.
 */
Check map_check(const tdo::map_t& m, const tdo_capacity& cap, double clearance);

/**
 * @brief map_check, then load the map into `grid`: tdo_grid_reset, every box and occupied voxel,
 *        tdo_grid_finish(clearance). The grid is untouched when map_check fails.
 * @param clearance m; < 0: the map's clearance hint
 * @return the map_check reasons, or grid_error (detail: the tdo_status name) when the library
 *         refuses; the grid is then reset but not finished (not plannable).
 */
Check map_to_grid(const tdo::map_t& m, const tdo_capacity& cap, double clearance, tdo_grid* grid);

/**
 * @brief Check that the grid can be finished with `clearance` (m) at resolution `res` (m): the
 *        library's clearance stencil must fit cap.max_clear_cells.
 * @return ok, non_finite, out_of_range (negative clearance or res <= 0) or map_capacity.
 */
Check clearance_check(double clearance, double res, const tdo_capacity& cap);

/** @return the clearance (m) a map asks for: `requested` unless negative, then the map's hint. */
double effective_clearance(const tdo::map_t& m, double requested);

/**
 * @brief Build a run-length map message (ids and utime left 0 for the caller).
 * @param occupancy one entry per voxel in x-fastest order (non-zero = occupied), or empty (no
 *        voxel occupied: boxes only)
 * @return ok; out_of_range / non_finite for a bad description, clearance or box; count_mismatch
 *         when occupancy is neither empty nor nx*ny*nz long; too_large for more than INT32_MAX
 *         runs or boxes.
 */
Check map_from_occupancy(const tdo_grid_desc& desc, const std::vector<uint8_t>& occupancy,
                         const std::vector<tdo_box>& boxes, double clearance, tdo::map_t* out);

/** @return occupancy of a grid (tdo_grid_is_occupied per voxel, x-fastest), for map_from_occupancy.
 */
std::vector<uint8_t> grid_occupancy(const tdo_grid* grid);

// ---- plan requests ---------------------------------------------------------------------------

/**
 * @brief A plan request message -> the library's request.
 * @param vehicle_id the vehicle this planner serves
 * @param[out] out start, goal and every parameter
 * @param[out] clearance m, the requested clearance (< 0: use the map's hint)
 *        Fields whose bit is set in use_defaults get libtdo's defaults first
 *        (tdo_plan_params_default; a_lat_max = a_max and v_cruise = v_max as tdo/params.h says;
 *        clearance -1, the map's hint); their values in `m` are ignored.
 * @return ok; out_of_range (use_defaults bits beyond USE_DEFAULT_ALL); other_vehicle; non_finite;
 *         out_of_range (negative max_expansions, map_id < -1, or a parameter outside its valid
 *         range in tdo/params.h, for the stages `depth` runs); bad_enum (an enum or boolean field
 *         outside its values, whatever the depth; samples); for the moving start (start_vel,
 *         start_acc -> out->state): non_finite, out_of_range (speed above v_max, acceleration
 *         above a_max, a non-zero state below DEPTH_TRAJECTORY). Every refusal but other_vehicle
 *         names the field (its LCM name, request_fields.h) in Check::field.
 */
Check plan_request_from_msg(const tdo::plan_request_t& m, int32_t vehicle_id, tdo_plan_request* out,
                            double* clearance);

/** Fill start, goal, the start state, clearance and every parameter of `out` from `req` (ids and
 *  utime untouched). */
void plan_request_to_msg(const tdo_plan_request& req, double clearance, tdo::plan_request_t* out);

// ---- answers ---------------------------------------------------------------------------------

/** Identity of an answer: copied from the request. */
struct AnswerIds {
  int64_t utime = 0;        /**< us since the epoch, when the answer is sent */
  int64_t request_id = -1;  /**< of the request */
  int64_t request_seq = -1; /**< plan_request_t.seq of the request */
  int32_t vehicle_id = 0;   /**< of the request */
  int64_t map_id = -1;      /**< map planned on; -1 = none */
};

/**
 * @brief A plan result -> trajectory message (status, paths, samples, metrics). The compact form
 *        is compact.h's compact_to_msg.
 * @param plan_ms ms, wall time of the library call
 * @param with_samples false: n_samples 0 and no samples (the request's SAMPLES_OFF)
 * @param planner the planner whose last plan `r` is: reads the samples the library did not store
 *        (r.samples NULL, tdo_capacity.stream_samples) with tdo_planner_each_sample
 *        (tdo_samples::plan_samples); may be null when r.samples is stored
 * @return ok; too_large (a count above INT32_MAX); non_finite (a path point or sample, or a NaN
 *         metric; metrics may be +inf where the library documents HUGE_VAL); count_mismatch (a
 *         null array with a non-zero count and no planner); library_error (the planner could not
 *         hand over r.n_samples samples).
 */
Check trajectory_to_msg(const tdo_plan_result& r, const tdo_plan_request& req, const AnswerIds& ids,
                        double plan_ms, tdo::trajectory_t* out, bool with_samples = true,
                        const tdo_planner* planner = nullptr);

/**
 * @brief A plan result -> feasibility message (maxima, limits, violations).
 * @param clearance m, the clearance the grid was finished with
 * @return ok; too_large; count_mismatch (null violations with a non-zero count); non_finite (a
 * NaN).
 */
Check feasibility_to_msg(const tdo_plan_result& r, const tdo_plan_request& req, double clearance,
                         const AnswerIds& ids, tdo::feasibility_t* out);

/**
 * @brief Error answers: empty arrays, status_code, status and detail. For requests that never
 *        reached the library use tdo::trajectory_t::STATUS_REJECTED and the reason's name.
 */
void error_answer(const AnswerIds& ids, int32_t status_code, const std::string& status,
                  const std::string& detail, tdo::trajectory_t* traj, tdo::feasibility_t* feas);

/**
 * @brief Trajectory message -> library samples (for a follower or a replay comparison).
 * @return ok; count_mismatch (n_samples vs samples, a sample not of 10 numbers); non_finite;
 *         out_of_range (times not increasing).
 */
Check samples_from_msg(const tdo::trajectory_t& m, std::vector<tdo_sample>* out);

// ---- counts ----------------------------------------------------------------------------------

/** @return ok or count_mismatch (naming the field) when a count field differs from its array. */
Check check_counts(const tdo::map_t& m);
Check check_counts(const tdo::obstacles_t& m);
Check check_counts(const tdo::trajectory_t& m);
Check check_counts(const tdo::feasibility_t& m);
Check check_counts(const tdo::status_t& m);

}  // namespace tdo_lcm

#endif  // TDO_LCM_ADAPTERS_H
