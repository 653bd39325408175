// tdo-planner: the LCM planning service (planner_node.h). Runs until SIGINT or SIGTERM (or
// --duration), then exits 0. Exit status 2: bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "planner_node.h"
#include "planner_options.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/run_loop.h"

int main(int argc, char** argv) {
  tdo_lcm::PlannerConfig cfg;
  tdo_lcm::RunOptions opt;
  opt.url = tdo_lcm::kDefaultUrl;
  std::vector<int> max_size;

  CLI::App app{
      "tdo-planner: answers TDO_PLAN_REQUEST with TDO_TRAJECTORY + TDO_FEASIBILITY on the latest "
      "TDO_MAP, with TDO_STATUS heartbeats. Stops on SIGINT/SIGTERM."};
  tdo_lcm::add_url_option(app, &opt);
  tdo_lcm::add_planner_options(app, cfg, max_size);
  app.add_option("--status-channel", cfg.status_channel, "heartbeats out")->capture_default_str();
  app.add_option("--heartbeat", cfg.heartbeat_period_s, "s between heartbeats (0 = none)")
      ->capture_default_str();
  tdo_lcm::add_run_options(app, &opt);
  if (int rc = 0; !tdo_lcm::parse_options(app, argc, argv, &rc)) return rc;
  tdo_lcm::apply_max_size(max_size, &cfg);

  tdo_lcm::install_stop_handlers();
  tdo_lcm::Bus bus(opt.url, opt.queue_capacity);
  if (!tdo_lcm::report_bus_start("tdo-planner", bus, opt.url)) return 2;
  tdo_lcm::PlannerNode node(&bus, cfg);
  if (!tdo_lcm::start_node("tdo-planner", &node)) return 2;
  if (!opt.quiet)
    std::fprintf(stderr, "tdo-planner: vehicle %d on %s, arena %zu bytes, maps up to %u voxels\n",
                 cfg.vehicle_id, opt.url.c_str(), node.arena_bytes(), node.capacity().max_voxels);

  const int exit_status = tdo_lcm::run_loop("tdo-planner", bus, opt, {},
                                            [&](tdo_lcm::SteadyTime now) { node.poll(now); });
  node.publish_status();  // a last heartbeat with the final counters
  const tdo_lcm::PlannerCounters& c = node.counters();
  if (!opt.quiet)
    std::fprintf(stderr,
                 "tdo-planner: stopped: %lld received, %lld answered (%lld ok, %lld failed), "
                 "%lld rejected, %lld ignored, %lld dropped by the queues\n",
                 static_cast<long long>(c.received), static_cast<long long>(c.answered),
                 static_cast<long long>(c.succeeded), static_cast<long long>(c.failed),
                 static_cast<long long>(c.rejected), static_cast<long long>(c.ignored),
                 static_cast<long long>(bus.dropped()));
  if (!opt.quiet)
    for (const auto& kv : c.reasons)
      std::fprintf(stderr, "tdo-planner:   %s %lld\n", kv.first.c_str(),
                   static_cast<long long>(kv.second));
  return exit_status;
}
