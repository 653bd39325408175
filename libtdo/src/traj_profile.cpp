// The planner's trajectory context for readers of its profile (traj_profile.h).
#include "tdo/traj_profile.h"

#include "planner_internal.h"

extern "C" const tdo_traj* tdo_planner_trajectory(const tdo_planner* planner) {
  if (planner == nullptr || planner->traj == nullptr || !planner->have_samples) return nullptr;
  return planner->traj;
}
