#include "tdo_lcm/run_loop.h"

#include <algorithm>
#include <csignal>
#include <cstdio>

namespace tdo_lcm {
namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_stop_signal(int /*sig*/) { g_stop = 1; }

}  // namespace

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a signal ends the wait inside lcm_handle_timeout at once
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() { return g_stop != 0; }

bool report_bus_start(const char* name, const Bus& bus, const std::string& url) {
  if (bus.good()) return true;
  std::fprintf(stderr,
               "%s: error: cannot start LCM on '%s' (for udpm on loopback a multicast "
               "route is needed: ip route add 224.0.0.0/4 dev lo)\n",
               name, url.c_str());
  return false;
}

int run_loop(const char* name, Bus& bus, const RunOptions& opt,
             const std::function<SteadyTime()>& next_due,
             const std::function<void(SteadyTime)>& poll) {
  const auto t_end = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(opt.duration));
  // A file:// log ends with an error from lcm_handle: the end of the input, a clean stop.
  const bool from_log = opt.url.rfind("file://", 0) == 0;
  int errors = 0;
  while (g_stop == 0) {
    // Wait for messages until the node is next due (at most 100 ms).
    int wait_ms = 100;
    if (next_due) {
      const auto now0 = std::chrono::steady_clock::now();
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_due() - now0);
      wait_ms = static_cast<int>(std::clamp<long long>(wait.count(), 0, 100));
    }
    const int rc = bus.handle_timeout(wait_ms);
    if (rc < 0 && g_stop == 0 && from_log) {
      if (!opt.quiet) std::fprintf(stderr, "%s: end of the log\n", name);
      break;
    }
    if (rc < 0 && g_stop == 0 && ++errors > 100) {
      std::fprintf(stderr, "%s: error: LCM keeps failing, stopping\n", name);
      break;
    }
    const auto now = std::chrono::steady_clock::now();
    poll(now);
    if (opt.duration > 0.0 && now >= t_end) break;
  }
  return errors > 100 ? 1 : 0;
}

}  // namespace tdo_lcm
