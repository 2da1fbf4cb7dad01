#pragma once
// score_raw_detections --explain: one line per missed person and per false detection, with what
// the detector measured there, so that a threshold is tuned on what it actually decides (the
// scores alone say how many, not which or why).
//   thermal miss   a scored person without a mask at IoU >= 0.5: the truth box, and the detected
//                  person or rejected region that overlaps it most (its reason and shape)
//   thermal false  a detected person that matches nobody: its box, height / width, fill, legs /
//                  torso width, mean temperature, and what it overlaps in the truth (an unscored
//                  person, or nobody: a confounder)
//   lidar miss     a scored person without a matching cluster: its range and bearing, and the
//                  verdict and shape of the object holding most of its points
//   lidar false    a detected person matching nobody: range, shape

#include "thermal_lidar_calibration/detection/detection_scoring.hpp"
#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace thermal_lidar_calibration {
namespace bench {

// The misses and false detections are the scorer's (`score`, from detection::scoreMask on the
// same masks); truth_ids: CV_16UC1 person ids; detected_mask: CV_8UC1.
void explainThermal(std::FILE* out, double stamp_s, const detection::ThermalSegmentation& segmentation,
                    const detection::FrameScore& score, const cv::Mat& detected_mask, const cv::Mat& truth_ids);

// The same for the LiDAR (`score` from detection::scoreClusters on `detection`); truth: per input
// point, the person id (0 = none).
void explainLidar(std::FILE* out, double stamp_s, const detection::LidarDetection& detection,
                  const detection::FrameScore& score, const std::vector<Eigen::Vector3f>& points,
                  const std::vector<std::uint32_t>& truth);

}  // namespace bench
}  // namespace thermal_lidar_calibration
