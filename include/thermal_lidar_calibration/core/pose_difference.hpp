#pragma once
// The difference between two extrinsics per camera axis: what the uncertainty, the reference
// comparison and the report talk about. Both sides map LiDAR points into the camera frame
// (p_C = R p_L + t), so the difference is expressed in the camera frame (x right, y down,
// z forward): the rotation that takes `reference` to `estimate` as seen from the camera
// (R_estimate = exp([w]x) R_reference, w about the camera's x, y, z) and t_estimate - t_reference.

#include <Eigen/Core>

#include "thermal_lidar_calibration/core/extrinsic.hpp"

namespace thermal_lidar_calibration {

struct PoseDifference {
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();    // w about camera x, y, z, degrees
  Eigen::Vector3d translation_cm = Eigen::Vector3d::Zero();  // t_estimate - t_reference, cm
  double angle_deg = 0.0;    // |w|: the whole rotation between the two, degrees
  double distance_cm = 0.0;  // |t_estimate - t_reference|, cm
};

PoseDifference poseDifference(const Extrinsic& estimate, const Extrinsic& reference);

// Six numbers in one vector, rotation first: (wx, wy, wz) deg then (tx, ty, tz) cm.
Eigen::Matrix<double, 6, 1> asVector(const PoseDifference& d);

}  // namespace thermal_lidar_calibration
