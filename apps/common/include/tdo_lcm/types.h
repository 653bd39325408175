/**
 * @file types.h
 * @brief The generated message types (C++ and, for their type info, C) and the default channels.
 *
 * lcm-gen's C++ classes do not initialise their members and their encoders trust the count
 * fields: always value-initialise a message (`tdo::map_t m{};`) and keep counts equal to the
 * array sizes (adapters.h check_counts).
 */
#ifndef TDO_LCM_TYPES_H
#define TDO_LCM_TYPES_H

#include <lcm/lcm_coretypes.h>

#include "tdo/feasibility_t.hpp"
#include "tdo/map_request_t.hpp"
#include "tdo/map_t.hpp"
#include "tdo/map_update_t.hpp"
#include "tdo/obstacles_t.hpp"
#include "tdo/plan_request_t.hpp"
#include "tdo/setpoint_t.hpp"
#include "tdo/status_t.hpp"
#include "tdo/trajectory_t.hpp"
#include "tdo/vehicle_state_t.hpp"
#include "tdo_feasibility_t.h"
#include "tdo_map_request_t.h"
#include "tdo_map_t.h"
#include "tdo_map_update_t.h"
#include "tdo_obstacles_t.h"
#include "tdo_plan_request_t.h"
#include "tdo_setpoint_t.h"
#include "tdo_status_t.h"
#include "tdo_trajectory_t.h"
#include "tdo_vehicle_state_t.h"

namespace tdo_lcm {

/** Default channel names (docs/design.md s.11). Every app can rename them on its command line. */
inline constexpr const char* kChannelMap = "TDO_MAP";
inline constexpr const char* kChannelMapUpdate = "TDO_MAP_UPDATE";
inline constexpr const char* kChannelMapRequest = "TDO_MAP_REQUEST";
inline constexpr const char* kChannelObstacles = "TDO_OBSTACLES";
inline constexpr const char* kChannelPlanRequest = "TDO_PLAN_REQUEST";
inline constexpr const char* kChannelTrajectory = "TDO_TRAJECTORY";
inline constexpr const char* kChannelFeasibility = "TDO_FEASIBILITY";
inline constexpr const char* kChannelVehicleState = "TDO_UAV_STATE";
inline constexpr const char* kChannelSetpoint = "TDO_SETPOINT";
inline constexpr const char* kChannelStatus = "TDO_STATUS";

/** Default LCM URL: UDP multicast that stays on this host (ttl=0), with a 4 MB receive buffer
 *  that holds the largest messages (url.h; Bus adds it to any udpm:// URL without one). */
inline constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

/** The generated C type info of a C++ message type (same fingerprint, same wire layout). */
template <class Msg>
struct TypeInfo;

#define TDO_LCM_TYPE_INFO(CPP, C)                                       \
  template <>                                                           \
  struct TypeInfo<CPP> {                                                \
    static const lcm_type_info_t* get() { return C##_get_type_info(); } \
  }
TDO_LCM_TYPE_INFO(tdo::map_t, tdo_map_t);
TDO_LCM_TYPE_INFO(tdo::obstacles_t, tdo_obstacles_t);
TDO_LCM_TYPE_INFO(tdo::plan_request_t, tdo_plan_request_t);
TDO_LCM_TYPE_INFO(tdo::trajectory_t, tdo_trajectory_t);
TDO_LCM_TYPE_INFO(tdo::feasibility_t, tdo_feasibility_t);
TDO_LCM_TYPE_INFO(tdo::vehicle_state_t, tdo_vehicle_state_t);
TDO_LCM_TYPE_INFO(tdo::setpoint_t, tdo_setpoint_t);
TDO_LCM_TYPE_INFO(tdo::status_t, tdo_status_t);
TDO_LCM_TYPE_INFO(tdo::map_update_t, tdo_map_update_t);
TDO_LCM_TYPE_INFO(tdo::map_request_t, tdo_map_request_t);
#undef TDO_LCM_TYPE_INFO

}  // namespace tdo_lcm

#endif  // TDO_LCM_TYPES_H
