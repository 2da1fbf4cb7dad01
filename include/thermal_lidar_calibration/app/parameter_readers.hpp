#pragma once
// Typed, range-checked reads from a ParameterSource, shared by the core-parameter table and the
// node-only parameters, so every bad value is reported the same way:
//   parameter 'population_size' = -3: must be an integer in [2, 100000]

#include "thermal_lidar_calibration/app/parameters.hpp"

#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

std::string formatParameterNumber(double v);
// The value as the user wrote it, for error messages.
std::string parameterValueText(const ParameterSource& source, const std::string& key);
[[noreturn]] void throwBadParameter(const ParameterSource& source, const std::string& key,
                                    const std::string& requirement);

// Each read leaves `target` (the default) untouched when the key is absent.
template <typename Int>
void readIntParameter(const ParameterSource& source, const std::string& key, long long lo,
                      long long hi, Int& target) {
  if (!source.has(key)) return;
  const auto v = source.getInt(key);
  if (!v || *v < lo || *v > hi) {
    throwBadParameter(source, key,
                      "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  target = static_cast<Int>(*v);
}
// Range [lo, hi], or (lo, hi] when lo_open.
void readDoubleParameter(const ParameterSource& source, const std::string& key, double lo,
                         bool lo_open, double hi, double& target);
void readStringParameter(const ParameterSource& source, const std::string& key,
                         std::string& target);
void readBoolParameter(const ParameterSource& source, const std::string& key, bool& target);

}  // namespace thermal_lidar_calibration
