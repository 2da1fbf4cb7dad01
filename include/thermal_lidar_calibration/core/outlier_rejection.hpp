#pragma once
// Algorithm 2 of the paper, as written: iter_outlier times, fit Algorithm 1 on min_sample random
// pairs, score the remaining pairs with Eq. (1); if at least ratio_solution of them are within
// threshold_sample, mark the others outliers. Then Algorithm 1 on the inliers.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/evolutionary_optimizer.hpp"

#include <functional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct OutlierOutcome {
  std::vector<bool> inliers;  // isInlier, one per pair of the evaluator
  int fits_accepted = 0;      // fits whose ratio_inliers >= ratio_solution
  EvolutionOutcome final_fit; // Algorithm 1 on the inliers
  std::uint64_t evaluations = 0;
  bool stopped = false;
};

// Same as GenerationCallback plus the stage name ("outlier_fit 1/2", "final_fit").
using StageCallback = std::function<bool(const std::string& stage, int generation,
                                         double best_loss, const Extrinsic& best,
                                         std::uint64_t evaluations)>;

class OutlierRejection {
 public:
  OutlierRejection(const LossEvaluator& loss, EvolutionConfig evolution, OutlierConfig config,
                   int threads);
  // Throws std::invalid_argument if there are not more pairs than min_sample.
  OutlierOutcome run(Rng& rng, const StageCallback& callback = {}) const;

 private:
  const LossEvaluator& loss_;
  EvolutionConfig evolution_;
  OutlierConfig config_;
  int threads_;
};

}  // namespace thermal_lidar_calibration
