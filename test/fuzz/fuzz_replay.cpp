// libFuzzer target of tdo-replay's reader: the input, up to 1 MB, as an LCM log file replayed
// through tdo-planner's node (small capacities). replay_log must return 0, 1 or 2 with a message
// for 2; never crash, hang or report a sanitizer error.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "replay.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1u << 20)) return 0;
  static const std::string path = "/tmp/tdo_fuzz_" + std::to_string(::getpid()) + ".lcmlog";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  const bool written = size == 0 || std::fwrite(data, 1, size, f) == size;
  std::fclose(f);
  if (!written) return 0;
  tdo_lcm::ReplayOptions opt;
  opt.planner.max_nx = 64;
  opt.planner.max_ny = 64;
  opt.planner.max_nz = 32;
  opt.planner.max_nodes = 50000;
  opt.planner.max_boxes = 600;
  tdo_lcm::ReplayReport report;
  std::string error;
  const int rc = tdo_lcm::replay_log(path, opt, &report, &error);
  if (rc < 0 || rc > 2 || (rc == 2 && error.empty())) __builtin_trap();
  return 0;
}
