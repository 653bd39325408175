// tdo-replay LOG: re-run the planner on every request of an LCM log and compare with the recorded
// answers (replay.h). Exit status 0 all match, 1 a mismatch (listed on stdout), 2 bad input.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "planner_options.h"
#include "replay.h"
#include "tdo_lcm/app_cli.h"

int main(int argc, char** argv) {
  tdo_lcm::ReplayOptions opt;
  std::string log_path;
  std::vector<int> max_size;
  std::vector<std::string> overrides;
  int max_lines = 40;
  CLI::App app{
      "tdo-replay: feeds the TDO_MAP and TDO_PLAN_REQUEST events of an LCM log to tdo-planner's "
      "node in-process and compares its answers with the recorded TDO_TRAJECTORY and "
      "TDO_FEASIBILITY (by vehicle and request id; utime and plan_time_ms are not compared). "
      "Exit status: 0 all match, 1 a mismatch, 2 bad input."};
  app.add_option("log", log_path, "LCM log (lcm-logger output)")->required();
  tdo_lcm::add_planner_options(app, opt.planner, max_size);
  app.add_option("--override", overrides,
                 "NAME=VALUE: change a request field before planning (the check should then "
                 "fail); NAME one of: " +
                     tdo_lcm::override_names());
  app.add_option("--tolerance", opt.tolerance,
                 "relative tolerance on numbers (0 = bit-exact; the library is deterministic)")
      ->capture_default_str();
  app.add_option("--max-diffs", opt.max_diffs_per_answer, "differing values listed per answer")
      ->capture_default_str();
  app.add_option("--max-lines", max_lines, "diff lines printed in all (0 = every line)")
      ->capture_default_str();
  int parse_rc = 0;
  if (!tdo_lcm::parse_options(app, argc, argv, &parse_rc)) return parse_rc;
  tdo_lcm::apply_max_size(max_size, &opt.planner);
  std::string error;
  for (const std::string& o : overrides) {
    tdo_lcm::Override ov;
    if (!tdo_lcm::parse_override(o, &ov, &error)) {
      std::fprintf(stderr, "tdo-replay: error: %s\n", error.c_str());
      return 2;
    }
    opt.overrides.push_back(ov);
  }
  if (!(opt.tolerance >= 0.0)) {
    std::fprintf(stderr, "tdo-replay: error: --tolerance must be >= 0\n");
    return 2;
  }

  tdo_lcm::ReplayReport r;
  const int rc = tdo_lcm::replay_log(log_path, opt, &r, &error);
  if (rc == 2) {
    std::fprintf(stderr, "tdo-replay: error: %s\n", error.c_str());
    return 2;
  }
  std::size_t shown = 0;
  for (const std::string& line : r.diffs) {
    if (max_lines > 0 && shown >= static_cast<std::size_t>(max_lines)) {
      std::printf("DIFF ... %zu more lines (--max-lines 0 shows all)\n", r.diffs.size() - shown);
      break;
    }
    std::printf("DIFF %s\n", line.c_str());
    ++shown;
  }
  std::printf(
      "tdo-replay: %s: %lld events, %lld maps, %lld requests; %lld answers compared: %lld match, "
      "%lld differ, %lld not in the log, %lld not replayed (%lld for other vehicles skipped): "
      "%s\n",
      log_path.c_str(), static_cast<long long>(r.events), static_cast<long long>(r.maps),
      static_cast<long long>(r.requests), static_cast<long long>(r.compared),
      static_cast<long long>(r.matched), static_cast<long long>(r.differed),
      static_cast<long long>(r.not_recorded), static_cast<long long>(r.not_replayed),
      static_cast<long long>(r.other_vehicles), rc == 0 ? "PASS" : "FAIL");
  return rc;
}
