#pragma once
// The person detectors' parameters (issue #7): flat keys like every other parameter, read by the
// detection nodelets (~key), calibrate_bag --detect --config and detect_people --config. The
// member initialisers of the detection config structs are the defaults; their rows:
// src/app/parameters/detection_parameter_table.cpp.

#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/detection/image_flip.hpp"
#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"
#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

// The LiDAR detector looks all around; for calibration it counts only the people within 25 deg
// of the LiDAR's +x axis (forward, REP 103), where a forward-looking thermal camera sees them (a
// FLIR A65 sees +-22.5 deg; 2.5 deg of margin): a person the LiDAR counts but the camera cannot
// see makes a frame's counts agree by chance with someone else in the image and gives a wrong
// pair. Measured on synthetic raw drives: with the whole circle 1 of 5 drives failed outright;
// with +-45 deg, once the detectors found side-on people, a realistic drive failed (39 deg off:
// 11 of its 67 pairs matched a person at 23-43 deg in the cloud with another in the image); with
// +-25 deg all 10 drives calibrate. A camera with a wider view or facing elsewhere sets
// lidar_min_azimuth_deg / lidar_max_azimuth_deg to its view.
inline detection::LidarDetectorConfig calibrationLidarDefaults() {
  detection::LidarDetectorConfig c;
  c.person.min_azimuth_deg = -25.0;
  c.person.max_azimuth_deg = 25.0;
  return c;
}

struct DetectionParameters {
  detection::ThermalSegmenterConfig thermal;
  detection::LidarDetectorConfig lidar = calibrationLidarDefaults();
  // Applied to the raw thermal image before segmentation and calibration (a camera that stores
  // its images upside down or mirrored; a mirrored image has no rigid extrinsic).
  detection::ImageFlip input_flip = detection::ImageFlip::kNone;
};

// Its rows (detection_parameter_table.cpp) and the rules across keys that follow them; with these,
// parameterTable<>, loadParameters<> and describeParameters (parameter_table.hpp) serve this
// struct, and the named forms below are theirs.
template <>
ParameterTable<DetectionParameters> makeParameterTable();
template <>
void finishLoading(const ParameterSource& source, DetectionParameters& params);

inline const ParameterTable<DetectionParameters>& detectionParameterTable() {
  return parameterTable<DetectionParameters>();
}
// The defaults overridden by what `source` has, then the detectors' rules across keys. Throws
// std::invalid_argument naming the key, the value and the allowed range.
inline DetectionParameters loadDetectionParameters(const ParameterSource& source) {
  return loadParameters<DetectionParameters>(source);
}
// Every detection key with its effective value, in table order.
inline std::vector<std::pair<std::string, std::string>> describeDetectionParameters(const DetectionParameters& p) {
  return describeParameters(p);
}

// A one-line warning when the LiDAR's bearing window (lidar_min/max_azimuth_deg) is more than
// 10 deg wider than the camera's horizontal field of view: the LiDAR then counts people the camera
// cannot see, and a frame's counts can agree by chance with someone else in the image (wrong
// pairs). "" when the window fits. Only the widths are compared: where the camera faces is what
// the calibration finds.
std::string lidarWindowWarning(const detection::LidarPersonConfig& lidar, const CameraModel& camera);

}  // namespace thermal_lidar_calibration
