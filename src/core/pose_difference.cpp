#include "thermal_lidar_calibration/core/pose_difference.hpp"

#include <cmath>

namespace thermal_lidar_calibration {

PoseDifference poseDifference(const Extrinsic& estimate, const Extrinsic& reference) {
  constexpr double kDeg = 180.0 / M_PI;
  // R_e R_r^T is the rotation applied after the reference's, i.e. in the camera frame.
  const Eigen::Matrix3d delta = estimate.rotationMatrix() * reference.rotationMatrix().transpose();
  PoseDifference d;
  d.rotation_deg = matrixToRodrigues(delta) * kDeg;
  d.translation_cm = (estimate.translation - reference.translation) * 100.0;
  d.angle_deg = d.rotation_deg.norm();
  d.distance_cm = d.translation_cm.norm();
  return d;
}

Eigen::Matrix<double, 6, 1> asVector(const PoseDifference& d) {
  Eigen::Matrix<double, 6, 1> v;
  v << d.rotation_deg, d.translation_cm;
  return v;
}

}  // namespace thermal_lidar_calibration
