/**
 * @file collision.h
 * @brief Exact continuous clearance queries against the grid's obstacle geometry.
 *
 * Geometry = the obstacle boxes (exact, including their parts outside the grid bounds) plus the
 * occupied voxel cubes of voxel maps and OcTrees. Queries are exact (closed-form segment-to-box
 * distance); no sampling that can step over a thin obstacle. Two structures built by
 * tdo_grid_finish make them fast:
 * - a bucket index of the boxes over coarse cells (4^3 voxels or more): a box is listed in every
 *   cell that the box grown by the reach max(clearance of the finish, 2 voxel edges) touches, so a
 *   query that reaches no further than that looks only at the cells the segment crosses; queries
 *   reaching further (a larger clearance or cap) scan every box;
 * - a distance field (exact centre-to-centre Euclidean distance to the nearest occupied voxel),
 *   used only as a bound to skip pieces of a segment far from the cubes;
 * - a brick index of the surface cubes (4^3 voxels per brick: a mask and a tight box), so the
 *   exact distance near a piece visits the nearest bricks first and stops at the first that
 *   cannot hold anything nearer (docs/design.md s.0, "Distance to the cubes").
 * All functions are read-only on the grid, allocate nothing, do bounded work and give bit-identical
 * results for identical inputs.
 */
#ifndef TDO_COLLISION_H
#define TDO_COLLISION_H

#include "tdo/grid.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Exact Euclidean distance from p (anywhere, also outside the bounds) to the obstacle
 *        geometry, capped.
 * @param cap m, >= 0; the result is min(true distance, cap). Caps beyond the bucket reach cost a
 *        scan of every box when no box lies within the reach.
 * @return m; 0 inside or on an obstacle; -1 for a null or unfinished grid, a non-finite p or a
 *         negative or NaN cap.
 */
double tdo_collision_point_distance(const tdo_grid* grid, tdo_vec3 p, double cap);

/**
 * @brief Exact minimum distance from the segment [a, b] (anywhere) to the obstacle geometry,
 * capped.
 * @param cap m, >= 0, as for tdo_collision_point_distance.
 * @return m, min(true distance, cap); 0 when the segment touches or enters an obstacle; -1 for a
 *         null or unfinished grid, non-finite points or a negative or NaN cap.
 */
double tdo_collision_segment_distance(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double cap);

/**
 * @brief 1 when every point of [a, b] lies inside the closed grid bounds
 *        [origin, origin + n*res] and keeps at least `clearance` (m, finite, >= 0) from the
 *        obstacle geometry, and the segment does not touch any obstacle (so with clearance 0 it
 *        must stay off every obstacle); else 0. Exact: a 1 is a proof. Points exactly at the
 *        clearance pass. 0 as well for a null or unfinished grid or non-finite arguments, and in
 *        the (unreachable on int32 grids) case that the fixed subdivision budget runs out.
 */
int tdo_collision_segment_clear(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance);

/**
 * @brief 1 when every point of the cubic Bezier curve with control points c[0..3] lies inside the
 *        closed bounds and keeps at least `clearance` (m); else 0. De Casteljau subdivision: a
 *        piece passes when its control points lie inside the bounds and its chord c0-c3 passes
 *        tdo_collision_segment_clear at clearance + h, h = the largest distance of c1, c2 from the
 *        chord (the curve lies within h of its chord). So a 1 is a proof; a 0 may be conservative
 *        for curves whose clearance or distance to the bounds lies within `tolerance` (m, finite,
 *        >= 0; values below 1e-9 m are raised to it) of the limit. Bounded: at most 16384 pieces,
 *        beyond which the answer is 0.
 */
int tdo_collision_bezier_clear(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                               double tolerance);

#ifdef __cplusplus
}
#endif

#endif /* TDO_COLLISION_H */
