#include "thermal_lidar_calibration/detection/person_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace detection {

const char* toString(ShapeVerdict verdict) {
  switch (verdict) {
    case ShapeVerdict::kPerson: return "person";
    case ShapeVerdict::kOutOfRange: return "out_of_range";
    case ShapeVerdict::kOutOfView: return "out_of_view";
    case ShapeVerdict::kTooFewPoints: return "too_few_points";
    case ShapeVerdict::kTooLow: return "too_low";
    case ShapeVerdict::kTooTall: return "too_tall";
    case ShapeVerdict::kFloating: return "floating";
    case ShapeVerdict::kTooNarrow: return "too_narrow";
    case ShapeVerdict::kTooWide: return "too_wide";
    case ShapeVerdict::kTooDeep: return "too_deep";
    case ShapeVerdict::kTooSquat: return "too_squat";
    case ShapeVerdict::kStraight: return "straight";
    case ShapeVerdict::kNarrowNoLegs: return "narrow_no_legs";
    case ShapeVerdict::kCutByViewTop: return "cut_by_view_top";
    case ShapeVerdict::kGapInHeight: return "gap_in_height";
  }
  return "unknown";
}

PersonShape measureShape(const std::vector<Eigen::Vector3f>& levelled, const std::vector<float>& heights,
                         const std::vector<int>& indices) {
  PersonShape shape;
  shape.points = static_cast<int>(indices.size());
  if (indices.empty()) return shape;
  Eigen::Vector2f sum = Eigen::Vector2f::Zero();
  float top = -std::numeric_limits<float>::infinity();
  float bottom = std::numeric_limits<float>::infinity();
  for (int i : indices) {
    sum += levelled[i].head<2>();
    top = std::max(top, heights[i]);
    bottom = std::min(bottom, heights[i]);
  }
  shape.centroid_xy = sum / static_cast<float>(indices.size());
  shape.range_m = shape.centroid_xy.norm();
  shape.top_m = top;
  shape.bottom_m = bottom;
  // Axes of the line of sight through the centroid.
  const Eigen::Vector2f along = shape.range_m > 1e-6f ? Eigen::Vector2f(shape.centroid_xy / shape.range_m)
                                                      : Eigen::Vector2f(Eigen::Vector2f::UnitX());
  const Eigen::Vector2f across(-along.y(), along.x());
  const float inf = std::numeric_limits<float>::infinity();
  float a_min = inf, a_max = -inf, c_min = inf, c_max = -inf;
  float leg_min = inf, leg_max = -inf, torso_min = inf, torso_max = -inf, head_min = inf, head_max = -inf;
  // Zone bounds as fractions of the top: legs 20-45 % (above stray ground points at the feet),
  // torso and arms 50-85 % (below the head), head above 85 %.
  const float leg_bottom = 0.2f * top, leg_top = 0.45f * top, torso_bottom = 0.5f * top, torso_top = 0.85f * top;
  for (int i : indices) {
    const Eigen::Vector2f p = levelled[i].head<2>();
    const float a = p.dot(along), c = p.dot(across);
    a_min = std::min(a_min, a);
    a_max = std::max(a_max, a);
    c_min = std::min(c_min, c);
    c_max = std::max(c_max, c);
    const float h = heights[i];
    if (h >= leg_bottom && h <= leg_top) {
      leg_min = std::min(leg_min, c);
      leg_max = std::max(leg_max, c);
    } else if (h >= torso_bottom && h <= torso_top) {
      torso_min = std::min(torso_min, c);
      torso_max = std::max(torso_max, c);
    } else if (h > torso_top) {
      head_min = std::min(head_min, c);
      head_max = std::max(head_max, c);
    }
  }
  shape.depth_m = a_max - a_min;
  shape.width_m = c_max - c_min;
  // A zone whose points line up along the line of sight (a single column, 1 cm across) has no
  // width to compare: its ratio would be noise (seen: 1100).
  constexpr float kMinZoneWidthM = 0.02f;
  if (leg_max >= leg_min) shape.leg_width_m = leg_max - leg_min;
  if (torso_max >= torso_min) shape.torso_width_m = torso_max - torso_min;
  if (head_max >= head_min) shape.head_width_m = head_max - head_min;
  if (leg_max - leg_min >= kMinZoneWidthM && torso_max - torso_min >= kMinZoneWidthM) {
    shape.leg_to_torso_width = (leg_max - leg_min) / (torso_max - torso_min);
  }
  return shape;
}

