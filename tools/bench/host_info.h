// What the bench tools print about the machine a run was on (load average, CPU model).
#ifndef TDO_TOOLS_BENCH_HOST_INFO_H
#define TDO_TOOLS_BENCH_HOST_INFO_H

#include <fstream>
#include <string>

namespace tdo_bench {

/** The 1, 5 and 15 minute load averages of /proc/loadavg ("unknown" when unreadable). */
inline std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  if (!(f >> a >> b >> c)) return "unknown";
  return a + " " + b + " " + c;
}

/** The first "model name" of /proc/cpuinfo ("unknown" when absent). */
inline std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("model name", 0) == 0) {
      const size_t c = line.find(':');
      if (c != std::string::npos) return line.substr(c + 2);
    }
  }
  return "unknown";
}

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_HOST_INFO_H
