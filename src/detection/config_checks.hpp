#pragma once
// Range checks shared by the detector configurations: the message names the parameter key, the
// value and the allowed range, e.g. "parameter 'thermal_min_area_px' = -3: must be in [1, 10000000]".

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace detection {
namespace checks {

enum class Bound { kClosed, kOpen };

template <typename T>
void requireRange(const char* key, T value, T lo, T hi, Bound lo_bound = Bound::kClosed,
                  Bound hi_bound = Bound::kClosed) {
  const double v = static_cast<double>(value);
  const bool lo_ok = lo_bound == Bound::kOpen ? value > lo : value >= lo;
  const bool hi_ok = hi_bound == Bound::kOpen ? value < hi : value <= hi;
  if (!std::isfinite(v) || !lo_ok || !hi_ok) {
    std::ostringstream s;
    s << "parameter '" << key << "' = " << value << ": must be in "
      << (lo_bound == Bound::kOpen ? "(" : "[") << lo << ", " << hi
      << (hi_bound == Bound::kOpen ? ")" : "]");
    throw std::invalid_argument(s.str());
  }
}

// Cross-key rule: lo < hi (strict) or lo <= hi.
inline void requireOrdered(const char* lo_key, double lo, const char* hi_key, double hi, bool strict) {
  if (strict ? lo < hi : lo <= hi) return;
  std::ostringstream s;
  s << "parameters '" << lo_key << "' = " << lo << " and '" << hi_key << "' = " << hi << ": " << lo_key
    << (strict ? " must be below " : " must not exceed ") << hi_key;
  throw std::invalid_argument(s.str());
}

}  // namespace checks
}  // namespace detection
}  // namespace thermal_lidar_calibration
