#pragma once
// Draws the calibration overlay: the thermal image (contrast-stretched to 8 bit, as BGR), the
// person mask outlined, the LiDAR person points projected with an estimate (one colour per
// label) and, when given, a full point cloud coloured by range. Pure OpenCV + core types.

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {

struct OverlayInput {
  cv::Mat thermal;                         // CV_8UC1 or CV_16UC1 (required)
  cv::Mat mask;                            // optional, same size, 0 = background
  const Extrinsic* estimate = nullptr;     // no points are drawn without one
  std::vector<Eigen::Vector3f> cluster_points;  // LiDAR frame
  std::vector<std::int32_t> cluster_labels;
  const std::vector<Eigen::Vector3f>* cloud_points = nullptr;  // full cloud, LiDAR frame
};

class OverlayRenderer {
 public:
  // max_points: at most this many cloud points are drawn (evenly subsampled).
  // max_range_m: the far end of the range colour scale.
  OverlayRenderer(CameraModel camera, int max_points, double max_range_m = 30.0);

  cv::Mat render(const OverlayInput& input) const;  // CV_8UC3, BGR

 private:
  CameraModel camera_;
  int max_points_;
  double max_range_m_;
  cv::Mat range_lut_;  // 256 x 1 BGR colour scale
};

}  // namespace thermal_lidar_calibration
