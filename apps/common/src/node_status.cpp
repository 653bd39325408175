#include "tdo_lcm/node_status.h"

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

void send_status(Bus* bus, const std::string& channel, const tdo::status_t& s, int64_t* seq) {
  if (!check_counts(s).ok()) return;
  tdo::status_t out = s;
  out.queue_capacity = bus->queue_capacity();
  out.dropped = bus->dropped();
  bus->publish(channel, out);
  ++*seq;
}

}  // namespace tdo_lcm