RowProfile measureRows(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& indices, float range_m) {
  constexpr float kRowBreakRad = 0.1f * static_cast<float>(M_PI) / 180.f;
  std::vector<float> elevation;
  elevation.reserve(indices.size());
  for (int i : indices) {
    const Eigen::Vector3f& p = points[i];
    elevation.push_back(std::atan2(p.z(), std::hypot(p.x(), p.y())));
  }
  std::sort(elevation.begin(), elevation.end());
  std::vector<float> centres;  // ascending
  float sum = 0;
  int count = 0;
  for (std::size_t k = 0; k < elevation.size(); ++k) {
    if (k > 0 && elevation[k] - elevation[k - 1] > kRowBreakRad) {
      centres.push_back(sum / count);
      sum = 0;
      count = 0;
    }
    sum += elevation[k];
    ++count;
  }
  if (count > 0) centres.push_back(sum / count);
  RowProfile rows;
  rows.rows = static_cast<int>(centres.size());
  if (rows.rows < 3) return rows;
  std::vector<float> gaps;
  for (std::size_t k = 1; k < centres.size(); ++k) gaps.push_back(centres[k] - centres[k - 1]);
  for (std::size_t k = 0; k < gaps.size(); ++k) {
    const float below = k > 0 ? gaps[k - 1] : 0.f;
    const float above = k + 1 < gaps.size() ? gaps[k + 1] : 0.f;
    rows.largest_hole = std::max(rows.largest_hole, gaps[k] / std::max(below, above));
  }
  rows.bottom_spacing_m = range_m * std::tan(gaps.front());
  rows.top_spacing_m = range_m * std::tan(gaps.back());
  return rows;
}

ShapeVerdict judgeSampling(const PersonShape& s, const RowProfile& rows, const LidarPersonConfig& c,
                           double ground_tolerance_m) {
  if (c.row_gap_factor <= 0.0 || rows.rows < 3) return ShapeVerdict::kPerson;
  // Heights are measured above the estimated local ground, good to its tolerance.
  if (s.top_m < c.min_person_height_m - rows.top_spacing_m - ground_tolerance_m) return ShapeVerdict::kTooLow;
  if (s.bottom_m > ground_tolerance_m + c.row_gap_factor * rows.bottom_spacing_m) return ShapeVerdict::kFloating;
  if (rows.largest_hole > c.row_gap_factor) return ShapeVerdict::kGapInHeight;
  return ShapeVerdict::kPerson;
}

double minPersonPoints(double range_m, const LidarPersonConfig& config) {
  const double r = std::max(range_m, 0.1);
  return std::max(static_cast<double>(config.min_points), config.min_points_at_10m * (10.0 / r) * (10.0 / r));
}

ShapeVerdict judgeShape(const PersonShape& s, const LidarPersonConfig& c) {
  if (s.range_m < c.min_range_m || s.range_m > c.max_range_m) return ShapeVerdict::kOutOfRange;
  const double bearing_deg = std::atan2(s.centroid_xy.y(), s.centroid_xy.x()) * 180.0 / M_PI;
  if (bearing_deg < c.min_azimuth_deg || bearing_deg > c.max_azimuth_deg) return ShapeVerdict::kOutOfView;
  if (c.view_top_margin_deg > 0.0 && s.view_top_gap_deg < c.view_top_margin_deg) return ShapeVerdict::kCutByViewTop;
  if (s.top_m > c.max_height_m) return ShapeVerdict::kTooTall;
  if (s.top_m < c.min_height_m) return ShapeVerdict::kTooLow;
  if (s.bottom_m > c.max_bottom_m) return ShapeVerdict::kFloating;
  if (s.width_m > c.max_width_m) return ShapeVerdict::kTooWide;
  if (s.depth_m > c.max_depth_m) return ShapeVerdict::kTooDeep;
  if (s.width_m < c.min_width_m) return ShapeVerdict::kTooNarrow;
  if (s.top_m < c.min_height_to_width * s.width_m) return ShapeVerdict::kTooSquat;
  const double ratio = s.leg_to_torso_width;  // 0 = not measured
  // Legs as wide as the torso: a post, unless a head narrower than the torso sits on top (a
  // person striding across the view, or with the legs hidden, reads as straight below).
  const bool has_head = s.head_width_m > 0.0f && s.head_width_m < c.post_max_head_ratio * s.torso_width_m;
  if (s.width_m <= c.post_max_width_m && ratio >= c.post_leg_to_torso_ratio &&
      ratio <= 1.0 / c.post_leg_to_torso_ratio && !has_head) {
    return ShapeVerdict::kStraight;
  }
  const bool shows_legs =
      ratio > 0.0 && ratio < c.post_leg_to_torso_ratio && s.torso_width_m - s.leg_width_m >= c.narrow_leg_margin_m;
  if (s.width_m < c.narrow_width_m && s.depth_m < c.narrow_min_depth_m && !shows_legs) {
    return ShapeVerdict::kNarrowNoLegs;
  }
  if (s.points < minPersonPoints(s.range_m, c)) return ShapeVerdict::kTooFewPoints;
  return ShapeVerdict::kPerson;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
