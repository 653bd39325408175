/**
 * @file sense.h
 * @brief A range sensor with line of sight over the true world's obstacle boxes: which hidden
 *        boxes the vehicle sees now (docs/design.md s.4, "Sensing").
 *
 * The true world is a list of boxes; the caller keeps a `known` flag per box (1 known, 0 hidden).
 * One call reveals every hidden box that is visible from the vehicle position p within `range`:
 * - candidate points of box B: the point of B closest to p, and, on each face of B whose plane
 *   separates p from B (at most three faces), a lattice of TDO_SENSE_FACE_GRID + 1 by
 *   TDO_SENSE_FACE_GRID + 1 points spanning the face (corners and edges included);
 * - a candidate point q is visible when |q - p| <= range and the segment from p to q does not
 *   enter the open interior of another true box (known or hidden; boxes only touching the
 *   segment, or touched at q, do not block; slab test with a relative tolerance of 1e-9 on the
 *   segment parameter);
 * - B is revealed when one of its candidate points is visible, or p lies in B (closed box).
 * Guarantee: the box nearest to p (of all true boxes) is revealed whenever it is within range,
 * because another box entering the segment to its closest point would be nearer. So a vehicle
 * whose range exceeds its clearance is never within clearance of a box it has not seen.
 * The line of sight is a discretisation: a box seen only through a gap narrower than the lattice
 * spacing may be revealed later than exact visibility would (never earlier).
 * Fixed memory (the caller's arrays), no I/O, deterministic; every loop is bounded by the box
 * count: at most n_boxes * (1 + 3 (G+1)^2) * n_boxes segment tests per call (G the face grid).
 */
#ifndef TDO_SENSE_H
#define TDO_SENSE_H

#include <stdint.h>

#include "tdo/grid_update.h"
#include "tdo/status.h"
#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Intervals per face edge of the candidate lattice (so 5 x 5 points per visible face). */
#define TDO_SENSE_FACE_GRID 4

/** One sensing step. */
typedef struct tdo_sense_input {
  tdo_vec3 p;            /**< m, world frame: the sensor (vehicle) position */
  double range;          /**< m, > 0: reach of the sensor */
  const tdo_box* boxes;  /**< m, world frame: every obstacle box of the true world */
  uint32_t n_boxes;      /**< count */
  uint8_t* known;        /**< caller-owned, n_boxes flags: 1 known, 0 hidden; a revealed box's
                              flag is set to 1 */
  uint32_t* revealed;    /**< caller-owned buffer: indices into boxes revealed by this call, in
                              increasing order */
  uint32_t max_revealed; /**< capacity of revealed */
} tdo_sense_input;

/** What one step did. */
typedef struct tdo_sense_output {
  uint32_t n_revealed;    /**< entries written to revealed */
  uint32_t hidden_left;   /**< boxes still hidden after the call */
  uint64_t segment_tests; /**< segment-box interior tests done (the work) */
} tdo_sense_output;

/**
 * @brief Reveal every hidden box visible from `in->p` within `in->range` (see the file comment).
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers (with n_boxes > 0), a non-finite p
 *         or a range not finite and > 0; TDO_ERR_INVALID_BOX for a true box with max <= min or a
 *         non-finite corner (nothing revealed); TDO_ERR_BOX_CAPACITY when more boxes became
 *         visible than max_revealed: the first max_revealed of them (by index) are revealed and
 *         listed, the others stay hidden for the next call.
 */
tdo_status tdo_sense_run(const tdo_sense_input* in, tdo_sense_output* out);

/**
 * @brief A map update that adds the revealed boxes: copies boxes[revealed[k]] into `buffer` and
 *        points `update` at them (no voxels, no work budget).
 * @param buffer caller-owned, `capacity` boxes; must stay alive while `update` is used
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers (with n_revealed > 0) or an index
 *         not below n_boxes; TDO_ERR_BOX_CAPACITY when n_revealed > capacity (update untouched).
 */
tdo_status tdo_sense_update(const tdo_box* boxes, uint32_t n_boxes, const uint32_t* revealed,
                            uint32_t n_revealed, tdo_box* buffer, uint32_t capacity,
                            tdo_grid_update* update);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SENSE_H */
