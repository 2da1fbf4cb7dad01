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

// Row extents (leftmost to rightmost pixel of the region in a row) of a region's zones, by height
// above its bottom row: the median over the legs zone (10-40 %) and the torso zone (50-80 %),
// and the narrowest row of the neck zone (78-92 %, between shoulders and head), px; 0 where a
// zone has no pixel or was not measured.
struct ZoneWidths {
  double legs_px = 0;
  double torso_px = 0;
  double neck_px = 0;
  double legsOverTorso() const { return legs_px > 0 && torso_px > 0 ? legs_px / torso_px : 0.0; }
  // A post's shape: measured, the legs as wide as the torso (legs / torso in [r, 1 / r]) and no
  // neck narrower than r times the torso; or too narrow to tell, at most 1 / (1 - r) px wide,
  // where one pixel less is already within the ratio (3 px against 4 says nothing).
  bool straight(double r) const;
};

// A connected component of `labels` (value `label`), or the part of it inside `bbox`'s columns.
struct WarmRegion {
  int label = 0;
  cv::Rect bbox;
  int area_px = 0;
  cv::Point2d centroid;
  // A part of a split one has cut columns that say nothing about its sides (a person half
  // behind another loses an arm to the cut): only its neck is judged, not its straight sides.
  ZoneWidths zones;
  bool split_part = false;
};

// The size limits of a person region in an image of `size`: the pixel floors of the
// configuration raised to the size floor from geometry (thermal_segmenter_config.hpp), and the
// largest area.
struct RegionLimits {
  double min_area_px = 0;
  double max_area_px = 0;
  double min_height_px = 0;
};
RegionLimits regionLimits(const ThermalSegmenterConfig& config, const cv::Size& size);

// The first shape filter a region fails, or "" for a person ("too_small" for specks and spots
// under the size floor); reads region.zones for a slender region's straight-sides test.
std::string shapeFailure(const WarmRegion& region, const ThermalSegmenterConfig& config, const RegionLimits& limits);

// The legs over torso width reported for a region: 0 for a split part (its cut sides say nothing).
inline double legsOverTorso(const WarmRegion& region) {
  return region.split_part ? 0.0 : region.zones.legsOverTorso();
}

// True when `box` has a pixel within `margin_px` of the edge of an image of `size` (0: never).
bool cutByBorder(const cv::Rect& box, const cv::Size& size, int margin_px);

// The zone widths of the pixels of `region.label` in `region.bbox`: a post's are equal; a
// person's legs together are ~0.5-0.8 of the torso (striding across the view, wider) and the neck
// ~0.4.
ZoneWidths measureZoneWidths(const cv::Mat& labels, const WarmRegion& region);

// The `fraction` quantile of the image values of a region's pixels (`label` within its bbox:
// a split part's box covers only its columns), in raw units. image: CV_8UC1 or CV_16UC1. With
// `only` (CV_8UC1, the image's size), only the pixels where it is non-zero count.
double regionQuantile(const cv::Mat& image, const cv::Mat& labels, const WarmRegion& region, double fraction,
                      const cv::Mat& only = cv::Mat());

// Statistics of the pixels of `label` in the columns [x0, x1) of `bbox` (rows of bbox only).
WarmRegion measureColumns(const cv::Mat& labels, int label, const cv::Rect& bbox, int x0, int x1);

// The parts of a region between the valleys of its top profile (the highest pixel per column)
// that dip at least dip_fraction of the region's height below the heads on both sides; the
// valley columns themselves belong to no part. One part (the region) when there is no valley.
// The profile is read from `opened`, the binary mask before its closing: two heads 1-2 px apart
// (a person half behind another) are joined by the closing, which fills the valley between them.
std::vector<WarmRegion> splitAtHeads(const cv::Mat& labels, const cv::Mat& opened, const WarmRegion& region,
                                     double dip_fraction);

}  // namespace detection
}  // namespace thermal_lidar_calibration
