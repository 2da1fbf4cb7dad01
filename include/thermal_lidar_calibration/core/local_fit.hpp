#pragma once
// The calibration's refinement stage alone, from a given estimate (no evolution): what the
// drift watch fits on a window of pairs, starting at the extrinsic in use.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {

struct LocalFit {
  Extrinsic estimate;             // rotation vector with its angle in [0, pi]
  std::vector<std::size_t> used;  // the inliers it rests on, sorted
  std::uint64_t evaluations = 0;
};

// Refines from `start` on all `candidates`, re-selects the inliers among them with the paper's
// test (Eq. 1 <= threshold_sample_px, at least the better half), and refines again until the
// set is stable (at most 5 rounds), as calibrate() does after the evolution. Starting on ALL
// candidates, not on the start's inliers, lets the fit follow the majority of the pairs after
// a change, when every new pair is an outlier of the old extrinsic. `refinement` must search
// `nearest.withPixelRule(kBilinear)`.
LocalFit fitLocally(const LossEvaluator& nearest, const LocalRefinement& refinement,
                    const Extrinsic& start, const std::vector<std::size_t>& candidates,
                    const CalibrationConfig& config);

}  // namespace thermal_lidar_calibration
