#include "thermal_lidar_calibration/app/parameters/unknown_parameters.hpp"

#include <algorithm>

namespace thermal_lidar_calibration {

std::vector<std::string> unknownParameterKeys(const std::vector<std::string>& keys,
                                              const std::vector<std::string>& known) {
  std::vector<std::string> unknown;
  for (const auto& k : keys) {
    if (std::find(known.begin(), known.end(), k) == known.end()) unknown.push_back(k);
  }
  return unknown;
}

}  // namespace thermal_lidar_calibration
