// tdo-sim: the simulated vehicle and moving obstacles on LCM (sim_node.h). Runs until SIGINT or
// SIGTERM (or
// --duration), then exits 0. Exit status 2: bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "sim_node.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/run_loop.h"

namespace {

// The counters on stderr when tdo-sim stops.
void print_summary(const tdo_lcm::SimNode& node) {
  const tdo_lcm::SimCounters& c = node.counters();
  const tdo_sim_output s = node.current();
  std::fprintf(stderr,
               "tdo-sim: stopped: %lld received, %lld steps (%lld braking, %lld in collision: "
               "%lld static, %lld mover), %lld of %lld hidden boxes revealed, "
               "%lld rejected, %lld ignored; at (%.3f, %.3f, %.3f) after %.2f s\n",
               static_cast<long long>(c.received), static_cast<long long>(c.steps),
               static_cast<long long>(c.brakes), static_cast<long long>(c.collision_steps),
               static_cast<long long>(c.static_collisions),
               static_cast<long long>(c.mover_collisions), static_cast<long long>(c.boxes_revealed),
               static_cast<long long>(c.boxes_hidden), static_cast<long long>(c.rejected),
               static_cast<long long>(c.ignored), s.state.p.x, s.state.p.y, s.state.p.z, s.state.t);
  std::fprintf(stderr,
               "tdo-sim: %lld ticks waited for the answer to their state, %lld late steps "
               "braked, %lld answers came after their state\n",
               static_cast<long long>(c.waits), static_cast<long long>(c.late_steps),
               static_cast<long long>(c.late_setpoints));
  for (const auto& kv : c.reasons)
    std::fprintf(stderr, "tdo-sim:   %s %lld\n", kv.first.c_str(),
                 static_cast<long long>(kv.second));
}

}  // namespace

