#pragma once
// One test of the drift watch: does the extrinsic in use (the reference) still fit the latest
// window of kept pairs, or has the rig changed by more than this window can resolve?
//
// The fit: the calibration's local refinement alone (no evolution), started at the reference,
// on the window's pairs (people cut by the image border left out, as in the calibration), with
// the same inlier re-selection (Eq. 1 <= threshold_sample_px).
//
// The test (the change must be larger than the window's uncertainty): a fit always moves a
// little towards its own pairs' noise, so its loss on those pairs says nothing. Instead the
// window is split into `folds` interleaved folds; each fold's pairs are scored by a fit made
// WITHOUT them, against the reference (cross-fitting). If the rig has not changed, a fit on
// fewer pairs predicts unseen pairs no better than the reference (worse, by its own noise); if
// it has, the held-out pairs fit the new pose better, pair after pair. The per-pair loss
// differences (sub-pixel rule) go to a one-sided Wilcoxon signed-rank test. Pairs that neither
// pose explains (Eq. 1 above the threshold at both: mismatched people) are left out. A window
// counts as changed when that test is significant AND the change matters: the reference's loss
// on the window is several times the fit's, and the change reaches the size thresholds. The
// held-out test alone is not enough: the folds share the window's few scenes, and each scene
// has its own loss optimum a few tenths of a degree from the truth, a real but small effect
// (drift_config.hpp).
//
// The offset test (a window counts as changed when either test says so): each pair's image
// offset against the reference (image_offset.hpp), the pan/tilt that centres its points in its
// mask, needs no fit and so has none of a fit's wander. Across the image and down it
// separately, the window's offsets (pairs the fit may use and that some offset explains: Eq. 1
// within the threshold) go to a two-sided signed-rank test against zero; a change is a
// significant offset whose Hodges-Lehmann centre reaches monitor_min_offset_x_px (or _y_px).

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/image_offset.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {

// The fit against the reference per camera axis (x right, y down, z forward): the rotation
// R_fit R_reference^T as a rotation vector, and t_fit - t_reference.
struct DriftChange {
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();
  Eigen::Vector3d translation_cm = Eigen::Vector3d::Zero();
  double angle_deg = 0.0;    // |rotation_deg|: the whole rotation
  double distance_cm = 0.0;  // |translation_cm|
};
DriftChange driftChange(const Extrinsic& fit, const Extrinsic& reference);

struct DriftWindowTest {
  Extrinsic fit;                 // the window's fit from the reference
  DriftChange change;            // fit against the reference
  double loss_reference = 0.0;   // Eq. (3), nearest rule, at the reference, on the fit's pairs
  double loss_fit = 0.0;         // the same at the fit
  // How far the fit moves the people's LiDAR points in the image against the reference: the
  // mean over the fit's pairs of each pair's mean shift, px. What the change does where it
  // can be seen (a shift along a direction the window cannot resolve moves little).
  double image_shift_px = 0.0;
  std::size_t pairs_in_window = 0;
  std::size_t pairs_used = 0;    // the fit's inliers
  std::size_t held_out_pairs = 0;  // differences in the signed-rank test
  double p_value = 1.0;          // one-sided: the held-out fits beat the reference
  bool significant = false;      // p_value < significance
  // loss_reference >= min_loss_ratio * loss_fit, and angle >= min_rotation_deg or distance >=
  // min_translation_cm: the change matters.
  bool large = false;
  // The offset test: the Hodges-Lehmann centre of the window's image offsets against the
  // reference (x across, y down the image), the two-sided signed-rank p-values of each axis,
  // and the pairs in it.
  Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();
  Eigen::Vector2d offset_p_value = Eigen::Vector2d::Ones();
  std::size_t offset_pairs = 0;
  // An axis with offset_p_value < significance and |offset_px| >= min_offset_*_px.
  bool offset_changed = false;
  bool changed() const { return (significant && large) || offset_changed; }
  // The p-value of what made the window count as changed: the held-out test's when it counted,
  // else the smallest of the offset axes that counted (p_value when nothing counted).
  double changed_p_value = 1.0;
  std::uint64_t evaluations = 0; // loss evaluations of all fits
};

// `window` in time order. Throws std::invalid_argument on a bad config or fewer than
// 2 * folds pairs. Deterministic: no random draw, and the loss sums do not depend on the
// thread count.
// The refinement settings of the drift fits: the calibration's, within the monitor's budget.
RefineConfig driftRefineConfig(const DriftConfig& drift, const CalibrationConfig& calibration);

DriftWindowTest testDriftWindow(const CameraModel& camera,
                                const std::vector<CalibrationPair>& window,
                                const Extrinsic& reference, const DriftConfig& drift,
                                const CalibrationConfig& calibration);
// The same with each window pair's image offset against `reference` already known (the monitor
// works each pair's out once, when it arrives): `offsets[i]` for window[i]. Throws
// std::invalid_argument when the sizes differ.
DriftWindowTest testDriftWindow(const CameraModel& camera,
                                const std::vector<CalibrationPair>& window,
                                const Extrinsic& reference, const DriftConfig& drift,
                                const CalibrationConfig& calibration,
                                const std::vector<ImageOffset>& offsets);

}  // namespace thermal_lidar_calibration
