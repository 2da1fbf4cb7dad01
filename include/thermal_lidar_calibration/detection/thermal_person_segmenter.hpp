#pragma once
// Classical thermal person segmentation: warm regions against a robust per-frame background
// level (and, for a radiometric 16-bit image, an absolute body-surface band in kelvin), a
// morphological clean-up, 8-connected components and shape filters (area, height / width,
// fill). One threshold pass to 8 bits and integer work after it keep a 640x512 16-bit frame
// within ~2-3 ms on one core (bench/detection_benchmark.cpp).
//
// What fools it, and how the calibration survives it, is in the README ("Person detectors").

#include "thermal_lidar_calibration/detection/thermal_segmenter_config.hpp"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

struct ThermalPerson {
  int id = 0;              // value in the mask, 1..n
  cv::Rect bbox;           // pixels
  int area_px = 0;         // mask pixels
  cv::Point2d centroid;    // pixels
  double fill = 0.0;       // area / bounding-box area
  double mean_level = 0.0; // mean pixel value inside the mask: kelvin if radiometric, else raw
  // Median row extent of the legs zone (10-40 % of the height above the bottom) over the torso
  // zone's (50-80 %); 0 when a zone is empty or the region is a part of a split one (not
  // measured: thermal_straight_ratio is not applied).
  double leg_to_torso_width = 0.0;
};

// A warm region at least min_area_px large that failed a shape filter, for tuning.
struct RejectedRegion {
  cv::Rect bbox;
  int area_px = 0;
  std::string reason;  // "too_large", "too_short", "too_squat", "too_thin", "too_sparse", "too_full", "straight",
                      // "no_neck", "cut_by_border", "no_warm_core", "too_short_for_range" (person_size_model.hpp)
  double leg_to_torso_width = 0.0;  // as ThermalPerson's
};

struct ThermalSegmentation {
  cv::Mat mask;  // CV_8UC1, same size as the image: 0 = background, ids 1..n (n <= 255)
  std::vector<ThermalPerson> people;  // in id order
  bool radiometric = false;     // true: levels below are kelvin, else raw pixel values
  double background_level = 0;  // median of the sampled pixels
  double threshold_low = 0;     // a person pixel is in [threshold_low, threshold_high]
  double threshold_high = 0;
  int components = 0;           // connected components before the shape filters
  int border_cut = 0;           // regions of a person's size dropped because the image border cuts them
  double min_area_px = 0;       // the size floor applied to this image (thermal_segmenter_config.hpp)
  double min_height_px = 0;
  double core_threshold = 0;    // relative mode: the level a region's warm core had to reach (0 = not applied)
  std::vector<RejectedRegion> rejected;  // regions of at least min_area_px that failed a filter
};

class ThermalPersonSegmenter {
 public:
  // Throws std::invalid_argument (from config.validate()) on a bad configuration.
  explicit ThermalPersonSegmenter(const ThermalSegmenterConfig& config = {});

  // image: CV_8UC1 or CV_16UC1, non-empty. Throws std::invalid_argument otherwise.
  ThermalSegmentation segment(const cv::Mat& image) const;

  const ThermalSegmenterConfig& config() const { return config_; }

 private:
  ThermalSegmenterConfig config_;
  cv::Mat open_kernel_;
  cv::Mat close_kernel_;
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
