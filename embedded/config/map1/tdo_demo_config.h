/* Capacities of the Map1 firmware configuration (docs/embedded.md explains every number). */
#ifndef TDO_DEMO_CONFIG_H
#define TDO_DEMO_CONFIG_H

/* m, obstacle clearance (tdo-plan's default for .tdomap files) */
#define TDO_DEMO_CLEARANCE 0.5
/* search states per direction: Map1's query needs 1799 with the default parameters (retry off),
 * +10.3 % */
#define TDO_DEMO_MAX_NODES 1984u
/* open-list items per direction: Map1's query holds at most 1595 (tdo-plan's open_list_peak), +5.3
 * %
 */
#define TDO_DEMO_MAX_OPEN 1680u
/* voxels in one grid path (Map1's path has 26; it also sizes the correction's arrays) */
#define TDO_DEMO_MAX_PATH 32u
/* trajectory samples at dt = 0.01 s (Map1's flight: 1359) */
#define TDO_DEMO_MAX_SAMPLES 2048u
/* 1: samples are not stored (0 bytes instead of 84 each); verified and printed in streaming passes
 */
#define TDO_DEMO_STREAM_SAMPLES 1u
/* speed-profile pieces: 8 per plateau + 1; Map1's plan has 10 segments, 4 lines and 6 corner
 * curves, each curve flown in 4 parts (trajectory.h): 8 x (4 + 4 x 6) + 1 */
#define TDO_DEMO_MAX_PROFILE 225u
/* waypoints after the correction (Map1's plan has 5); sizes the smoothing and trajectory
 * segment arrays (3 segments per waypoint) */
#define TDO_DEMO_MAX_WAYPOINTS 8u
/* feasibility violations listed in the report (all are counted) */
#define TDO_DEMO_MAX_VIOLATIONS 16u
/* bytes of the static arena; the demo checks tdo_planner_footprint against it */
#define TDO_DEMO_ARENA_BYTES (236u * 1024u)

#endif /* TDO_DEMO_CONFIG_H */
