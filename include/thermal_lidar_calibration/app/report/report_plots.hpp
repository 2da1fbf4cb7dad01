#pragma once
// The pictures of the visual report (issue 8), drawn with OpenCV: each a BGR image a person reads
// in seconds. ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/coverage.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace thermal_lidar_calibration {

// Best loss per step of each stage (one colour per stage, log scale), then the refinement.
cv::Mat drawConvergence(const std::vector<ConvergenceStep>& history, int width = 900, int height = 420);

// Eq. (1) of every pair at the result, in time order: inliers (used) blue, outliers red, the
// inlier threshold dashed.
cv::Mat drawPairLosses(const std::vector<double>& pair_losses, const std::vector<bool>& inliers,
                       double threshold_px, int width = 900, int height = 360);

// The 95 % interval half-width per axis: rotation about camera x, y, z (deg) and translation
// along them (cm), one bar each, with the value written.
cv::Mat drawUncertainty(const Uncertainty& uncertainty, int width = 900, int height = 360);

// The loss along the camera's time offset (issue 21): the coarse search's profile (ms, px, the
// pose refined at each offset), the result's offset marked, with its 95 % interval when given.
cv::Mat drawTimeOffsetProfile(const std::vector<double>& offsets_s, const std::vector<double>& losses_px,
                              double result_s, double halfwidth_ms, int width = 900, int height = 360);

// The coverage grid over the image: each cell shaded by its share of person pixels, the share
// written in it, empty cells marked.
cv::Mat drawCoverage(const Coverage& coverage, int width = 640, int height = 512);

// One pair's overlay: the image (or the mask when there is none), the mask outlined, the
// person points projected with `estimate` coloured by their distance to the mask (green on it,
// yellow within 3 px, red beyond), and a caption.
cv::Mat drawPairOverlay(const CameraModel& camera, const CalibrationPair& pair,
                        const Extrinsic& estimate, const std::string& caption);

}  // namespace thermal_lidar_calibration
