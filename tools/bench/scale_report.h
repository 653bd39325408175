// What tdo-bench-scale prints: per workload and planner the times, per-query ratios to A*, turns,
// lengths, arena bytes and resident memory, then the goals of issue 19. Host-side bench code.
#ifndef TDO_TOOLS_BENCH_SCALE_REPORT_H
#define TDO_TOOLS_BENCH_SCALE_REPORT_H

#include <cstddef>
#include <string>
#include <vector>

#include "scale_runner.h"

namespace tdo_bench {

/** One planner on one workload: an outcome per query (ran = false where it did not run). */
struct PlannerRecord {
  std::vector<ScaleOutcome> q;
  ScaleSetup setup; /**< largest arena, RSS growth and set-up time over the workload's maps */
};

/** Everything measured on one workload. */
struct WorkloadRecord {
  std::string name;
  std::string what;
  std::vector<std::string> labels; /**< per query */
  PlannerRecord p[kScalePlanners]; /**< indexed by ScalePlanner */
  double load_ms = 0.0;            /**< ms, tdo_io::load_map of its maps, summed */
  double start_rss_mb = 0.0; /**< MB, VmRSS before the workload's first map loaded (memory earlier
                                  workloads left resident is part of the peak) */
  double peak_rss_mb = 0.0;  /**< MB, VmHWM at the end of the workload */
  bool peak_reset = false;   /**< the peak was reset before the workload's maps loaded */
};

/** Figures of one planner on one workload. */
struct Summary {
  bool ran = false;
  size_t n = 0;          /**< queries it ran on */
  size_t ok = 0;         /**< successes ("ok" and, for tdo, "ok_infeasible") */
  size_t infeasible = 0; /**< tdo: path found, trajectory over the dynamic limits */
  double median = 0.0, mean = 0.0, p90 = 0.0; /**< ms, over every query it ran on */
  size_t ratio_n = 0;                         /**< queries where it and A* both succeeded */
  double ratio_median = 0.0, ratio_max = 0.0; /**< of time / A*'s time on those queries */
  size_t common = 0;                          /**< queries every path planner that ran solved */
  unsigned long long turns_total = 0;         /**< over the common queries */
  double turns_median = 0.0;                  /**< over the common queries */
  double length_total = 0.0;                  /**< m, over the common queries */
  size_t missed = 0;                          /**< queries A* solved and this planner did not */
};

/** Summarize planner `p` on `w`. */
Summary summarize(const WorkloadRecord& w, int p);

/** Print the tables (Markdown). */
void print_tables(const std::vector<WorkloadRecord>& ws);

/**
 * @brief Print the goals block (issue 19's ratios, completeness, the textbook cost check).
 * @return false when tdo missed a query A* solved or A*'s cost differs from the textbook's.
 */
bool print_goals(const std::vector<WorkloadRecord>& ws);

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_SCALE_REPORT_H
