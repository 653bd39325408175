/**
 * @file replay.h
 * @brief tdo-replay minus its main(): re-run tdo-planner's node in-process on the inputs recorded
 * in an LCM log and compare its answers with the recorded ones.
 *
 * Every TDO_MAP and TDO_PLAN_REQUEST event of the log is fed, in log order, to a PlannerNode (the
 * very code of tdo-planner, on a private memq:// bus) configured like the recorded planner (vehicle
 * id, channels, capacities). Each answer it publishes is paired with the recorded TDO_TRAJECTORY /
 * TDO_FEASIBILITY of the same (vehicle_id, request_id), in order, and compared field by field;
 * only the wall-clock fields (utime, plan_time_ms) are skipped. Recorded answers for other vehicles
 * are not expected; recorded answers for the served vehicle that the replay does not produce are
 * mismatches, and so are answers the replay produces that the log lacks.
 */
#ifndef TDO_REPLAY_H
#define TDO_REPLAY_H

#include <cstdint>
#include <string>
#include <vector>

#include "planner_node.h"

namespace tdo_lcm {

/** A request field replaced before the replay: `name=value` (see override_names()). */
struct Override {
  std::string name;
  double value = 0.0;
};

/** @return the names --override accepts, comma-separated. */
std::string override_names();

/** @brief Parse "name=value". @return false with a message when the name or value is bad. */
bool parse_override(const std::string& text, Override* out, std::string* error);

/** @brief Apply overrides to a request. @return false (and error) for an unknown name. */
bool apply_overrides(const std::vector<Override>& overrides, tdo::plan_request_t* m,
                     std::string* error);

struct ReplayOptions {
  PlannerConfig planner;           /**< as the recorded tdo-planner ran (heartbeats are off) */
  std::vector<Override> overrides; /**< request fields changed before planning */
  double tolerance = 0.0;          /**< |got - expected| <= tolerance * max(1, |expected|); 0 =
                                        bit-exact (NaN equals NaN) */
  int max_diffs_per_answer = 8;    /**< differing fields listed per answer, then a count */
};

struct ReplayReport {
  int64_t events = 0;             /**< events in the log */
  int64_t maps = 0;               /**< TDO_MAP events fed */
  int64_t requests = 0;           /**< TDO_PLAN_REQUEST events fed */
  int64_t recorded = 0;           /**< recorded answers (trajectory + feasibility) to compare */
  int64_t other_vehicles = 0;     /**< recorded answers for other vehicles (not compared) */
  int64_t compared = 0;           /**< answer pairs compared */
  int64_t matched = 0;            /**< of them equal */
  int64_t differed = 0;           /**< of them different */
  int64_t not_recorded = 0;       /**< replayed answers the log lacks */
  int64_t not_replayed = 0;       /**< recorded answers the replay did not produce */
  std::vector<std::string> diffs; /**< one line per difference */
};

/**
 * @brief Replay `log_path`.
 * @return 0 every answer matches; 1 a mismatch (report.diffs says which); 2 bad input (error
 *         says why: the log cannot be read, holds no plan request, a recorded answer cannot be
 *         decoded, the planner cannot start, a bad override).
 */
int replay_log(const std::string& log_path, const ReplayOptions& options, ReplayReport* report,
               std::string* error);

}  // namespace tdo_lcm

#endif  // TDO_REPLAY_H
