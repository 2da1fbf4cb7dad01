#include "thermal_lidar_calibration/core/calibration_config.hpp"

#include "thermal_lidar_calibration/core/parameter_range.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
using detail::requireRange;

void LossConfig::validate() const {
  requireRange("behind_camera_penalty_c1", behind_camera_penalty_c1, 0.0, 1e6, true);
  requireRange("margin_px", margin_px, 0.0, 1000.0);
}

void EvolutionConfig::validate() const {
  requireRange("population_size", population_size, 2, 100000);
  requireRange("max_iterations", max_iterations, 1, 100000);
  requireRange("rotation_interval_rad", rotation_interval_rad, 0.0, 10.0, true);
  requireRange("translation_interval_m", translation_interval_m, 0.0, 1000.0, true);
  requireRange("elite_fraction", elite_fraction, 0.0, 1.0);
  requireRange("crossover_fraction", crossover_fraction, 0.0, 1.0);
  if (elite_fraction + crossover_fraction > 1.0 + 1e-12) {
    throw std::invalid_argument("parameters 'elite_fraction' + 'crossover_fraction' = " +
                                std::to_string(elite_fraction + crossover_fraction) +
                                ": must not exceed 1");
  }
  requireRange("initial_population_factor", initial_population_factor, 1, 1000);
  requireRange("sigma_rot_rad", sigma_rot_rad, 0.0, 3.5, true);
  requireRange("sigma_trans_m", sigma_trans_m, 0.0, 100.0, true);
  requireRange("min_inside_fraction", min_inside_fraction, 0.0, 1.0);
}

void OutlierConfig::validate() const {
  requireRange("min_sample_large", min_sample_large, 1, 100000);
  requireRange("min_sample_small", min_sample_small, 1, 100000);
  requireRange("min_sample_switch", min_sample_switch, 1, 100000);
  requireRange("outlier_iterations", iterations, 0, 1000);
  requireRange("ratio_solution", ratio_solution, 0.0, 1.0);
  requireRange("threshold_sample_px", threshold_px, 0.0, 1e6, true);
}

void RefineConfig::validate() const {
  requireRange("refine_initial_step_rot_rad", initial_step_rot_rad, 0.0, 1.0, true);
  requireRange("refine_initial_step_trans_m", initial_step_trans_m, 0.0, 10.0, true);
  requireRange("refine_min_step_rot_rad", min_step_rot_rad, 0.0, initial_step_rot_rad, true);
  requireRange("refine_min_step_trans_m", min_step_trans_m, 0.0, initial_step_trans_m, true);
  requireRange("refine_max_evaluations", max_evaluations, 1, 100000000);
}

const char* toString(TimeOffsetMode mode) {
  switch (mode) {
    case TimeOffsetMode::kEstimate: return "estimate";
    case TimeOffsetMode::kFixed: return "fixed";
    case TimeOffsetMode::kNone: return "none";
  }
  return "none";
}

void TimeOffsetConfig::validate() const {
  requireRange("time_offset_max_s", max_s, 0.0, 2.0, true);
  requireRange("time_offset_s", offset_s, -2.0, 2.0);
  if (mode == TimeOffsetMode::kEstimate && std::abs(offset_s) > max_s) {
    throw std::invalid_argument("parameter 'time_offset_s' = " + std::to_string(offset_s) +
                                ": the search starts there, so it must lie within +-time_offset_max_s (" +
                                std::to_string(max_s) + ")");
  }
  requireRange("time_offset_coarse_step_s", coarse_step_s, 0.0, max_s, true);
  requireRange("time_offset_initial_step_s", initial_step_s, 0.0, 1.0, true);
  requireRange("time_offset_min_step_s", min_step_s, 0.0, initial_step_s, true);
  requireRange("time_offset_max_resolution_ms", max_resolution_ms, 0.0, 1e6, true);
  requireRange("time_offset_unresolved_min_gain", unresolved_min_gain, 0.0, 1.0);
}

void VerticalCentringConfig::validate() const {
  requireRange("vertical_centring_margin_px", margin_px, 0.0, 50.0);
  requireRange("vertical_centring_max_mean_cost_px", max_mean_cost_px, 0.0, 1e6);
  requireRange("vertical_centring_tolerance", tolerance, 0.0, 10.0);
  requireRange("vertical_centring_rays", rays, 3, 360);
  requireRange("vertical_centring_iterations", iterations, 1, 100);
  requireRange("vertical_centring_resample_rays", resample_rays, 3, 360);
  requireRange("vertical_centring_resample_bisections", resample_bisections, 1, 30);
  requireRange("vertical_centring_pair_fit_px", pair_fit_px, 0.0, 1e6);
  requireRange("vertical_centring_min_fitting_fraction", min_fitting_fraction, 0.0, 1.0);
}

void CalibrationConfig::validate() const {
  if (algorithm != Algorithm::kPlain && algorithm != Algorithm::kOutlierRejection) {
    throw std::invalid_argument("parameter 'algorithm': must be 1 or 2");
  }
  evolution.validate();
  outlier.validate();
  refine.validate();
  time_offset.validate();
  vertical_centring.validate();
  LossConfig{behind_camera_penalty_c1, PixelRule::kNearest}.validate();
  requireRange("num_threads", num_threads, 0, 1024);
}

}  // namespace thermal_lidar_calibration
