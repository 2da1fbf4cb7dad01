#pragma once
// The person detectors' parameters (issue #7): flat keys like every other parameter, read by the
// detection nodelets (~key), calibrate_bag --detect --config and detect_people --config. The
// member initialisers of the detection config structs are the defaults; their rows:
// src/app/detection_parameter_table.cpp.

#include "thermal_lidar_calibration/app/parameter_table.hpp"
#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"
#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

struct DetectionParameters {
  detection::ThermalSegmenterConfig thermal;
  detection::LidarDetectorConfig lidar;
};

const ParameterTable<DetectionParameters>& detectionParameterTable();

// The defaults overridden by what `source` has, then the detectors' rules across keys. Throws
// std::invalid_argument naming the key, the value and the allowed range.
DetectionParameters loadDetectionParameters(const ParameterSource& source);
// Every detection key with its effective value, in table order.
std::vector<std::pair<std::string, std::string>> describeDetectionParameters(const DetectionParameters& p);

}  // namespace thermal_lidar_calibration
