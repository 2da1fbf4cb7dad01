#pragma once
// One set of rules for a camera's intrinsics as ROS writes them, whether they arrive as a
// sensor_msgs/CameraInfo message or as a camera_calibration YAML file: both readers fill a
// CameraCalibration and build the model here, so a camera accepted live is accepted from a file.

#include "thermal_lidar_calibration/core/camera_model.hpp"

#include <array>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct CameraCalibration {
  long long width = 0, height = 0;  // pixels (wide type: the caller passes what it read)
  std::array<double, 9> K{};        // row-major 3x3
  std::string distortion_model;     // "plumb_bob", "none" or empty; others only with D = 0
  std::vector<double> D;
};

// The pinhole (+ plumb_bob) model, validated. Throws std::invalid_argument with a one-line
// reason and what to do (the caller prefixes where the calibration came from).
CameraModel cameraModelFromCalibration(const CameraCalibration& calibration);

}  // namespace thermal_lidar_calibration
