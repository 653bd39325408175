// The shape check of one path segment (internal), shared by the stages that read a tdo_path
// (metrics, trajectory): a known kind, finite control points, a finite length >= 0.
#ifndef TDO_SRC_PATH_SEGMENT_H
#define TDO_SRC_PATH_SEGMENT_H

#include <math.h>

#include "tdo/path.h"
#include "vec3.h"

namespace tdo_internal {

// Control points a segment of `kind` uses: a line 2, an arc 3, a cubic Bezier 4.
inline int segment_points(int kind) {
  return kind == TDO_SEGMENT_BEZIER ? 4 : (kind == TDO_SEGMENT_ARC ? 3 : 2);
}

// True when `s` has a known kind, finite used control points and a finite length >= 0.
inline bool segment_shape_ok(const tdo_path_segment& s) {
  if (s.kind != TDO_SEGMENT_LINE && s.kind != TDO_SEGMENT_BEZIER && s.kind != TDO_SEGMENT_ARC)
    return false;
  const int np = segment_points(s.kind);
  for (int k = 0; k < np; ++k)
    if (!finite3(s.p[k])) return false;
  return isfinite(s.length) && s.length >= 0.0;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_PATH_SEGMENT_H
