#include "thermal_lidar_calibration/core/outlier_rejection.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

OutlierRejection::OutlierRejection(const LossEvaluator& loss, EvolutionConfig evolution,
                                   OutlierConfig config, int threads)
    : loss_(loss), evolution_(evolution), config_(config), threads_(threads) {
  evolution_.validate();
  config_.validate();
}

OutlierOutcome OutlierRejection::run(Rng& rng, const StageCallback& callback) const {
  const std::size_t n = loss_.pairCount();
  const std::size_t min_sample = static_cast<std::size_t>(config_.minSample(n));
  if (n <= min_sample) {
    throw std::invalid_argument(
        "Algorithm 2 needs more than min_sample = " + std::to_string(min_sample) +
        " pairs to test the others for outliers, but has " + std::to_string(n) +
        ": collect more pairs or use Algorithm 1 (algorithm: 1)");
  }
  const EvolutionaryOptimizer optimizer(loss_, evolution_, threads_);
  OutlierOutcome outcome;
  outcome.inliers.assign(n, true);  // line 1
  auto stageCallback = [&](const std::string& stage) -> GenerationCallback {
    return [&, stage](int generation, double best, const Extrinsic& e, std::uint64_t evals) {
      return !callback || callback(stage, generation, best, e, outcome.evaluations + evals);
    };
  };

  for (int iteration = 1; iteration <= config_.iterations; ++iteration) {
    // Lines 3-4: D_train = min_sample pairs drawn without replacement, D_val = the rest.
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    for (std::size_t i = 0; i < min_sample; ++i) {
      std::swap(order[i], order[i + rng.index(n - i)]);
    }
    const std::vector<std::size_t> train(order.begin(), order.begin() + min_sample);
    const std::vector<std::size_t> validation(order.begin() + min_sample, order.end());

    const std::string stage =
        "outlier_fit " + std::to_string(iteration) + "/" + std::to_string(config_.iterations);
    const EvolutionOutcome fit = optimizer.run(train, rng, stageCallback(stage));  // line 5
    outcome.evaluations += fit.evaluations;
    if (fit.stopped) {
      outcome.stopped = true;
      outcome.final_fit = fit;
      return outcome;
    }
    // Lines 6-14.
    std::vector<double> losses(validation.size());
    std::size_t within = 0;
    for (std::size_t k = 0; k < validation.size(); ++k) {
      losses[k] = loss_.pairLoss(validation[k], fit.best);
      if (losses[k] <= config_.threshold_px) ++within;
    }
    const double ratio_inliers =
        static_cast<double>(within) / static_cast<double>(validation.size());
    if (ratio_inliers >= config_.ratio_solution) {
      ++outcome.fits_accepted;
      for (std::size_t k = 0; k < validation.size(); ++k) {
        if (losses[k] > config_.threshold_px) outcome.inliers[validation[k]] = false;
      }
    }
  }

  // Lines 16-17.
  std::vector<std::size_t> inliers;
  for (std::size_t i = 0; i < n; ++i) {
    if (outcome.inliers[i]) inliers.push_back(i);
  }
  if (inliers.empty()) {
    throw std::invalid_argument(
        "Algorithm 2 marked every pair an outlier (threshold_sample_px = " +
        std::to_string(config_.threshold_px) +
        "): the people in the two modalities do not match; check the mask and cluster topics");
  }
  outcome.final_fit = optimizer.run(inliers, rng, stageCallback("final_fit"));
  outcome.evaluations += outcome.final_fit.evaluations;
  outcome.stopped = outcome.final_fit.stopped;
  return outcome;
}

}  // namespace thermal_lidar_calibration
