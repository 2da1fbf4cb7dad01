#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

void QualityConfig::validate() const {
  uncertainty.validate();
  time_offset.validate();
  coverage.validate();
  verdict.validate();
}

std::vector<std::size_t> usedPairs(const CalibrationResult& result) {
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < result.inliers.size(); ++i) {
    if (result.inliers[i]) used.push_back(i);
  }
  return used;
}

namespace {

// The pairs the bootstrap draws from: the used ones the skip rule made. A pair of the final
// round's (outside_skip_rule) sees the people of the frame beside it a few centimetres on; drawn
// as if independent, thrice as many pairs of one scene would shrink the intervals by about
// sqrt(3) while the scenes, the source of the spread, stay as many (MS2-like clean drives: the
// truth inside 46 of 60 axis checks so drawn). The intervals are those of the spaced pairs' fit,
// put around the estimate.
std::vector<std::size_t> resampled(const std::vector<CalibrationPair>& pairs, const std::vector<std::size_t>& used) {
  std::vector<std::size_t> spaced;
  for (std::size_t i : used) {
    if (!pairs[i].outside_skip_rule) spaced.push_back(i);
  }
  return spaced.size() >= 3 ? spaced : used;
}

}  // namespace

QualityAssessment assessQuality(const CameraModel& camera,
                                const std::vector<CalibrationPair>& pairs,
                                const CalibrationResult& result, const QualityConfig& config,
                                double behind_camera_penalty_c1,
                                const std::optional<Extrinsic>& reference,
                                const UncertaintyCallback& callback) {
  config.validate();
  if (result.inliers.size() != pairs.size()) {
    throw std::invalid_argument("quality: the result has " + std::to_string(result.inliers.size()) +
                                " pair flags for " + std::to_string(pairs.size()) + " pairs");
  }
  const std::vector<std::size_t> used = usedPairs(result);
  QualityAssessment q;
  q.coverage = computeCoverage(camera, pairs, used, result.extrinsic, config.coverage);
  // The pairs at the fit's time offset (issue 21): the bootstrap refines it too when it was
  // estimated.
  const bool timed = result.time_offset_mode != TimeOffsetMode::kNone;
  const LossEvaluator read(camera, pairs,
                           LossConfig{behind_camera_penalty_c1, PixelRule::kBilinear,
                                      timed ? std::optional<double>(result.time_offset_s) : std::nullopt});
  // The resamples read what the fit read: the rings' ends too when it did (ring_ends.hpp).
  const LossEvaluator loss = result.ring_ends > 0 && config.ring_end_weight > 0.0
                                 ? read.withRingEnds(pairs, result.extrinsic, config.ring_end_weight)
                                 : read.withPixelRule(PixelRule::kBilinear);
  if (config.uncertainty_enabled && used.size() >= 3) {
    const bool estimated = result.time_offset_mode == TimeOffsetMode::kEstimate;
    // When calibrate() ran the vertical centring, each resample goes through it too.
    const VerticalCentringOutcome* centring = result.vertical_centring.ran ? &result.vertical_centring : nullptr;
    q.uncertainty = estimateUncertainty(loss, result.extrinsic, resampled(pairs, used), config.uncertainty, callback,
                                        estimated ? std::optional<TimeOffsetConfig>(config.time_offset) : std::nullopt,
                                        centring);
  }
  q.timing = assessTiming(camera, pairs, result, q.uncertainty, config.time_offset, behind_camera_penalty_c1);
  q.verdict = judgeQuality(q.coverage, q.uncertainty, config.verdict, result.loss, q.timing);
  if (reference && !used.empty()) {
    q.reference = compareWithReference(loss, result.extrinsic, *reference, used, q.uncertainty);
  }
  return q;
}

}  // namespace thermal_lidar_calibration
