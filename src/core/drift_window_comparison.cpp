#include "thermal_lidar_calibration/core/drift_window_comparison.hpp"

#include "thermal_lidar_calibration/core/inlier_selection.hpp"
#include "thermal_lidar_calibration/core/local_fit.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/signed_rank_statistic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

// Mean over `pairs` of the mean image distance between each point projected by `a` and by `b`
// (points behind either camera pose are skipped).
double meanImageShiftPx(const CameraModel& camera, const std::vector<CalibrationPair>& window,
                        const std::vector<std::size_t>& pairs, const Extrinsic& a,
                        const Extrinsic& b) {
  const Eigen::Isometry3d Ta = a.T_camera_lidar(), Tb = b.T_camera_lidar();
  double sum = 0.0;
  std::size_t counted = 0;
  for (std::size_t i : pairs) {
    double pair_sum = 0.0;
    std::size_t n = 0;
    for (const Eigen::Vector3f& p : window[i].points) {
      const Eigen::Vector3d pa = Ta * p.cast<double>(), pb = Tb * p.cast<double>();
      if (pa.z() <= 0.0 || pb.z() <= 0.0) continue;
      pair_sum += (camera.project(pa) - camera.project(pb)).norm();
      ++n;
    }
    if (n == 0) continue;
    sum += pair_sum / static_cast<double>(n);
    ++counted;
  }
  return counted == 0 ? 0.0 : sum / static_cast<double>(counted);
}

// The offset test on the window's usable pairs (see the header).
void testOffsets(const std::vector<ImageOffset>& offsets, const std::vector<std::size_t>& candidates,
                 double threshold_px, const DriftConfig& drift, DriftWindowTest& out) {
  std::vector<double> across, down;
  for (std::size_t i : candidates) {
    if (offsets[i].loss_px > threshold_px) continue;  // no offset explains this pair
    across.push_back(offsets[i].offset_px.x());
    down.push_back(offsets[i].offset_px.y());
  }
  out.offset_pairs = across.size();
  out.offset_px = Eigen::Vector2d(hodgesLehmann(across), hodgesLehmann(down));
  out.offset_p_value = Eigen::Vector2d(signedRankTestTwoSided(across).p_value,
                                       signedRankTestTwoSided(down).p_value);
  const Eigen::Vector2d min_offset(drift.min_offset_x_px, drift.min_offset_y_px);
  double counted_p = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    if (out.offset_p_value[axis] < drift.significance &&
        std::abs(out.offset_px[axis]) >= min_offset[axis]) {
      out.offset_changed = true;
      counted_p = std::min(counted_p, out.offset_p_value[axis]);
    }
  }
  out.changed_p_value = out.significant && out.large ? out.p_value
                        : out.offset_changed         ? counted_p
                                                     : out.p_value;
}

