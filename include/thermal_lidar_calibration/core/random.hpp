#pragma once
// The one source of randomness: an explicitly seeded 64-bit Mersenne Twister with portable
// conversions (std:: distributions differ between standard libraries).

#include <cstddef>
#include <cstdint>
#include <random>

namespace thermal_lidar_calibration {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Uniform integer in [0, n), unbiased.
  std::size_t index(std::size_t n) {
    const std::uint64_t bound = static_cast<std::uint64_t>(n);
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % bound;
    std::uint64_t x;
    do {
      x = engine_();
    } while (x >= limit);
    return static_cast<std::size_t>(x % bound);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace thermal_lidar_calibration
