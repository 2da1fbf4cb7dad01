#pragma once
// Warm regions of the thermal segmenter: connected components of the cleaned binary mask, their
// shape statistics, the shape filters, and the split of a region holding people side by side
// (two heads in the region's top profile). Internal to the detection library.

#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

// A connected component of `labels` (value `label`), or the part of it inside `bbox`'s columns.
struct WarmRegion {
  int label = 0;
  cv::Rect bbox;
  int area_px = 0;
  cv::Point2d centroid;
};

// The first shape filter a region fails, or "" for a person ("too_small" for specks).
std::string shapeFailure(const WarmRegion& region, const ThermalSegmenterConfig& config, double max_area_px);

// Statistics of the pixels of `label` in the columns [x0, x1) of `bbox` (rows of bbox only).
WarmRegion measureColumns(const cv::Mat& labels, int label, const cv::Rect& bbox, int x0, int x1);

// The parts of a region between the valleys of its top profile (the highest pixel per column)
// that dip at least dip_fraction of the region's height below the heads on both sides; the
// valley columns themselves belong to no part. One part (the region) when there is no valley.
std::vector<WarmRegion> splitAtHeads(const cv::Mat& labels, const WarmRegion& region, double dip_fraction);

}  // namespace detection
}  // namespace thermal_lidar_calibration
