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

/**
 * The metrics of `mi` into r->metrics, with the samples of stage 5 (status ts, output to of the
 * last run of `traj`, period dt) when it gave a trajectory (ok or infeasible, >= 2 samples), read
 * stored or regenerated (tdo_samples::traj_samples): r->has_trajectory and r->feasible then set.
 * False with r->status named after the status when the samples or the metrics fail.
 */
bool metrics_with_trajectory(tdo_metrics_input mi, tdo_status ts, const tdo_traj* traj,
                             const tdo_traj_output& to, double dt, PlanResult* r);

}  // namespace tdo_baselines

#endif  // TDO_BASELINES_PLANNERS_INTERNAL_H
