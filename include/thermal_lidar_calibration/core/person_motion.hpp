#pragma once
// How each person moves relative to the LiDAR, measured from the neighbouring scans (issue 21):
// the vehicle's own motion and turning and the person's walk together, which is exactly what the
// camera sees change between its exposure and the scan. Each scan's person clusters are reduced
// to one centroid per person (ScanPeople); the same person is found in the scans before and
// after by position (labels of a detector are per scan, not persistent), and a straight-line
// fit of the centroids over time gives the velocity and its standard error. A person found in no
// other scan is "not measured": velocity zero, so that pair's points do not move with delta.
// ROS-free.

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// One LiDAR scan's person clusters, one centroid each.
struct ScanPeople {
  struct Person {
    std::int32_t label = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // LiDAR frame, m
    double time_s = 0.0;  // when its points were captured: the scan stamp, or their mean time
    int points = 0;
  };
  double stamp_s = 0.0;  // the cloud's header stamp
  std::vector<Person> people;
};

// `point_time_s` (relative to `stamp_s`, one per point) may be empty: every point at the stamp.
ScanPeople summariseScan(double stamp_s, const std::vector<Eigen::Vector3f>& points,
                         const std::vector<std::int32_t>& labels,
                         const std::vector<float>& point_time_s = {});

struct MotionConfig {
  int window_scans = 2;         // scans before and after the pair's own used for the fit
  double max_speed_mps = 20.0;  // fastest relative motion a person is searched within (a car at
                                // 15 m/s beside someone walking); wider gates pair up strangers
  double max_gap_s = 0.35;      // a neighbour scan further than this (per step) from the last
                                // one found is not used: a dropped stretch of scans ends a track
  // 1-sigma noise of one cluster centroid: where rings meet a person moves it by a few cm
  // between scans. Used for the standard error when only two scans were found.
  double centroid_noise_m = 0.05;
  void validate() const;  // throws std::invalid_argument naming the key and range
};

struct PersonMotion {
  std::int32_t label = 0;                                 // in the pair's own scan
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();  // relative to the LiDAR frame
  Eigen::Vector3d std_error_mps = Eigen::Vector3d::Zero();
  // The vehicle's yaw rate about the LiDAR's z axis (rad/s, counter-clockwise seen from above),
  // the same for every person of the scan: what bends their straight lines (turnRate).
  double turn_rate_rps = 0.0;
  int scans = 1;  // scans the fit used, the pair's own included; 1 = not measured
  bool measured() const { return scans >= 2; }
};

// The motion of every person of scans[centre], from up to `window_scans` scans on each side.
// When the vehicle turns at w about the LiDAR's z axis, everything it passes moves on an arc
// relative to the LiDAR: a standing person's velocity v turns with it, an acceleration -w x v,
// and a straight line from v alone misses the arc by w |v| T^2 / 2 after T (a car at 5 m/s in a
// 15 m turn: 4 mm at 60 ms, 13 mm at 110 ms, mostly sideways). w is read from how the people's
// tracks bend (a parabola through each track with scans on both sides, followed up to four scans
// each way, its acceleration against its velocity, pooled over the scan's people), and every
// measured person gets it. The velocity itself is still fitted over window_scans.
// `scans` are in time order. Throws std::invalid_argument on a bad index or config.
std::vector<PersonMotion> estimateMotion(const std::vector<ScanPeople>& scans, std::size_t centre,
                                         const MotionConfig& config);

}  // namespace thermal_lidar_calibration
