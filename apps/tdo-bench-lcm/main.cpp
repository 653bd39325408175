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
#include "tdo_lcm/app_cli.h"
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

struct Options {
  std::string url = tdo_lcm::kDefaultUrl;
  std::string map_path;
  double rate = 0.0;       // requests per second, 0 = closed loop
  double duration = 10.0;  // s of sending
  double clearance = 0.5;  // m
  double drain = 5.0;      // s
  int32_t vehicle_id = 0;
  double dt = 0.0;  // s, 0 = the default
  bool samples = false;
};

/** Parses the command line into `o`; returns -1 to go on, else the exit status (help 0, bad 2). */
int parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"tdo-bench-lcm: load benchmark of a running tdo-planner"};
  app.add_option("map", o->map_path,
                 "map file with a default query (start, goal), e.g. map5.tdomap")
      ->required();
  app.add_option("--lcm-url", o->url, "LCM URL")->capture_default_str();
  app.add_option("--rate", o->rate, "requests per second (0 = closed loop, as fast as answered)")
      ->capture_default_str();
  app.add_option("--duration", o->duration, "s of sending")->capture_default_str();
  app.add_option("--clearance", o->clearance, "m, clearance hint of the map")
      ->capture_default_str();
  app.add_option("--drain", o->drain, "s to wait for the last answers")->capture_default_str();
  app.add_option("--vehicle-id", o->vehicle_id, "vehicle of the requests")->capture_default_str();
  app.add_option("--dt", o->dt, "s, trajectory sample period of the requests (0 = the default)")
      ->capture_default_str();
  app.add_flag("--samples", o->samples,
               "ask for the sampled form too (SAMPLES_ON, ~280 kB answers on Map5) instead of the "
               "compact form alone (~6 kB)");
  int parse_rc = 0;
  if (!tdo_lcm::parse_options(app, argc, argv, &parse_rc)) return parse_rc;
  if (!(o->rate >= 0.0) || !(o->duration > 0.0) || !(o->drain >= 0.0)) {
    std::fprintf(stderr, "tdo-bench-lcm: error: --rate >= 0, --duration > 0, --drain >= 0\n");
    return 2;
  }
  return -1;
}

/** One benchmark run: the requests in flight, the answers and their latencies. */
class Bench {
 public:
  Bench(const Options& o, tdo_lcm::Bus* bus, const tdo::map_t& map,
        const tdo_lcm::MapFileInfo& info)
      : o_(o), bus_(bus), map_(map), info_(info) {
    tdo_plan_params_default(&base_.params);
    if (o.dt > 0.0) base_.params.dt = o.dt;
  }

  /** Listens to the trajectories and feasibility reports of this run's vehicle. */
  void subscribe() {
    bus_->subscribe(tdo_lcm::kChannelTrajectory,
                    [this](const void* d, std::size_t n, const std::string&) { on_traj(d, n); });
    bus_->subscribe(tdo_lcm::kChannelFeasibility,
                    [this](const void* d, std::size_t n, const std::string&) { on_feas(d, n); });
  }

  /** Map, then a probe request until the planner answers it with the map loaded (at most 20 s). */
  bool probe() {
    const auto probe_end = Clock::now() + std::chrono::seconds(20);
    bool ready = false;
    while (!ready && Clock::now() < probe_end) {
      map_.utime = now_us();
      bus_->publish(tdo_lcm::kChannelMap, map_);
      bus_->handle_timeout(50);
      send(0);
      const auto until = Clock::now() + std::chrono::seconds(1);
      while (Clock::now() < until && pending_.count(0) != 0) bus_->handle_timeout(20);
      ready = pending_.count(0) == 0 && last_status_ == "ok";
      pending_.erase(0);
    }
    if (!ready) {
      std::fprintf(stderr, "tdo-bench-lcm: error: no ok answer from a planner on %s (last: '%s')\n",
                   o_.url.c_str(), last_status_.c_str());
    }
    return ready;
  }

