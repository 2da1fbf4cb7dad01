#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"

#include "config_checks.hpp"

namespace thermal_lidar_calibration {
namespace detection {

using checks::Bound;
using checks::requireRange;

// Per-key ranges as in the parameter table (src/app/parameters/detection_parameter_table.cpp), then the
// rules across keys.
void LidarGroundConfig::validate() const {
  requireRange("lidar_max_tilt_deg", max_tilt_deg, 0.0, 60.0);
  requireRange("lidar_level_radius_m", level_radius_m, 1.0, 200.0, Bound::kOpen);
  requireRange("lidar_ground_sectors", sectors, 4, 3600);
  requireRange("lidar_ground_bin_m", bin_m, 0.1, 20.0);
  requireRange("lidar_ground_max_slope_deg", max_slope_deg, 0.0, 45.0);
  requireRange("lidar_ground_max_step_m", max_step_m, 0.0, 2.0);
  requireRange("lidar_ground_tolerance_m", tolerance_m, 0.0, 2.0);
  requireRange("lidar_ground_object_spread_m", object_spread_m, 0.0, 10.0, Bound::kOpen);
}

void LidarPersonConfig::validate() const {
  requireRange("lidar_min_range_m", min_range_m, 0.0, 1000.0);
  requireRange("lidar_max_range_m", max_range_m, 0.0, 1000.0, Bound::kOpen);
  requireRange("lidar_min_azimuth_deg", min_azimuth_deg, -180.0, 180.0);
  requireRange("lidar_max_azimuth_deg", max_azimuth_deg, -180.0, 180.0);
  requireRange("lidar_view_top_margin_deg", view_top_margin_deg, 0.0, 10.0);
  requireRange("lidar_max_object_height_m", max_object_height_m, 0.0, 100.0, Bound::kOpen);
  requireRange("lidar_cluster_cell_m", cluster_cell_m, 0.02, 2.0);
  requireRange("lidar_max_split_extent_m", max_split_extent_m, 0.0, 100.0);
  requireRange("lidar_split_tolerance_m", split_tolerance_m, 0.01, 1.0);
  requireRange("lidar_head_dip_m", head_dip_m, 0.01, 2.0);
  requireRange("lidar_min_height_m", min_height_m, 0.0, 10.0);
  requireRange("lidar_max_height_m", max_height_m, 0.0, 10.0, Bound::kOpen);
  requireRange("lidar_max_bottom_m", max_bottom_m, 0.0, 10.0);
  requireRange("lidar_min_width_m", min_width_m, 0.0, 20.0);
  requireRange("lidar_max_width_m", max_width_m, 0.0, 20.0, Bound::kOpen);
  requireRange("lidar_max_depth_m", max_depth_m, 0.0, 20.0, Bound::kOpen);
  requireRange("lidar_min_height_to_width", min_height_to_width, 0.0, 100.0);
  requireRange("lidar_post_max_width_m", post_max_width_m, 0.0, 20.0);
  requireRange("lidar_post_leg_to_torso_ratio", post_leg_to_torso_ratio, 0.0, 1.0, Bound::kOpen);
  requireRange("lidar_post_max_head_ratio", post_max_head_ratio, 0.0, 1.0);
  requireRange("lidar_narrow_width_m", narrow_width_m, 0.0, 20.0);
  requireRange("lidar_narrow_min_depth_m", narrow_min_depth_m, 0.0, 20.0);
  requireRange("lidar_narrow_leg_margin_m", narrow_leg_margin_m, 0.0, 20.0);
  requireRange("lidar_min_person_height_m", min_person_height_m, 0.0, 3.0);
  requireRange("lidar_row_gap_factor", row_gap_factor, 0.0, 100.0);
  requireRange("lidar_min_points", min_points, 1, 1000000);
  requireRange("lidar_min_points_at_10m", min_points_at_10m, 0.0, 1e6);
  checks::requireOrdered("lidar_min_range_m", min_range_m, "lidar_max_range_m", max_range_m, true);
  checks::requireOrdered("lidar_min_azimuth_deg", min_azimuth_deg, "lidar_max_azimuth_deg", max_azimuth_deg, true);
  checks::requireOrdered("lidar_min_height_m", min_height_m, "lidar_max_height_m", max_height_m, true);
  checks::requireOrdered("lidar_min_width_m", min_width_m, "lidar_max_width_m", max_width_m, true);
}

void LidarDetectorConfig::validate() const {
  ground.validate();
  person.validate();
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
