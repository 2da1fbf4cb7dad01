#pragma once
// Opening and parsing a user's YAML file (parameters, camera_info, result or truth), with one
// wording for what went wrong: "<kind> <path>: cannot be opened ...", "... is not valid YAML
// (<reason> at line N)".

#include <yaml-cpp/yaml.h>

#include <string>

namespace thermal_lidar_calibration {

// Throws std::invalid_argument. An empty file gives a Null node (callers decide what it means).
YAML::Node loadYamlFile(const std::string& path, const std::string& kind);

}  // namespace thermal_lidar_calibration
