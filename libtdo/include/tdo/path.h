/**
 * @file path.h
 * @brief The geometric path shared by smoothing, time parameterisation and metrics.
 *
 * Every segment is parameterised by arclength s in [0, length] (m). Evaluation is pure, bounded
 * and deterministic: lines and arcs in closed form; cubic Beziers through an arclength -> t map
 * computed on the fly (adaptive 8-point Gauss-Legendre quadrature of |B'(t)| with at most
 * TDO_PATH_MAX_QUAD_DEPTH halvings, then a safeguarded Newton/bisection inversion of at most
 * TDO_PATH_MAX_INVERSION_STEPS steps). Nothing is cached, so the struct stays plain data.
 *
 * Contract for callers: `length` must be the value tdo_segment_length() returns for the segment
 * (the smoothing stage fills it that way); evaluation clamps s to [0, length] and returns the exact
 * end control point for s >= length (p[1] for lines and arcs, p[3] for Beziers) and the exact start
 * p[0] for s <= 0, so consecutive segments meet bit-exactly at shared end points.
 */
#ifndef TDO_PATH_H
#define TDO_PATH_H

#include "tdo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Halvings of the adaptive quadrature of a Bezier's arclength (bounds the work per call). */
#define TDO_PATH_MAX_QUAD_DEPTH 12u
/** Newton/bisection steps of the arclength -> t inversion of a Bezier (bounds the work). */
#define TDO_PATH_MAX_INVERSION_STEPS 60u

/** Kind of a path segment. */
typedef enum tdo_segment_kind {
  TDO_SEGMENT_LINE = 0,   /**< straight line p[0] -> p[1] */
  TDO_SEGMENT_BEZIER = 1, /**< cubic Bezier with control points p[0..3] (G2 corner halves) */
  TDO_SEGMENT_ARC = 2     /**< circular arc from p[0] to p[1] about centre p[2], sweep < pi;
                               radius = |p[0] - p[2]| (m) */
} tdo_segment_kind;

/** One piece of the path. Consecutive segments share end points with continuous tangents. */
typedef struct tdo_path_segment {
  tdo_segment_kind kind; /**< how p[] is read */
  tdo_vec3 p[4];         /**< m, world frame: see tdo_segment_kind (unused entries are zero) */
  double length;         /**< m, arclength of the segment (= tdo_segment_length(this)) */
  double v_limit;        /**< m/s, speed cap on this segment from its curvature and fit */
  int stop_at_end; /**< 1 when the vehicle must be at rest at the segment's end (stop point) */
} tdo_path_segment;

/** A path: segments in flight order. Storage belongs to the stage that produced it. */
typedef struct tdo_path {
  const tdo_path_segment* seg; /**< segments */
  uint32_t n;                  /**< number of segments */
  double length;               /**< m, total arclength */
} tdo_path;

/** Local differential geometry of a segment at one arclength. */
typedef struct tdo_segment_state {
  tdo_vec3 p;       /**< m, world frame, point */
  tdo_vec3 t;       /**< unit tangent (dimensionless, world frame), direction of travel */
  tdo_vec3 kn;      /**< 1/m, world frame, curvature vector kappa * N = dT/ds (zero on lines) */
  double kappa;     /**< 1/m, unsigned curvature |kn| */
  double dkappa_ds; /**< 1/m^2, derivative of the unsigned curvature along the arclength; where
                         kappa is exactly 0 on a Bezier, the one-sided limit of its magnitude */
} tdo_segment_state;

/**
 * @brief Arclength of a segment, computed from its geometry (the `length` field is ignored).
 * @return m; 0 for a null pointer, an unknown kind or non-finite points. Lines: |p1 - p0|;
 *         arcs: radius * sweep; Beziers: adaptive Gauss-Legendre, relative error ~1e-13.
 */
double tdo_segment_length(const tdo_path_segment* seg);

/** @return point at arclength s (m, clamped to [0, length]) of segment `seg`. */
tdo_vec3 tdo_segment_point(const tdo_path_segment* seg, double s);

/** @return signed-free curvature (1/m) at arclength s of segment `seg` (0 on lines). */
double tdo_segment_curvature(const tdo_path_segment* seg, double s);

/** @return unit tangent at arclength s (m, clamped) of `seg`; zero vector for a degenerate one. */
tdo_vec3 tdo_segment_tangent(const tdo_path_segment* seg, double s);

/**
 * @brief Point, unit tangent, curvature vector, curvature and curvature rate at arclength s (m,
 *        clamped to [0, length]) in one call (one arclength inversion for a Bezier).
 * @return 1 on success; 0 for null pointers (out untouched) or a degenerate segment (out zeroed
 *         apart from the point).
 */
int tdo_segment_eval(const tdo_path_segment* seg, double s, tdo_segment_state* out);

/**
 * @brief Bezier parameter t in [0, 1] at arclength s (m, clamped to [0, length]).
 *        Lines and arcs: s / length. Exposed for tests and for callers that sample densely.
 */
double tdo_segment_param(const tdo_path_segment* seg, double s);

/**
 * @brief Find the segment holding path arclength s (m, clamped to [0, path->length]).
 * @param[out] local_s m, arclength inside that segment (may be NULL)
 * @return segment index in [0, n), the last segment for s >= the sum of lengths; UINT32_MAX for a
 *         null or empty path. Linear scan over the segments (bounded by n).
 */
uint32_t tdo_path_locate(const tdo_path* path, double s, double* local_s);

#ifdef __cplusplus
}
#endif

#endif /* TDO_PATH_H */
