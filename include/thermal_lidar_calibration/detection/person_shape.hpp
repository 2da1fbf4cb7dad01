#pragma once
// Shape of one candidate object in the levelled frame (z up, heights above the local ground) and
// the person test on it: height, how close to the ground it reaches, width across and depth
// along the line of sight, height / width (a bush is squat, a pole thin), and a point count that
// scales with 1 / range^2 as the beam footprint grows.

#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

struct PersonShape {
  int points = 0;
  Eigen::Vector2f centroid_xy = Eigen::Vector2f::Zero();  // levelled frame, m
  float range_m = 0;   // horizontal distance of the centroid
  float top_m = 0;     // highest point above the local ground
  float bottom_m = 0;  // lowest point above the local ground
  float width_m = 0;   // extent across the line of sight
  float depth_m = 0;   // extent along the line of sight
  // Width of the leg zone (20-45 % of the top) over the width of the torso zone (50-85 %):
  // ~0.5-0.7 for a standing person (legs are narrower than shoulders and arms), ~1 for a post;
  // 0 when a zone has no point or is under 2 cm wide (too few rings or columns at long range: the
  // test is then skipped).
  float leg_to_torso_width = 0;
  float leg_width_m = 0;    // the zones' widths across the line of sight (0: no point)
  float torso_width_m = 0;
  float head_width_m = 0;   // above 85 % of the top
  // Elevation of the highest point below the top of the scan's view, deg (scan_view_top.hpp);
  // +infinity when the scan showed no top. Set by the detector, not by measureShape.
  float view_top_gap_deg = std::numeric_limits<float>::infinity();
};

// The rows of points a spinning LiDAR puts on an object: its points grouped by elevation seen
// from the sensor (a new row where the elevation jumps by more than 0.1 deg; beams are >= 0.17
// deg apart on common sensors). Beam spacing differs along the view on many sensors (an HDL-64E's
// two blocks, a VLP-32C's dense middle), so every gap is compared with its neighbours, and the
// top and the bottom with the spacing there, in metres at the object's range.
struct RowProfile {
  int rows = 0;                // the rest is 0 when fewer than 3 rows
  float top_spacing_m = 0;     // between the two highest rows
  float bottom_spacing_m = 0;  // between the two lowest rows
  float largest_hole = 0;      // the largest gap between rows over the larger of its neighbouring gaps
};

enum class ShapeVerdict {
  kPerson,
  kOutOfRange,
  kOutOfView,    // outside the bearing window
  kTooFewPoints,
  kTooLow,
  kTooTall,
  kFloating,     // does not reach down to the ground
  kTooNarrow,    // a pole
  kTooWide,
  kTooDeep,
  kTooSquat,     // height / width too small: a bush, a vehicle
  kStraight,     // narrow, the legs as wide as the torso and no narrower head: a post, a trunk
  kNarrowNoLegs, // narrower than a person from the front, shallow, no legs narrower than the torso: a thin post
  kCutByViewTop, // its top is at the top of the scan's view: it may go on above (a trunk, a post)
  kGapInHeight,  // a gap between its rows the beams would have filled on a person (a car's slice, a fence)
};
const char* toString(ShapeVerdict verdict);

// levelled: levelled-frame points; heights: above the local ground; indices: the object's points.
PersonShape measureShape(const std::vector<Eigen::Vector3f>& levelled, const std::vector<float>& heights,
                         const std::vector<int>& indices);
ShapeVerdict judgeShape(const PersonShape& shape, const LidarPersonConfig& config);
// points: sensor frame; indices: the object's points; range_m: its horizontal range.
RowProfile measureRows(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& indices, float range_m);
// What the beams show of an object that passed judgeShape, for their spacing on it (the
// lidar_min_person_height_m and lidar_row_gap_factor rules): kPerson, kTooLow, kFloating or
// kGapInHeight. An object with fewer than 3 rows is not judged (kPerson).
ShapeVerdict judgeSampling(const PersonShape& shape, const RowProfile& rows, const LidarPersonConfig& config,
                           double ground_tolerance_m);
// The fewest points a person at this horizontal range must have.
double minPersonPoints(double range_m, const LidarPersonConfig& config);

}  // namespace detection
}  // namespace thermal_lidar_calibration
