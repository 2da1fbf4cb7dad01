#include "thermal_lidar_calibration/core/calibration_config.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
const ParameterRanges<LossConfig>& LossConfig::ranges() {
  static const auto ranges = ParameterRanges<LossConfig>()
      .add("behind_camera_penalty_c1", &LossConfig::behind_camera_penalty_c1, aboveRange(0, 1e6))
      .add("margin_px", &LossConfig::margin_px, closedRange(0, 1000))
      .add("outline_px", &LossConfig::outline_px, closedRange(0, 1))
      .add("ring_end_weight", &LossConfig::ring_end_weight, closedRange(0, 100));
  return ranges;
}

void LossConfig::validate() const {
  ranges().check(*this);
}

const ParameterRanges<EvolutionConfig>& EvolutionConfig::ranges() {
  static const auto ranges = ParameterRanges<EvolutionConfig>()
      .add("population_size", &EvolutionConfig::population_size, IntRange{2, 100000})
      .add("max_iterations", &EvolutionConfig::max_iterations, IntRange{1, 100000})
      .add("rotation_interval_rad", &EvolutionConfig::rotation_interval_rad, aboveRange(0, 10))
      .add("translation_interval_m", &EvolutionConfig::translation_interval_m, aboveRange(0, 1000))
      .add("elite_fraction", &EvolutionConfig::elite_fraction, closedRange(0, 1))
      .add("crossover_fraction", &EvolutionConfig::crossover_fraction, closedRange(0, 1))
      .add("initial_population_factor", &EvolutionConfig::initial_population_factor, IntRange{1, 1000})
      .add("sigma_rot_rad", &EvolutionConfig::sigma_rot_rad, aboveRange(0, 3.5))
      .add("sigma_trans_m", &EvolutionConfig::sigma_trans_m, aboveRange(0, 100))
      .add("min_inside_fraction", &EvolutionConfig::min_inside_fraction, closedRange(0, 1));
  return ranges;
}

void EvolutionConfig::validate() const {
  ranges().check(*this);
  if (elite_fraction + crossover_fraction > 1.0 + 1e-12) {
    throw std::invalid_argument("parameters 'elite_fraction' + 'crossover_fraction' = " +
                                std::to_string(elite_fraction + crossover_fraction) +
                                ": must not exceed 1");
  }
}

const ParameterRanges<OutlierConfig>& OutlierConfig::ranges() {
  static const auto ranges = ParameterRanges<OutlierConfig>()
      .add("min_sample_large", &OutlierConfig::min_sample_large, IntRange{1, 100000})
      .add("min_sample_small", &OutlierConfig::min_sample_small, IntRange{1, 100000})
      .add("min_sample_switch", &OutlierConfig::min_sample_switch, IntRange{1, 100000})
      .add("outlier_iterations", &OutlierConfig::iterations, IntRange{0, 1000})
      .add("ratio_solution", &OutlierConfig::ratio_solution, closedRange(0, 1))
      .add("threshold_sample_px", &OutlierConfig::threshold_px, aboveRange(0, 1e6));
  return ranges;
}

void OutlierConfig::validate() const {
  ranges().check(*this);
}

const ParameterRanges<RefineConfig>& RefineConfig::ranges() {
  static const auto ranges = ParameterRanges<RefineConfig>()
      .add("refine_initial_step_rot_rad", &RefineConfig::initial_step_rot_rad, aboveRange(0, 1))
      .add("refine_initial_step_trans_m", &RefineConfig::initial_step_trans_m, aboveRange(0, 10))
      .add("refine_min_step_rot_rad", &RefineConfig::min_step_rot_rad, aboveRange(0, 1))
      .add("refine_min_step_trans_m", &RefineConfig::min_step_trans_m, aboveRange(0, 10))
      .add("refine_max_evaluations", &RefineConfig::max_evaluations, IntRange{1, 100000000})
      .add("refine_ring_alias_turns", &RefineConfig::ring_alias_turns, IntRange{0, 5})
      .add("refine_outline_px", &RefineConfig::outline_px, closedRange(0, 1))
      .add("refine_ring_end_weight", &RefineConfig::ring_end_weight, closedRange(0, 100))
      .add("refine_evolution_generations", &RefineConfig::evolution_generations, IntRange{0, 100000})
      .add("refine_evolution_min_share", &RefineConfig::evolution_min_share, closedRange(0, 1));
  return ranges;
}

EvolutionConfig CalibrationConfig::evolutionRun() const {
  EvolutionConfig run = evolution;
  if (refine.mode == RefineMode::kLocal && refine.evolution_generations > 0) {
    run.max_iterations = std::min(run.max_iterations, refine.evolution_generations);
  }
  return run;
}

