// One trapezoid of the energy integral over trajectory samples (internal). The trajectory stage's
// streaming pass and tdo_metrics_compute sum the same steps, so streamed and stored samples give
// the same energy bit for bit.
#ifndef TDO_SRC_SAMPLE_ENERGY_H
#define TDO_SRC_SAMPLE_ENERGY_H

#include <math.h>
#include <stdint.h>

#include "tdo/trajectory.h"
#include "vec3.h"

namespace tdo_internal {

/** energy_step from the squared accelerations aa = |a.a|^2 and ba = |b.a|^2 (m^2/s^4) and the
 *  step b.t - a.t (s), for a pass that keeps |a|^2 of the previous sample. */
inline double energy_step_sq(double aa, double ba, double step) { return 0.5 * (aa + ba) * step; }

/** Whether tdo_metrics_compute accepts samples [0, n) at period dt for its energy and flight time:
 *  dt finite and > 0, every t and a finite, the times increasing. The pipeline asks it before
 *  handing over the trajectory stage's own sum instead of the samples. */
inline bool samples_accepted(const tdo_sample* s, uint32_t n, double dt) {
  if (!(isfinite(dt) && dt > 0.0)) return false;
  for (uint32_t i = 0; i < n; ++i) {  // bounded by n
    if (!isfinite(s[i].t) || !finite3(s[i].a)) return false;
    if (i > 0u && !(s[i].t > s[i - 1u].t)) return false;
  }
  return true;
}

/** m^2/s^4 times s: integral |a|^2 dt from sample a to sample b by the trapezoid rule. */
inline double energy_step(const tdo_sample& a, const tdo_sample& b) {
  return energy_step_sq(dot(a.a, a.a), dot(b.a, b.a), b.t - a.t);
}

}  // namespace tdo_internal

#endif  // TDO_SRC_SAMPLE_ENERGY_H
