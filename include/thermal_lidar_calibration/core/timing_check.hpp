#pragma once
// Can this drive tell a late camera from one mounted elsewhere, and do the residuals say the
// stamps are off (issue 21)? A constant time offset delta moves each point on the image by
// delta times its image speed (its velocity relative to the LiDAR, projected); a change of the
// pose moves the points by a pattern of six parameters. What the pose cannot mimic is what
// measures delta: the linearised spread of delta given the pose (`resolution_ms`, 1 sigma) is
// that part's size against a pixel-scale residual. Straight driving at one speed past standing
// people moves every point alike, so a translation mimics it all and the resolution is
// unbounded. And when the time offset was not estimated, pairs whose people cross the image
// faster fitting worse (rank correlation of their Eq. 1 loss with their image speed) is the
// signature of stamps that are off. ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

struct TimingAssessment {
  TimeOffsetMode mode = TimeOffsetMode::kNone;  // as applied by the fit
  double time_offset_s = 0.0;
  std::optional<double> halfwidth_ms;  // the bootstrap's 95 % half-width (mode estimate)
  std::size_t pairs_with_motion = 0;   // of the pairs used
  double mean_image_speed_px_s = 0.0;  // of the people's points on the image, pairs used
  // 1 sigma of delta the drive's motion can resolve with the pose free (infinite: none at all).
  double resolution_ms = 0.0;
  // Spearman rank correlation of the used pairs' Eq. 1 losses with their mean image speed.
  double speed_loss_correlation = 0.0;
  // When the offset was not estimated (none, fixed): the offset and loss a joint refinement of
  // pose and offset reaches from the fit, and the loss it started from (sub-pixel rule). An
  // offset far from the applied one that fits clearly better says the stamps are off.
  std::optional<double> probe_offset_s;
  double probe_loss = 0.0, fit_loss = 0.0;
};

// `pairs` and `result` as given to / returned by calibrate(); `uncertainty` its bootstrap, if
// any; `timing` the fit's time offset settings (the probe's range). nullopt when no used pair has
// its people's motion measured (nothing to judge).
std::optional<TimingAssessment> assessTiming(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                                             const CalibrationResult& result,
                                             const std::optional<Uncertainty>& uncertainty,
                                             const TimeOffsetConfig& timing, double behind_camera_penalty_c1);

// Spearman's rank correlation of x and y (ties share their mean rank); 0 with fewer than 3.
double rankCorrelation(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace thermal_lidar_calibration
