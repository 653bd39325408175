/**
 * @file va_optimum.h
 * @brief The v/a time optimum along a sampled path: the yardstick of a trajectory's flight time.
 *
 * Given the positions of a trajectory's samples, the fastest rest-to-rest traversal of the same
 * geometric path with |v| <= v_max and total |a| <= a_max (tangential and centripetal combined),
 * jerk unlimited: the classic forward/backward pass over the speed profile. The curvature is taken
 * from the samples themselves (the circle through a sample and its neighbours about `span` m of
 * arclength before and after it), so it measures the path the vehicle flies, whatever produced it.
 */
#ifndef TDO_TOOLS_VA_OPTIMUM_H
#define TDO_TOOLS_VA_OPTIMUM_H

#include <vector>

#include "tdo/types.h"

namespace tdo_tools {

/** Result of va_optimum. */
struct VaOptimum {
  double time_s = 0.0;    /**< s, rest-to-rest time of the v/a-optimal profile */
  double length_m = 0.0;  /**< m, arclength of the sampled path */
  double max_kappa = 0.0; /**< 1/m, largest curvature estimate along the path */
  std::size_t nodes = 0;  /**< distinct positions the passes ran over */
  /** s, with j_max > 0: the same pass with v_max, a_max and j_max raised by the trajectory
   *  check's 1 % tolerance and, at every point, the speed cap of the normal jerk: a flight along
   *  the path has normal jerk 3 kappa v a_t + dkappa/ds v^3, at least dkappa/ds v^3 - 3 kappa v
   *  |a_t|, so no flight within j_max is faster there (dkappa/ds from the curvature of the same
   *  neighbours). A lower bound of every jerk-limited flight's time, up to the sampling of the
   *  curvature; 0 without j_max. */
  double jerk_bound_s = 0.0;
};

/**
 * @brief v/a time optimum along the polyline of `points` (consecutive duplicates are skipped).
 * @param v_max m/s, > 0
 * @param a_max m/s^2, > 0 (bounds sqrt(a_t^2 + (kappa v^2)^2))
 * @param span m, > 0: arclength to the neighbours of the curvature circle (default 0.02 m)
 * @param j_max m/s^3: > 0 also computes jerk_bound_s
 * @return time 0 for fewer than two distinct points; non-positive limits give time 0 too.
 */
VaOptimum va_optimum(const std::vector<tdo_vec3>& points, double v_max, double a_max,
                     double span = 0.02, double j_max = 0.0);

}  // namespace tdo_tools

#endif  // TDO_TOOLS_VA_OPTIMUM_H
