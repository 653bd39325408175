#include "tdo_lcm/node_status.h"

#include <cmath>
#include <new>

#include "tdo_lcm/adapters.h"

namespace tdo_lcm {

int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::chrono::steady_clock::duration steady_seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}

void advance_deadline(std::chrono::steady_clock::time_point* next,
                      std::chrono::steady_clock::time_point now,
                      std::chrono::steady_clock::duration period) {
  *next += period;
  if (*next <= now) *next = now + period;  // fell behind: no burst
}

bool fail_start(std::string* error, const std::string& msg) {
  if (error != nullptr) *error = msg;
  return false;
}

const char* start_problem(const Bus* bus, bool already_started, double rate_hz) {
  if (bus == nullptr || !bus->good()) return "LCM is not initialised";
  if (already_started) return "already started";
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) return "the rate must be finite and > 0";
  return "";
}

std::size_t alloc_node_arena(std::unique_ptr<std::max_align_t[]>* arena, std::size_t bytes,
                             std::string* error) {
  const std::size_t words = (bytes + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t);
  arena->reset(new (std::nothrow) std::max_align_t[words]);
  if (*arena && words > 0) return words * sizeof(std::max_align_t);
  fail_start(error, "cannot allocate an arena of " + std::to_string(bytes) + " bytes");
  return 0;
}

void fill_status(tdo::status_t* s, const char* program, int64_t seq, int32_t vehicle_id,
                 std::chrono::steady_clock::time_point started,
                 const std::map<std::string, int64_t>& reasons) {
  s->utime = wall_utime();
  s->seq = seq;
  s->program = program;
  s->vehicle_id = vehicle_id;
  s->uptime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  for (const auto& kv : reasons) {
    s->reason.push_back(kv.first);
    s->reason_count.push_back(kv.second);
  }
  s->n_reasons = static_cast<int32_t>(s->reason.size());
}

tdo::status_t make_status(const char* program, int64_t seq, int32_t vehicle_id,
                          std::chrono::steady_clock::time_point started,
                          const std::map<std::string, int64_t>& reasons, const StatusCounts& c) {
  tdo::status_t s{};
  fill_status(&s, program, seq, vehicle_id, started, reasons);
  s.map_id = c.map_id;
  s.received = c.received;
  s.maps_loaded = c.maps_loaded;
  s.answered = c.answered;
  s.succeeded = c.succeeded;
  s.failed = c.failed;
  s.rejected = c.rejected;
  s.ignored = c.ignored;
  s.last_plan_ms = c.last_plan_ms;
  return s;
}

void send_status(Bus* bus, const std::string& channel, const tdo::status_t& s, int64_t* seq) {
  if (!check_counts(s).ok()) return;
  tdo::status_t out = s;
  out.queue_capacity = bus->queue_capacity();
  out.dropped = bus->dropped();
  bus->publish(channel, out);
  ++*seq;
}

}  // namespace tdo_lcm
