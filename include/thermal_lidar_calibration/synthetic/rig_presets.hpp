#pragma once
// Sensor rigs for the synthetic generator: thermal camera intrinsics, LiDAR beam pattern, the
// true extrinsic (p_C = R p_L + t) and how the rig sits on its vehicle.

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_model.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

struct RigPreset {
  std::string name;
  std::string description;
  CameraModel camera;
  LidarModel lidar;
  Extrinsic truth;                // T_camera_lidar: p_C = R p_L + t
  double lidar_height_m = 1.9;    // LiDAR origin above the flat ground
  double vehicle_speed_mps = 2.5; // along the path
};

// FieldSAFE-like: FLIR A65 640x512 with FieldSAFE's K and plumb_bob D, HDL-32E 1.9 m above
// ground, truth = FieldSAFE's own LiDAR-to-thermal transform (R orthonormalised with SVD). The
// camera sits ~0.4 m below and ~0.44 m left of the LiDAR, looking forward ~15 deg down.
// Tractor speed 2.5 m/s.
RigPreset fieldsafeRig();
// MS2-like (numbers chosen to look like the MS2 car, NOT the dataset's calibration): 640x256
// rectified thermal (fx = fy ~ 419 px, no distortion), VLP-16 on the roof 1.75 m above ground,
// camera 0.42 m below, 0.35 m ahead of and 0.12 m right of the LiDAR, pitched 4 deg down with a
// small yaw and roll. Car speed 4 m/s.
RigPreset ms2Rig();
// "fieldsafe" or "ms2"; anything else throws std::invalid_argument.
RigPreset rigByName(const std::string& name);
std::vector<std::string> rigNames();

// Camera orientation from the LiDAR frame (x fwd, y left, z up) for an optical camera looking
// along yaw/pitch(down positive)/roll, and its optical centre in the LiDAR frame.
Extrinsic extrinsicFromMount(double yaw_rad, double pitch_down_rad, double roll_rad,
                             const Eigen::Vector3d& camera_in_lidar_m);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
