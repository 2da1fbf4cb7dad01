#pragma once
// Settings of the drift watch (INTERFACE "Drift watch"): the rolling window of kept pairs, how
// often it is tested, and what counts as a change. The fits themselves use the calibration's
// refinement settings (CalibrationConfig::refine, threshold_sample_px, c1).

namespace thermal_lidar_calibration {

struct DriftConfig {
  int window_pairs = 30;   // monitor_window_pairs: the latest kept pairs a test looks at
  int period_pairs = 5;    // monitor_period_pairs: a test after this many new pairs
  int confirm_windows = 2; // monitor_confirm_windows: consecutive changed tests for ERROR
  // monitor_significance: a window counts as changed only if the fit beats the reference on
  // pairs it was not fitted on with a one-sided p-value below this (signed-rank test).
  double significance = 1e-3;
  // monitor_min_rotation_deg / monitor_min_translation_cm: ... and only if the change is at
  // least this large (rotation angle, or length of the translation change), so a reference a
  // hair off the data's optimum is not reported as drift.
  double min_rotation_deg = 0.2;
  double min_translation_cm = 1.5;
  int folds = 3;           // monitor_folds: cross-fitting folds of the held-out test
  // monitor_update_pairs: the new extrinsic after a confirmed change is fitted on the pairs
  // since the change; it is final once it rests on this many (a 30-pair window leaves the
  // translation a few cm uncertain on a typical drive, 60 pairs about 1 cm).
  int update_pairs = 60;
  // monitor_fit_max_evaluations: loss evaluations per refinement run of a drift fit (the
  // calibration's refine_max_evaluations when lower). A window fit from the reference needs
  // about a thousand; on a window that cannot pin the pose down the search would otherwise
  // wander along flat directions for the whole calibration budget, at sensor rate.
  int fit_max_evaluations = 3000;
  void validate() const;   // throws std::invalid_argument naming the key and range
};

}  // namespace thermal_lidar_calibration
