#pragma once
// The person detectors' parameters (issue #7): flat keys like every other parameter, read by the
// detection nodelets (~key), calibrate_bag --detect --config and detect_people --config. The
// member initialisers of the detection config structs are the defaults; their rows:
// src/app/detection_parameter_table.cpp.

#include "thermal_lidar_calibration/app/parameter_table.hpp"
#include "thermal_lidar_calibration/detection/image_flip.hpp"
#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"
#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

// The LiDAR detector looks all around; for calibration it counts only the people within 45 deg
// of the LiDAR's +x axis (forward, REP 103), where a forward-looking thermal camera sees them (a
// FLIR A65 sees +-22.5 deg): a person the LiDAR counts but the camera cannot see would make a
// frame's counts agree by chance and give a wrong pair (measured on synthetic raw drives: with
// the whole circle, 1 of 5 drives failed outright; with +-30..60 deg all calibrated). A camera
// facing elsewhere sets lidar_min_azimuth_deg / lidar_max_azimuth_deg to its view.
inline detection::LidarDetectorConfig calibrationLidarDefaults() {
  detection::LidarDetectorConfig c;
  c.person.min_azimuth_deg = -45.0;
  c.person.max_azimuth_deg = 45.0;
  return c;
}

struct DetectionParameters {
  detection::ThermalSegmenterConfig thermal;
  detection::LidarDetectorConfig lidar = calibrationLidarDefaults();
  // Applied to the raw thermal image before segmentation and calibration (a camera that stores
  // its images upside down or mirrored; a mirrored image has no rigid extrinsic).
  detection::ImageFlip input_flip = detection::ImageFlip::kNone;
};

const ParameterTable<DetectionParameters>& detectionParameterTable();

// The defaults overridden by what `source` has, then the detectors' rules across keys. Throws
// std::invalid_argument naming the key, the value and the allowed range.
DetectionParameters loadDetectionParameters(const ParameterSource& source);
// Every detection key with its effective value, in table order.
std::vector<std::pair<std::string, std::string>> describeDetectionParameters(const DetectionParameters& p);

}  // namespace thermal_lidar_calibration
