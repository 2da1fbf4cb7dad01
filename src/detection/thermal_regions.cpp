#include "thermal_regions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace thermal_lidar_calibration {
namespace detection {

namespace {

// The row extents of `label` over rows [y0, y1) of `box` (rows without a pixel skipped).
std::vector<int> rowExtents(const cv::Mat& labels, int label, const cv::Rect& box, int y0, int y1) {
  std::vector<int> extents;
  extents.reserve(static_cast<std::size_t>(std::max(0, y1 - y0)));
  for (int y = y0; y < y1; ++y) {
    const int* row = labels.ptr<int>(y);
    int left = -1, right = -1;
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (row[x] != label) continue;
      if (left < 0) left = x;
      right = x;
    }
    if (left >= 0) extents.push_back(right - left + 1);
  }
  return extents;
}

double median(std::vector<int> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

bool ZoneWidths::straight(double r) const {
  if (legs_px <= 0.0 || torso_px <= 0.0) return false;
  if (std::max(legs_px, torso_px) <= 1.0 / (1.0 - r)) return true;
  const double ratio = legs_px / torso_px;
  return ratio >= r && ratio <= 1.0 / r && neck_px >= r * torso_px;
}

ZoneWidths measureZoneWidths(const cv::Mat& labels, const WarmRegion& r) {
  const cv::Rect& b = r.bbox;
  const int bottom = b.y + b.height;  // one past the feet row
  auto row_at = [&](double fraction_above_bottom) {
    return bottom - static_cast<int>(std::lround(fraction_above_bottom * b.height));
  };
  ZoneWidths zones;
  zones.legs_px = median(rowExtents(labels, r.label, b, row_at(0.4), row_at(0.1)));
  zones.torso_px = median(rowExtents(labels, r.label, b, row_at(0.8), row_at(0.5)));
  const std::vector<int> neck = rowExtents(labels, r.label, b, row_at(0.92), row_at(0.78));
  zones.neck_px = neck.empty() ? 0.0 : *std::min_element(neck.begin(), neck.end());
  return zones;
}

RegionLimits regionLimits(const ThermalSegmenterConfig& c, const cv::Size& size) {
  const double focal_px = 0.5 * size.width / std::tan(0.5 * c.camera_hfov_deg * M_PI / 180.0);
  const double px_per_m = focal_px / c.max_range_m;  // at the farthest range
  RegionLimits limits;
  limits.min_area_px = std::max<double>(c.min_area_px, px_per_m * px_per_m * c.min_person_area_m2);
  limits.max_area_px = c.max_area_fraction * static_cast<double>(size.area());
  limits.min_height_px = std::max<double>(c.min_height_px, px_per_m * c.min_person_height_m);
  return limits;
}

std::string shapeFailure(const WarmRegion& r, const ThermalSegmenterConfig& c, const RegionLimits& limits) {
  const int w = r.bbox.width, h = r.bbox.height;
  if (r.area_px < limits.min_area_px) return "too_small";
  if (r.area_px > limits.max_area_px) return "too_large";
  if (h < limits.min_height_px) return "too_short";
  const double aspect = static_cast<double>(h) / w;
  const double fill = static_cast<double>(r.area_px) / (static_cast<double>(w) * h);
  if (aspect < c.min_aspect) return "too_squat";
  if (aspect > c.max_aspect) return "too_thin";
  if (fill < c.min_fill) return "too_sparse";
  if (fill > c.max_fill) return "too_full";
  if (!r.split_part && aspect >= c.straight_min_aspect && r.zones.straight(c.straight_ratio)) return "straight";
  // Slender regions have the straight-sides test (with a neck of its own); a far person side on
  // is a dozen pixels wide, where the neck is a pixel or two narrower than the torso.
  if (c.max_neck_ratio > 0.0 && aspect < c.straight_min_aspect && r.zones.neck_px > 0.0 && r.zones.torso_px > 0.0 &&
      r.zones.neck_px > c.max_neck_ratio * r.zones.torso_px) {
    return "no_neck";
  }
  return "";
}

bool cutByBorder(const cv::Rect& box, const cv::Size& size, int margin_px) {
  if (margin_px <= 0) return false;
  return box.x < margin_px || box.y < margin_px || box.x + box.width > size.width - margin_px ||
         box.y + box.height > size.height - margin_px;
}

namespace {

template <typename T>
std::vector<int> regionValues(const cv::Mat& image, const cv::Mat& labels, const WarmRegion& region,
                              const cv::Mat& only) {
  std::vector<int> values;
  values.reserve(static_cast<std::size_t>(region.area_px));
  const cv::Rect& b = region.bbox;
  for (int y = b.y; y < b.y + b.height; ++y) {
    const int* lab = labels.ptr<int>(y);
    const T* pix = image.ptr<T>(y);
    const std::uint8_t* keep = only.empty() ? nullptr : only.ptr<std::uint8_t>(y);
    for (int x = b.x; x < b.x + b.width; ++x) {
      if (lab[x] == region.label && (!keep || keep[x] != 0)) values.push_back(pix[x]);
    }
  }
  return values;
}

}  // namespace

double regionQuantile(const cv::Mat& image, const cv::Mat& labels, const WarmRegion& region, double fraction,
                      const cv::Mat& only) {
  std::vector<int> values = image.type() == CV_16UC1 ? regionValues<std::uint16_t>(image, labels, region, only)
                                                     : regionValues<std::uint8_t>(image, labels, region, only);
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(std::floor(fraction * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[static_cast<std::size_t>(k)];
}

WarmRegion measureColumns(const cv::Mat& labels, int label, const cv::Rect& bbox, int x0, int x1) {
  WarmRegion part;
  part.label = label;
  int top = bbox.y + bbox.height, bottom = bbox.y - 1, left = x1, right = x0 - 1;
  double sx = 0, sy = 0;
  for (int y = bbox.y; y < bbox.y + bbox.height; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = x0; x < x1; ++x) {
      if (row[x] != label) continue;
      ++part.area_px;
      sx += x;
      sy += y;
      top = std::min(top, y);
      bottom = std::max(bottom, y);
      left = std::min(left, x);
      right = std::max(right, x);
    }
  }
  if (part.area_px == 0) return part;
  part.bbox = cv::Rect(left, top, right - left + 1, bottom - top + 1);
  part.centroid = cv::Point2d(sx / part.area_px, sy / part.area_px);
  return part;
}

std::vector<WarmRegion> splitAtHeads(const cv::Mat& labels, const cv::Mat& opened, const WarmRegion& region,
                                     double dip_fraction) {
  const cv::Rect& b = region.bbox;
  // Height of the region's top above its bottom row, per column (0 = no pixel in the column).
  std::vector<int> profile(static_cast<std::size_t>(b.width), 0);
  for (int y = b.y + b.height - 1; y >= b.y; --y) {
    const int* row = labels.ptr<int>(y);
    const std::uint8_t* open_row = opened.ptr<std::uint8_t>(y);
    for (int x = b.x; x < b.x + b.width; ++x) {
      if (row[x] == region.label && open_row[x]) profile[static_cast<std::size_t>(x - b.x)] = b.y + b.height - y;
    }
  }
  // Walk across: a valley splits when both the peak before it and the rise after it clear dip.
  const double dip = dip_fraction * b.height;
  std::vector<int> cuts;
  int peak = profile[0], valley = profile[0], valley_x = 0;
  for (int x = 1; x < b.width; ++x) {
    const int h = profile[static_cast<std::size_t>(x)];
    if (peak - valley >= dip && h - valley >= dip) {
      cuts.push_back(valley_x);
      peak = valley = h;
      valley_x = x;
    } else if (h > peak) {
      peak = valley = h;
      valley_x = x;
    } else if (h < valley) {
      valley = h;
      valley_x = x;
    }
  }
  if (cuts.empty()) return {region};
  std::vector<WarmRegion> parts;
  int start = 0;
  cuts.push_back(b.width);
  for (int cut : cuts) {
    if (cut > start) {
      WarmRegion part = measureColumns(labels, region.label, b, b.x + start, b.x + cut);
      if (part.area_px > 0) parts.push_back(part);
    }
    start = cut + 1;  // the valley column is the seam
  }
  return parts;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
