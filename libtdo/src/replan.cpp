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

namespace {

// Squared distance from x to the segment a-b.
double segment_dist2(tdo_vec3 x, tdo_vec3 a, tdo_vec3 b) {
  const tdo_vec3 ab = sub(b, a), ax = sub(x, a);
  const double l2 = dot(ab, ab);
  double s = l2 > 0.0 ? dot(ax, ab) / l2 : 0.0;
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  const tdo_vec3 d = sub(ax, mul(ab, s));
  return dot(d, d);
}

// Voxel index range [lo, hi] on one axis covering world [a, b], clamped to [0, n - 1]; false when
// empty.
bool axis_range(double a, double b, double origin, double res, int32_t n, int32_t* lo,
                int32_t* hi) {
  const double fa = floor((a - origin) / res), fb = floor((b - origin) / res);
  if (fb < 0.0 || fa > static_cast<double>(n - 1)) return false;
  *lo = fa < 0.0 ? 0 : static_cast<int32_t>(fa);
  *hi = fb > static_cast<double>(n - 1) ? n - 1 : static_cast<int32_t>(fb);
  return true;
}

}  // namespace

extern "C" tdo_status tdo_replan_mover_voxels(const tdo_grid* grid,
                                              const tdo_replan_mover_region* r, tdo_voxel* out,
                                              uint32_t capacity, uint32_t* n_out) {
  if (n_out != nullptr) *n_out = 0u;
  if (grid == nullptr || r == nullptr || n_out == nullptr || (capacity > 0u && out == nullptr))
    return TDO_ERR_INVALID_ARGUMENT;
  if (!movers_ok(&r->mover, 1u) || !isfinite(r->t0) || !isfinite(r->t1) || !(r->t1 >= r->t0) ||
      !non_negative(r->pad) || !finite3(r->keep_free) || !non_negative(r->keep_radius))
    return TDO_ERR_INVALID_ARGUMENT;
  if (!(tdo_grid_clearance(grid) >= 0.0)) return TDO_ERR_MAP_NOT_READY;
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  const tdo_vec3 a = add(r->mover.p, mul(r->mover.v, r->t0));
  const tdo_vec3 b = add(r->mover.p, mul(r->mover.v, r->t1));
  const double reach = r->mover.radius + r->pad, reach2 = reach * reach;
  const double keep2 = r->keep_radius * r->keep_radius;
  int32_t lo[3], hi[3];
  const int32_t n[3] = {d.nx, d.ny, d.nz};
  for (int ax = 0; ax < 3; ++ax) {
    const double lo_w = dmin(vec_axis(a, ax), vec_axis(b, ax)) - reach;
    const double hi_w = dmax(vec_axis(a, ax), vec_axis(b, ax)) + reach;
    if (!axis_range(lo_w, hi_w, vec_axis(d.origin, ax), d.res, n[ax], &lo[ax], &hi[ax]))
      return TDO_OK;
  }
  tdo_status st = TDO_OK;
  for (int32_t k = lo[2]; k <= hi[2]; ++k) {
    for (int32_t j = lo[1]; j <= hi[1]; ++j) {
      for (int32_t i = lo[0]; i <= hi[0]; ++i) {
        const tdo_voxel v{i, j, k};
        const tdo_vec3 c = tdo_grid_voxel_center(grid, v);
        if (segment_dist2(c, a, b) > reach2) continue;
        const tdo_vec3 off = sub(c, r->keep_free);
        if (dot(off, off) <= keep2 || tdo_grid_is_occupied(grid, v)) continue;
        if (*n_out >= capacity) {
          st = TDO_ERR_MAP_CAPACITY;
          continue;
        }
        out[(*n_out)++] = v;
      }
    }
  }
  return st;
}
