#pragma once
// Ray casting of one instantaneous LiDAR scan against the ground plane and the world objects.

#include "thermal_lidar_calibration/synthetic/lidar_model.hpp"
#include "thermal_lidar_calibration/synthetic/world_object.hpp"

#include <Eigen/Core>

#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

struct LidarReturn {
  Eigen::Vector3f point;  // LiDAR frame, m (noise-free)
  float range_m = 0.f;
  int object = -1;        // index into the objects, -1 = ground
  int beam = 0;
  int azimuth = 0;
};

// All returns within [min_range, max_range]. `ground_z` is the ground plane height in the LiDAR
// frame (-mount height). Objects are culled by their bounding spheres per azimuth/beam window.
std::vector<LidarReturn> castLidarScan(const LidarModel& lidar, const std::vector<WorldObject>& objects,
                                       double ground_z);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
