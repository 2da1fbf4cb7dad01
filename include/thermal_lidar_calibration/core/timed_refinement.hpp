#pragma once
// Beyond the paper (issue 21): the local refinement over the pose and the camera time offset
// delta together, the seventh parameter. The same pattern search as LocalRefinement on
// (r, s = R pivot + t, delta); a probe at another delta reads the points moved to that instant
// (LossEvaluator::withTimeOffset, the distance maps shared). delta stays within
// +-TimeOffsetConfig::max_s.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {

struct TimedRefineOutcome {
  Extrinsic best;
  double time_offset_s = 0.0;
  double loss = 0.0;  // with the evaluator's pixel rule, at (best, time_offset_s)
  int iterations = 0;
  std::uint64_t evaluations = 0;
  bool converged = false;
  bool stopped = false;
};

class TimedRefinement {
 public:
  // `loss` must have a time offset (LossConfig::time_offset_s) and outlive the refinement.
  TimedRefinement(const LossEvaluator& loss, RefineConfig refine, TimeOffsetConfig timing, int threads);
  TimedRefineOutcome run(const Extrinsic& start, double start_offset_s,
                         const std::vector<std::size_t>& pairs, const RefineCallback& callback = {}) const;

 private:
  const LossEvaluator& loss_;
  RefineConfig refine_;
  TimeOffsetConfig timing_;
  int threads_;
};

}  // namespace thermal_lidar_calibration
