/* Capacities of the Map4-sized firmware configuration (50 x 50 x 20 voxels; docs/embedded.md). */
#ifndef TDO_DEMO_CONFIG_H
#define TDO_DEMO_CONFIG_H

/* m, obstacle clearance (tdo-plan's default for .tdomap files) */
#define TDO_DEMO_CLEARANCE 0.5
/* search states per direction: Map4's query needs 264566 with the default parameters (retry off),
 * +6.1 % */
#define TDO_DEMO_MAX_NODES 280704u
/* open-list items per direction: Map4's query holds at most 68884 (tdo-plan's open_list_peak), +5 %
 */
#define TDO_DEMO_MAX_OPEN 72336u
/* voxels in one grid path (Map4's path has 113) */
#define TDO_DEMO_MAX_PATH 160u
/* trajectory samples at dt = 0.01 s (Map4's flight: 7389) */
#define TDO_DEMO_MAX_SAMPLES 8192u
/* 1: samples are not stored (0 bytes instead of 84 each); verified and printed in streaming passes
 */
#define TDO_DEMO_STREAM_SAMPLES 1u
/* speed-profile pieces: 8 per plateau + 1; Map4's path has 52 segments, 18 lines and 34 corner
 * curves, each curve flown in 4 parts (trajectory.h): 8 x (18 + 4 x 34) + 1 */
#define TDO_DEMO_MAX_PROFILE 1233u
/* waypoints after the correction (Map4's plan has 19) */
#define TDO_DEMO_MAX_WAYPOINTS 40u
/* feasibility violations listed in the report (all are counted) */
#define TDO_DEMO_MAX_VIOLATIONS 16u
/* bytes of the static arena; the demo checks tdo_planner_footprint against it */
#define TDO_DEMO_ARENA_BYTES (20760u * 1024u)

#endif /* TDO_DEMO_CONFIG_H */
