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

/**
 * @brief Which of n_boxes true boxes start hidden: the one seeded choice shared by every
 *        simulator (tdo-sim, tdo-sim-run), so one seed hides the same boxes everywhere.
 *
 * Exactly h = floor(fraction * n_boxes + 0.5) boxes are hidden (known_out[i] = 0), the others
 * known (known_out[i] = 1). The choice is sequential selection sampling (Knuth's Algorithm S):
 * box i is hidden when r_i mod (n_boxes - i) < h - (boxes hidden before i), with r_i the i-th
 * output of a splitmix64 sequence started at `seed`; every h-subset is equally likely (up to the
 * modulo's bias below 2^-32). Deterministic and portable (integer arithmetic only), no heap, one
 * pass over the boxes.
 * @param known_out caller-owned, n_boxes flags (may be NULL when n_boxes is 0)
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for a fraction that is NaN or outside [0, 1], or a
 *         NULL known_out with n_boxes > 0 (known_out untouched).
 */
tdo_status tdo_sense_hide(uint32_t n_boxes, double fraction, uint64_t seed, uint8_t* known_out);

/**
 * @brief Exact Euclidean distance from p to the union of the boxes (closed boxes: 0 inside or on
 *        a face): the true world's contact check, shared by the simulators (tdo_sim_params.boxes).
 * @param[out] out m; HUGE_VAL when n_boxes is 0
 * @return TDO_OK; TDO_ERR_INVALID_ARGUMENT for null pointers (boxes with n_boxes > 0, out) or a
 *         non-finite p; TDO_ERR_INVALID_BOX for a box with max < min on an axis or a non-finite
 *         corner (out = HUGE_VAL). One pass over the boxes.
 */
tdo_status tdo_sense_distance(const tdo_box* boxes, uint32_t n_boxes, tdo_vec3 p, double* out);

#ifdef __cplusplus
}
#endif

#endif /* TDO_SENSE_H */
