// Factories of the planner families (baselines.cpp registry). Internal to tools/baselines.
#ifndef TDO_BASELINES_PLANNERS_INTERNAL_H
#define TDO_BASELINES_PLANNERS_INTERNAL_H

#include <memory>
#include <string>

#include "baselines.h"

namespace tdo_baselines {

/** tdo, msf-mtpo, astar, model-a .. model-e; null for other names. */
std::unique_ptr<Planner> make_pipeline_planner(const std::string& name);
/** rrtconnect, rrtconnect-simplify, rrtstar, rrtstar-simplify; null for other names. */
std::unique_ptr<Planner> make_ompl_planner(const std::string& name);
/** pso, gwo; null for other names. */
std::unique_ptr<Planner> make_swarm_planner(const std::string& name);

}  // namespace tdo_baselines

#endif  // TDO_BASELINES_PLANNERS_INTERNAL_H