void RefineConfig::validate() const {
  ranges().check(*this);
  requireRange("refine_min_step_rot_rad", min_step_rot_rad, 0.0, initial_step_rot_rad, true);
  requireRange("refine_min_step_trans_m", min_step_trans_m, 0.0, initial_step_trans_m, true);
}

const char* toString(TimeOffsetMode mode) {
  switch (mode) {
    case TimeOffsetMode::kEstimate: return "estimate";
    case TimeOffsetMode::kFixed: return "fixed";
    case TimeOffsetMode::kNone: return "none";
  }
  return "none";
}

const ParameterRanges<TimeOffsetConfig>& TimeOffsetConfig::ranges() {
  static const auto ranges = ParameterRanges<TimeOffsetConfig>()
      .add("time_offset_max_s", &TimeOffsetConfig::max_s, aboveRange(0, 2))
      .add("time_offset_s", &TimeOffsetConfig::offset_s, closedRange(-2, 2))
      .add("time_offset_coarse_step_s", &TimeOffsetConfig::coarse_step_s, aboveRange(0, 1))
      .add("time_offset_initial_step_s", &TimeOffsetConfig::initial_step_s, aboveRange(0.0, 1.0))
      .add("time_offset_max_resolution_ms", &TimeOffsetConfig::max_resolution_ms, aboveRange(0, 1e6))
      .add("time_offset_unresolved_min_gain", &TimeOffsetConfig::unresolved_min_gain, closedRange(0, 1))
      .add("time_offset_keep_start_sigmas", &TimeOffsetConfig::keep_start_sigmas, closedRange(0, 100));
  return ranges;
}

void TimeOffsetConfig::validate() const {
  ranges().check(*this);
  if (mode == TimeOffsetMode::kEstimate && std::abs(offset_s) > max_s) {
    throw std::invalid_argument("parameter 'time_offset_s' = " + std::to_string(offset_s) +
                                ": the search starts there, so it must lie within +-time_offset_max_s (" +
                                std::to_string(max_s) + ")");
  }
  requireRange("time_offset_coarse_step_s", coarse_step_s, 0.0, max_s, true);
  requireRange("time_offset_min_step_s", min_step_s, 0.0, initial_step_s, true);
}

const ParameterRanges<CalibrationConfig>& CalibrationConfig::ranges() {
  static const auto ranges = ParameterRanges<CalibrationConfig>()
      .add("num_threads", &CalibrationConfig::num_threads, IntRange{0, 1024});
  return ranges;
}

const ParameterRanges<VerticalCentringConfig>& VerticalCentringConfig::ranges() {
  static const auto ranges = ParameterRanges<VerticalCentringConfig>()
      .add("vertical_centring_margin_px", &VerticalCentringConfig::margin_px, closedRange(0, 50))
      .add("vertical_centring_max_mean_cost_px", &VerticalCentringConfig::max_mean_cost_px, closedRange(0, 1e6))
      .add("vertical_centring_tolerance", &VerticalCentringConfig::tolerance, closedRange(0, 10))
      .add("vertical_centring_outlying_fraction", &VerticalCentringConfig::outlying_fraction, closedRange(0, 0.5))
      .add("vertical_centring_rays", &VerticalCentringConfig::rays, IntRange{3, 360})
      .add("vertical_centring_iterations", &VerticalCentringConfig::iterations, IntRange{1, 100})
      .add("vertical_centring_resample_rays", &VerticalCentringConfig::resample_rays, IntRange{3, 360})
      .add("vertical_centring_resample_bisections", &VerticalCentringConfig::resample_bisections, IntRange{1, 30})
      .add("vertical_centring_pair_fit_px", &VerticalCentringConfig::pair_fit_px, closedRange(0, 1e6))
      .add("vertical_centring_min_fitting_fraction", &VerticalCentringConfig::min_fitting_fraction,
           closedRange(0, 1));
  return ranges;
}

// No table rows read these (the centring's settings are not user keys); the ranges still live
// here, in the same one home as the others.
void VerticalCentringConfig::validate() const { ranges().check(*this); }

void CalibrationConfig::validate() const {
  ranges().check(*this);
  if (algorithm != Algorithm::kPlain && algorithm != Algorithm::kOutlierRejection) {
    throw std::invalid_argument("parameter 'algorithm': must be 1 or 2");
  }
  evolution.validate();
  outlier.validate();
  refine.validate();
  time_offset.validate();
  vertical_centring.validate();
  LossConfig{behind_camera_penalty_c1, PixelRule::kNearest}.validate();
}

}  // namespace thermal_lidar_calibration
