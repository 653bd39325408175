#include "tdo/status.h"

extern "C" const char* tdo_status_str(tdo_status status) {
  switch (status) {
    case TDO_OK:
      return "ok";
    case TDO_ERR_INVALID_ARGUMENT:
      return "invalid_argument";
    case TDO_ERR_ARENA_TOO_SMALL:
      return "arena_too_small";
    case TDO_ERR_MAP_CAPACITY:
      return "map_capacity";
    case TDO_ERR_BOX_CAPACITY:
      return "box_capacity";
    case TDO_ERR_INVALID_BOX:
      return "invalid_box";
    case TDO_ERR_MAP_NOT_READY:
      return "map_not_ready";
    case TDO_ERR_START_OUT_OF_BOUNDS:
      return "start_out_of_bounds";
    case TDO_ERR_GOAL_OUT_OF_BOUNDS:
      return "goal_out_of_bounds";
    case TDO_ERR_START_BLOCKED:
      return "start_blocked";
    case TDO_ERR_GOAL_BLOCKED:
      return "goal_blocked";
    case TDO_ERR_START_EQUALS_GOAL:
      return "start_equals_goal";
    case TDO_ERR_NO_PATH:
      return "no_path";
    case TDO_ERR_NODE_CAPACITY:
      return "node_capacity";
    case TDO_ERR_PATH_CAPACITY:
      return "path_capacity";
    case TDO_ERR_BUDGET:
      return "budget";
    case TDO_ERR_INFEASIBLE:
      return "infeasible";
    case TDO_ERR_LOCAL_MINIMUM:
      return "local_minimum";
    case TDO_ERR_OBSTACLE_CAPACITY:
      return "obstacle_capacity";
    case TDO_ERR_SAMPLE_CAPACITY:
      return "sample_capacity";
    case TDO_ERR_CLEARANCE_CAPACITY:
      return "clearance_capacity";
    case TDO_ERR_NOT_CONFIGURED:
      return "not_configured";
    case TDO_ERR_OPEN_CAPACITY:
      return "open_capacity";
    case TDO_ERR_UPDATE_CONTRADICTORY:
      return "update_contradictory";
    case TDO_ERR_STATE_NOT_FINITE:
      return "state_not_finite";
    case TDO_ERR_STATE_TOO_FAST:
      return "state_too_fast";
    case TDO_ERR_STATE_OVER_LIMITS:
      return "state_over_limits";
    case TDO_ERR_STATE_CANNOT_STOP:
      return "state_cannot_stop";
    case TDO_ERR_SETPOINT_STALE:
      return "setpoint_stale";
    case TDO_STATUS_COUNT:
      break;
  }
  return "unknown_status";
}
