// Lower bound on the turns of any path through a row of full-height walls with doors (Map4), by
// counting the straight segments it needs: the "walls" column of tdo-turn-bound.
//
// Relaxation. Keep only the walls: bands a <= u <= a + t across the whole map (u = the coordinate
// along the start-goal axis), blocked over the full height except at doors. In such a band a point
// keeps the clearance c only inside a window [door_lo + c, door_hi - c] of the across coordinate
// v (full height: the distance to a wall piece is the horizontal one). Drop z and every other
// obstacle: that can only lower the count, so the bound holds for the real map.
//
// Each segment of a polyline path touches a run of consecutive bands i..j. The bands strictly
// inside the run it crosses whole, so its line v = p + q u lies in a window at both band edges;
// at an end band it either crosses whole too (the vertex lies beyond the band) or only meets the
// window (the vertex lies in the band, and the next segment starts there). Each case is a linear
// feasibility problem in (p, q), solved exactly over its breakpoints. A dynamic programme over
// the bands, with the start and the goal as point items at both ends, then gives the fewest
// segments of any chain of such runs, and every path's segments contain such a chain
// (docs/performance.md has the argument). Turns >= segments - 1, for polylines; bends of at most
// 1 degree, which `turns` does not count, are not covered.
#ifndef TDO_TOOLS_BENCH_WALL_LINKS_H
#define TDO_TOOLS_BENCH_WALL_LINKS_H

#include <vector>

#include "tdo_io/map_io.h"

namespace tdo_bench {

/** Free interval of the across coordinate v inside one wall band (m; infinite at an open map
 *  side, where no wall piece stands). */
struct WallWindow {
  double lo;
  double hi;
};

/** A full-height wall band between start and goal, in the start-to-goal frame. */
struct WallBand {
  double u_lo;  // m, band start along the start-goal axis (start side)
  double u_hi;  // m, band end (goal side)
  std::vector<WallWindow> windows;
};

/** Result of the bound. */
struct WallLinks {
  int axis = -1;                // 0 = x, 1 = y: the axis the bands cross; -1 = no band found
  std::vector<WallBand> bands;  // in order from start to goal
  int segments = 1;             // fewest straight segments of a path through the bands
};

/**
 * @brief The walls bound of `map` at `clearance` (m): walls are boxes spanning the full height of
 *        the bounds, grouped by equal extent along x or along y; a group counts when its pieces
 *        leave only gaps (doors) across the map and it lies strictly between start and goal. Both
 *        horizontal axes are tried; the larger bound is returned (each is valid on its own).
 */
WallLinks wall_links(const tdo_io::Map& map, double clearance);

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_WALL_LINKS_H
