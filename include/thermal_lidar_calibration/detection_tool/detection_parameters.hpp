#pragma once
// The detectors' settings as one struct (the flat keys of config/default.yaml).

#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"
#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

namespace thermal_lidar_calibration {

struct DetectionParameters {
  detection::ThermalSegmenterConfig thermal;
  detection::LidarDetectorConfig lidar;
};

}  // namespace thermal_lidar_calibration
