#include "thermal_lidar_calibration/core/calibrator.hpp"

#include "thermal_lidar_calibration/core/evolutionary_optimizer.hpp"
#include "thermal_lidar_calibration/core/inlier_selection.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/outlier_rejection.hpp"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <numeric>
#include <stdexcept>

namespace thermal_lidar_calibration {

CalibrationResult calibrate(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                            const CalibrationConfig& config, const ProgressCallback& progress) {
  const auto started = std::chrono::steady_clock::now();
  config.validate();
  if (pairs.empty()) {
    throw std::invalid_argument("calibration: no pairs were collected");
  }
  const LossEvaluator nearest(camera, pairs,
                              LossConfig{config.behind_camera_penalty_c1, PixelRule::kNearest});
  Rng rng(config.seed);
  CalibrationResult result;
  result.pairs_collected = pairs.size();

  std::uint64_t evaluations_before_stage = 0;
  // history_stage: the stage's name in the history when it differs from the progress one.
  auto report = [&](const std::string& stage, int generation, int total, double best,
                    const Extrinsic& e, std::uint64_t stage_evaluations,
                    const std::string& history_stage = {}) {
    result.history.push_back({history_stage.empty() ? stage : history_stage, generation, best,
                              evaluations_before_stage + stage_evaluations});
    if (!progress) return true;
    Progress p;
    p.stage = stage;
    p.generation = generation;
    p.generations_total = total;
    p.best_loss = best;
    p.evaluations = evaluations_before_stage + stage_evaluations;
    p.best = e;
    return progress(p);
  };
  const int generations = config.evolution.max_iterations;

  std::vector<std::size_t> used(pairs.size());
  std::iota(used.begin(), used.end(), std::size_t{0});
  EvolutionOutcome fit;
  if (config.algorithm == Algorithm::kOutlierRejection) {
    const OutlierRejection algorithm2(nearest, config.evolution, config.outlier,
                                      config.num_threads);
    const OutlierOutcome outcome = algorithm2.run(
        rng, [&](const std::string& stage, int g, double best, const Extrinsic& e,
                 std::uint64_t evals) { return report(stage, g, generations, best, e, evals); });
    fit = outcome.final_fit;
    result.inliers = outcome.inliers;
    result.outlier_fits_accepted = outcome.fits_accepted;
    result.evaluations = outcome.evaluations;
    result.stopped = outcome.stopped;
    used.clear();
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (outcome.inliers[i]) used.push_back(i);
    }
  } else {
    const EvolutionaryOptimizer algorithm1(nearest, config.evolution, config.num_threads);
    fit = algorithm1.run(used, rng, [&](int g, double best, const Extrinsic& e,
                                        std::uint64_t evals) {
      return report("plain_fit", g, generations, best, e, evals);
    });
    result.inliers.assign(pairs.size(), true);
    result.evaluations = fit.evaluations;
    result.stopped = fit.stopped;
  }
  result.evolution_extrinsic = fit.best;
  result.evolution_loss = nearest.loss(fit.best, used);
  result.extrinsic = fit.best;

  const LossEvaluator bilinear = nearest.withPixelRule(PixelRule::kBilinear);
  if (config.refine.mode == RefineMode::kLocal && !result.stopped) {
    const LocalRefinement refinement(bilinear, config.refine, config.num_threads);
    // Algorithm 2 can keep a mismatched pair (equal counts, different people) when neither of
    // its subset fits is accepted; one such pair pulls the optimum by decimetres. So the
    // refinement alternates: refine on the current inliers, then re-select the inliers among
    // ALL collected pairs with the paper's own test (Eq. 1 <= threshold_sample), keeping at least
    // the better half, until the set no longer changes. Pairs with people cut by the image
    // border are left out of the re-selection (refine.exclude_truncated).
    const std::vector<std::size_t> candidates =
        refinementCandidates(nearest, config.refine.exclude_truncated);
    if (!config.refine.reselect_inliers) {
      // One refinement on Algorithm 2's inliers, less the excluded pairs.
      std::vector<std::size_t> kept;
      std::set_intersection(used.begin(), used.end(), candidates.begin(), candidates.end(),
                            std::back_inserter(kept));
      if (!kept.empty()) used = kept;
    }
    constexpr int kMaxInlierRounds = 5;
    for (int round = 1; round <= kMaxInlierRounds; ++round) {
      evaluations_before_stage = result.evaluations;
      const std::string round_name = "refine " + std::to_string(round);
      result.history.push_back({round_name, 0, bilinear.loss(result.extrinsic, used),
                                evaluations_before_stage});
      const RefineOutcome refined = refinement.run(
          result.extrinsic, used,
          [&](int iteration, double loss, const Extrinsic& e, std::uint64_t evals) {
            return report("refine", iteration, 0, loss, e, evals, round_name);
          });
      result.extrinsic = refined.best;
      result.evaluations += refined.evaluations;
      result.stopped = refined.stopped;
      if (result.stopped || !config.refine.reselect_inliers) break;
      const std::vector<std::size_t> reselected =
          selectInliers(nearest, result.extrinsic, config.outlier.threshold_px, candidates);
      if (reselected == used) break;
      used = reselected;
    }
    result.inliers.assign(pairs.size(), false);
    for (std::size_t i : used) result.inliers[i] = true;
  }

  // The search explores rotation vectors up to |r| = sqrt(3) * 3.5 rad; report the same
  // rotation with its angle in [0, pi] so files and logs read naturally.
  result.extrinsic.rotation_vector = matrixToRodrigues(result.extrinsic.rotationMatrix());
  result.evolution_extrinsic.rotation_vector =
      matrixToRodrigues(result.evolution_extrinsic.rotationMatrix());
  result.pairs_used = used.size();
  result.loss = nearest.loss(result.extrinsic, used);
  result.loss_bilinear = bilinear.loss(result.extrinsic, used);
  result.pair_losses.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    result.pair_losses[i] = nearest.pairLoss(i, result.extrinsic);
  }
  result.points_projected = nearest.pointsEvaluated();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace thermal_lidar_calibration
