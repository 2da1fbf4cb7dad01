#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {

Eigen::Matrix3d rodriguesToMatrix(const Eigen::Vector3d& r) {
  const double theta = r.norm();
  if (theta < 1e-12) {
    // First-order expansion keeps the map smooth through zero.
    Eigen::Matrix3d skew;
    skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return Eigen::Matrix3d::Identity() + skew;
  }
  return Eigen::AngleAxisd(theta, r / theta).toRotationMatrix();
}

Eigen::Vector3d matrixToRodrigues(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

Eigen::Matrix3d Extrinsic::rotationMatrix() const { return rodriguesToMatrix(rotation_vector); }

Eigen::Quaterniond Extrinsic::quaternion() const {
  Eigen::Quaterniond q(rotationMatrix());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;  // one canonical sign for files and tf
  return q;
}

Eigen::Isometry3d Extrinsic::T_camera_lidar() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotationMatrix();
  T.translation() = translation;
  return T;
}

Extrinsic Extrinsic::fromRotationMatrix(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  // Project onto SO(3) first: matrices typed from papers are only approximately orthonormal.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) *= -1.0;
  Extrinsic e;
  e.rotation_vector = matrixToRodrigues(U * V.transpose());
  e.translation = t;
  return e;
}

double rotationErrorRad(const Extrinsic& a, const Extrinsic& b) {
  const Eigen::Matrix3d d = a.rotationMatrix().transpose() * b.rotationMatrix();
  const double c = std::clamp((d.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c);
}

double translationErrorM(const Extrinsic& a, const Extrinsic& b) {
  return (a.translation - b.translation).norm();
}

}  // namespace thermal_lidar_calibration
