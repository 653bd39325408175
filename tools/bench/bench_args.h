// Command-line pieces of the hand-rolled parsers of tdo-bench-search and tdo-bench-scale: whole
// counts and the value of an option.
#ifndef TDO_TOOLS_BENCH_BENCH_ARGS_H
#define TDO_TOOLS_BENCH_BENCH_ARGS_H

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace tdo_bench {

/** A decimal count in [min, max] into *out; false (out untouched) for a sign, junk or range. */
inline bool parse_count(const char* s, uint64_t min, uint64_t max, uint64_t* out) {
  if (s == nullptr || *s == '\0' || *s == '-' || *s == '+') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s, &end, 10);
  if (errno != 0 || *end != '\0' || v < min || v > max) return false;
  *out = v;
  return true;
}

/**
 * The value after option argv[*i] (which takes one when `takes_value`), *i advanced onto it.
 * nullptr with *rc = 3 after the usage on stdout for -h / --help, or *rc = 2 after
 * "PROG: unknown argument 'A'" and the usage, or "PROG: A needs a value", on stderr.
 */
inline const char* option_value(const char* prog, int argc, char** argv, int* i, bool takes_value,
                                void (*usage)(FILE*), int* rc) {
  const std::string a = argv[*i];
  *rc = 3;
  if (a == "-h" || a == "--help") {
    usage(stdout);
    return nullptr;
  }
  *rc = 2;
  if (!takes_value) {
    std::fprintf(stderr, "%s: unknown argument '%s'\n", prog, a.c_str());
    usage(stderr);
    return nullptr;
  }
  if (*i + 1 >= argc) {
    std::fprintf(stderr, "%s: %s needs a value\n", prog, a.c_str());
    return nullptr;
  }
  return argv[++*i];
}

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_BENCH_ARGS_H
