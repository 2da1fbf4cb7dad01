#pragma once
// The calibration result: p_C = R p_L + t with R = Rodrigues(r). Metres and radians.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace thermal_lidar_calibration {

struct Extrinsic {
  Eigen::Vector3d rotation_vector = Eigen::Vector3d::Zero();  // Rodrigues r, rad
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();      // t, m

  Eigen::Matrix3d rotationMatrix() const;
  Eigen::Quaterniond quaternion() const;
  Eigen::Isometry3d T_camera_lidar() const;
  static Extrinsic fromRotationMatrix(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
};

// Angle of R_a^T R_b in radians and |t_a - t_b| in metres: the errors we report against truth.
double rotationErrorRad(const Extrinsic& a, const Extrinsic& b);
double translationErrorM(const Extrinsic& a, const Extrinsic& b);

// Rodrigues vector <-> matrix (same convention as cv::Rodrigues), no OpenCV call in hot paths.
Eigen::Matrix3d rodriguesToMatrix(const Eigen::Vector3d& r);
Eigen::Vector3d matrixToRodrigues(const Eigen::Matrix3d& R);

}  // namespace thermal_lidar_calibration
