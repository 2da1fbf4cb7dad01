#pragma once
// Everything the user needs to decide whether to trust a calibration, in one call after
// calibrate(): the uncertainty per axis (bootstrap over the pairs used), the coverage of those
// pairs, the verdict, and, when a reference transform is known, the comparison with it.

#include <optional>
#include <vector>

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/coverage.hpp"
#include "thermal_lidar_calibration/core/reference_comparison.hpp"
#include "thermal_lidar_calibration/core/timing_check.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"
#include "thermal_lidar_calibration/core/verdict.hpp"

namespace thermal_lidar_calibration {

struct QualityConfig {
  bool uncertainty_enabled = true;  // false: no bootstrap (coverage and verdict only)
  UncertaintyConfig uncertainty;    // its seed and threads are normally the calibration's
  CoverageConfig coverage;
  VerdictConfig verdict;
  TimeOffsetConfig time_offset;  // the fit's time offset settings (normally the calibration's)
  // The refinement's LossConfig::ring_end_weight (normally the calibration's): when the fit read
  // ring ends (CalibrationResult::ring_ends), the resamples read them too, assigned at the estimate.
  double ring_end_weight = 0.0;
  void validate() const;
};

struct QualityAssessment {
  std::optional<Uncertainty> uncertainty;
  Coverage coverage;
  VerdictReport verdict;
  std::optional<ReferenceComparison> reference;
  std::optional<TimingAssessment> timing;  // when the used pairs' motion was measured
};

// `pairs` and `result` as given to / returned by calibrate(). `reference`: a transform the user
// already has; the caller fills the comparison's source and origin. Throws std::invalid_argument
// on a bad config or a result that does not belong to the pairs.
QualityAssessment assessQuality(const CameraModel& camera,
                                const std::vector<CalibrationPair>& pairs,
                                const CalibrationResult& result, const QualityConfig& config,
                                double behind_camera_penalty_c1,
                                const std::optional<Extrinsic>& reference = std::nullopt,
                                const UncertaintyCallback& callback = {});

// The indices of the pairs a result used (its inliers), in order.
std::vector<std::size_t> usedPairs(const CalibrationResult& result);

}  // namespace thermal_lidar_calibration
