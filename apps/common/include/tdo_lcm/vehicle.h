/**
 * @file vehicle.h
 * @brief Vehicle messages <-> libtdo structs (apf.h, sim.h): vehicle_state_t <-> tdo_vehicle_state,
 *        setpoint_t <-> tdo_setpoint, obstacles_t <-> tdo_mover. Same rules as adapters.h: every
 *        function validates counts, finiteness and ranges and names why it refused; none throws.
 *
 * Time: the library works in seconds on a monotonic clock, the messages in microseconds since the
 * epoch (utime). A program picks a reference utime (its start, or the first message) and converts
 * with seconds_since / utime_at, so that the seconds keep full precision (an exact integer
 * difference before the conversion, not 1.7e9 s in a double).
 */
#ifndef TDO_LCM_VEHICLE_H
#define TDO_LCM_VEHICLE_H

#include <cstdint>
#include <vector>

#include "tdo/apf.h"
#include "tdo/types.h"
#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/** @return s from `utime_ref` to `utime` (both us since the epoch); negative when before. */
double seconds_since(int64_t utime, int64_t utime_ref);

/** @return us since the epoch of `t` s after `utime_ref`, rounded to the microsecond. */
int64_t utime_at(int64_t utime_ref, double t);

/**
 * @brief vehicle_state_t -> tdo_vehicle_state (t = seconds_since(utime, utime_ref)).
 * @param vehicle_id the vehicle this program serves
 * @return ok; other_vehicle (checked first); non_finite (position, velocity, acceleration, yaw,
 *         naming the field and index).
 */
Check vehicle_state_from_msg(const tdo::vehicle_state_t& m, int32_t vehicle_id, int64_t utime_ref,
                             tdo_vehicle_state* out);

/**
 * @brief tdo_vehicle_state -> vehicle_state_t (utime = utime_at(utime_ref, s.t)).
 * @param yaw rad, heading about z
 * @return ok; non_finite (the message is then not written).
 */
Check vehicle_state_to_msg(const tdo_vehicle_state& s, int64_t utime_ref, int32_t vehicle_id,
                           int64_t seq, double yaw, tdo::vehicle_state_t* out);

/**
 * @brief setpoint_t -> tdo_setpoint. The message carries the time it was computed, so
 *        out->t = seconds_since(utime, utime_ref); a consumer that needs the target time adds its
 *        step. The status fields are not interpreted.
 * @return ok; other_vehicle (checked first); non_finite (position, velocity, acceleration, yaw).
 */
Check setpoint_from_msg(const tdo::setpoint_t& m, int32_t vehicle_id, int64_t utime_ref,
                        tdo_setpoint* out);

/**
 * @brief tdo_setpoint -> setpoint_t.
 * @param utime us since the epoch, when it was computed (the time of the state it answers)
 * @param request_id trajectory followed; -1 = none (hold)
 * @param status the follower step's status (status_code and its tdo_status_str name)
 * @return ok; non_finite (the message is then not written).
 */
Check setpoint_to_msg(const tdo_setpoint& s, int64_t utime, int32_t vehicle_id, int64_t seq,
                      int64_t request_id, double yaw, tdo_status status, tdo::setpoint_t* out);

/**
 * @brief obstacles_t -> movers at the message's time.
 * @param vehicle_id the vehicle this program serves; messages for -1 (every vehicle) or it pass
 * @param max_movers the program's capacity
 * @return ok; other_vehicle (checked first); count_mismatch (n against each array, a row not of 3
 *         numbers); over_capacity (n > max_movers); non_finite (position, velocity, radius);
 *         out_of_range (radius not > 0, id < 0).
 */
Check movers_from_msg(const tdo::obstacles_t& m, int32_t vehicle_id, uint32_t max_movers,
                      std::vector<tdo_mover>* out);

/**
 * @brief Movers -> obstacles_t.
 * @param utime us since the epoch, time of the positions
 * @return ok; count_mismatch (null array with n > 0); too_large (n > INT32_MAX or an id above
 *         INT32_MAX); non_finite; out_of_range (radius not > 0).
 */
Check movers_to_msg(const tdo_mover* movers, uint32_t n, int64_t utime, int32_t vehicle_id,
                    int64_t seq, tdo::obstacles_t* out);

/**
 * @brief Movers observed at `t_obs` moved on, at constant velocity, to `t` (both s); the shift
 *        is clamped to [0, max_shift_s] so a late or early message never throws them far.
 */
void movers_advance(std::vector<tdo_mover>* movers, double t_obs, double t, double max_shift_s);

/** @return rad, heading of v about z (atan2(vy, vx)), or `previous` when |v_xy| < 0.1 m/s. */
double heading_of(tdo_vec3 v, double previous);

}  // namespace tdo_lcm

#endif  // TDO_LCM_VEHICLE_H