int main(int argc, char** argv) {
  tdo_lcm::SimConfig cfg;
  tdo_lcm::RunOptions opt;
  opt.url = tdo_lcm::kDefaultUrl;
  std::vector<double> start;
  std::vector<double> bounds;
  std::vector<double> goal;
  bool no_movers = false;

  CLI::App app{
      "tdo-sim: libtdo's deterministic simulator. A vehicle follows TDO_SETPOINT and reports "
      "TDO_UAV_STATE; moving spheres go out on TDO_OBSTACLES; a map file goes out on TDO_MAP. "
      "TDO_STATUS heartbeats. Stops on SIGINT/SIGTERM."};
  tdo_lcm::add_url_option(app, &opt);
  app.add_option("--vehicle-id", cfg.vehicle_id, "vehicle simulated; other setpoints are ignored")
      ->capture_default_str();
  app.add_option("--map", cfg.map_file,
                 "map file (.tdomap, .3dmap, .bt, .ot): published on the map channel, its movers "
                 "simulated, its geometry checked for collisions, its start used")
      ->check(CLI::ExistingFile);
  app.add_option("--map-id", cfg.map_id, "map_id of the published map")->capture_default_str();
  app.add_option("--map-clearance", cfg.map_clearance, "m, clearance hint sent with the map")
      ->capture_default_str();
  app.add_option("--map-resolution", cfg.map_resolution,
                 "m, voxel edge for OcTrees (0 = the tree's)")
      ->capture_default_str();
  app.add_option("--map-period", cfg.map_period_s,
                 "s between re-publications of the map (0 = once)")
      ->capture_default_str();
  app.add_flag("--no-movers", no_movers, "do not simulate the map's moving spheres");
  app.add_option("--start", start, "m, initial position X Y Z (default: the map's start)")
      ->expected(3);
  app.add_option("--bounds", bounds,
                 "m, XMIN YMIN ZMIN XMAX YMAX ZMAX where movers reflect (default: the map's)")
      ->expected(6);
  app.add_flag("--request-goal", cfg.request_goal,
               "demo: send one TDO_PLAN_REQUEST (request 1, libtdo's default parameters) from the "
               "start to the goal after --request-delay s, as a ground station would");
  app.add_option("--goal", goal, "m, goal X Y Z of --request-goal (default: the map's goal)")
      ->expected(3);
  app.add_option("--request-delay", cfg.request_delay_s, "s after start before --request-goal")
      ->capture_default_str();
  app.add_option("--request-channel", cfg.request_channel, "plan request out (--request-goal)")
      ->capture_default_str();
  app.add_option("--rate", cfg.rate_hz, "Hz, simulator steps per second")->capture_default_str();
  app.add_flag(
      "--lockstep", cfg.lockstep,
      "one step per received setpoint, at once, instead of the timer (deterministic runs)");
  app.add_option(
         "--start-utime", cfg.start_utime,
         "us, utime of the initial state (0 = now); the clock then advances by 1/rate per step")
      ->capture_default_str();
  app.add_option("--seed", cfg.seed, "seed of the disturbance and of the hidden obstacles")
      ->capture_default_str();
  app.add_option("--unknown", cfg.unknown_fraction,
                 "share in [0, 1] of the map's boxes hidden until the range sensor sees them; "
                 "revealed ones go out as map updates")
      ->capture_default_str();
  app.add_option("--sensor-range", cfg.sensor_range, "m, reach of the range sensor (--unknown)")
      ->capture_default_str();
  app.add_option("--accel-noise", cfg.accel_noise, "m/s^2, standard deviation of the disturbance")
      ->capture_default_str();
  app.add_option("--v-max", cfg.v_max, "m/s, speed limit")->capture_default_str();
  app.add_option("--a-max", cfg.a_max, "m/s^2, acceleration limit")->capture_default_str();
  app.add_option("--j-max", cfg.j_max, "m/s^3, jerk limit")->capture_default_str();
  app.add_option("--vehicle-radius", cfg.vehicle_radius, "m, for the mover collision check")
      ->capture_default_str();
  app.add_option("--static-clearance", cfg.static_clearance,
                 "m, a static collision is closer than this to the map")
      ->capture_default_str();
  app.add_option("--setpoint-timeout", cfg.setpoint_timeout_s,
                 "s without a setpoint before the vehicle brakes")
      ->capture_default_str();
  app.add_option("--setpoint-max-age", cfg.setpoint_max_age_steps,
                 "steps (of 1/rate), timed mode: a setpoint whose utime lies further behind the "
                 "simulated clock is stale (setpoint_stale): the vehicle brakes (0 = no check)")
      ->capture_default_str();
  app.add_option("--setpoint-wait", cfg.setpoint_wait_s,
                 "s of wall clock, timed mode: a step waits this long past its tick for the "
                 "setpoint answering the current state; without it the vehicle brakes "
                 "(setpoint_late); 0 = fly the latest setpoint (--setpoint-max-age applies)")
      ->capture_default_str();
  app.add_option("--max-movers", cfg.max_movers, "capacity: movers simulated")
      ->capture_default_str();
  app.add_option("--setpoint-channel", cfg.setpoint_channel, "setpoints in")->capture_default_str();
  app.add_option("--state-channel", cfg.state_channel, "vehicle states out")->capture_default_str();
  app.add_option("--obstacles-channel", cfg.obstacles_channel, "moving obstacles out")
      ->capture_default_str();
  app.add_option("--map-channel", cfg.map_channel, "map out")->capture_default_str();
  app.add_option("--map-update-channel", cfg.map_update_channel, "revealed obstacles out")
      ->capture_default_str();
  app.add_option("--map-request-channel", cfg.map_request_channel,
                 "requests for the whole map in (--unknown)")
      ->capture_default_str();
  app.add_option("--status-channel", cfg.status_channel, "heartbeats out")->capture_default_str();
  app.add_option("--heartbeat", cfg.heartbeat_period_s, "s between heartbeats (0 = none)")
      ->capture_default_str();
  tdo_lcm::add_run_options(app, &opt);
  if (int rc = 0; !tdo_lcm::parse_options(app, argc, argv, &rc)) return rc;
  cfg.movers = !no_movers;
  cfg.log = !opt.quiet;
  if (start.size() == 3) {
    cfg.has_start = true;
    cfg.start = tdo_vec3{start[0], start[1], start[2]};
  }
  if (goal.size() == 3) {
    cfg.has_goal = true;
    cfg.goal = tdo_vec3{goal[0], goal[1], goal[2]};
  }
  if (bounds.size() == 6) {
    cfg.has_bounds = true;
    cfg.bounds = tdo_box{{bounds[0], bounds[1], bounds[2]}, {bounds[3], bounds[4], bounds[5]}};
  }

  tdo_lcm::install_stop_handlers();
  tdo_lcm::Bus bus(opt.url, opt.queue_capacity);
  if (!tdo_lcm::report_bus_start("tdo-sim", bus, opt.url)) return 2;
  tdo_lcm::SimNode node(&bus, cfg);
  if (!tdo_lcm::start_node("tdo-sim", &node)) return 2;
  if (!opt.quiet) {
    const tdo_sim_output s = node.current();
    std::fprintf(stderr,
                 "tdo-sim: vehicle %d on %s at %g Hz%s, start (%g, %g, %g), %u movers%s%s\n",
                 cfg.vehicle_id, opt.url.c_str(), cfg.rate_hz, cfg.lockstep ? " (lock-step)" : "",
                 s.state.p.x, s.state.p.y, s.state.p.z, s.n_movers, node.has_map() ? ", map " : "",
                 node.has_map() ? cfg.map_file.c_str() : "");
  }

  const int exit_status = tdo_lcm::run_loop(
      "tdo-sim", bus, opt, [&] { return node.next_due(); },
      [&](tdo_lcm::SteadyTime now) { node.poll(now); });
  node.publish_status();  // a last heartbeat with the final counters
  if (!opt.quiet) print_summary(node);
  return exit_status;
}
