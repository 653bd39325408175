/**
 * @file check.h
 * @brief The outcome of every adapter and wire check: a named reason plus a human-readable detail.
 *
 * Reasons are the keys the apps count in their status_t heartbeat and the `status` string of an
 * error answer, so their names are stable.
 */
#ifndef TDO_LCM_CHECK_H
#define TDO_LCM_CHECK_H

#include <cstdio>
#include <string>
#include <utility>

namespace tdo_lcm {

/** `v` with every significant digit (%.17g): a detail quotes the exact value it refused. */
inline std::string exact_num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

/** Why a message was not accepted. Reason::ok is the only success. */
enum class Reason {
  ok = 0,
  // ---- wire level (before decoding)
  bad_fingerprint, /**< the message's fingerprint is not the expected type's */
  truncated,       /**< fewer bytes than the fields and array counts need */
  trailing_bytes,  /**< more bytes than the message needs */
  negative_count,  /**< an array count is negative */
  bad_string,      /**< a string without its terminating zero, or of length 0 on the wire */
  decode_error,    /**< the generated decoder failed after the wire check passed */
  // ---- content
  count_mismatch,       /**< an array count field differs from its array's size */
  non_finite,           /**< a NaN or infinite number where a finite one is required */
  out_of_range,         /**< a number outside its documented range */
  bad_enum,             /**< an enum-like field outside its constants */
  other_vehicle,        /**< addressed to another vehicle (ignored, not answered) */
  map_capacity,         /**< the map exceeds the planner's configured capacities */
  bad_encoding,         /**< unknown map encoding */
  unsupported_encoding, /**< a known encoding this build cannot decode */
  rle_mismatch,         /**< the run lengths do not add up to the voxel count */
  grid_error,           /**< the library refused the map (detail: the tdo_status name) */
  no_map,               /**< a request before any map was loaded */
  unknown_map,          /**< a request for a map id other than the loaded one */
  too_large,            /**< a library result does not fit in a message (count > INT32_MAX) */
  // ---- follower and simulator (tdo-avoid, tdo-sim)
  no_plan,       /**< a trajectory answer without a plan to follow (error status, < 2 samples) */
  over_capacity, /**< more items than the program's configured capacity (movers, samples) */
  library_error, /**< the library refused the input (detail: the tdo_status name) */
  // ---- map updates (map_update.h)
  gap,           /**< an update's seq skips one: updates are missing, the map is stale */
  stale_update,  /**< an update's seq is not after the last one applied (old or repeated) */
  other_map,     /**< an update for a map_id other than the loaded map */
  contradictory, /**< an update sets and clears the same voxel */
  map_stale,     /**< a request while the map is known to be stale (a full map was asked for) */
};

/** @return the stable lower-case name of a reason, e.g. "non_finite". */
const char* reason_str(Reason reason);

/** Outcome of a check: the reason and a detail naming the offending field and value. */
struct Check {
  Reason reason = Reason::ok;
  std::string detail; /**< empty when ok */
  std::string field;  /**< the message field at fault ("v_max", "start[2]"), when one is */

  bool ok() const { return reason == Reason::ok; }
};

/** @return a failed check. */
inline Check fail(Reason reason, std::string detail) {
  return Check{reason, std::move(detail), {}};
}

/** @return a failed check naming the field at fault. */
inline Check fail_field(Reason reason, std::string field, std::string detail) {
  return Check{reason, std::move(detail), std::move(field)};
}

}  // namespace tdo_lcm

#endif  // TDO_LCM_CHECK_H
