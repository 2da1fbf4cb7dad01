#pragma once
// Finding parameter keys this package does not know (likely typos) in a --config file.
// A warning, never an error: unknown keys are ignored by loadCoreParameters().

#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// Top-level keys of a YAML parameter file. Throws std::invalid_argument on a bad file.
std::vector<std::string> yamlFileKeys(const std::string& path);
// The keys of `keys` that are not in knownParameterKeys(), in the given order.
std::vector<std::string> unknownParameterKeys(const std::vector<std::string>& keys);

}  // namespace thermal_lidar_calibration
