/**
 * @file app_cli.h
 * @brief Command-line options every LCM app shares (CLI11; header-only, for the apps' mains).
 */
#ifndef TDO_LCM_APP_CLI_H
#define TDO_LCM_APP_CLI_H

#include <CLI/CLI.hpp>

#include "tdo_lcm/run_loop.h"

namespace tdo_lcm {

/** @brief Add --lcm-url (into opt->url) and --queue-capacity (opt->queue_capacity). */
inline void add_url_option(CLI::App& app, RunOptions* opt) {
  app.add_option("--lcm-url", opt->url, "LCM URL (memq://, udpm://..., file://LOG?speed=0)")
      ->capture_default_str();
  app.add_option("--queue-capacity", opt->queue_capacity,
                 "messages each subscription queue holds; more unhandled ones are dropped and "
                 "counted in TDO_STATUS.dropped (docs/lcm.md)")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
}

/** @brief Add --duration and --quiet (the last options of every app). */
inline void add_run_options(CLI::App& app, RunOptions* opt) {
  app.add_option("--duration", opt->duration,
                 "s to run, then exit as on SIGTERM (0 = until a signal)")
      ->capture_default_str();
  app.add_flag("--quiet", opt->quiet, "no start and stop lines on stderr");
}

/**
 * @brief Parse the command line. @return false when main must return `*rc` at once (help: 0, bad
 * options: 2, after CLI11 printed the message).
 */
inline bool parse_options(CLI::App& app, int argc, char** argv, int* rc) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    *rc = app.exit(e) == 0 ? 0 : 2;
    return false;
  }
  return true;
}

}  // namespace tdo_lcm

#endif  // TDO_LCM_APP_CLI_H
