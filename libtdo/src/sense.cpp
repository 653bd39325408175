// Range sensor with line of sight over the true world's boxes (sense.h): which hidden boxes the
// vehicle sees now, and the map update that adds them.
#include "tdo/sense.h"

#include <math.h>
#include <stddef.h>

#include "scalar.h"
#include "vec3.h"

using namespace tdo_internal;  // vec3.h, scalar.h

namespace {

constexpr double kParamTol = 1e-9;  // relative tolerance on the segment parameter
constexpr int kGrid = TDO_SENSE_FACE_GRID;

bool box_ok(const tdo_box& b) {
  return finite3(b.min) && finite3(b.max) && b.max.x > b.min.x && b.max.y > b.min.y &&
         b.max.z > b.min.z;
}

double clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

// The point of box b closest to p (p itself when inside).
tdo_vec3 closest_point(const tdo_box& b, tdo_vec3 p) {
  return v3(clampd(p.x, b.min.x, b.max.x), clampd(p.y, b.min.y, b.max.y),
            clampd(p.z, b.min.z, b.max.z));
}

// 1 when the segment p + s d, s in (tol, 1 - tol), meets the open interior of b (slab test).
bool enters_interior(const tdo_box& b, tdo_vec3 p, tdo_vec3 d) {
  double enter = kParamTol, leave = 1.0 - kParamTol;
  for (int a = 0; a < 3; ++a) {
    const double o = vec_axis(p, a), di = vec_axis(d, a);
    const double lo = vec_axis(b.min, a), hi = vec_axis(b.max, a);
    if (fabs(di) <= 0.0) {
      if (!(o > lo && o < hi)) return false;
      continue;
    }
    double s0 = (lo - o) / di, s1 = (hi - o) / di;
    if (s0 > s1) {
      const double t = s0;
      s0 = s1;
      s1 = t;
    }
    enter = dmax(enter, s0);
    leave = dmin(leave, s1);
    if (!(enter < leave)) return false;
  }
  return true;
}

// 1 when q is within range of p and no true box but `self` has its interior on the segment.
bool point_visible(const tdo_sense_input* in, uint32_t self, tdo_vec3 q, uint64_t* tests) {
  const tdo_vec3 d = sub(q, in->p);
  const double len = norm(d);
  if (len > in->range) return false;
  for (uint32_t j = 0; j < in->n_boxes; ++j) {
    if (j == self) continue;
    const tdo_box& b = in->boxes[j];
    // A box farther from p than q cannot meet the segment.
    if (norm(sub(closest_point(b, in->p), in->p)) >= len) continue;
    ++*tests;
    if (enters_interior(b, in->p, d)) return false;
  }
  return true;
}

// 1 when box i is visible from the sensor (sense.h: closest point, then the facing faces'
// lattices).
bool box_visible(const tdo_sense_input* in, uint32_t i, uint64_t* tests) {
  const tdo_box& b = in->boxes[i];
  const tdo_vec3 c = closest_point(b, in->p);
  const double dc = norm(sub(c, in->p));
  if (dc > in->range) return false;
  if (!(dc > 0.0)) return true;  // the sensor is in the box
  if (point_visible(in, i, c, tests)) return true;
  for (int a = 0; a < 3; ++a) {
    const double pa = vec_axis(in->p, a);
    double plane;
    if (pa < vec_axis(b.min, a))
      plane = vec_axis(b.min, a);
    else if (pa > vec_axis(b.max, a))
      plane = vec_axis(b.max, a);
    else
      continue;  // this axis's faces do not face the sensor
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    for (int iu = 0; iu <= kGrid; ++iu) {
      for (int iw = 0; iw <= kGrid; ++iw) {
        tdo_vec3 q = in->p;
        set_vec_axis(&q, a, plane);
        set_vec_axis(&q, u,
                     vec_axis(b.min, u) + (vec_axis(b.max, u) - vec_axis(b.min, u)) *
                                              (static_cast<double>(iu) / kGrid));
        set_vec_axis(&q, w,
                     vec_axis(b.min, w) + (vec_axis(b.max, w) - vec_axis(b.min, w)) *
                                              (static_cast<double>(iw) / kGrid));
        if (point_visible(in, i, q, tests)) return true;
      }
    }
  }
  return false;
}

}  // namespace

