#pragma once
// Can this drive tell a late camera from one mounted elsewhere (timing_resolution.hpp), and do
// the residuals say the stamps are off (issue 21)? When the time offset was not estimated, a
// joint refinement of pose and offset from the fit that finds a clearly better fit elsewhere is
// the signature of stamps that are off (pairs whose people cross the image faster fit worse:
// their rank correlation is reported too). ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

struct TimingAssessment {
  TimeOffsetMode mode = TimeOffsetMode::kNone;   // as applied by the fit
  TimeOffsetMode asked = TimeOffsetMode::kNone;  // as configured
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