DriftWindowTest testWindow(const CameraModel& camera, const std::vector<CalibrationPair>& window,
                           const Extrinsic& reference, const DriftConfig& drift,
                           const CalibrationConfig& calibration,
                           const std::vector<ImageOffset>* known_offsets) {
  drift.validate();
  calibration.validate();
  if (window.size() < 2 * static_cast<std::size_t>(drift.folds)) {
    throw std::invalid_argument("drift test: the window has " + std::to_string(window.size()) +
                                " pairs; it needs at least " + std::to_string(2 * drift.folds));
  }
  if (known_offsets && known_offsets->size() != window.size()) {
    throw std::invalid_argument("drift test: " + std::to_string(known_offsets->size()) +
                                " image offsets for a window of " +
                                std::to_string(window.size()) + " pairs");
  }
  const LossEvaluator nearest(
      camera, window, LossConfig{calibration.behind_camera_penalty_c1, PixelRule::kNearest});
  const LossEvaluator bilinear = nearest.withPixelRule(PixelRule::kBilinear);
  const LocalRefinement refinement(bilinear, driftRefineConfig(drift, calibration),
                                   calibration.num_threads);
  const std::vector<std::size_t> candidates =
      refinementCandidates(nearest, calibration.refine.exclude_truncated);

  DriftWindowTest out;
  out.pairs_in_window = window.size();
  const LocalFit full = fitLocally(nearest, refinement, reference, candidates, calibration);
  out.fit = full.estimate;
  out.evaluations = full.evaluations;
  out.pairs_used = full.used.size();
  out.change = driftChange(full.estimate, reference);
  out.loss_reference = nearest.loss(reference, full.used);
  out.loss_fit = nearest.loss(full.estimate, full.used);
  out.image_shift_px = meanImageShiftPx(camera, window, full.used, full.estimate, reference);
  out.large = out.loss_reference >= drift.min_loss_ratio * out.loss_fit &&
              (out.change.angle_deg >= drift.min_rotation_deg ||
               out.change.distance_cm >= drift.min_translation_cm);

  // Cross-fitting: fold k = every folds-th candidate in time order, so each fold spans the
  // whole window (a change inside the window shows in every fold alike).
  const double threshold = calibration.outlier.threshold_px;
  std::vector<double> differences;
  for (int k = 0; k < drift.folds; ++k) {
    std::vector<std::size_t> train, held_out;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      (static_cast<int>(j % drift.folds) == k ? held_out : train).push_back(candidates[j]);
    }
    const LocalFit fold = fitLocally(nearest, refinement, reference, train, calibration);
    out.evaluations += fold.evaluations;
    for (std::size_t i : held_out) {
      const double at_reference = bilinear.pairLoss(i, reference);
      const double at_fit = bilinear.pairLoss(i, fold.estimate);
      if (std::min(at_reference, at_fit) > threshold) continue;  // neither explains this pair
      differences.push_back(at_reference - at_fit);
    }
  }
  const SignedRankResult test = signedRankTestGreater(differences);
  out.held_out_pairs = test.n;
  out.p_value = test.p_value;
  out.significant = test.n > 0 && test.p_value < drift.significance;

  std::vector<ImageOffset> offsets;
  if (known_offsets) {
    offsets = *known_offsets;
  } else {
    for (std::size_t i = 0; i < window.size(); ++i) {
      offsets.push_back(pairImageOffset(bilinear, i, reference, {}, calibration.num_threads));
    }
  }
  testOffsets(offsets, candidates, threshold, drift, out);
  return out;
}

}  // namespace

DriftChange driftChange(const Extrinsic& fit, const Extrinsic& reference) {
  DriftChange c;
  const Eigen::Matrix3d delta = fit.rotationMatrix() * reference.rotationMatrix().transpose();
  c.rotation_deg = matrixToRodrigues(delta) * kDegPerRad;
  c.translation_cm = (fit.translation - reference.translation) * 100.0;
  c.angle_deg = c.rotation_deg.norm();
  c.distance_cm = c.translation_cm.norm();
  return c;
}

RefineConfig driftRefineConfig(const DriftConfig& drift, const CalibrationConfig& calibration) {
  RefineConfig refine = calibration.refine;
  refine.max_evaluations = std::min(refine.max_evaluations, drift.fit_max_evaluations);
  return refine;
}

DriftWindowTest testDriftWindow(const CameraModel& camera,
                                const std::vector<CalibrationPair>& window,
                                const Extrinsic& reference, const DriftConfig& drift,
                                const CalibrationConfig& calibration) {
  return testWindow(camera, window, reference, drift, calibration, nullptr);
}

DriftWindowTest testDriftWindow(const CameraModel& camera,
                                const std::vector<CalibrationPair>& window,
                                const Extrinsic& reference, const DriftConfig& drift,
                                const CalibrationConfig& calibration,
                                const std::vector<ImageOffset>& offsets) {
  return testWindow(camera, window, reference, drift, calibration, &offsets);
}

}  // namespace thermal_lidar_calibration
