#pragma once
// Finding parameter keys this package does not know (likely typos) in a --config file or under
// a node's private namespace. A warning, never an error: the tables ignore unknown keys.

#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// The keys of `keys` that are not in `known`, in the given order.
std::vector<std::string> unknownParameterKeys(const std::vector<std::string>& keys,
                                              const std::vector<std::string>& known);

}  // namespace thermal_lidar_calibration
