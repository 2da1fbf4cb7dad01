#include "thermal_lidar_calibration/core/local_fit.hpp"

#include "thermal_lidar_calibration/core/inlier_selection.hpp"

#include <utility>

namespace thermal_lidar_calibration {

LocalFit fitLocally(const LossEvaluator& nearest, const LocalRefinement& refinement,
                    const Extrinsic& start, const std::vector<std::size_t>& candidates,
                    const CalibrationConfig& config) {
  LocalFit fit;
  fit.estimate = start;
  fit.used = candidates;
  constexpr int kMaxInlierRounds = 5;  // as calibrate()
  for (int round = 1; round <= kMaxInlierRounds; ++round) {
    const RefineOutcome refined = refinement.run(fit.estimate, fit.used);
    fit.estimate = refined.best;
    fit.evaluations += refined.evaluations;
    if (!config.refine.reselect_inliers) break;
    std::vector<std::size_t> reselected =
        selectInliers(nearest, fit.estimate, config.outlier.threshold_px, candidates);
    if (reselected == fit.used) break;
    fit.used = std::move(reselected);
  }
  fit.estimate.rotation_vector = matrixToRodrigues(fit.estimate.rotationMatrix());
  return fit;
}

}  // namespace thermal_lidar_calibration
