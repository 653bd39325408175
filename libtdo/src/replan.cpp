// Replanning in flight (replan.h): the blocked check of the active trajectory and the takeover
// state of the next plan.
#include "tdo/replan.h"

#include <math.h>

#include "scalar.h"
#include "tdo/collision.h"
#include "vec3.h"

using namespace tdo_internal;  // vec3.h, scalar.h

namespace {

// Sample period of a uniform trajectory from 0, or 0 when the samples are not (first two, last).
double uniform_dt(const tdo_sample* s, uint32_t n) {
  if (s == nullptr || n < 2u) return 0.0;
  const double dt = s[1].t - s[0].t;
  if (!(fabs(s[0].t) <= 1e-9) || !positive(dt)) return 0.0;
  const double last = static_cast<double>(n - 1u) * dt;
  if (!isfinite(s[n - 1u].t) || fabs(s[n - 1u].t - last) > 1e-6 * dmax(last, 1.0)) return 0.0;
  return dt;
}

// Index of the sample at or before time t (clamped to [0, n - 1]).
uint32_t index_at(double t, double dt, uint32_t n) {
  const double f = floor(t / dt + 1e-9);
  if (!(f > 0.0)) return 0u;
  if (f >= static_cast<double>(n - 1u)) return n - 1u;
  return static_cast<uint32_t>(f);
}

bool movers_ok(const tdo_mover* m, uint32_t n) {
  if (n > 0u && m == nullptr) return false;
  for (uint32_t i = 0; i < n; ++i)
    if (!finite3(m[i].p) || !finite3(m[i].v) || !positive(m[i].radius)) return false;
  return true;
}

// The first mover whose predicted position at trajectory time ts comes within radius +
// clearance of p; returns its index or n.
uint32_t mover_hit(const tdo_replan_check_input* in, tdo_vec3 p, double ts) {
  const double dt = ts - in->t;
  for (uint32_t k = 0; k < in->n_movers; ++k) {
    const tdo_mover& m = in->movers[k];
    const tdo_vec3 q = add(m.p, mul(m.v, dt));
    if (norm(sub(p, q)) < m.radius + in->mover_clearance) return k;
  }
  return in->n_movers;
}

void set_blocked(tdo_replan_check_result* out, tdo_replan_cause cause, uint32_t i, double dt) {
  out->blocked = 1;
  out->cause = cause;
  out->index = i;
  out->t_blocked = static_cast<double>(i) * dt;
}

}  // namespace

extern "C" tdo_status tdo_replan_check(const tdo_replan_check_input* in,
                                       tdo_replan_check_result* out) {
  if (in == nullptr || out == nullptr || in->grid == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  out->blocked = 0;
  out->cause = TDO_REPLAN_CLEAR;
  out->t_blocked = HUGE_VAL;
  out->index = 0u;
  out->mover_id = 0u;
  out->pieces_checked = 0u;
  const double dt = uniform_dt(in->samples, in->n_samples);
  if (!(dt > 0.0) || !non_negative(in->t) || !non_negative(in->horizon) ||
      !non_negative(in->clearance) || !non_negative(in->mover_clearance) ||
      !movers_ok(in->movers, in->n_movers))
    return TDO_ERR_INVALID_ARGUMENT;
  if (!(tdo_grid_clearance(in->grid) >= 0.0)) return TDO_ERR_MAP_NOT_READY;
  const uint32_t n = in->n_samples;
  const uint32_t first = index_at(in->t, dt, n);
  const double t_end = in->t + in->horizon;
  for (uint32_t i = first; i < n; ++i) {
    const double ti = static_cast<double>(i) * dt;
    if (ti > t_end) break;
    const tdo_sample& s = in->samples[i];
    if (!finite3(s.p)) return TDO_ERR_INVALID_ARGUMENT;
    // The sample against the movers (from the check's start on).
    if (ti >= in->t - 1e-9 * dt) {
      const uint32_t k = mover_hit(in, s.p, ti);
      if (k < in->n_movers) {
        set_blocked(out, TDO_REPLAN_MOVER, i, dt);
        out->mover_id = in->movers[k].id;
        return TDO_OK;
      }
    }
    // The piece to the next sample against the grid.
    if (i + 1u < n) {
      ++out->pieces_checked;
      if (!tdo_collision_segment_clear(in->grid, s.p, in->samples[i + 1u].p, in->clearance)) {
        set_blocked(out, TDO_REPLAN_STATIC, i, dt);
        return TDO_OK;
      }
    }
  }
  return TDO_OK;
}

extern "C" tdo_status tdo_replan_takeover(const tdo_sample* samples, uint32_t n_samples, double t,
                                          double latency, tdo_replan_takeover_result* out) {
  if (out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  const double dt = uniform_dt(samples, n_samples);
  if (!(dt > 0.0) || !non_negative(t) || !non_negative(latency)) return TDO_ERR_INVALID_ARGUMENT;
  const double f = ceil((t + latency) / dt - 1e-9);
  uint32_t i = n_samples - 1u;
  if (!(f > 0.0))
    i = 0u;
  else if (f < static_cast<double>(n_samples - 1u))
    i = static_cast<uint32_t>(f);
  const tdo_sample& s = samples[i];
  if (!finite3(s.p) || !finite3(s.v) || !finite3(s.a)) return TDO_ERR_INVALID_ARGUMENT;
  out->index = i;
  out->t = static_cast<double>(i) * dt;
  out->p = s.p;
  out->state.v = s.v;
  out->state.a = s.a;
  return TDO_OK;
}
