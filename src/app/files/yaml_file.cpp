#include "thermal_lidar_calibration/app/files/yaml_file.hpp"

#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {

YAML::Node loadYamlFile(const std::string& path, const std::string& kind) {
  if (!std::ifstream(path)) {
    throw std::invalid_argument(kind + " " + path +
                                ": cannot be opened (missing or unreadable); check the path");
  }
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(kind + " " + path + ": is not valid YAML (" + e.msg +
                                " at line " + std::to_string(e.mark.line + 1) + ")");
  }
}

}  // namespace thermal_lidar_calibration
