#include "thermal_lidar_calibration/core/drift_update_fit.hpp"

#include "thermal_lidar_calibration/core/drift_window_comparison.hpp"
#include "thermal_lidar_calibration/core/inlier_selection.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/signed_rank_statistic.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

const char* toString(DriftUpdateModel model) {
  switch (model) {
    case DriftUpdateModel::kTurn: return "turn";
    case DriftUpdateModel::kShift: return "shift";
    case DriftUpdateModel::kFull: return "full";
  }
  return "full";
}

namespace {

void checkUpdateInput(std::size_t pairs, const DriftConfig& drift, const CalibrationConfig& calibration) {
  drift.validate();
  calibration.validate();
  if (pairs < 2 * static_cast<std::size_t>(drift.folds)) {
    throw std::invalid_argument("drift update: " + std::to_string(pairs) + " pairs; it needs at least " +
                                std::to_string(2 * drift.folds));
  }
}

}  // namespace

DriftUpdateFit fitDriftUpdate(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                              const Extrinsic& reference, const Extrinsic& start,
                              const DriftConfig& drift, const CalibrationConfig& calibration) {
  checkUpdateInput(pairs.size(), drift, calibration);  // before the distance maps are built
  const LossEvaluator nearest(
      camera, pairs, LossConfig{calibration.behind_camera_penalty_c1, PixelRule::kNearest});
  return fitDriftUpdate(nearest, reference, start, drift, calibration);
}

DriftUpdateFit fitDriftUpdate(const LossEvaluator& nearest, const Extrinsic& reference,
                              const Extrinsic& start, const DriftConfig& drift,
                              const CalibrationConfig& calibration) {
  checkUpdateInput(nearest.pairCount(), drift, calibration);
  const LossEvaluator bilinear = nearest.withPixelRule(PixelRule::kBilinear);
  const RefineConfig refine = driftRefineConfig(drift, calibration);
  const int threads = calibration.num_threads;
  const std::array<LocalRefinement, 3> searches{
      LocalRefinement(bilinear, refine, threads, RefineFreedom::kCameraTurn),
      LocalRefinement(bilinear, refine, threads, RefineFreedom::kCameraShift),
      LocalRefinement(bilinear, refine, threads, RefineFreedom::kFull)};
  // The turn starts at the start's rotation with the reference's camera centre (R' = D R,
  // t' = D t), the shift at the reference.
  const Eigen::Matrix3d D = start.rotationMatrix() * reference.rotationMatrix().transpose();
  const std::array<Extrinsic, 3> starts{
      Extrinsic::fromRotationMatrix(start.rotationMatrix(), D * reference.translation), reference,
      start};
  const std::vector<std::size_t> candidates =
      refinementCandidates(nearest, calibration.refine.exclude_truncated);
  constexpr int kTurn = 0, kShift = 1, kFull = 2;

  DriftUpdateFit out;
  auto fit = [&](int model, const std::vector<std::size_t>& on) {
    LocalFit f = fitLocally(nearest, searches[model], starts[model], on, calibration);
    out.evaluations += f.evaluations;
    return f;
  };
  if (drift.update_full_significance >= 1.0) {
    out.fit = fit(kFull, candidates);
    out.model = DriftUpdateModel::kFull;
    out.full_p_value = 0.0;
    return out;
  }

  // Cross-fitting, interleaved folds as in the window test: each model's loss on each held-out
  // pair that some model explains.
  const double threshold = calibration.outlier.threshold_px;
  std::array<std::vector<double>, 3> held_out_loss;
  for (int k = 0; k < drift.folds; ++k) {
    std::vector<std::size_t> train, held_out;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      (static_cast<int>(j % drift.folds) == k ? held_out : train).push_back(candidates[j]);
    }
    std::array<Extrinsic, 3> fold_fit;
    for (int model : {kTurn, kShift, kFull}) fold_fit[model] = fit(model, train).estimate;
    for (std::size_t i : held_out) {
      std::array<double, 3> loss;
      for (int model : {kTurn, kShift, kFull}) loss[model] = bilinear.pairLoss(i, fold_fit[model]);
      if (*std::min_element(loss.begin(), loss.end()) > threshold) continue;
      for (int model : {kTurn, kShift, kFull}) held_out_loss[model].push_back(loss[model]);
    }
  }
  auto minus = [](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
    return d;
  };
  const int simpler =
      hodgesLehmann(minus(held_out_loss[kTurn], held_out_loss[kShift])) > 0.0 ? kShift : kTurn;
  const SignedRankResult full_better =
      signedRankTestGreater(minus(held_out_loss[simpler], held_out_loss[kFull]));
  out.full_p_value = full_better.p_value;
  const bool full = full_better.n > 0 && full_better.p_value < drift.update_full_significance;
  const int chosen = full ? kFull : simpler;
  out.model = chosen == kTurn ? DriftUpdateModel::kTurn
              : chosen == kShift ? DriftUpdateModel::kShift
                                 : DriftUpdateModel::kFull;
  out.fit = fit(chosen, candidates);
  return out;
}

}  // namespace thermal_lidar_calibration
