// Which searches are turn-penalised (docs/design.md s.1, "State space"): the one predicate the
// search and the coarse guide share. Internal to libtdo.
#ifndef TDO_SRC_SEARCH_HEADED_H
#define TDO_SRC_SEARCH_HEADED_H

#include "tdo/search.h"

namespace tdo_internal {

// theta_max in (0, pi) constrains the directions; outside it the search is unconstrained.
inline bool search_constrained(double theta_max) {
  return theta_max > 0.0 && theta_max < 3.14159265358979323846;
}

// d_th in (0, 1) is a deviation threshold; outside it there is none.
inline double search_d_th(double d_th) { return d_th > 0.0 && d_th < 1.0 ? d_th : 0.0; }

// A query whose heading carries a cost (a turn penalty, a deviation term, a direction constraint
// or a deviation threshold): its states are (voxel, heading), or voxel states with turn costs.
// Otherwise it is plain A* or bidirectional A* over voxels.
inline bool search_headed(const tdo_search_input* in) {
  return in->lambda > 0.0 || in->mu > 0.0 || search_constrained(in->theta_max) ||
         search_d_th(in->d_th) > 0.0;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_SEARCH_HEADED_H