extern "C" tdo_status tdo_sense_run(const tdo_sense_input* in, tdo_sense_output* out) {
  if (in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  out->n_revealed = 0u;
  out->hidden_left = 0u;
  out->segment_tests = 0u;
  if (in->n_boxes > 0u && (in->boxes == nullptr || in->known == nullptr)) {
    return TDO_ERR_INVALID_ARGUMENT;
  }
  if (in->max_revealed > 0u && in->revealed == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (!finite3(in->p) || !positive(in->range)) return TDO_ERR_INVALID_ARGUMENT;
  for (uint32_t i = 0; i < in->n_boxes; ++i)
    if (!box_ok(in->boxes[i])) return TDO_ERR_INVALID_BOX;
  tdo_status st = TDO_OK;
  uint64_t tests = 0u;
  for (uint32_t i = 0; i < in->n_boxes; ++i) {
    if (in->known[i] != 0u) continue;
    if (st == TDO_OK && box_visible(in, i, &tests)) {
      if (out->n_revealed < in->max_revealed) {
        in->known[i] = 1u;
        in->revealed[out->n_revealed++] = i;
        continue;
      }
      st = TDO_ERR_BOX_CAPACITY;
    }
    ++out->hidden_left;
  }
  out->segment_tests = tests;
  return st;
}

extern "C" tdo_status tdo_sense_update(const tdo_box* boxes, uint32_t n_boxes,
                                       const uint32_t* revealed, uint32_t n_revealed,
                                       tdo_box* buffer, uint32_t capacity,
                                       tdo_grid_update* update) {
  if (update == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  if (n_revealed > 0u && (boxes == nullptr || revealed == nullptr || buffer == nullptr))
    return TDO_ERR_INVALID_ARGUMENT;
  if (n_revealed > capacity) return TDO_ERR_BOX_CAPACITY;
  for (uint32_t k = 0; k < n_revealed; ++k)
    if (revealed[k] >= n_boxes) return TDO_ERR_INVALID_ARGUMENT;
  for (uint32_t k = 0; k < n_revealed; ++k) buffer[k] = boxes[revealed[k]];
  update->set = nullptr;
  update->n_set = 0u;
  update->clear = nullptr;
  update->n_clear = 0u;
  update->boxes = n_revealed > 0u ? buffer : nullptr;
  update->n_boxes = n_revealed;
  update->max_cells = 0u;
  return TDO_OK;
}

extern "C" tdo_status tdo_sense_hide(uint32_t n_boxes, double fraction, uint64_t seed,
                                     uint8_t* known_out) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) return TDO_ERR_INVALID_ARGUMENT;
  if (n_boxes > 0u && known_out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  // h <= n_boxes: fraction <= 1 and n_boxes + 0.5 is exact in a double.
  uint32_t left = static_cast<uint32_t>(floor(fraction * static_cast<double>(n_boxes) + 0.5));
  uint64_t state = seed;
  for (uint32_t i = 0; i < n_boxes; ++i) {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);  // splitmix64
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const bool hide = left > 0u && z % static_cast<uint64_t>(n_boxes - i) < left;
    known_out[i] = hide ? 0u : 1u;
    if (hide) --left;
  }
  return TDO_OK;
}

extern "C" tdo_status tdo_sense_distance(const tdo_box* boxes, uint32_t n_boxes, tdo_vec3 p,
                                         double* out) {
  if (out == nullptr || (n_boxes > 0u && boxes == nullptr)) return TDO_ERR_INVALID_ARGUMENT;
  *out = HUGE_VAL;
  if (!finite3(p)) return TDO_ERR_INVALID_ARGUMENT;
  double best2 = HUGE_VAL;
  for (uint32_t i = 0; i < n_boxes; ++i) {
    const tdo_box& b = boxes[i];
    if (!finite3(b.min) || !finite3(b.max) || b.max.x < b.min.x || b.max.y < b.min.y ||
        b.max.z < b.min.z)
      return TDO_ERR_INVALID_BOX;
    const tdo_vec3 d = sub(p, closest_point(b, p));
    best2 = dmin(best2, dot(d, d));
  }
  *out = n_boxes > 0u ? sqrt(best2) : HUGE_VAL;
  return TDO_OK;
}