  /** Sends for --duration (open or closed loop), then waits up to --drain for the answers. */
  void load() {
    const auto t0 = Clock::now();
    const auto t_end = t0 + std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(o_.duration));
    auto next = t0;
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(o_.rate > 0.0 ? 1.0 / o_.rate : 0.0));
    while (Clock::now() < t_end) {
      const auto now = Clock::now();
      if (o_.rate > 0.0) {
        if (now >= next) {
          send(++sent_);
          next += period;
        }
        const auto wait_ms =
            std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count();
        bus_->handle_timeout(static_cast<int>(std::clamp<int64_t>(wait_ms, 0, 10)));
      } else {
        if (pending_.empty()) send(++sent_);
        bus_->handle_timeout(10);
      }
    }
    sending_s_ = std::chrono::duration<double>(Clock::now() - t0).count();
    const auto drain_end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(o_.drain));
    while (!pending_.empty() && Clock::now() < drain_end) bus_->handle_timeout(10);
  }

  /** Prints the summary; the exit status: 0 all answered ok, 1 a request lost or not ok. */
  int report() const {
    const int64_t lost = static_cast<int64_t>(pending_.size());
    char rate_buf[64];
    std::snprintf(rate_buf, sizeof rate_buf, "open loop %g req/s", o_.rate);
    const std::string mode = o_.rate > 0.0 ? rate_buf : "closed loop (as fast as answered)";
    std::printf(
        "tdo-bench-lcm: %s, %s, %.1f s on %s: sent %lld, answered %lld (%lld not ok), lost %lld, "
        "%.1f answers/s, dt %g s, %s\n",
        o_.map_path.c_str(), mode.c_str(), sending_s_, o_.url.c_str(),
        static_cast<long long>(sent_), static_cast<long long>(answered_),
        static_cast<long long>(failed_), static_cast<long long>(lost),
        static_cast<double>(answered_) / sending_s_, base_.params.dt,
        o_.samples ? "compact form + samples" : "compact form");
    std::printf(
        "  latency ms (request sent -> trajectory + report received): p50 %.2f  p90 %.2f  "
        "p99 %.2f  max %.2f\n",
        percentile(latency_ms_, 0.5), percentile(latency_ms_, 0.9), percentile(latency_ms_, 0.99),
        percentile(latency_ms_, 1.0));
    std::printf(
        "  library plan_time_ms (inside the planner):          p50 %.2f  p90 %.2f  "
        "p99 %.2f  max %.2f\n",
        percentile(plan_ms_, 0.5), percentile(plan_ms_, 0.9), percentile(plan_ms_, 0.99),
        percentile(plan_ms_, 1.0));
    if (unexpected_ > 0)
      std::printf("  %lld answers to requests not sent by this run\n",
                  static_cast<long long>(unexpected_));
    return (lost == 0 && failed_ == 0) ? 0 : 1;
  }

 private:
  // Request `id`: even ids fly the map's query backwards, odd ones forwards.
  void send(int64_t id) {
    tdo_plan_request r = base_;
    r.start = (id % 2 == 0) ? info_.goal : info_.start;
    r.goal = (id % 2 == 0) ? info_.start : info_.goal;
    tdo::plan_request_t m{};
    tdo_lcm::plan_request_to_msg(r, -1.0, &m);
    m.utime = now_us();
    m.request_id = id;
    m.seq = id;
    m.vehicle_id = o_.vehicle_id;
    m.map_id = map_.map_id;
    m.samples = o_.samples ? tdo::plan_request_t::SAMPLES_ON : tdo::plan_request_t::SAMPLES_OFF;
    pending_[id] = Pending{Clock::now()};
    bus_->publish(tdo_lcm::kChannelPlanRequest, m);
  }

  void on_traj(const void* d, std::size_t n) {
    tdo::trajectory_t m{};
    if (!tdo_lcm::decode(d, n, &m).ok() || m.vehicle_id != o_.vehicle_id) return;
    auto it = pending_.find(m.request_id);
    if (it == pending_.end()) {
      ++unexpected_;
      return;
    }
    it->second.traj = true;
    it->second.ok = m.status == "ok";
    it->second.plan_ms = m.plan_time_ms;
    last_status_ = m.status;
    settle(m.request_id);
  }

  void on_feas(const void* d, std::size_t n) {
    tdo::feasibility_t m{};
    if (!tdo_lcm::decode(d, n, &m).ok() || m.vehicle_id != o_.vehicle_id) return;
    auto it = pending_.find(m.request_id);
    if (it == pending_.end()) return;
    it->second.feas = true;
    settle(m.request_id);
  }

  // A request with both answers in: its latency counts (not the warm-up probe, id 0).
  void settle(int64_t id) {
    auto it = pending_.find(id);
    if (it == pending_.end() || !it->second.traj || !it->second.feas) return;
    if (id > 0) {
      latency_ms_.push_back(
          std::chrono::duration<double, std::milli>(Clock::now() - it->second.sent).count());
      plan_ms_.push_back(it->second.plan_ms);
      ++answered_;
      if (!it->second.ok) ++failed_;
    }
    pending_.erase(it);
  }

  const Options& o_;
  tdo_lcm::Bus* bus_;
  tdo::map_t map_;
  tdo_lcm::MapFileInfo info_;
  tdo_plan_request base_{};
  std::map<int64_t, Pending> pending_;
  std::vector<double> latency_ms_, plan_ms_;
  int64_t sent_ = 0, answered_ = 0, failed_ = 0, unexpected_ = 0;
  std::string last_status_;
  double sending_s_ = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const int rc = parse_options(argc, argv, &o);
  if (rc >= 0) return rc;
  tdo::map_t map{};
  tdo_lcm::MapFileInfo info;
  std::string error;
  if (!tdo_lcm::map_msg_from_file(o.map_path, o.clearance, &map, &info, &error)) {
    std::fprintf(stderr, "tdo-bench-lcm: error: %s\n", error.c_str());
    return 2;
  }
  if (!info.has_query) {
    std::fprintf(stderr, "tdo-bench-lcm: error: %s has no start and goal\n", o.map_path.c_str());
    return 2;
  }
  map.map_id = 5;
  tdo_lcm::Bus bus(o.url);
  if (!bus.good()) {
    std::fprintf(stderr, "tdo-bench-lcm: error: cannot start LCM on '%s'\n", o.url.c_str());
    return 2;
  }
  Bench bench(o, &bus, map, info);
  bench.subscribe();
  if (!bench.probe()) return 2;
  bench.load();
  return bench.report();
}
