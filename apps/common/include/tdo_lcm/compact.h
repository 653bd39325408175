/**
 * @file compact.h
 * @brief The compact form of a trajectory message (trajectory_t's segment_* and piece_* fields):
 *        library -> message, and message -> tdo_traj_eval.h view or samples at dt.
 */
#ifndef TDO_LCM_COMPACT_H
#define TDO_LCM_COMPACT_H

#include <cstdint>
#include <vector>

#include "tdo/path.h"
#include "tdo/traj_profile.h"
#include "tdo/trajectory.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"
#include "tdo_traj_eval.h"

namespace tdo_lcm {

/** Empty the compact form of `out` (no trajectory). */
void clear_compact(tdo::trajectory_t* out);

/**
 * @brief The compact form of the trajectory the last tdo_traj_run of `traj` computed on `path`
 *        (the segments that run was given): segments, pieces, duration, length, sample count.
 * @return ok; library_error when `traj` has no profile (detail: the tdo_status name); too_large
 *         (a count above INT32_MAX / 12); non_finite (a point, length or piece value). `out`'s
 *         compact form is empty unless ok.
 */
Check compact_to_msg(const tdo_path& path, const tdo_traj* traj, tdo::trajectory_t* out);

/**
 * @brief Point a tdo_traj_view at the compact form of `m` (valid while `m` is unchanged).
 * @return ok; count_mismatch (a count and its array, or n_segment_points != 12 n_segments);
 *         no_plan (no segments or pieces); non_finite, bad_enum (segment kind), out_of_range
 *         (order of knots and segment starts, negative lengths): tdo_traj_check's verdict.
 */
Check compact_view(const tdo::trajectory_t& m, tdo_traj_view* out);

/**
 * @brief The samples at dt (t = i * dt, i < sample_count) regenerated from the compact form.
 * @param max_samples capacity: more samples are refused (over_capacity)
 * @return compact_view's reasons; out_of_range (dt <= 0 or non-finite, sample_count < 2);
 *         over_capacity.
 */
Check samples_from_compact(const tdo::trajectory_t& m, uint32_t max_samples,
                           std::vector<tdo_sample>* out);

}  // namespace tdo_lcm

#endif  // TDO_LCM_COMPACT_H
