#include "thermal_lidar_calibration/synthetic/rig_presets.hpp"

#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {

Extrinsic extrinsicFromMount(double yaw_rad, double pitch_down_rad, double roll_rad,
                             const Eigen::Vector3d& camera_in_lidar_m) {
  const Eigen::Vector3d z_c(std::cos(pitch_down_rad) * std::cos(yaw_rad),
                            std::cos(pitch_down_rad) * std::sin(yaw_rad), -std::sin(pitch_down_rad));
  const Eigen::Vector3d x0 = z_c.cross(Eigen::Vector3d::UnitZ()).normalized();  // right
  const Eigen::Vector3d y0 = z_c.cross(x0);                                     // down
  const Eigen::Vector3d x_c = std::cos(roll_rad) * x0 + std::sin(roll_rad) * y0;
  const Eigen::Vector3d y_c = z_c.cross(x_c);
  Eigen::Matrix3d R;
  R.row(0) = x_c.transpose();
  R.row(1) = y_c.transpose();
  R.row(2) = z_c.transpose();
  return Extrinsic::fromRotationMatrix(R, -R * camera_in_lidar_m);
}

RigPreset fieldsafeRig() {
  RigPreset rig;
  rig.name = "fieldsafe";
  rig.description = "FieldSAFE-like: FLIR A65 640x512 + Velodyne HDL-32E on a tractor";
  rig.camera = CameraModel::fromK(640, 512, {772.41, 0.0, 322.67, 0.0, 772.83, 250.66, 0.0, 0.0, 1.0},
                                  {-0.0496, 0.3632, 0.0, 0.0, 0.0});
  rig.lidar = LidarModel::hdl32e();
  Eigen::Matrix3d R;
  R << 0.0336, -0.9994, 0.0120,  //
      -0.2518, -0.0201, -0.9676,  //
      0.9672, 0.0295, -0.2523;
  // fromRotationMatrix projects R (4 decimals, so only nearly orthonormal) onto SO(3).
  rig.truth = Extrinsic::fromRotationMatrix(R, Eigen::Vector3d(0.443, -0.393, -0.079));
  rig.lidar_height_m = 1.9;
  rig.vehicle_speed_mps = 2.5;
  return rig;
}

RigPreset ms2Rig() {
  RigPreset rig;
  rig.name = "ms2";
  rig.description = "MS2-like (not the dataset's numbers): 640x256 rectified thermal + Velodyne VLP-16 on a car";
  rig.camera = CameraModel::fromK(640, 256, {418.5, 0.0, 319.4, 0.0, 418.9, 127.8, 0.0, 0.0, 1.0}, {});
  rig.lidar = LidarModel::vlp16();
  constexpr double kDeg = M_PI / 180.0;
  rig.truth = extrinsicFromMount(1.5 * kDeg, 4.0 * kDeg, 0.5 * kDeg, Eigen::Vector3d(0.35, -0.12, -0.42));
  rig.lidar_height_m = 1.75;
  rig.vehicle_speed_mps = 4.0;
  return rig;
}

std::vector<std::string> rigNames() { return {"fieldsafe", "ms2"}; }

RigPreset rigByName(const std::string& name) {
  if (name == "fieldsafe") return fieldsafeRig();
  if (name == "ms2") return ms2Rig();
  throw std::invalid_argument("unknown rig '" + name + "' (use fieldsafe or ms2)");
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
