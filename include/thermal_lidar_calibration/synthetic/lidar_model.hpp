#pragma once
// Spinning multi-beam LiDAR: beam elevations and azimuth sampling. Each scan is treated as
// instantaneous at its stamp. LiDAR frame: x forward, y left, z up.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

struct LidarModel {
  std::string name;
  std::vector<double> elevations_rad;  // one per beam, ascending
  int azimuth_count = 0;               // firings per revolution
  double min_range_m = 1.0;
  double max_range_m = 100.0;

  int beamCount() const { return static_cast<int>(elevations_rad.size()); }
  double azimuthRad(int azimuth_index) const;  // 0 = +x, counter-clockwise towards +y
  Eigen::Vector3d direction(int beam, int azimuth_index) const;  // unit vector
  void validate() const;  // throws std::invalid_argument

  // Velodyne HDL-32E: 32 beams, -30.67 to +10.67 deg (1.333 deg apart), 2170 azimuths at 10 Hz
  // (0.166 deg), 1-100 m.
  static LidarModel hdl32e();
  // Velodyne VLP-16: 16 beams, -15 to +15 deg (2 deg apart), 1800 azimuths at 10 Hz (0.2 deg),
  // 1-100 m.
  static LidarModel vlp16();
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
