// tdo-sim: the simulated vehicle and moving obstacles on LCM (sim_node.h). Runs until SIGINT or
// SIGTERM (or
// --duration), then exits 0. Exit status 2: bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "sim_node.h"

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
  tdo_lcm::SimConfig cfg;
  std::string url = tdo_lcm::kDefaultUrl;
  std::vector<double> start;
  std::vector<double> bounds;
  std::vector<double> goal;
  bool no_movers = false;
  double duration = 0.0;
  bool quiet = false;

  CLI::App app{
      "tdo-sim: libtdo's deterministic simulator. A vehicle follows TDO_SETPOINT and reports "
      "TDO_UAV_STATE; moving spheres go out on TDO_OBSTACLES; a map file goes out on TDO_MAP. "
      "TDO_STATUS heartbeats. Stops on SIGINT/SIGTERM."};
  app.add_option("--lcm-url", url, "LCM URL (memq://, udpm://..., file://LOG?speed=0)")
      ->capture_default_str();
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
  app.add_option("--seed", cfg.seed, "seed of the disturbance")->capture_default_str();
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
  app.add_option("--max-movers", cfg.max_movers, "capacity: movers simulated")
      ->capture_default_str();
  app.add_option("--setpoint-channel", cfg.setpoint_channel, "setpoints in")->capture_default_str();
  app.add_option("--state-channel", cfg.state_channel, "vehicle states out")->capture_default_str();
  app.add_option("--obstacles-channel", cfg.obstacles_channel, "moving obstacles out")
      ->capture_default_str();
  app.add_option("--map-channel", cfg.map_channel, "map out")->capture_default_str();
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
  cfg.movers = !no_movers;
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

  install_signal_handlers();
  tdo_lcm::Bus bus(url);
  if (!bus.good()) {
    std::fprintf(stderr,
                 "tdo-sim: error: cannot start LCM on '%s' (for udpm on loopback a multicast "
                 "route is needed: ip route add 224.0.0.0/4 dev lo)\n",
                 url.c_str());
    return 2;
  }
  tdo_lcm::SimNode node(&bus, cfg);
  std::string error;
  if (!node.start(&error)) {
    std::fprintf(stderr, "tdo-sim: error: %s\n", error.c_str());
    return 2;
  }
  if (!quiet) {
    const tdo_sim_output s = node.current();
    std::fprintf(stderr,
                 "tdo-sim: vehicle %d on %s at %g Hz%s, start (%g, %g, %g), %u movers%s%s\n",
                 cfg.vehicle_id, url.c_str(), cfg.rate_hz, cfg.lockstep ? " (lock-step)" : "",
                 s.state.p.x, s.state.p.y, s.state.p.z, s.n_movers, node.has_map() ? ", map " : "",
                 node.has_map() ? cfg.map_file.c_str() : "");
  }

  const auto t_end = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(duration));
  // A file:// log ends with an error from lcm_handle: the end of the input, a clean stop.
  const bool from_log = url.rfind("file://", 0) == 0;
  int errors = 0;
  while (g_stop == 0) {
    // Wait for messages until the next step, map or heartbeat is due (at most 100 ms).
    const auto now0 = std::chrono::steady_clock::now();
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(node.next_due() - now0);
    const int wait_ms = static_cast<int>(std::clamp<long long>(wait.count(), 0, 100));
    const int rc = bus.handle_timeout(wait_ms);
    if (rc < 0 && g_stop == 0 && from_log) {
      if (!quiet) std::fprintf(stderr, "tdo-sim: end of the log\n");
      break;
    }
    if (rc < 0 && g_stop == 0 && ++errors > 100) {
      std::fprintf(stderr, "tdo-sim: error: LCM keeps failing, stopping\n");
      break;
    }
    const auto now = std::chrono::steady_clock::now();
    node.poll(now);
    if (duration > 0.0 && now >= t_end) break;
  }
  node.publish_status();  // a last heartbeat with the final counters
  const tdo_lcm::SimCounters& c = node.counters();
  if (!quiet) {
    const tdo_sim_output s = node.current();
    std::fprintf(stderr,
                 "tdo-sim: stopped: %lld received, %lld steps (%lld braking, %lld in collision), "
                 "%lld rejected, %lld ignored; at (%.3f, %.3f, %.3f) after %.2f s\n",
                 static_cast<long long>(c.received), static_cast<long long>(c.steps),
                 static_cast<long long>(c.brakes), static_cast<long long>(c.collision_steps),
                 static_cast<long long>(c.rejected), static_cast<long long>(c.ignored), s.state.p.x,
                 s.state.p.y, s.state.p.z, s.state.t);
    for (const auto& kv : c.reasons)
      std::fprintf(stderr, "tdo-sim:   %s %lld\n", kv.first.c_str(),
                   static_cast<long long>(kv.second));
  }
  return errors > 100 ? 1 : 0;
}
