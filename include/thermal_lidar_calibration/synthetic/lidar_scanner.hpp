#pragma once
// Ray casting of a LiDAR scan against the ground plane and the world objects: one instantaneous
// scan (castLidarScan), or a scan built piece by piece (ScanGrid), as a swept scan is: each
// sector's azimuths against the objects where they were when the head turned past them.

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

// The nearest hit per ray so far. `ground_z` is the ground plane height in the LiDAR frame
// (-mount height); the flat ground looks the same from every pose of a level vehicle, so it is
// cast once, for every azimuth, at construction.
class ScanGrid {
 public:
  ScanGrid(const LidarModel& lidar, double ground_z);
  // Casts `solid`, reported as object `object`, through the rays its bounding sphere may reach;
  // with `sector_of` (one sector per azimuth index), only through the azimuths of `sector`.
  void cast(const Solid& solid, int object, const std::vector<int>* sector_of = nullptr, int sector = 0);
  // Every return within [min_range, max_range], beam by beam, azimuth by azimuth.
  std::vector<LidarReturn> returns() const;

 private:
  // A ray's direction is LidarModel::direction's, from these (the same values): sin and cos per
  // beam and per azimuth once, instead of per ray (they were a sixth of a bag's generation).
  Eigen::Vector3d direction(int beam, int azimuth) const {
    return Eigen::Vector3d(cos_el_[static_cast<std::size_t>(beam)] * cos_az_[static_cast<std::size_t>(azimuth)],
                           cos_el_[static_cast<std::size_t>(beam)] * sin_az_[static_cast<std::size_t>(azimuth)],
                           sin_el_[static_cast<std::size_t>(beam)]);
  }

  const LidarModel& lidar_;
  std::vector<double> cos_el_, sin_el_, cos_az_, sin_az_;
  std::vector<double> range_;
  std::vector<int> owner_;  // -2 none, -1 ground, >= 0 object
};

// All returns within [min_range, max_range] of one instantaneous scan. Objects are culled by
// their bounding spheres per azimuth/beam window.
std::vector<LidarReturn> castLidarScan(const LidarModel& lidar, const std::vector<WorldObject>& objects,
                                       double ground_z);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
