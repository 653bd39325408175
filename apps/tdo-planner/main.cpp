// tdo-planner: the LCM planning service (planner_node.h). Runs until SIGINT or SIGTERM (or
// --duration), then exits 0. Exit status 2: bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "planner_node.h"
#include "planner_options.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_signal(int /*sig*/) { g_stop = 1; }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a signal ends the wait inside lcm_handle_timeout at once
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
  tdo_lcm::PlannerConfig cfg;
  std::string url = tdo_lcm::kDefaultUrl;
  std::vector<int> max_size;
  double duration = 0.0;
  bool quiet = false;

  CLI::App app{
      "tdo-planner: answers TDO_PLAN_REQUEST with TDO_TRAJECTORY + TDO_FEASIBILITY on the latest "
      "TDO_MAP, with TDO_STATUS heartbeats. Stops on SIGINT/SIGTERM."};
  app.add_option("--lcm-url", url, "LCM URL (memq://, udpm://..., file://LOG?speed=0)")
      ->capture_default_str();
  tdo_lcm::add_planner_options(app, cfg, max_size);
  app.add_option("--status-channel", cfg.status_channel, "heartbeats out")->capture_default_str();
  app.add_option("--heartbeat", cfg.heartbeat_period_s, "s between heartbeats (0 = none)")
      ->capture_default_str();
  app.add_option("--duration", duration, "s to run, then exit as on SIGTERM (0 = until a signal)")
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "no start and stop lines on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  tdo_lcm::apply_max_size(max_size, &cfg);

  install_signal_handlers();
  tdo_lcm::Bus bus(url);
  if (!bus.good()) {
    std::fprintf(stderr,
                 "tdo-planner: error: cannot start LCM on '%s' (for udpm on loopback a multicast "
                 "route is needed: ip route add 224.0.0.0/4 dev lo)\n",
                 url.c_str());
    return 2;
  }
  tdo_lcm::PlannerNode node(&bus, cfg);
  std::string error;
  if (!node.start(&error)) {
    std::fprintf(stderr, "tdo-planner: error: %s\n", error.c_str());
    return 2;
  }
  if (!quiet)
    std::fprintf(stderr, "tdo-planner: vehicle %d on %s, arena %zu bytes, maps up to %u voxels\n",
                 cfg.vehicle_id, url.c_str(), node.arena_bytes(), node.capacity().max_voxels);

  const auto t_end = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(duration));
  // A file:// log ends with an error from lcm_handle: the end of the input, a clean stop.
  const bool from_log = url.rfind("file://", 0) == 0;
  int errors = 0;
  while (g_stop == 0) {
    const int rc = bus.handle_timeout(100);
    if (rc < 0 && g_stop == 0 && from_log) {
      if (!quiet) std::fprintf(stderr, "tdo-planner: end of the log\n");
      break;
    }
    if (rc < 0 && g_stop == 0 && ++errors > 100) {
      std::fprintf(stderr, "tdo-planner: error: LCM keeps failing, stopping\n");
      break;
    }
    const auto now = std::chrono::steady_clock::now();
    node.poll(now);
    if (duration > 0.0 && now >= t_end) break;
  }
  node.publish_status();  // a last heartbeat with the final counters
  const tdo_lcm::PlannerCounters& c = node.counters();
  if (!quiet)
    std::fprintf(stderr,
                 "tdo-planner: stopped: %lld received, %lld answered (%lld ok, %lld failed), "
                 "%lld rejected, %lld ignored\n",
                 static_cast<long long>(c.received), static_cast<long long>(c.answered),
                 static_cast<long long>(c.succeeded), static_cast<long long>(c.failed),
                 static_cast<long long>(c.rejected), static_cast<long long>(c.ignored));
  if (!quiet)
    for (const auto& kv : c.reasons)
      std::fprintf(stderr, "tdo-planner:   %s %lld\n", kv.first.c_str(),
                   static_cast<long long>(kv.second));
  return errors > 100 ? 1 : 0;
}
