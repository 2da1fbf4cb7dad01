#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include "config_checks.hpp"

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace detection {

using checks::Bound;
using checks::requireRange;

// Per-key ranges as in the parameter table (src/app/parameters/detection_parameter_table.cpp), then the
// rules across keys.
void ThermalSegmenterConfig::validate() const {
  requireRange("kelvin_per_count", kelvin_per_count, 0.0, 10.0);
  requireRange("kelvin_offset", kelvin_offset, -10000.0, 10000.0);
  requireRange("thermal_body_min_k", body_min_k, 150.0, 400.0);
  requireRange("thermal_body_max_k", body_max_k, 150.0, 500.0, Bound::kOpen);
  requireRange("thermal_min_contrast_k", min_contrast_k, 0.0, 100.0);
  requireRange("thermal_relative_threshold", relative_threshold, 0.0, 1.0, Bound::kOpen);
  requireRange("thermal_relative_tail_percentile", relative_tail_percentile, 50.0, 100.0);
  requireRange("thermal_relative_min_contrast_noise", relative_min_contrast_noise, 0.0, 1000.0);
  requireRange("thermal_relative_min_core", relative_min_core, 0.0, 1.0);
  requireRange("thermal_background_step_px", background_step_px, 1, 64);
  requireRange("thermal_open_radius_px", open_radius_px, 0, 10);
  requireRange("thermal_close_radius_px", close_radius_px, 0, 10);
  requireRange("thermal_border_margin_px", border_margin_px, 0, 1000);
  requireRange("thermal_camera_hfov_deg", camera_hfov_deg, 0.0, 170.0, Bound::kOpen);
  requireRange("thermal_max_range_m", max_range_m, 0.0, 10000.0, Bound::kOpen);
  requireRange("thermal_min_person_height_m", min_person_height_m, 0.0, 3.0);
  requireRange("thermal_min_person_area_m2", min_person_area_m2, 0.0, 5.0);
  requireRange("thermal_min_area_px", min_area_px, 1, 10000000);
  requireRange("thermal_max_area_fraction", max_area_fraction, 0.0, 1.0, Bound::kOpen);
  requireRange("thermal_min_height_px", min_height_px, 1, 100000);
  requireRange("thermal_min_aspect", min_aspect, 0.0, 100.0, Bound::kOpen);
  requireRange("thermal_max_aspect", max_aspect, 0.0, 100.0, Bound::kOpen);
  requireRange("thermal_min_fill", min_fill, 0.0, 1.0);
  requireRange("thermal_max_fill", max_fill, 0.0, 1.0);
  requireRange("thermal_straight_min_aspect", straight_min_aspect, 0.0, 100.0, Bound::kOpen);
  requireRange("thermal_straight_ratio", straight_ratio, 0.0, 1.0, Bound::kOpen);
  requireRange("thermal_max_neck_ratio", max_neck_ratio, 0.0, 10.0);
  requireRange("thermal_split_max_aspect", split_max_aspect, 0.0, 100.0, Bound::kOpen);
  requireRange("thermal_head_dip_fraction", head_dip_fraction, 0.0, 1.0, Bound::kOpen);
  requireRange("thermal_size_history", size_history, 0, 100000);
  requireRange("thermal_size_min_samples", size_min_samples, 10, 100000);
  requireRange("thermal_size_min_ratio", size_min_ratio, 0.0, 1.0);
  checks::requireOrdered("thermal_body_min_k", body_min_k, "thermal_body_max_k", body_max_k, true);
  checks::requireOrdered("thermal_min_aspect", min_aspect, "thermal_max_aspect", max_aspect, false);
  checks::requireOrdered("thermal_min_fill", min_fill, "thermal_max_fill", max_fill, false);
}

ThermalScale parseThermalScale(const std::string& text) {
  if (text == "auto") return ThermalScale::kAuto;
  if (text == "relative") return ThermalScale::kRelative;
  throw std::invalid_argument("parameter 'thermal_scale' = " + text + ": must be one of {auto, relative}");
}

const char* toString(ThermalScale scale) {
  return scale == ThermalScale::kRelative ? "relative" : "auto";
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
