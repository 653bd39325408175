/* Capacities of the Map5 firmware configuration (50 x 50 x 20 voxels, 500 columns;
 * docs/embedded.md): the 1 MB goal of issue 19. Needs from `tdo-plan --map maps/map5.tdomap --retry
 * off` (the firmware has no obstacle-aware retry). */
#ifndef TDO_DEMO_CONFIG_H
#define TDO_DEMO_CONFIG_H

/* m, obstacle clearance (tdo-plan's default for .tdomap files) */
#define TDO_DEMO_CLEARANCE 0.5
/* search states per direction: Map5's query needs 1608 (tdo-plan's states line), +10 % */
#define TDO_DEMO_MAX_NODES 1768u
/* open-list items per direction: Map5's query holds at most 1428 (open_list_peak), +10 % */
#define TDO_DEMO_MAX_OPEN 1568u
/* voxels in one grid path (Map5's path has 55) */
#define TDO_DEMO_MAX_PATH 64u
/* trajectory samples at dt = 0.01 s (Map5's flight: 29.23 s, 2924 samples) */
#define TDO_DEMO_MAX_SAMPLES 4096u
/* 1: samples are not stored (0 bytes instead of 84 each); verified and printed in streaming passes
 */
#define TDO_DEMO_STREAM_SAMPLES 1u
/* speed-profile pieces: TDO_TRAJ_PIECES_PER_SEGMENT (32) per path segment + 1, Map5's plan has 16
 * segments (the demo's @path_segments line): every curve flown in its 4 parts, as tdo-plan flies it
 */
#define TDO_DEMO_MAX_PROFILE 513u
/* waypoints after the correction (Map5's plan has 7) */
#define TDO_DEMO_MAX_WAYPOINTS 12u
/* feasibility violations listed in the report (all are counted) */
#define TDO_DEMO_MAX_VIOLATIONS 16u
/* bytes of the static arena; the demo checks tdo_planner_footprint against it */
#define TDO_DEMO_ARENA_BYTES (779u * 1024u)

#endif /* TDO_DEMO_CONFIG_H */
