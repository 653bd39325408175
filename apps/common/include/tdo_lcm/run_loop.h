/**
 * @file run_loop.h
 * @brief The part of an LCM app's main shared by tdo-avoid, tdo-sim and tdo-planner: a clean stop
 * on SIGINT/SIGTERM, starting the bus, and the handle/poll loop until a signal, --duration, the end
 * of a file:// log or repeated LCM errors.
 */
#ifndef TDO_LCM_RUN_LOOP_H
#define TDO_LCM_RUN_LOOP_H

#include <chrono>
#include <functional>
#include <string>

#include "tdo_lcm/bus.h"

namespace tdo_lcm {

/** Options every LCM app has (--lcm-url, --queue-capacity, --duration, --quiet). */
struct RunOptions {
  std::string url;        ///< LCM URL
  double duration = 0.0;  ///< s to run, then stop as on SIGTERM (0 = until a signal)
  bool quiet = false;     ///< no start and stop lines on stderr
  int queue_capacity = Bus::kDefaultQueueCapacity;  ///< messages each subscription queue holds
};

/**
 * @brief Make SIGINT and SIGTERM request a clean stop (stop_requested()). No SA_RESTART: a signal
 * ends the wait inside lcm_handle_timeout at once.
 */
void install_stop_handlers();

/** @return true once SIGINT or SIGTERM arrived after install_stop_handlers(). */
bool stop_requested();

/**
 * @brief When `bus` did not start, print "<name>: error: cannot start LCM on '<url>' ..." to
 * stderr. @return bus.good().
 */
bool report_bus_start(const char* name, const Bus& bus, const std::string& url);

/** Steady-clock time point of the apps' nodes. */
using SteadyTime = std::chrono::steady_clock::time_point;

/**
 * @brief Handle messages and poll a node until a stop is requested, `opt.duration` s passed, a
 * file:// log ended or LCM failed more than 100 times.
 * @param next_due when the node next needs a poll: each wait lasts until then, at most 100 ms
 *                 (empty: always 100 ms)
 * @param poll     the node's poll(now), called after every wait
 * @return the exit status: 0 on a clean stop, 1 when LCM kept failing
 */
int run_loop(const char* name, Bus& bus, const RunOptions& opt,
             const std::function<SteadyTime()>& next_due,
             const std::function<void(SteadyTime)>& poll);

}  // namespace tdo_lcm

#endif  // TDO_LCM_RUN_LOOP_H
