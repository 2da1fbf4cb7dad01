#pragma once
// Pictures for looking at what the detectors did: the thermal image with the mask drawn over
// it, and a bird's-eye view of a scan with the people coloured by label.

#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

// BGR: the image stretched between its 1st and 99th percentiles, each person tinted in its
// colour with its box and id.
cv::Mat renderMaskOverlay(const cv::Mat& image, const ThermalSegmentation& segmentation);

// BGR top view (x forward = up, y left = left), `range_m` around the sensor at `px_per_m`: all
// points grey by height above the local ground, people in their colours with their labels,
// rejected person-high objects outlined in dark red.
cv::Mat renderBirdsEye(const std::vector<Eigen::Vector3f>& points, const LidarDetection& detection,
                       const LidarPersonDetector& detector, double range_m, double px_per_m = 20.0);

}  // namespace detection
}  // namespace thermal_lidar_calibration
