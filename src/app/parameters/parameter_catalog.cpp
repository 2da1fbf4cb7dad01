#include "thermal_lidar_calibration/app/parameters/parameter_catalog.hpp"

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/node_parameters.hpp"

namespace thermal_lidar_calibration {

std::vector<ParameterDoc> allParameterDocs() {
  std::vector<ParameterDoc> docs = coreParameterTable().docs();
  for (auto& doc : detectionParameterTable().docs()) docs.push_back(std::move(doc));
  for (auto& doc : nodeParameterTable().docs()) docs.push_back(std::move(doc));
  return docs;
}

const std::vector<std::string>& knownParameterKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const auto& doc : allParameterDocs()) k.push_back(doc.key);
    return k;
  }();
  return keys;
}

}  // namespace thermal_lidar_calibration
