#pragma once
// Internal to the core: the range check every config's validate() uses, so each bad value is
// reported the same way ("parameter 'key' = value: must be in [lo, hi]").

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace detail {

template <typename T>
void requireRange(const char* key, T value, T lo, T hi, bool lo_open = false) {
  const bool ok = std::isfinite(static_cast<double>(value)) &&
                  (lo_open ? value > lo : value >= lo) && value <= hi;
  if (!ok) {
    std::ostringstream s;
    s << "parameter '" << key << "' = " << value << ": must be in " << (lo_open ? "(" : "[")
      << lo << ", " << hi << "]";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace detail
}  // namespace thermal_lidar_calibration
