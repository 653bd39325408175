/**
 * @file tdo.h
 * @brief Umbrella header of libtdo, the TDO-MSF UAV trajectory planner.
 */
#ifndef TDO_TDO_H
#define TDO_TDO_H

#include "tdo/apf.h"
#include "tdo/arena.h"
#include "tdo/collision.h"
#include "tdo/config.h"
#include "tdo/correct.h"
#include "tdo/grid.h"
#include "tdo/grid_update.h"
#include "tdo/metrics.h"
#include "tdo/params.h"
#include "tdo/path.h"
#include "tdo/pipeline.h"
#include "tdo/planner.h"
#include "tdo/replan.h"
#include "tdo/search.h"
#include "tdo/sense.h"
#include "tdo/sim.h"
#include "tdo/smooth.h"
#include "tdo/status.h"
#include "tdo/traj_profile.h"
#include "tdo/trajectory.h"
#include "tdo/types.h"

#endif /* TDO_TDO_H */
