#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"

namespace thermal_lidar_calibration {
namespace detection {

const ParameterRanges<LidarGroundConfig>& LidarGroundConfig::ranges() {
  static const auto ranges = ParameterRanges<LidarGroundConfig>()
      .add("lidar_max_tilt_deg", &LidarGroundConfig::max_tilt_deg, closedRange(0, 60))
      .add("lidar_level_radius_m", &LidarGroundConfig::level_radius_m, aboveRange(1, 200))
      .add("lidar_ground_sectors", &LidarGroundConfig::sectors, IntRange{4, 3600})
      .add("lidar_ground_bin_m", &LidarGroundConfig::bin_m, closedRange(0.1, 20))
      .add("lidar_ground_max_slope_deg", &LidarGroundConfig::max_slope_deg, closedRange(0, 45))
      .add("lidar_ground_max_step_m", &LidarGroundConfig::max_step_m, closedRange(0, 2))
      .add("lidar_ground_tolerance_m", &LidarGroundConfig::tolerance_m, closedRange(0, 2))
      .add("lidar_ground_object_spread_m", &LidarGroundConfig::object_spread_m, aboveRange(0, 10));
  return ranges;
}

void LidarGroundConfig::validate() const {
  ranges().check(*this);
}

const ParameterRanges<LidarPersonConfig>& LidarPersonConfig::ranges() {
  static const auto ranges = ParameterRanges<LidarPersonConfig>()
      .add("lidar_min_range_m", &LidarPersonConfig::min_range_m, closedRange(0, 1000))
      .add("lidar_max_range_m", &LidarPersonConfig::max_range_m, aboveRange(0, 1000))
      .add("lidar_min_azimuth_deg", &LidarPersonConfig::min_azimuth_deg, closedRange(-180, 180))
      .add("lidar_max_azimuth_deg", &LidarPersonConfig::max_azimuth_deg, closedRange(-180, 180))
      .add("lidar_view_top_margin_deg", &LidarPersonConfig::view_top_margin_deg, closedRange(0, 10))
      .add("lidar_max_object_height_m", &LidarPersonConfig::max_object_height_m, aboveRange(0, 100))
      .add("lidar_cluster_cell_m", &LidarPersonConfig::cluster_cell_m, closedRange(0.02, 2))
      .add("lidar_max_split_extent_m", &LidarPersonConfig::max_split_extent_m, closedRange(0, 100))
      .add("lidar_split_tolerance_m", &LidarPersonConfig::split_tolerance_m, closedRange(0.01, 1))
      .add("lidar_head_dip_m", &LidarPersonConfig::head_dip_m, closedRange(0.01, 2))
      .add("lidar_min_height_m", &LidarPersonConfig::min_height_m, closedRange(0, 10))
      .add("lidar_max_height_m", &LidarPersonConfig::max_height_m, aboveRange(0, 10))
      .add("lidar_max_bottom_m", &LidarPersonConfig::max_bottom_m, closedRange(0, 10))
      .add("lidar_min_width_m", &LidarPersonConfig::min_width_m, closedRange(0, 20))
      .add("lidar_max_width_m", &LidarPersonConfig::max_width_m, aboveRange(0, 20))
      .add("lidar_max_depth_m", &LidarPersonConfig::max_depth_m, aboveRange(0, 20))
      .add("lidar_min_height_to_width", &LidarPersonConfig::min_height_to_width, closedRange(0, 100))
      .add("lidar_post_max_width_m", &LidarPersonConfig::post_max_width_m, closedRange(0, 20))
      .add("lidar_post_leg_to_torso_ratio", &LidarPersonConfig::post_leg_to_torso_ratio, aboveRange(0, 1))
      .add("lidar_post_max_head_ratio", &LidarPersonConfig::post_max_head_ratio, closedRange(0, 1))
      .add("lidar_narrow_width_m", &LidarPersonConfig::narrow_width_m, closedRange(0, 20))
      .add("lidar_narrow_min_depth_m", &LidarPersonConfig::narrow_min_depth_m, closedRange(0, 20))
      .add("lidar_narrow_leg_margin_m", &LidarPersonConfig::narrow_leg_margin_m, closedRange(0, 20))
      .add("lidar_min_person_height_m", &LidarPersonConfig::min_person_height_m, closedRange(0, 3))
      .add("lidar_row_gap_factor", &LidarPersonConfig::row_gap_factor, closedRange(0, 100))
      .add("lidar_min_points", &LidarPersonConfig::min_points, IntRange{1, 1000000})
      .add("lidar_min_points_at_10m", &LidarPersonConfig::min_points_at_10m, closedRange(0, 1e6));
  return ranges;
}

void LidarPersonConfig::validate() const {
  ranges().check(*this);
  requireOrdered("lidar_min_range_m", min_range_m, "lidar_max_range_m", max_range_m, true);
  requireOrdered("lidar_min_azimuth_deg", min_azimuth_deg, "lidar_max_azimuth_deg", max_azimuth_deg, true);
  requireOrdered("lidar_min_height_m", min_height_m, "lidar_max_height_m", max_height_m, true);
  requireOrdered("lidar_min_width_m", min_width_m, "lidar_max_width_m", max_width_m, true);
}

void LidarDetectorConfig::validate() const {
  ground.validate();
  person.validate();
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
