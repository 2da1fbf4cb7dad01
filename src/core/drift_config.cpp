#include "thermal_lidar_calibration/core/drift_config.hpp"

#include "thermal_lidar_calibration/core/parameter_range.hpp"

namespace thermal_lidar_calibration {
using detail::requireRange;

void DriftConfig::validate() const {
  requireRange("monitor_window_pairs", window_pairs, 6, 100000);
  requireRange("monitor_period_pairs", period_pairs, 1, window_pairs);
  requireRange("monitor_confirm_windows", confirm_windows, 1, 1000);
  requireRange("monitor_significance", significance, 0.0, 0.5, true);
  requireRange("monitor_min_loss_ratio", min_loss_ratio, 1.0, 1e6);
  requireRange("monitor_min_rotation_deg", min_rotation_deg, 0.0, 180.0);
  requireRange("monitor_min_translation_cm", min_translation_cm, 0.0, 1e5);
  requireRange("monitor_min_offset_x_px", min_offset_x_px, 0.0, 1e4);
  requireRange("monitor_min_offset_y_px", min_offset_y_px, 0.0, 1e4);
  requireRange("monitor_folds", folds, 2, window_pairs / 3);
  requireRange("monitor_update_pairs", update_pairs, 6, 100000);
  requireRange("monitor_update_full_significance", update_full_significance, 0.0, 1.0, true);
  if (update_uncertainty_resamples != 0) {
    requireRange("monitor_update_uncertainty_resamples", update_uncertainty_resamples, 2, 100000);
  }
  requireRange("monitor_fit_max_evaluations", fit_max_evaluations, 1, 100000000);
  requireRange("monitor_max_update_rotation_deg", max_update_rotation_deg, 0.0, 180.0);
  requireRange("monitor_max_update_translation_cm", max_update_translation_cm, 0.0, 1e5);
  requireRange("monitor_min_timing_change_ms", min_timing_change_ms, 0.0, 1e4);
  requireRange("monitor_timing_explained_fraction", timing_explained_fraction, 0.0, 1.0);
}

}  // namespace thermal_lidar_calibration
