#pragma once
// Ground under a LiDAR scan on rolling terrain and with a tilted mount, in two steps:
//  1. Levelling: a robust plane through the lowest points near the sensor (a coarse grid of
//     minima, trimmed least squares) gives the mount's tilt; the scan is rotated so that plane is
//     horizontal, and heights are measured from it.
//  2. Local ground: in the levelled frame, the lowest point per (azimuth sector, range bin) is
//     followed outward per sector (Himmelsbach et al. 2010): a bin's minimum becomes a ground
//     anchor when it stays within max_step + tan(max_slope) * distance of the previous anchor
//     and its cell is not an object standing on lower ground. Between anchors the ground is
//     linear in range, so every point gets its height above the local ground.
// Unordered clouds work (no ring or azimuth order is needed): KITTI .bin, merged clouds.

#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"

#include <Eigen/Core>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

class TerrainGround {
 public:
  explicit TerrainGround(const LidarGroundConfig& config);

  // Estimates the ground for the points within `max_range_m` (horizontal, levelled frame) and
  // the height of each point above it. Non-finite points and points beyond the range get a NaN
  // height.
  void estimate(const std::vector<Eigen::Vector3f>& points, double max_range_m);

  // Results of the last estimate(), per input point where indexed.
  const std::vector<Eigen::Vector3f>& levelledPoints() const { return levelled_; }  // levelled frame
  const std::vector<float>& heights() const { return height_; }  // above the local ground, m
  const Eigen::Matrix3f& levelFromSensor() const { return R_level_sensor_; }
  double tiltDeg() const { return tilt_deg_; }          // mount tilt found (0 if not levelled)
  double sensorHeightM() const { return sensor_height_m_; }  // above the fitted plane
  bool levelled() const { return levelled_ok_; }
  // Local ground height (above the levelling plane) at a levelled-frame position, m.
  float groundAt(const Eigen::Vector2f& xy) const;

 private:
  void fitLevellingPlane(const std::vector<Eigen::Vector3f>& points);
  void followSectors();
  int cellOf(const Eigen::Vector2f& xy, float* range) const;

  LidarGroundConfig config_;
  int bins_ = 0;
  double max_range_m_ = 0;
  Eigen::Matrix3f R_level_sensor_ = Eigen::Matrix3f::Identity();
  double tilt_deg_ = 0;
  double sensor_height_m_ = 0;
  bool levelled_ok_ = false;
  std::vector<Eigen::Vector3f> levelled_;
  std::vector<float> height_;
  std::vector<int> cell_of_point_;
  // Per (sector, bin) cell: lowest and highest point height above the plane and the range of
  // the lowest; then the local ground line z = ground_z + ground_slope * (r - ground_r).
  std::vector<float> cell_min_, cell_max_, cell_min_r_;
  std::vector<float> ground_z_, ground_r_, ground_slope_;
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
