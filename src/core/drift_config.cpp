#include "thermal_lidar_calibration/core/drift_config.hpp"

namespace thermal_lidar_calibration {
const ParameterRanges<DriftConfig>& DriftConfig::ranges() {
  static const auto ranges = ParameterRanges<DriftConfig>()
      .add("monitor_window_pairs", &DriftConfig::window_pairs, IntRange{6, 100000})
      .add("monitor_period_pairs", &DriftConfig::period_pairs, IntRange{1, 100000})
      .add("monitor_confirm_windows", &DriftConfig::confirm_windows, IntRange{1, 1000})
      .add("monitor_significance", &DriftConfig::significance, aboveRange(0, 0.5))
      .add("monitor_min_loss_ratio", &DriftConfig::min_loss_ratio, closedRange(1, 1e6))
      .add("monitor_min_rotation_deg", &DriftConfig::min_rotation_deg, closedRange(0, 180))
      .add("monitor_min_translation_cm", &DriftConfig::min_translation_cm, closedRange(0, 1e5))
      .add("monitor_min_offset_x_px", &DriftConfig::min_offset_x_px, closedRange(0, 1e4))
      .add("monitor_min_offset_y_px", &DriftConfig::min_offset_y_px, closedRange(0, 1e4))
      .add("monitor_folds", &DriftConfig::folds, IntRange{2, 100000})
      .add("monitor_update_pairs", &DriftConfig::update_pairs, IntRange{6, 100000})
      .add("monitor_update_full_significance", &DriftConfig::update_full_significance, aboveRange(0, 1))
      .add("monitor_update_uncertainty_resamples", &DriftConfig::update_uncertainty_resamples, IntRange{0, 100000})
      .add("monitor_fit_max_evaluations", &DriftConfig::fit_max_evaluations, IntRange{1, 100000000})
      .add("monitor_max_update_rotation_deg", &DriftConfig::max_update_rotation_deg, closedRange(0, 180))
      .add("monitor_max_update_translation_cm", &DriftConfig::max_update_translation_cm, closedRange(0, 1e5))
      .add("monitor_min_timing_change_ms", &DriftConfig::min_timing_change_ms, closedRange(0, 1e4))
      .add("monitor_timing_explained_fraction", &DriftConfig::timing_explained_fraction, closedRange(0, 1));
  return ranges;
}

void DriftConfig::validate() const {
  ranges().check(*this);
  requireRange("monitor_period_pairs", period_pairs, 1, window_pairs);
  requireRange("monitor_folds", folds, 2, window_pairs / 3);
  if (update_uncertainty_resamples != 0) {
    requireRange("monitor_update_uncertainty_resamples", update_uncertainty_resamples, 2, 100000);
  }
}

}  // namespace thermal_lidar_calibration
