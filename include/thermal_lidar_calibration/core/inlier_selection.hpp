#pragma once
// Which pairs the local refinement may use and which it keeps: shared by the calibration's
// refinement and the drift monitor's window fits, so both judge pairs by the same rules.

#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstddef>
#include <vector>

namespace thermal_lidar_calibration {

// Pairs the refinement may use: all, or, with exclude_truncated, those whose people do not
// touch the image border, as long as that leaves at least half of them.
std::vector<std::size_t> refinementCandidates(const LossEvaluator& loss, bool exclude_truncated);

// Candidates whose Eq. (1) loss at `estimate` is within the threshold; if fewer than half pass
// (the estimate is still far off), the better half, so the next refinement has enough pairs to
// move. Sorted by index.
std::vector<std::size_t> selectInliers(const LossEvaluator& loss, const Extrinsic& estimate,
                                       double threshold_px,
                                       const std::vector<std::size_t>& candidates);

// The share of all the pairs whose Eq. (1) loss at `estimate` is within the threshold: the test
// Algorithm 2 puts to a subset's fit (ratio_solution), also asked of an initial extrinsic and of
// the default run's fit after its shortened evolution. 0 without pairs.
double shareWithinThreshold(const LossEvaluator& loss, const Extrinsic& estimate, double threshold_px);

}  // namespace thermal_lidar_calibration
