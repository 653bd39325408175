// Deterministic, allocation-free random numbers for the libtdo tests (splitmix64), identical on
// every platform so a failing seed reproduces anywhere.
#ifndef TDO_TEST_LIBTDO_RNG_H
#define TDO_TEST_LIBTDO_RNG_H

#include <stdint.h>

namespace tdo_test {

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /** Uniform in [0, 1). */
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /** Uniform in [a, b). */
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /** Uniform integer in [0, n), n > 0. */
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }
  /** Uniform integer in [lo, hi]. */
  int32_t range(int32_t lo, int32_t hi) {
    return lo + static_cast<int32_t>(below(static_cast<uint32_t>(hi - lo + 1)));
  }

 private:
  uint64_t state_;
};

}  // namespace tdo_test

#endif  // TDO_TEST_LIBTDO_RNG_H
