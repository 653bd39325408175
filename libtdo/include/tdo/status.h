/**
 * @file status.h
 * @brief The one status enum of libtdo: a name for every failure.
 */
#ifndef TDO_STATUS_H
#define TDO_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

/** Result of every fallible libtdo call. TDO_OK is zero; every failure has its own name. */
typedef enum tdo_status {
  TDO_OK = 0,                      /**< success */
  TDO_ERR_INVALID_ARGUMENT = 1,    /**< null pointer, non-finite or out-of-range parameter */
  TDO_ERR_ARENA_TOO_SMALL = 2,     /**< the caller's arena is smaller than the footprint */
  TDO_ERR_MAP_CAPACITY = 3,        /**< map has more voxels than the configured capacity */
  TDO_ERR_BOX_CAPACITY = 4,        /**< more obstacle boxes than the configured capacity */
  TDO_ERR_INVALID_BOX = 5,         /**< box with max <= min on an axis, or non-finite corner */
  TDO_ERR_MAP_NOT_READY = 6,       /**< planning before a map was finished */
  TDO_ERR_START_OUT_OF_BOUNDS = 7, /**< start outside the map bounds */
  TDO_ERR_GOAL_OUT_OF_BOUNDS = 8,  /**< goal outside the map bounds */
  TDO_ERR_START_BLOCKED = 9,       /**< start voxel intersects an obstacle or is within clearance */
  TDO_ERR_GOAL_BLOCKED = 10,       /**< goal voxel intersects an obstacle or is within clearance */
  TDO_ERR_START_EQUALS_GOAL = 11,  /**< start and goal are the same point */
  TDO_ERR_NO_PATH = 12,            /**< search exhausted: goal unreachable */
  TDO_ERR_NODE_CAPACITY = 13,      /**< search node pool full */
  TDO_ERR_PATH_CAPACITY = 14,      /**< path longer than the path buffer */
  TDO_ERR_BUDGET = 15,             /**< expansion or iteration budget exhausted */
  TDO_ERR_INFEASIBLE = 16,         /**< no trajectory within the dynamic limits */
  TDO_ERR_LOCAL_MINIMUM = 17,      /**< potential-field follower trapped, escape failed */
  TDO_ERR_OBSTACLE_CAPACITY = 18,  /**< more moving obstacles than the configured capacity */
  TDO_ERR_SAMPLE_CAPACITY = 19,    /**< more trajectory samples than the configured capacity */
  TDO_ERR_CLEARANCE_CAPACITY =
      20,                      /**< clearance reaches further than the configured voxel radius */
  TDO_ERR_NOT_CONFIGURED = 21, /**< a pipeline stage was asked for but its capacities are zero */
  TDO_ERR_OPEN_CAPACITY = 22,  /**< search open list full (tdo_search_config.max_open) */
  TDO_ERR_UPDATE_CONTRADICTORY = 23, /**< a map update sets and clears the same voxel */
  TDO_ERR_STATE_NOT_FINITE = 24,     /**< start velocity or acceleration has a NaN or infinity */
  TDO_ERR_STATE_TOO_FAST = 25,       /**< start speed above v_max */
  TDO_ERR_STATE_OVER_LIMITS =
      26, /**< start acceleration above a_max, or the jerk-limited removal of the acceleration
               would take the speed above v_max (docs/design.md s.5, moving start) */
  TDO_ERR_STATE_CANNOT_STOP =
      27, /**< an obstacle or the map bound lies within the stopping distance along the start
               velocity: no braking or curving in keeps the clearance (docs/design.md s.5) */
  TDO_ERR_SETPOINT_STALE =
      28, /**< the setpoint's time lies more than tdo_sim_params.setpoint_max_age behind the
               simulator's clock: the step braked to a hover instead of flying it (sim.h) */
  TDO_STATUS_COUNT = 29 /**< number of statuses (not a status) */
} tdo_status;

/**
 * @brief Stable lower-case name of a status, e.g. "start_blocked".
 * @return a static string; "unknown_status" for values outside the enum.
 */
const char* tdo_status_str(tdo_status status);

#ifdef __cplusplus
}
#endif

#endif /* TDO_STATUS_H */
