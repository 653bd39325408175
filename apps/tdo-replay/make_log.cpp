// tdo-make-replay-log: writes the regression log test/data/map6_run.lcmlog (docs/lcm.md).
//
// Runs tdo-planner's node in-process on a memq:// bus, publishes a scripted session to it and
// records every message on the six channels with lcm's LogFile writer, in delivery order (what
// lcm-logger records from a live planner). The session: a request before any map (answered
// no_map), Map1, its default query, a request for another vehicle (ignored), a request with a NaN
// goal (answered non_finite), a truncated request (counted, not answered), Map6's static part
// (its 500 columns; the moving spheres are the follower's business), its default query with the
// default parameters, with A* to the smoothing stage, with only start and goal (use_defaults) and
// with v_max 0 (refused, naming the field), and a last heartbeat. Map1's answer carries the
// sampled form as well (SAMPLES_ON), the others only the compact form.
// Rerun: tdo-make-replay-log --maps maps -o test/data/map6_run.lcmlog
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <string>
#include <vector>

#include "planner_node.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/node_status.h"

namespace {

tdo::plan_request_t make_request(int64_t id, int32_t vehicle, const tdo_vec3& start,
                                 const tdo_vec3& goal) {
  tdo_plan_request r{};
  tdo_plan_params_default(&r.params);
  r.start = start;
  r.goal = goal;
  tdo::plan_request_t m{};
  tdo_lcm::plan_request_to_msg(r, -1.0, &m);  // clearance: the map's hint
  m.utime = tdo_lcm::wall_utime();
  m.request_id = id;
  m.seq = id;  // one request per id, in order
  m.vehicle_id = vehicle;
  m.map_id = -1;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::string maps_dir = "maps";
  std::string out_path;
  double clearance = 0.5;
  CLI::App app{"tdo-make-replay-log: record a scripted tdo-planner session (Map1, Map6) to a log"};
  app.add_option("--maps", maps_dir, "directory with map1.tdomap and map6.tdomap")
      ->capture_default_str();
  app.add_option("-o,--output", out_path, "LCM log to write (replaced)")->required();
  app.add_option("--clearance", clearance, "m, clearance hint sent with the maps")
      ->capture_default_str();
  int parse_rc = 0;
  if (!tdo_lcm::parse_options(app, argc, argv, &parse_rc)) return parse_rc;

  tdo::map_t map1{}, map6{};
  tdo_lcm::MapFileInfo info1, info6;
  std::string error;
  if (!tdo_lcm::map_msg_from_file(maps_dir + "/map1.tdomap", clearance, &map1, &info1, &error) ||
      !tdo_lcm::map_msg_from_file(maps_dir + "/map6.tdomap", clearance, &map6, &info6, &error)) {
    std::fprintf(stderr, "tdo-make-replay-log: error: %s\n", error.c_str());
    return 2;
  }
  if (!info1.has_query || !info6.has_query) {
    std::fprintf(stderr, "tdo-make-replay-log: error: map1/map6 without a start and goal\n");
    return 2;
  }
  map1.map_id = 1;
  map6.map_id = 6;

  tdo_lcm::Bus bus("memq://");
  tdo_lcm::PlannerConfig cfg;  // tdo-planner's defaults: tdo-replay's defaults replay this log
  cfg.heartbeat_period_s = 0.0;
  tdo_lcm::PlannerNode node(&bus, cfg);
  if (!bus.good() || !node.start(&error)) {
    std::fprintf(stderr, "tdo-make-replay-log: error: planner: %s\n", error.c_str());
    return 2;
  }
  lcm::LogFile log(out_path, "w");
  if (!log.good()) {
    std::fprintf(stderr, "tdo-make-replay-log: error: cannot write %s\n", out_path.c_str());
    return 2;
  }
  int64_t events = 0;
  for (const std::string& ch : {cfg.map_channel, cfg.request_channel, cfg.trajectory_channel,
                                cfg.feasibility_channel, cfg.status_channel}) {
    bus.subscribe(ch, [&](const void* data, std::size_t size, const std::string& channel) {
      lcm::LogEvent ev{};
      ev.timestamp = tdo_lcm::wall_utime();
      ev.channel = channel;
      ev.datalen = static_cast<int32_t>(size);
      ev.data = const_cast<void*>(data);
      if (log.writeEvent(&ev) == 0) ++events;
    });
  }
  auto pump = [&]() {
    for (int i = 0; i < 1000 && bus.handle_timeout(0) > 0; ++i) {
    }
  };
  auto send = [&](const std::string& ch, const auto& msg) {
    bus.publish(ch, msg);
    pump();
  };

  send(cfg.request_channel, make_request(1, cfg.vehicle_id, info1.start, info1.goal));  // no_map
  map1.utime = tdo_lcm::wall_utime();
  send(cfg.map_channel, map1);
  tdo::plan_request_t sampled = make_request(2, cfg.vehicle_id, info1.start, info1.goal);
  sampled.samples =
      tdo::plan_request_t::SAMPLES_ON;  // the sampled form too, compared sample by sample
  send(cfg.request_channel, sampled);
  send(cfg.request_channel, make_request(3, cfg.vehicle_id + 1, info1.start, info1.goal));
  tdo::plan_request_t bad = make_request(4, cfg.vehicle_id, info1.start, info1.goal);
  bad.goal[2] = std::numeric_limits<double>::quiet_NaN();
  send(cfg.request_channel, bad);
  {
    const tdo::plan_request_t r = make_request(5, cfg.vehicle_id, info1.start, info1.goal);
    std::vector<uint8_t> b(static_cast<std::size_t>(r.getEncodedSize()));
    r.encode(b.data(), 0, static_cast<int>(b.size()));
    bus.publish_raw(cfg.request_channel, b.data(), b.size() - 9);  // truncated
    pump();
  }
  map6.utime = tdo_lcm::wall_utime();
  send(cfg.map_channel, map6);
  send(cfg.request_channel, make_request(6, cfg.vehicle_id, info6.start, info6.goal));
  tdo::plan_request_t astar = make_request(7, cfg.vehicle_id, info6.start, info6.goal);
  astar.search = tdo::plan_request_t::SEARCH_ASTAR;
  astar.depth = tdo::plan_request_t::DEPTH_SMOOTH;
  send(cfg.request_channel, astar);
  // Only start and goal, every parameter left to the library's defaults (zeros elsewhere).
  tdo::plan_request_t bare{};
  bare.utime = tdo_lcm::wall_utime();
  bare.request_id = 8;
  bare.seq = 8;
  bare.vehicle_id = cfg.vehicle_id;
  bare.map_id = -1;
  for (int a = 0; a < 3; ++a) {
    bare.start[a] = (&info6.start.x)[a];
    bare.goal[a] = (&info6.goal.x)[a];
  }
  bare.use_defaults = tdo::plan_request_t::USE_DEFAULT_ALL;
  send(cfg.request_channel, bare);
  tdo::plan_request_t slow = make_request(9, cfg.vehicle_id, info6.start, info6.goal);
  slow.v_max = 0.0;  // refused, naming v_max
  send(cfg.request_channel, slow);
  node.publish_status();
  pump();

  const tdo_lcm::PlannerCounters& c = node.counters();
  std::fprintf(stderr,
               "tdo-make-replay-log: %s: %lld events; planner: %lld received, %lld answered (%lld "
               "ok, %lld failed), %lld rejected, %lld ignored\n",
               out_path.c_str(), static_cast<long long>(events), static_cast<long long>(c.received),
               static_cast<long long>(c.answered), static_cast<long long>(c.succeeded),
               static_cast<long long>(c.failed), static_cast<long long>(c.rejected),
               static_cast<long long>(c.ignored));
  return c.succeeded == 4 ? 0 : 1;
}
