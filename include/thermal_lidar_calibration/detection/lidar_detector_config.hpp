#pragma once
// Settings of the LiDAR person detector. The member initialisers are the defaults; every
// threshold carries its unit and allowed range, and validate() names the key, the value and the
// range of the first bad one (keys = the flat parameter keys of config/default.yaml).

#include "thermal_lidar_calibration/core/parameter_range.hpp"

namespace thermal_lidar_calibration {
namespace detection {

struct LidarGroundConfig {
  // Levelling: a plane through the lowest points near the sensor takes out the mount's tilt.
  double max_tilt_deg = 30.0;     // lidar_max_tilt_deg: largest mount tilt accepted from the levelling fit, deg; [0, 60]
  double level_radius_m = 20.0;   // lidar_level_radius_m: lowest points within this horizontal range fit the plane, m; (1, 200]
  // Local ground: lowest points per (azimuth sector, range bin), followed outward per sector.
  int sectors = 120;              // lidar_ground_sectors: azimuth sectors over 360 deg; integer [4, 3600]
  double bin_m = 1.0;             // lidar_ground_bin_m: range bin length, m; [0.1, 20]
  double max_slope_deg = 12.0;    // lidar_ground_max_slope_deg: steepest ground slope followed between bins, deg; [0, 45]
  double max_step_m = 0.12;       // lidar_ground_max_step_m: height jump accepted between neighbouring ground bins besides the slope, m; [0, 2]
  double tolerance_m = 0.15;      // lidar_ground_tolerance_m: points up to this above the local ground are ground, m; [0, 2]
  double object_spread_m = 0.4;   // lidar_ground_object_spread_m: a cell whose points span more than this in height holds an object; its lowest point anchors the ground only within lidar_ground_tolerance_m of the predicted ground, m; (0, 10]
  static const ParameterRanges<LidarGroundConfig>& ranges();  // checked by validate()
  void validate() const;
};

struct LidarPersonConfig {
  double min_range_m = 1.0;       // lidar_min_range_m: nearest person centre (horizontal), m; [0, 1000], below lidar_max_range_m
  double max_range_m = 30.0;      // lidar_max_range_m: farthest person centre (horizontal), m; (0, 1000]
  // Bearing window of person centres, deg in the levelled sensor frame (0 = +x, positive towards
  // +y). Set it to the camera's field of view (with a margin) so that the LiDAR counts only the
  // people the camera can see: the frame gate compares the two counts.
  double min_azimuth_deg = -180.0;  // lidar_min_azimuth_deg: deg; [-180, 180], below lidar_max_azimuth_deg
  double max_azimuth_deg = 180.0;   // lidar_max_azimuth_deg: deg; [-180, 180]
  // An object whose highest point lies within view_top_margin_deg below the top of the scan's
  // view (detection/scan_view_top.hpp) may go on above it (a trunk, a post under an HDL-64E's
  // +2 deg top beam): its height is unknown, it is not a person. 0.2 deg is half the finest beam
  // spacing of common sensors (HDL-64E upper block ~0.4 deg); a person's head is below the top
  // beam by degrees (HDL-64E at 1.73 m: 2 deg at 9 m and more nearer and farther), under an
  // HDL-32E's or a VLP-16's top beam by 10 deg or more.
  double view_top_margin_deg = 0.2;  // lidar_view_top_margin_deg: deg; 0 = off; [0, 10]
  double max_object_height_m = 3.0;  // lidar_max_object_height_m: points higher above the ground are ignored, m; (0, 100]
  double cluster_cell_m = 0.2;    // lidar_cluster_cell_m: 2-D grid cell joining above-ground points into objects, m; [0.02, 2]
  double max_split_extent_m = 6.0;// lidar_max_split_extent_m: objects too big for one person but at most this wide and deep are searched for people standing close together, m; [0, 100]
  double split_tolerance_m = 0.1; // lidar_split_tolerance_m: horizontal gap that separates people in such an object (PCL Euclidean clustering), m; [0.01, 1]
  double head_dip_m = 0.15;       // lidar_head_dip_m: people touching side by side are split where the height profile across the line of sight dips this far below both heads, m; [0.01, 2]
  double min_height_m = 1.1;      // lidar_min_height_m: top of a person above the local ground, m; [0, 10], below lidar_max_height_m
  double max_height_m = 2.2;      // lidar_max_height_m: m; (0, 10]
  double max_bottom_m = 0.7;      // lidar_max_bottom_m: lowest point of a person above the ground (legs reach down), m; [0, 10]
  double min_width_m = 0.12;      // lidar_min_width_m: extent across the line of sight (a person side on ~0.15-0.2), m; [0, 20], below lidar_max_width_m
  double max_width_m = 1.0;       // lidar_max_width_m: m; (0, 20]
  double max_depth_m = 0.9;       // lidar_max_depth_m: extent along the line of sight, m; (0, 20]
  double min_height_to_width = 1.4;  // lidar_min_height_to_width: top height / width (a bush is squat); [0, 100]
  // A post: at most post_max_width_m wide, its leg zone (20-45 % of the height) as wide as its
  // torso zone (50-85 %) within a ratio r in [post_leg_to_torso_ratio, 1 / that], and no head
  // zone (above 85 %) narrower than post_max_head_ratio times the torso zone. A standing
  // person's legs are ~0.5-0.7 of the torso; a person walking across the view is wider than a
  // post or has legs wider than the torso, except at the moments of its stride when they are as
  // wide, and a person whose legs are hidden reads as straight too: the head tells them from a
  // post (people refused as posts before the head test: head / torso median 0.5 on the synthetic
  // drives; the posts 0.67 or more in 9 of 10 scans). post_max_head_ratio 0 turns it off.
  double post_max_width_m = 0.35;         // lidar_post_max_width_m: m; [0, 20]
  double post_leg_to_torso_ratio = 0.8;   // lidar_post_leg_to_torso_ratio: r; (0, 1]
  double post_max_head_ratio = 0.6;       // lidar_post_max_head_ratio: [0, 1]
  // Narrower than narrow_width_m (a person side on, or a thin post a few columns of points
  // wide), an object is a person only when it is at least narrow_min_depth_m deep along the line
  // of sight (a person side on shows the near arm and shoulder: 0.19-0.34 m on the synthetic
  // drives; a post shows the front half of its girth) or when its legs zone is narrower than its
  // torso zone by the ratio r above AND by narrow_leg_margin_m (about one column of an HDL-32E
  // at 17 m: a post's zones differ by a column at most).
  double narrow_width_m = 0.2;            // lidar_narrow_width_m: m; [0, 20]
  double narrow_min_depth_m = 0.18;       // lidar_narrow_min_depth_m: m; [0, 20]
  double narrow_leg_margin_m = 0.05;      // lidar_narrow_leg_margin_m: m; [0, 20]
  // What the beams must show of an adult, for the sampling they give at the object's range (the
  // spacing of its own rows of points, detection/person_shape.hpp): the highest row is at most
  // one spacing and the ground tolerance below min_person_height_m (the beam above a head passes
  // within one; heights are above the estimated ground, good to its tolerance); the lowest
  // row at most row_gap_factor spacings above the ground tolerance (legs reach the ground: one
  // row may pass between them); no gap between rows wider than row_gap_factor times its
  // neighbouring gaps (one missing row passes). A parked car's rear slice, a bush, a bicycle or
  // a fence fails one of them at an HDL-64E's sampling (0.1 m at 15 m); at a VLP-16's (0.5 m at
  // 15 m) the floors above decide.
  double min_person_height_m = 1.5;  // lidar_min_person_height_m: the smallest adult looked for, m; [0, 3]
  double row_gap_factor = 2.5;       // lidar_row_gap_factor: in row spacings; 0 = off; [0, 100]
  int min_points = 5;             // lidar_min_points: points on a person at any range; integer [1, 1000000]
  double min_points_at_10m = 20.0;// lidar_min_points_at_10m: points on a person at 10 m, scaled with (10 m / range)^2; [0, 1e6]
  static const ParameterRanges<LidarPersonConfig>& ranges();  // checked by validate()
  void validate() const;
};

struct LidarDetectorConfig {
  LidarGroundConfig ground;
  LidarPersonConfig person;
  void validate() const;  // throws std::invalid_argument naming key, value and range
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
