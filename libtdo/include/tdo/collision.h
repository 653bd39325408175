/**
 * @file collision.h
 * @brief Exact continuous clearance queries against the grid's obstacle geometry.
 *
 * Geometry = the obstacle boxes (exact) plus the occupied voxel cubes of voxel maps and OcTrees.
 * Queries are exact (closed-form segment-to-box distance), accelerated by a distance field built in
 * tdo_grid_finish; no sampling that can step over a thin obstacle. Obstacle parts outside the grid
 * bounds are considered too.
 */
#ifndef TDO_COLLISION_H
#define TDO_COLLISION_H

#include "tdo/grid.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Exact Euclidean distance from p to the obstacle geometry, capped.
 * @param cap m; the result is min(true distance, cap). Larger caps cost more work.
 * @return m; 0 inside an obstacle; -1 for a null or unfinished grid.
 */
double tdo_collision_point_distance(const tdo_grid* grid, tdo_vec3 p, double cap);

/**
 * @brief Exact minimum distance from the segment [a, b] to the obstacle geometry, capped.
 * @return m, min(true distance, cap); -1 for a null or unfinished grid or non-finite points.
 */
double tdo_collision_segment_distance(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double cap);

/**
 * @brief 1 when every point of [a, b] lies inside the grid bounds and keeps at least `clearance`
 *        (m) from the obstacle geometry; else 0. Exact, conservative never, bounded work.
 */
int tdo_collision_segment_clear(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance);

/**
 * @brief 1 when every point of the cubic Bezier curve with control points c[0..3] lies inside the
 *        bounds and keeps at least `clearance` (m); else 0. Subdivides with the convex-hull bound,
 *        so a 1 is a proof; a 0 may be conservative within `tolerance` (m) of the limit.
 */
int tdo_collision_bezier_clear(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                               double tolerance);

#ifdef __cplusplus
}
#endif

#endif /* TDO_COLLISION_H */
