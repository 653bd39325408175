// tdo-publish-map FILE: publish a map file (.tdomap, .3dmap, .bt/.ot) on TDO_MAP as a run-length
// map_t (map_file.h). Once, or every --period seconds until --count messages or SIGINT/SIGTERM.
// --update-box T X0 Y0 Z0 X1 Y1 Z1 (repeatable) publishes a box added T s after the map on
// TDO_MAP_UPDATE; --serve answers TDO_MAP_REQUEST with the whole current map (map_publisher.h).
// This is the map-publishing part of tdo-sim (docs/design.md s.11); tdo-sim can call
// map_msg_from_file too. Exit status 0 published, 2 bad input (options, map file, LCM).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "map_publisher.h"
#include "tdo_lcm/app_cli.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/types.h"

namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int /*sig*/) { g_stop = 1; }
int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}
struct TimedBox {
  double t;  // s after the map
  tdo_box box;
};

// The map, its box updates at their times, whole maps on request; 0 done, 2 a publish failed.
int run_updates(tdo_lcm::Bus* bus, const std::string& channel, int32_t vehicle_id,
                const tdo::map_t& m, const std::vector<double>& spec, bool serve, double period,
                double duration) {
  std::vector<TimedBox> boxes;
  for (std::size_t k = 0; k + 7 <= spec.size(); k += 7)
    boxes.push_back(TimedBox{spec[k], tdo_box{tdo_vec3{spec[k + 1], spec[k + 2], spec[k + 3]},
                                              tdo_vec3{spec[k + 4], spec[k + 5], spec[k + 6]}}});
  std::stable_sort(boxes.begin(), boxes.end(),
                   [](const TimedBox& a, const TimedBox& b) { return a.t < b.t; });
  tdo_lcm::MapPublisherConfig cfg;
  cfg.map_channel = channel;
  cfg.vehicle_id = vehicle_id;
  tdo_lcm::MapPublisher pub(bus, cfg, m);
  std::string error;
  if (!pub.start(&error) || !pub.publish_map()) {
    std::fprintf(stderr, "tdo-publish-map: error: %s\n",
                 error.empty() ? "publish failed" : error.c_str());
    return 2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto since = [&]() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::size_t next = 0;
  double next_map = period;
  // Bounded: ends at --duration, after the last update without --serve, or on a signal.
  while (g_stop == 0) {
    const double t = since();
    if (duration > 0.0 && t >= duration) break;
    if (duration <= 0.0 && !serve && next >= boxes.size()) break;
    for (; next < boxes.size() && boxes[next].t <= t; ++next) {
      if (!pub.publish_boxes({boxes[next].box})) return 2;
      std::fprintf(stderr, "tdo-publish-map: t=%.2f s: update %lld of map %lld: box added\n", t,
                   static_cast<long long>(pub.seq()), static_cast<long long>(pub.map_id()));
    }
    if (period > 0.0 && t >= next_map) {
      if (!pub.publish_map()) return 2;
      next_map += period;
    }
    bus->handle_timeout(10);
  }
  std::fprintf(
      stderr, "tdo-publish-map: %zu update(s), %lld map request(s) answered, last map_id %lld\n",
      next, static_cast<long long>(pub.requests_answered()), static_cast<long long>(pub.map_id()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  std::string url = tdo_lcm::kDefaultUrl;
  std::string channel = tdo_lcm::kChannelMap;
  int64_t map_id = 0;
  int32_t vehicle_id = -1;
  double clearance = 0.5;
  double period = 0.0;
  int count = 1;
  bool octomap = false;
  double resolution = 0.0;
  CLI::App app{"tdo-publish-map: publish a map file on TDO_MAP (run-length map_t)"};
  app.add_option("map", path, "map file: .tdomap, .3dmap, .bt, .ot")->required();
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  app.add_option("--channel", channel, "channel")->capture_default_str();
  app.add_option("--map-id", map_id, "map_id of the message (>= 0)")->capture_default_str();
  app.add_option("--vehicle-id", vehicle_id, "vehicle the map is for (-1 = every vehicle)")
      ->capture_default_str();
  app.add_option("--clearance", clearance, "m, clearance hint (>= 0)")->capture_default_str();
  app.add_option("--period", period, "s between messages (0 = once)")->capture_default_str();
  app.add_option("--count", count, "messages to send with --period (0 = until a signal)")
      ->capture_default_str();
  app.add_flag("--octomap", octomap,
               "send a .bt file's bytes as they are (ENCODING_OCTOMAP_BT) instead of run lengths");
  app.add_option("--resolution", resolution, "m, grid voxel edge for OcTrees (0 = the tree's)")
      ->capture_default_str();
  std::vector<double> update_box;
  bool serve = false;
  double duration = 0.0;
  app.add_option("--update-box", update_box,
                 "T XMIN YMIN ZMIN XMAX YMAX ZMAX: at T s after the map, publish an update adding "
                 "this box (m) on TDO_MAP_UPDATE (repeatable)")
      ->expected(7)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_flag("--serve", serve,
               "answer map requests (TDO_MAP_REQUEST) with the whole current map under a new id");
  app.add_option("--duration", duration,
                 "s to run with --update-box or --serve (0 = until the last update, or a signal "
                 "with --serve)")
      ->capture_default_str();
  int parse_rc = 0;
  if (!tdo_lcm::parse_options(app, argc, argv, &parse_rc)) return parse_rc;
  if (!octomap && resolution > 0.0) {
    std::fprintf(stderr, "tdo-publish-map: error: --resolution applies with --octomap\n");
    return 2;
  }
  if (map_id < 0 || !(clearance >= 0.0) || !(period >= 0.0) || count < 0) {
    std::fprintf(stderr,
                 "tdo-publish-map: error: --map-id, --clearance, --period and --count "
                 "must be >= 0\n");
    return 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  tdo::map_t m{};
  std::string error;
  const bool ok = octomap ? tdo_lcm::octomap_msg_from_file(path, resolution, clearance, &m, &error)
                          : tdo_lcm::map_msg_from_file(path, clearance, &m, nullptr, &error);
  if (!ok) {
    std::fprintf(stderr, "tdo-publish-map: error: %s\n", error.c_str());
    return 2;
  }
  m.map_id = map_id;
  m.vehicle_id = vehicle_id;
  tdo_lcm::Bus bus(url);
  if (!bus.good()) {
    std::fprintf(stderr, "tdo-publish-map: error: cannot start LCM on '%s'\n", url.c_str());
    return 2;
  }
  if (!update_box.empty() || serve) {
    if (update_box.size() % 7 != 0 || !(duration >= 0.0)) {
      std::fprintf(stderr, "tdo-publish-map: error: --update-box takes 7 numbers each\n");
      return 2;
    }
    return run_updates(&bus, channel, vehicle_id, m, update_box, serve, period, duration);
  }
  int sent = 0;
  while (g_stop == 0) {
    m.utime = now_us();
    if (!bus.publish(channel, m)) {
      std::fprintf(stderr, "tdo-publish-map: error: publish failed on %s\n", channel.c_str());
      return 2;
    }
    ++sent;
    if (period <= 0.0 || (count > 0 && sent >= count)) break;
    const auto until = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(period));
    while (g_stop == 0 && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::fprintf(stderr,
               "tdo-publish-map: %s -> %s: %d message(s), %d x %d x %d voxels at %g m, %d runs, "
               "%d boxes, %d OctoMap bytes, %d bytes each\n",
               path.c_str(), channel.c_str(), sent, m.size[0], m.size[1], m.size[2], m.resolution,
               m.n_runs, m.n_boxes, m.n_bytes, m.getEncodedSize());
  return 0;
}
