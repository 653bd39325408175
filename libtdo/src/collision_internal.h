// Internal collision queries shared by the stages (not part of the public API).
#ifndef TDO_SRC_COLLISION_INTERNAL_H
#define TDO_SRC_COLLISION_INTERNAL_H

#include <stdint.h>

#include "tdo/collision.h"

namespace tdo_internal {

/**
 * tdo_collision_segment_clear with a hint for runs of similar queries: *hint (1 + the index of
 * the box that failed the last query, 0 for none) is tested first against the whole segment, and
 * the query stops as "not clear" when that box is certainly closer than the clearance (by more
 * than a rounding margin, so the full query would fail too); otherwise the full query runs and a
 * box that fails it becomes the hint. Same answer as tdo_collision_segment_clear, always.
 */
int segment_clear_hinted(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                         uint32_t* hint);

/**
 * 1 when box hint - 1 (hint as in segment_clear_hinted, 0: none) is certainly closer than the
 * clearance to [a, b] (both inside the bounds), by more than the hint's rounding margin: then
 * tdo_collision_segment_clear(a, b, clearance) is 0, and so is every query from a to a point
 * between b and another end point b' the same box blocks (the end points p whose segment from a
 * comes that close to a convex box form a convex set). 0 otherwise (no claim).
 */
int segment_blocked_by_hint(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                            uint32_t hint);

/** State of point_distance_hinted between calls (valid = 0 to start). */
struct PointHint {
  double q[3];    // m, world frame: the last point evaluated in full
  double others;  // m, lower bound of the distance from q to every obstacle but `box`
  uint32_t box;   // index of the box nearest to q
  int valid;      // 1 when the fields above hold
  double lower;   // m, set by every call: a proven lower bound of the uncapped distance of the
                  // point of that call, at least its result (beyond the cap on maps of cubes
                  // only, from the distance field), so a caller may skip points farther away
};

/**
 * tdo_collision_point_distance for runs of nearby points (same result, bit for bit): when the box
 * nearest to the last fully evaluated point q is still nearer to p than every other obstacle can
 * be (their bound at q minus |p - q|, with a margin far above rounding), its distance is the
 * answer; otherwise the full query runs and renews the hint. Box-only maps, points inside the
 * bounds; anything else runs the full query.
 */
double point_distance_hinted(const tdo_grid* grid, tdo_vec3 p, double cap, PointHint* h);

/** Largest squared offset (voxel^2) voxel_gap2_lower tabulates. */
constexpr uint32_t kGapTableMax = 256;

/**
 * The smallest squared gap (voxel^2) between the closed cubes of two voxels whose integer centre
 * offset d has |d|^2 >= n: min of sum_i max(|d_i| - 1, 0)^2 over those offsets. 0xFFFFFFFF for
 * n > kGapTableMax (not tabulated). A voxel whose distance field entry shows no occupied voxel
 * within sqrt(n) voxels is that far (squared) from every occupied cube with its whole box.
 */
uint32_t voxel_gap2_lower(uint32_t n);

/**
 * tdo_collision_segment_clear (with segment_clear_hinted's hint when hint is not null, updated
 * the same way), the same answer always, cheaper on voxel maps. The cube part walks cubes_clear's
 * halvings of [a, b] but skips every piece the steering already proved clear. Steering, from the
 * first point not yet proven: the distance field bounds that point's distance (and that of its
 * voxel's whole box) to the cubes from below, so the segment is clear up to where that bound,
 * less the length walked, drops to the clearance plus a margin far above rounding; it steps on
 * from there while the steps stay long. A leaf piece it does not cover gets the block test
 * (block_clear's: no voxel cube near the piece) and then cubes_clear's own exact leaf test, on
 * the same piece. *cube_hint (may be null; 0 to start): 1 + the voxel of the surface cube that
 * failed the last query; a query first tests it, and stops as "not clear" when it certainly comes
 * closer than the clearance (by a margin far above rounding; at clearance 0, the segment passes
 * through its interior), where cubes_clear fails too.
 */
int segment_clear_steered(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance,
                          uint32_t* hint, uint32_t* cube_hint);

/**
 * 1 when no occupied voxel lies near [a, b]: every voxel whose box comes within the clearance
 * (plus a margin far above rounding) of the segment's bounding box, at most 64 of them, is free,
 * and, on maps with boxes, inside the grid. Then tdo_collision_segment_clear(a, b, clearance) is
 * 1. 0: no claim (a larger block, an occupied voxel, an end point outside the bounds).
 */
int block_clear(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, double clearance);

/**
 * tdo_collision_bezier_clear (the same answer always) with segment_clear_steered's hints carried
 * in and out (*hint, *cube_hint: 0 to start), for runs of checks of nearby curves.
 */
int bezier_clear_hinted(const tdo_grid* grid, const tdo_vec3 c[4], double clearance,
                        double tolerance, uint32_t* hint, uint32_t* cube_hint);

// The correction's bounds on its tightening keeps (segment_cube_distance, correct.cpp's
// keep_bounds) pay at clearances of a quarter voxel and below; the 32-bit firmware plans at larger
// ones and its flash is scarce, so they are compiled into 64-bit builds only.
#if UINTPTR_MAX > 0xFFFFFFFFu
#define TDO_KEEP_BOUNDS 1
/**
 * min(cap, m), m the smallest distance of the surface cube `cube` (a voxel index) over the leaves
 * tdo_collision_segment_distance cuts [a, b] into, each evaluated as that query evaluates it (0
 * for a leaf whose midpoint lies in a cube): a result below cap is one of the values that query
 * takes the minimum of, so its result is at most that. Leaves whose bounding box stays farther
 * than the running minimum from the cube are not evaluated. -1 for a cube that is not a surface
 * cube, an invalid query or a walk over its bounds.
 */
double segment_cube_distance(const tdo_grid* grid, tdo_vec3 a, tdo_vec3 b, uint32_t cube,
                             double cap);
#endif

/** True when p lies in the closed grid bounds: the bounds test the segment checks apply to their
 *  end points (segment_clear_steered, block_clear), by the same expressions. */
bool point_in_bounds(const tdo_grid* grid, tdo_vec3 p);

}  // namespace tdo_internal

#endif  // TDO_SRC_COLLISION_INTERNAL_H
