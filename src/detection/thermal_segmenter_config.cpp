#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace detection {

const ParameterRanges<ThermalSegmenterConfig>& ThermalSegmenterConfig::ranges() {
  static const auto ranges = ParameterRanges<ThermalSegmenterConfig>()
      .add("kelvin_per_count", &ThermalSegmenterConfig::kelvin_per_count, closedRange(0, 10))
      .add("kelvin_offset", &ThermalSegmenterConfig::kelvin_offset, closedRange(-10000, 10000))
      .add("thermal_body_min_k", &ThermalSegmenterConfig::body_min_k, closedRange(150, 400))
      .add("thermal_body_max_k", &ThermalSegmenterConfig::body_max_k, aboveRange(150, 500))
      .add("thermal_min_contrast_k", &ThermalSegmenterConfig::min_contrast_k, closedRange(0, 100))
      .add("thermal_relative_threshold", &ThermalSegmenterConfig::relative_threshold, aboveRange(0, 1))
      .add("thermal_relative_tail_percentile", &ThermalSegmenterConfig::relative_tail_percentile, closedRange(50, 100))
      .add("thermal_relative_min_contrast_noise", &ThermalSegmenterConfig::relative_min_contrast_noise, closedRange(0, 1000))
      .add("thermal_relative_min_core", &ThermalSegmenterConfig::relative_min_core, closedRange(0, 1))
      .add("thermal_background_step_px", &ThermalSegmenterConfig::background_step_px, IntRange{1, 64})
      .add("thermal_open_radius_px", &ThermalSegmenterConfig::open_radius_px, IntRange{0, 10})
      .add("thermal_close_radius_px", &ThermalSegmenterConfig::close_radius_px, IntRange{0, 10})
      .add("thermal_restore_px", &ThermalSegmenterConfig::restore_px, IntRange{0, 50})
      .add("thermal_border_margin_px", &ThermalSegmenterConfig::border_margin_px, IntRange{0, 1000})
      .add("thermal_camera_hfov_deg", &ThermalSegmenterConfig::camera_hfov_deg, aboveRange(0, 170))
      .add("thermal_max_range_m", &ThermalSegmenterConfig::max_range_m, aboveRange(0, 10000))
      .add("thermal_min_person_height_m", &ThermalSegmenterConfig::min_person_height_m, closedRange(0, 3))
      .add("thermal_min_person_area_m2", &ThermalSegmenterConfig::min_person_area_m2, closedRange(0, 5))
      .add("thermal_min_area_px", &ThermalSegmenterConfig::min_area_px, IntRange{1, 10000000})
      .add("thermal_max_area_fraction", &ThermalSegmenterConfig::max_area_fraction, aboveRange(0, 1))
      .add("thermal_min_height_px", &ThermalSegmenterConfig::min_height_px, IntRange{1, 100000})
      .add("thermal_min_aspect", &ThermalSegmenterConfig::min_aspect, aboveRange(0, 100))
      .add("thermal_max_aspect", &ThermalSegmenterConfig::max_aspect, aboveRange(0, 100))
      .add("thermal_min_fill", &ThermalSegmenterConfig::min_fill, closedRange(0, 1))
      .add("thermal_max_fill", &ThermalSegmenterConfig::max_fill, closedRange(0, 1))
      .add("thermal_straight_min_aspect", &ThermalSegmenterConfig::straight_min_aspect, aboveRange(0, 100))
      .add("thermal_straight_ratio", &ThermalSegmenterConfig::straight_ratio, aboveRange(0, 1))
      .add("thermal_max_neck_ratio", &ThermalSegmenterConfig::max_neck_ratio, closedRange(0, 10))
      .add("thermal_split_max_aspect", &ThermalSegmenterConfig::split_max_aspect, aboveRange(0, 100))
      .add("thermal_head_dip_fraction", &ThermalSegmenterConfig::head_dip_fraction, aboveRange(0, 1))
      .add("thermal_size_history", &ThermalSegmenterConfig::size_history, IntRange{0, 100000})
      .add("thermal_size_min_samples", &ThermalSegmenterConfig::size_min_samples, IntRange{10, 100000})
      .add("thermal_size_min_ratio", &ThermalSegmenterConfig::size_min_ratio, closedRange(0, 1));
  return ranges;
}

void ThermalSegmenterConfig::validate() const {
  ranges().check(*this);
  requireOrdered("thermal_body_min_k", body_min_k, "thermal_body_max_k", body_max_k, true);
  requireOrdered("thermal_min_aspect", min_aspect, "thermal_max_aspect", max_aspect, false);
  requireOrdered("thermal_min_fill", min_fill, "thermal_max_fill", max_fill, false);
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
