#pragma once
// The ROS camera_calibration / camera_info_manager YAML format (image_width, image_height,
// camera_name, camera_matrix{rows,cols,data}, distortion_model, distortion_coefficients, ...).

#include "thermal_lidar_calibration/core/camera_model.hpp"

#include <string>

namespace thermal_lidar_calibration {

// Throws std::invalid_argument ("camera info file X: <what is wrong>") on a missing or bad file.
CameraModel loadCameraInfoFile(const std::string& path);
void writeCameraInfoFile(const std::string& path, const CameraModel& camera,
                         const std::string& camera_name);

}  // namespace thermal_lidar_calibration
