// tdo-request: send one plan request to a running tdo-planner; with --wait, print its answer as
// tdo-plan's summary table. Parameters not given with --param are left to libtdo's defaults
// (plan_request_t.use_defaults). Exit status: 0 sent (with --wait: answered ok), 1 answered with
// another status or no answer within --timeout, 2 bad options or LCM could not start.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "request_cli.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/node_status.h"
#include "tdo_lcm/types.h"
#include "tdo_lcm/wire.h"

namespace {

// One kind of answer to the request: the last message on its channel for the request and vehicle.
template <typename Msg>
struct Answer {
  Msg msg{};
  std::size_t bytes = 0;  // encoded size of msg
  bool have = false;

  void subscribe(tdo_lcm::Bus* bus, const std::string& channel, int64_t request_id,
                 int32_t vehicle_id) {
    bus->subscribe(
        channel, [this, request_id, vehicle_id](const void* d, std::size_t n, const std::string&) {
          Msg m{};
          if (!tdo_lcm::decode(d, n, &m).ok() || m.request_id != request_id ||
              m.vehicle_id != vehicle_id)
            return;
          msg = std::move(m);
          bytes = n;
          have = true;
        });
  }
};

}  // namespace

int main(int argc, char** argv) {
  tdo_lcm::RunOptions opt;
  opt.url = tdo_lcm::kDefaultUrl;
  std::vector<double> start, goal;
  std::vector<std::string> params;
  bool wait = false, samples = false;
  double timeout = 30.0;
  int32_t vehicle_id = 0;
  int64_t map_id = -1;
  int64_t request_id = -1;
  std::string request_channel = tdo_lcm::kChannelPlanRequest;
  std::string trajectory_channel = tdo_lcm::kChannelTrajectory;
  std::string feasibility_channel = tdo_lcm::kChannelFeasibility;

  CLI::App app{
      "tdo-request: send one TDO_PLAN_REQUEST to a running tdo-planner; with --wait, print the "
      "answer (TDO_TRAJECTORY + TDO_FEASIBILITY) as tdo-plan's summary. Parameters not given "
      "with --param are left to libtdo's defaults (use_defaults). Exit 0 sent / answered ok, 1 "
      "answered with another status or no answer in time, 2 bad options."};
  tdo_lcm::add_url_option(app, &opt);
  app.add_option("--start", start, "start X Y Z in m")->expected(3)->required();
  app.add_option("--goal", goal, "goal X Y Z in m")->expected(3)->required();
  app.add_option("--param", params,
                 "NAME=VALUE, repeatable: a plan_request_t parameter (" +
                     tdo_lcm::request_param_names() + "); enums by their constants' values")
      ->take_all();
  app.add_flag("--wait", wait, "wait for the answer and print it");
  app.add_option("--timeout", timeout, "s to wait for the answer with --wait")
      ->capture_default_str();
  app.add_flag("--samples", samples, "ask for the sampled form too (SAMPLES_ON)");
  app.add_option("--vehicle-id", vehicle_id, "vehicle to plan for")->capture_default_str();
  app.add_option("--map-id", map_id, "map to plan on (-1 = the planner's latest)")
      ->capture_default_str();
  app.add_option("--request-id", request_id, "request id (-1 = from the clock)")
      ->capture_default_str();
  app.add_option("--request-channel", request_channel, "requests out")->capture_default_str();
  app.add_option("--trajectory-channel", trajectory_channel, "answers in")->capture_default_str();
  app.add_option("--feasibility-channel", feasibility_channel, "reports in")->capture_default_str();
  if (int rc = 0; !tdo_lcm::parse_options(app, argc, argv, &rc)) return rc;
  if (!(timeout > 0.0) || !(timeout <= 3600.0)) {
    std::fprintf(stderr, "tdo-request: error: --timeout must be in (0, 3600] s\n");
    return 2;
  }

  tdo::plan_request_t req{};
  std::string error;
  if (!tdo_lcm::build_request(start.data(), goal.data(), params, &req, &error)) {
    std::fprintf(stderr, "tdo-request: error: %s\n", error.c_str());
    return 2;
  }
  req.utime = tdo_lcm::wall_utime();
  req.request_id = request_id >= 0 ? request_id : req.utime;
  req.seq = 1;  // one request per run
  req.vehicle_id = vehicle_id;
  req.map_id = map_id;
  req.samples = samples ? tdo::plan_request_t::SAMPLES_ON : tdo::plan_request_t::SAMPLES_OFF;

  Answer<tdo::trajectory_t> traj;  // before the bus: its handlers write here
  Answer<tdo::feasibility_t> feas;
  tdo_lcm::Bus bus(opt.url);
  if (!bus.good()) {
    std::fprintf(stderr, "tdo-request: error: cannot start LCM on '%s'\n", opt.url.c_str());
    return 2;
  }
  traj.subscribe(&bus, trajectory_channel, req.request_id, vehicle_id);
  feas.subscribe(&bus, feasibility_channel, req.request_id, vehicle_id);
  if (!bus.publish(request_channel, req)) {
    std::fprintf(stderr, "tdo-request: error: cannot publish on %s\n", request_channel.c_str());
    return 2;
  }
  if (!wait) {
    std::printf("tdo-request: sent request %lld on %s\n", static_cast<long long>(req.request_id),
                request_channel.c_str());
    return 0;
  }
  const auto end = std::chrono::steady_clock::now() + tdo_lcm::steady_seconds(timeout);
  while (!(traj.have && feas.have) && std::chrono::steady_clock::now() < end)
    if (bus.handle_timeout(50) < 0) break;  // bounded by the timeout; < 0: LCM error
  if (!(traj.have && feas.have)) {
    std::fprintf(stderr, "tdo-request: no answer to request %lld within %g s (%s)\n",
                 static_cast<long long>(req.request_id), timeout,
                 traj.have ? "trajectory only" : (feas.have ? "report only" : "nothing"));
    return 1;
  }
  std::fputs(tdo_lcm::answer_summary(req, traj.msg, feas.msg, traj.bytes).c_str(), stdout);
  return traj.msg.status == "ok" ? 0 : 1;
}
