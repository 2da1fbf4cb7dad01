#pragma once
// Pinhole camera with optional plumb_bob (OpenCV 5-coefficient) distortion.
// With zero distortion, project() is exactly the paper's K (R p + t) followed by the
// homogeneous division.

#include <Eigen/Core>

#include <array>
#include <vector>
#include <string>

namespace thermal_lidar_calibration {

struct CameraModel {
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0, skew = 0;
  // plumb_bob order as in sensor_msgs/CameraInfo: k1, k2, p1, p2, k3.
  std::array<double, 5> distortion{{0, 0, 0, 0, 0}};

  // Throws std::invalid_argument naming the bad field if the model cannot be used.
  void validate() const;
  bool hasDistortion() const;
  Eigen::Matrix3d K() const;

  // Camera-frame point (z > 0) to pixel coordinates (u right, v down; pixel centres at integers).
  Eigen::Vector2d project(const Eigen::Vector3d& p_camera) const;
  // Normalised image coordinates (x/z, y/z) to distorted normalised coordinates.
  Eigen::Vector2d distort(const Eigen::Vector2d& normalised) const;

  // Build from K (row-major 3x3) and D (0 or 5 values; anything else throws).
  static CameraModel fromK(int width, int height, const std::array<double, 9>& K,
                           const std::vector<double>& D);
  std::string describe() const;  // one line, for logs
};

}  // namespace thermal_lidar_calibration
