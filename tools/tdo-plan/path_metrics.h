/**
 * @file path_metrics.h
 * @brief Geometric metrics of a polyline for the host tools (tdo-plan, bench).
 */
#ifndef TDO_TOOLS_PATH_METRICS_H
#define TDO_TOOLS_PATH_METRICS_H

#include <vector>

#include "tdo/types.h"

namespace tdo_tools {

/** Turn statistics of a polyline. */
struct TurnStats {
  int turns = 0;               /**< interior points with deflection > the threshold */
  double total_turn_deg = 0.0; /**< deg, sum of those deflections */
};

/** @return m, sum of the segment lengths of `pts` (0 for fewer than two points). */
double polyline_length(const std::vector<tdo_vec3>& pts);

/**
 * @brief Deflection (deg, in [0, 180]) at interior point i: angle between the incoming and the
 *        outgoing segment. Zero-length neighbours are skipped (the next distinct point is used).
 */
double deflection_deg(const tdo_vec3& prev, const tdo_vec3& at, const tdo_vec3& next);

/**
 * @brief Count interior points whose deflection exceeds `threshold_deg` (default 1 degree) and sum
 *        their deflections. Repeated points are merged first.
 */
TurnStats turn_stats(const std::vector<tdo_vec3>& pts, double threshold_deg = 1.0);

}  // namespace tdo_tools

#endif  // TDO_TOOLS_PATH_METRICS_H
