#include "thermal_regions.hpp"

#include <algorithm>

namespace thermal_lidar_calibration {
namespace detection {

std::string shapeFailure(const WarmRegion& r, const ThermalSegmenterConfig& c, double max_area_px) {
  const int w = r.bbox.width, h = r.bbox.height;
  if (r.area_px < c.min_area_px) return "too_small";
  if (r.area_px > max_area_px) return "too_large";
  if (h < c.min_height_px) return "too_short";
  const double aspect = static_cast<double>(h) / w;
  const double fill = static_cast<double>(r.area_px) / (static_cast<double>(w) * h);
  if (aspect < c.min_aspect) return "too_squat";
  if (aspect > c.max_aspect) return "too_thin";
  if (fill < c.min_fill) return "too_sparse";
  if (fill > c.max_fill) return "too_full";
  return "";
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

std::vector<WarmRegion> splitAtHeads(const cv::Mat& labels, const WarmRegion& region, double dip_fraction) {
  const cv::Rect& b = region.bbox;
  // Height of the region's top above its bottom row, per column (0 = no pixel in the column).
  std::vector<int> profile(static_cast<std::size_t>(b.width), 0);
  for (int y = b.y + b.height - 1; y >= b.y; --y) {
    const int* row = labels.ptr<int>(y);
    for (int x = b.x; x < b.x + b.width; ++x) {
      if (row[x] == region.label) profile[static_cast<std::size_t>(x - b.x)] = b.y + b.height - y;
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
