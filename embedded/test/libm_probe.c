/*
 * libm probe: does the target's libm (newlib) round like the host's (glibc)? Evaluates the
 * transcendental functions libtdo calls, plus two correctly rounded IEEE operations as controls,
 * on 200000 pseudo-random arguments each and prints an fnv1a64 checksum of the result bits per
 * function. `bash scripts/embedded.sh libm` runs it on both platforms and compares the lines.
 * Built for the firmware (target/firmware.c) and the host (host/host_main.c) like the demo.
 */
#include <math.h>
#include <string.h>

#include "tdo_demo.h"

enum { kArgs = 200000 };

static uint64_t next_state(uint64_t s) {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return s;
}

/* uniform in [lo, hi), exactly the same doubles on every IEEE platform */
static double uniform(uint64_t* s, double lo, double hi) {
  *s = next_state(*s);
  return lo + (hi - lo) * ((double)(*s >> 11) * (1.0 / 9007199254740992.0));
}

static double eval(int f, double x, double y) {
  switch (f) {
    case 0:
      return sin(x);
    case 1:
      return cos(x);
    case 2:
      return acos(x / 4.0);
    case 3:
      return atan2(y, x);
    case 4:
      return tan(x * 0.39);
    case 5:
      return cbrt(x * 100.0);
    case 6:
      return sqrt(fabs(x));
    default:
      return x / (y + 5.0);
  }
}

int tdo_demo_run(tdo_demo_info* info) {
  static const char* const names[8] = {"sin", "cos",  "acos",           "atan2",
                                       "tan", "cbrt", "sqrt (control)", "divide (control)"};
  static const char hex[] = "0123456789abcdef";
  memset(info, 0, sizeof(*info));
  for (int f = 0; f < 8; ++f) {
    uint64_t state = 88172645463325252ull;
    uint64_t h = 0xcbf29ce484222325ull;
    for (int i = 0; i < kArgs; ++i) {
      const double x = uniform(&state, -4.0, 4.0);
      const double y = uniform(&state, -4.0, 4.0);
      const double r = eval(f, x, y);
      uint64_t bits;
      memcpy(&bits, &r, sizeof(bits));
      h ^= bits;
      h *= 0x100000001b3ull;
    }
    char line[64];
    size_t n = strlen(names[f]);
    memcpy(line, names[f], n);
    line[n++] = ' ';
    for (int shift = 60; shift >= 0; shift -= 4) line[n++] = hex[(h >> shift) & 0xFu];
    line[n++] = '\n';
    line[n] = '\0';
    tdo_demo_write(line);
  }
  tdo_demo_write("end\n");
  return 0;
}

void tdo_demo_print_platform(const char* key, uint32_t value) {
  (void)key;
  (void)value;
}
