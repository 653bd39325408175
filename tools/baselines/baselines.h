/**
 * @file baselines.h
 * @brief One planner interface for the bench (tdo-bench, tdo-tune): the TDO-MSF pipeline and its
 *        ablation stages, the paper's baselines (A*, MSF-MTPO), OMPL RRTConnect / RRT* (raw and
 *        simplified) and pagmo2 PSO / grey wolf optimizers. Host code (exceptions, allocation).
 *
 * Every planner plans in an Environment: a map loaded into a libtdo planner whose grid is finished
 * at the query clearance. All collision checks go through libtdo's exact clearance queries
 * (collision.h) on that grid, and every result is measured by the same code (libtdo's
 * tdo_metrics_compute, see evaluate()). A result is a success only when its final path begins
 * exactly at the start, ends exactly at the goal and keeps the clearance everywhere (checked here
 * again, whatever the planner claims).
 */
#ifndef TDO_BASELINES_BASELINES_H
#define TDO_BASELINES_BASELINES_H

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace tdo_baselines {

/** A map in a libtdo planner at one clearance, plus the stage contexts used to measure paths. */
class Environment {
 public:
  /**
   * @brief Load `map` into a fresh libtdo planner finished at `clearance` (m).
   * @param node_cap search states per direction (sizes the arena); 0 = as many as the grid has
   * @return null with `error` on a set-up failure (capacity, bad map).
   */
  static std::unique_ptr<Environment> create(const tdo_io::Map& map, double clearance,
                                             uint32_t node_cap, std::string* error);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  tdo_planner* planner() { return planner_; }
  const tdo_grid* grid() const { return grid_; }
  const tdo_io::Map& map() const { return map_; }
  double clearance() const { return clearance_; }
  tdo_vec3 lo() const { return lo_; } /**< m, minimum corner of the grid bounds */
  tdo_vec3 hi() const { return hi_; } /**< m, maximum corner of the grid bounds */

  /** 1 when p is inside the closed bounds and at least `clearance` from every obstacle (exact). */
  bool point_valid(const tdo_vec3& p) const;
  /** Exact continuous check of the segment [a, b] (tdo_collision_segment_clear). */
  bool segment_valid(const tdo_vec3& a, const tdo_vec3& b) const;

  /** Stage contexts for measuring raw polylines (stop-and-go time parameterisation). */
  tdo_smooth* smoother() { return smooth_; }
  tdo_traj* traj() { return traj_; }
  uint32_t max_polyline() const { return max_polyline_; }

 private:
  Environment() = default;
  tdo_io::Map map_;
  double clearance_ = 0.0;
  tdo_vec3 lo_{};
  tdo_vec3 hi_{};
  std::unique_ptr<unsigned char[]> memory_;
  std::unique_ptr<unsigned char[]> extra_;
  tdo_planner* planner_ = nullptr;
  tdo_grid* grid_ = nullptr;
  tdo_smooth* smooth_ = nullptr;
  tdo_traj* traj_ = nullptr;
  uint32_t max_polyline_ = 0;
};

/** What one planning call produced, measured identically for every planner. */
struct PlanResult {
  bool ok = false;             /**< a path from start to goal that keeps the clearance */
  std::string status = "";     /**< "ok", or why not (libtdo status name, "collides", ...) */
  std::vector<tdo_vec3> path;  /**< m, the polyline whose turns are counted: a raw path, a grid
                                    path or P2 ("waypoints", docs/design.md s.10); exact start
                                    and goal */
  std::vector<tdo_vec3> curve; /**< m, the final path sampled for pictures (the polyline itself
                                    for raw-path planners) */
  tdo_metrics metrics{};       /**< libtdo metrics of the final path (valid when ok) */
  bool has_trajectory = false; /**< energy / flight time come from a trajectory */
  bool feasible = false;       /**< libtdo's feasibility check passed on that trajectory */
  bool smooth = false;       /**< curvature-continuous final path whose feasibility check passed */
  double plan_time_ms = 0.0; /**< ms, wall time of planning (metrics and checks excluded where
                                  the planner allows: see each planner) */
  uint64_t expansions = 0;   /**< search expansions, OMPL iterations or fitness evaluations */
};

/** The planner interface. Parameters are doubles by name; integers are rounded. */
class Planner {
 public:
  virtual ~Planner() = default;
  /** Registry name (make_planner). */
  virtual std::string name() const = 0;
  /** One line: what it is. */
  virtual std::string description() const = 0;
  /** true when the result depends on the seed. */
  virtual bool stochastic() const { return false; }
  /** Names of the parameters, in order. */
  std::vector<std::string> param_names() const;
  /** Set a parameter. @return false with `error` for an unknown name or a value out of range. */
  bool set_param(const std::string& name, double value, std::string* error);
  /** A parameter's value (NaN for an unknown name). */
  double param(const std::string& name) const;
  /**
   * @brief Plan from `start` to `goal` (m, world frame) in `env`. Deterministic for a fixed seed.
   *        Never throws for a planning failure: it is reported in the result.
   */
  virtual PlanResult plan(Environment& env, const tdo_vec3& start, const tdo_vec3& goal,
                          uint64_t seed) = 0;

 protected:
  struct Param {
    double value;
    double min;
    double max;
  };
  void add_param(const std::string& name, double value, double min, double max);
  double p(const std::string& name) const { return params_.at(name).value; }

 private:
  std::vector<std::string> order_;
  std::map<std::string, Param> params_;
};

/** Names make_planner accepts, in the order the bench lists them. */
const std::vector<std::string>& planner_names();

/** A new planner by name; null with `error` for an unknown name. */
std::unique_ptr<Planner> make_planner(const std::string& name, std::string* error);

/**
 * @brief Measure and check a raw polyline (exact start and goal at its ends): every segment must
 *        pass Environment::segment_valid, else the result fails with status "collides". Metrics:
 *        tdo_metrics_compute on the polyline (discrete curvature); energy and flight time from the
 *        stop-and-go trajectory libtdo makes of it (smoothing = none: at rest at every corner;
 *        stage 5 with the default limits). plan_time_ms and expansions are left to the caller.
 */
PlanResult evaluate_polyline(Environment& env, const std::vector<tdo_vec3>& pts,
                             const tdo_vec3& start, const tdo_vec3& goal);

/** Default libtdo parameters used by every pipeline-based planner (tdo_plan_params_default). */
tdo_plan_params default_params();

}  // namespace tdo_baselines

#endif  // TDO_BASELINES_BASELINES_H
