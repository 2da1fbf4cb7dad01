#pragma once
// How well a set of pairs can tell the camera's time offset delta from the pose (issue 21). A
// constant delta moves each point on the image by delta times its image speed (its velocity
// relative to the LiDAR, projected); a change of the pose moves the points by a pattern of six
// parameters. What the pose cannot mimic is what measures delta: the Schur complement of the
// pose block in the linearised 7x7 normal matrix of the points' image positions (each pair
// weighing one: its points share one mask and one scan), against a residual of a pixel, is
// delta's 1-sigma given the pose. Straight driving at one speed past standing people moves
// every point alike, a translation mimics it all, and the resolution is unbounded. The measured
// velocities' errors (PersonMotion::std_error_mps, where the pairs carry it) also make people
// move differently, which no pose mimics either: their expected share of the information is
// taken off, so a drive resolves delta by what the people truly do. ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <vector>

namespace thermal_lidar_calibration {

struct TimingResolution {
  double resolution_ms = 0.0;  // 1 sigma of delta with the pose free; infinite: none at all
  std::size_t pairs_with_motion = 0;
  std::vector<std::size_t> pairs;        // the pairs with measured motion among those given
  std::vector<double> image_speed_px_s;  // their points' mean image speed, same order
};

// `used`: indices into `pairs`.
TimingResolution timingResolution(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                                  const std::vector<std::size_t>& used, const Extrinsic& extrinsic,
                                  double time_offset_s);

}  // namespace thermal_lidar_calibration
