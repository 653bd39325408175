// tdo-avoid: the E-APF follower on LCM (avoid_node.h). Runs until SIGINT or SIGTERM (or
// --duration), then exits 0. Exit status 2: bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "avoid_node.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/run_loop.h"

int main(int argc, char** argv) {
  tdo_lcm::AvoidConfig cfg;
  tdo_lcm::RunOptions opt;
  opt.url = tdo_lcm::kDefaultUrl;
  std::vector<int> max_size = {cfg.max_nx, cfg.max_ny, cfg.max_nz};
  const std::map<std::string, tdo_follower_kind> kinds = {{"eapf", TDO_FOLLOWER_EAPF},
                                                          {"apf", TDO_FOLLOWER_APF}};

  CLI::App app{
      "tdo-avoid: the E-APF follower. Follows the latest TDO_TRAJECTORY of its vehicle around the "
      "TDO_OBSTACLES, with static repulsion from TDO_MAP, and sends a TDO_SETPOINT for the latest "
      "TDO_UAV_STATE at a fixed rate, with TDO_STATUS heartbeats. Stops on SIGINT/SIGTERM."};
  tdo_lcm::add_url_option(app, &opt);
  app.add_option("--vehicle-id", cfg.vehicle_id, "vehicle served; other messages are ignored")
      ->capture_default_str();
  app.add_option("--follower", cfg.kind, "eapf (trajectory-guided) or apf (classical baseline)")
      ->transform(CLI::CheckedTransformer(kinds, CLI::ignore_case))
      ->default_str("eapf");
  app.add_option("--rate", cfg.rate_hz, "Hz, setpoints per second (the follower's step)")
      ->capture_default_str();
  app.add_flag("--lockstep", cfg.lockstep,
               "one setpoint per received state, at once, instead of the timer (with tdo-sim "
               "--lockstep: deterministic runs)");
  app.add_option("--trajectory-channel", cfg.trajectory_channel, "trajectories in")
      ->capture_default_str();
  app.add_option("--obstacles-channel", cfg.obstacles_channel, "moving obstacles in")
      ->capture_default_str();
  app.add_option("--state-channel", cfg.state_channel, "vehicle states in")->capture_default_str();
  app.add_option("--map-channel", cfg.map_channel, "static maps in")->capture_default_str();
  app.add_option("--map-update-channel", cfg.map_update_channel, "map updates in")
      ->capture_default_str();
  app.add_option("--map-request-channel", cfg.map_request_channel,
                 "requests for a whole map out (when the map is stale)")
      ->capture_default_str();
  app.add_option("--setpoint-channel", cfg.setpoint_channel, "setpoints out")
      ->capture_default_str();
  app.add_option("--status-channel", cfg.status_channel, "heartbeats out")->capture_default_str();
  app.add_option("--request-channel", cfg.request_channel,
                 "plan requests watched: one for this vehicle promises a trajectory")
      ->capture_default_str();
  app.add_option("--feasibility-channel", cfg.feasibility_channel,
                 "feasibility reports watched: one for this vehicle promises a trajectory")
      ->capture_default_str();
  app.add_option("--answer-timeout", cfg.answer_timeout_s,
                 "s: a promised trajectory missing this long is reported (trajectory.missing)")
      ->capture_default_str();
  app.add_option("--heartbeat", cfg.heartbeat_period_s, "s between heartbeats (0 = none)")
      ->capture_default_str();
  app.add_option("--v-max", cfg.v_max, "m/s, speed limit")->capture_default_str();
  app.add_option("--a-max", cfg.a_max, "m/s^2, acceleration limit")->capture_default_str();
  app.add_option("--j-max", cfg.j_max, "m/s^3, jerk limit")->capture_default_str();
  app.add_option("--vehicle-radius", cfg.vehicle_radius, "m")->capture_default_str();
  app.add_option("--max-size", max_size, "capacity: voxels NX NY NZ of the largest map")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--max-boxes", cfg.max_boxes, "capacity: obstacle boxes per map")
      ->capture_default_str();
  app.add_option("--max-clearance-ratio", cfg.max_clearance_ratio,
                 "capacity: largest map clearance / resolution")
      ->capture_default_str();
  app.add_option("--max-samples", cfg.max_samples, "capacity: trajectory samples")
      ->capture_default_str();
  app.add_option("--max-movers", cfg.max_movers, "capacity: moving obstacles per message")
      ->capture_default_str();
  bool no_replan = false;
  app.add_flag("--no-replan", no_replan,
               "never ask for a new plan (a blocked trajectory: brake, path_blocked)");
  app.add_option("--replan-lead", cfg.replan_lead_s,
                 "s from a replan's trigger to the takeover of the new plan")
      ->capture_default_str();
  app.add_option("--max-replans", cfg.max_replans,
                 "requests per trigger without a usable plan before a safe stop (replan_failed)")
      ->capture_default_str();
  app.add_option("--max-replans-total", cfg.max_replans_total, "replan requests in all")
      ->capture_default_str();
  app.add_option("--replan-deviation", cfg.replan_deviation_m,
                 "m off the path for 1 s that makes the follower ask for a new plan")
      ->capture_default_str();
  app.add_option("--replan-id-base", cfg.replan_id_base,
                 "request_id of the first replan (then +1 per replan)")
      ->capture_default_str();
  tdo_lcm::add_run_options(app, &opt);
  if (int rc = 0; !tdo_lcm::parse_options(app, argc, argv, &rc)) return rc;
  cfg.replan = !no_replan;
  cfg.max_nx = max_size[0];
  cfg.max_ny = max_size[1];
  cfg.max_nz = max_size[2];

  tdo_lcm::install_stop_handlers();
  tdo_lcm::Bus bus(opt.url, opt.queue_capacity);
  if (!tdo_lcm::report_bus_start("tdo-avoid", bus, opt.url)) return 2;
  tdo_lcm::AvoidNode node(&bus, cfg);
  if (!tdo_lcm::start_node("tdo-avoid", &node)) return 2;
  if (!opt.quiet)
    std::fprintf(stderr, "tdo-avoid: vehicle %d on %s, %s at %g Hz%s, arena %zu bytes\n",
                 cfg.vehicle_id, opt.url.c_str(), cfg.kind == TDO_FOLLOWER_APF ? "apf" : "eapf",
                 cfg.rate_hz, cfg.lockstep ? " (lock-step)" : "", node.arena_bytes());

  const int exit_status = tdo_lcm::run_loop(
      "tdo-avoid", bus, opt, [&] { return node.next_due(); },
      [&](tdo_lcm::SteadyTime now) { node.poll(now); });
  node.publish_status();  // a last heartbeat with the final counters
  const tdo_lcm::AvoidCounters& c = node.counters();
  if (!opt.quiet)
    std::fprintf(stderr,
                 "tdo-avoid: stopped: %lld received, %lld setpoints (%lld followed, %lld failed, "
                 "%lld hover), %lld rejected, %lld ignored; %lld replans (%lld taken over), "
                 "%lld safe stops\n",
                 static_cast<long long>(c.received), static_cast<long long>(c.setpoints),
                 static_cast<long long>(c.steps_ok), static_cast<long long>(c.steps_failed),
                 static_cast<long long>(c.holds), static_cast<long long>(c.rejected),
                 static_cast<long long>(c.ignored), static_cast<long long>(c.replans),
                 static_cast<long long>(c.replan_switches), static_cast<long long>(c.safe_stops));
  if (!opt.quiet)
    for (const auto& kv : c.reasons)
      std::fprintf(stderr, "tdo-avoid:   %s %lld\n", kv.first.c_str(),
                   static_cast<long long>(kv.second));
  return exit_status;
}
