// tdo-bench-lcm: load benchmark of a running tdo-planner over LCM (docs/lcm.md). Publishes a map
// file on TDO_MAP, then plan requests (the map's default query, alternately forwards and
// backwards) for a bounded time, either closed-loop (--rate 0: the next request as soon as the
// previous one is answered, i.e. as fast as the planner takes them) or open-loop at a steady
// --rate per second. Latency: request published -> both its trajectory and its feasibility report
// received. Prints sent / answered / lost and latency percentiles; exit status 1 when a request
// was lost or answered with an error, 2 bad input. Not a test: run it by hand
// (scripts/bench_lcm.sh).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/wire.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Pending {
  Clock::time_point sent;
  bool traj = false;
  bool feas = false;
  bool ok = false;
  double plan_ms = 0.0;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string url = tdo_lcm::kDefaultUrl;
  std::string map_path;
  double rate = 0.0;
  double duration = 10.0;
  double clearance = 0.5;
  double drain = 5.0;
  int32_t vehicle_id = 0;
  double dt = 0.0;
  CLI::App app{"tdo-bench-lcm: load benchmark of a running tdo-planner"};
  app.add_option("map", map_path, "map file with a default query (start, goal), e.g. map5.tdomap")
      ->required();
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  app.add_option("--rate", rate, "requests per second (0 = closed loop, as fast as answered)")
      ->capture_default_str();
  app.add_option("--duration", duration, "s of sending")->capture_default_str();
  app.add_option("--clearance", clearance, "m, clearance hint of the map")->capture_default_str();
  app.add_option("--drain", drain, "s to wait for the last answers")->capture_default_str();
  app.add_option("--vehicle-id", vehicle_id, "vehicle of the requests")->capture_default_str();
  app.add_option("--dt", dt, "s, trajectory sample period of the requests (0 = the default)")
      ->capture_default_str();
  bool samples = false;
  app.add_flag("--samples", samples,
               "ask for the sampled form too (SAMPLES_ON, ~280 kB answers on Map5) instead of the "
               "compact form alone (~6 kB)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (!(rate >= 0.0) || !(duration > 0.0) || !(drain >= 0.0)) {
    std::fprintf(stderr, "tdo-bench-lcm: error: --rate >= 0, --duration > 0, --drain >= 0\n");
    return 2;
  }
  tdo::map_t map{};
  tdo_lcm::MapFileInfo info;
  std::string error;
  if (!tdo_lcm::map_msg_from_file(map_path, clearance, &map, &info, &error)) {
    std::fprintf(stderr, "tdo-bench-lcm: error: %s\n", error.c_str());
    return 2;
  }
  if (!info.has_query) {
    std::fprintf(stderr, "tdo-bench-lcm: error: %s has no start and goal\n", map_path.c_str());
    return 2;
  }
  map.map_id = 5;
  tdo_lcm::Bus bus(url);
  if (!bus.good()) {
    std::fprintf(stderr, "tdo-bench-lcm: error: cannot start LCM on '%s'\n", url.c_str());
    return 2;
  }

  std::map<int64_t, Pending> pending;
  std::vector<double> latency_ms, plan_ms;
  int64_t answered = 0, failed = 0, unexpected = 0;
  auto settle = [&](int64_t id) {
    auto it = pending.find(id);
    if (it == pending.end() || !it->second.traj || !it->second.feas) return;
    if (id > 0) {  // 0 is the warm-up probe
      latency_ms.push_back(
          std::chrono::duration<double, std::milli>(Clock::now() - it->second.sent).count());
      plan_ms.push_back(it->second.plan_ms);
      ++answered;
      if (!it->second.ok) ++failed;
    }
    pending.erase(it);
  };
  std::string last_status;
  bus.subscribe(tdo_lcm::kChannelTrajectory, [&](const void* d, std::size_t n, const std::string&) {
    tdo::trajectory_t m{};
    if (!tdo_lcm::decode(d, n, &m).ok() || m.vehicle_id != vehicle_id) return;
    auto it = pending.find(m.request_id);
    if (it == pending.end()) {
      ++unexpected;
      return;
    }
    it->second.traj = true;
    it->second.ok = m.status == "ok";
    it->second.plan_ms = m.plan_time_ms;
    last_status = m.status;
    settle(m.request_id);
  });
  bus.subscribe(tdo_lcm::kChannelFeasibility,
                [&](const void* d, std::size_t n, const std::string&) {
                  tdo::feasibility_t m{};
                  if (!tdo_lcm::decode(d, n, &m).ok() || m.vehicle_id != vehicle_id) return;
                  auto it = pending.find(m.request_id);
                  if (it == pending.end()) return;
                  it->second.feas = true;
                  settle(m.request_id);
                });

  tdo_plan_request base{};
  tdo_plan_params_default(&base.params);
  if (dt > 0.0) base.params.dt = dt;
  auto send = [&](int64_t id) {
    tdo_plan_request r = base;
    r.start = (id % 2 == 0) ? info.goal : info.start;
    r.goal = (id % 2 == 0) ? info.start : info.goal;
    tdo::plan_request_t m{};
    tdo_lcm::plan_request_to_msg(r, -1.0, &m);
    m.utime = now_us();
    m.request_id = id;
    m.seq = id;
    m.vehicle_id = vehicle_id;
    m.map_id = map.map_id;
    m.samples = samples ? tdo::plan_request_t::SAMPLES_ON : tdo::plan_request_t::SAMPLES_OFF;
    pending[id] = Pending{Clock::now()};
    bus.publish(tdo_lcm::kChannelPlanRequest, m);
  };

  // Map, then a probe request until the planner answers it with the map loaded (at most 20 s).
  const auto probe_end = Clock::now() + std::chrono::seconds(20);
  bool ready = false;
  while (!ready && Clock::now() < probe_end) {
    map.utime = now_us();
    bus.publish(tdo_lcm::kChannelMap, map);
    bus.handle_timeout(50);
    send(0);
    const auto until = Clock::now() + std::chrono::seconds(1);
    while (Clock::now() < until && pending.count(0) != 0) bus.handle_timeout(20);
    ready = pending.count(0) == 0 && last_status == "ok";
    pending.erase(0);
  }
  if (!ready) {
    std::fprintf(stderr, "tdo-bench-lcm: error: no ok answer from a planner on %s (last: '%s')\n",
                 url.c_str(), last_status.c_str());
    return 2;
  }

  int64_t sent = 0;
  const auto t0 = Clock::now();
  const auto t_end =
      t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(duration));
  auto next = t0;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(rate > 0.0 ? 1.0 / rate : 0.0));
  while (Clock::now() < t_end) {
    const auto now = Clock::now();
    if (rate > 0.0) {
      if (now >= next) {
        send(++sent);
        next += period;
      }
      const auto wait_ms =
          std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count();
      bus.handle_timeout(static_cast<int>(std::clamp<int64_t>(wait_ms, 0, 10)));
    } else {
      if (pending.empty()) send(++sent);
      bus.handle_timeout(10);
    }
  }
  const double sending_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto drain_end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(drain));
  while (!pending.empty() && Clock::now() < drain_end) bus.handle_timeout(10);
  const int64_t lost = static_cast<int64_t>(pending.size());

  char rate_buf[64];
  std::snprintf(rate_buf, sizeof rate_buf, "open loop %g req/s", rate);
  const std::string mode = rate > 0.0 ? rate_buf : "closed loop (as fast as answered)";
  std::printf(
      "tdo-bench-lcm: %s, %s, %.1f s on %s: sent %lld, answered %lld (%lld not ok), lost %lld, "
      "%.1f answers/s, dt %g s, %s\n",
      map_path.c_str(), mode.c_str(), sending_s, url.c_str(), static_cast<long long>(sent),
      static_cast<long long>(answered), static_cast<long long>(failed),
      static_cast<long long>(lost), static_cast<double>(answered) / sending_s, base.params.dt,
      samples ? "compact form + samples" : "compact form");
  std::printf(
      "  latency ms (request sent -> trajectory + report received): p50 %.2f  p90 %.2f  "
      "p99 %.2f  max %.2f\n",
      percentile(latency_ms, 0.5), percentile(latency_ms, 0.9), percentile(latency_ms, 0.99),
      percentile(latency_ms, 1.0));
  std::printf(
      "  library plan_time_ms (inside the planner):          p50 %.2f  p90 %.2f  "
      "p99 %.2f  max %.2f\n",
      percentile(plan_ms, 0.5), percentile(plan_ms, 0.9), percentile(plan_ms, 0.99),
      percentile(plan_ms, 1.0));
  if (unexpected > 0)
    std::printf("  %lld answers to requests not sent by this run\n",
                static_cast<long long>(unexpected));
  return (lost == 0 && failed == 0) ? 0 : 1;
}
