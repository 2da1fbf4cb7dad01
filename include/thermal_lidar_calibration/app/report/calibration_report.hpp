#pragma once
// The visual report (calibrate_bag --report DIR, the node's ~report_dir; issue 8): pictures a
// person reads in seconds and an index.html that shows them with the numbers.
//   overlays.png     the 3 best and the 3 worst pairs at the result (points coloured by their
//                    distance to the mask)
//   coverage.png     where the people were (share of person pixels per image cell)
//   convergence.png  best loss per generation of each stage, then the refinement
//   pair_losses.png  Eq. (1) per pair, used and outliers, the inlier threshold
//   uncertainty.png  the 95 % interval per axis (when the bootstrap ran)
//   index.html       all of it, with the result, the verdict and its reasons, the comparison
//                    with the calibration in use
// ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct ReportInput {
  const CameraModel* camera = nullptr;
  const std::vector<CalibrationPair>* pairs = nullptr;  // as given to calibrate()
  const CalibrationResult* result = nullptr;
  const QualityAssessment* quality = nullptr;           // optional
  double threshold_px = 5.0;                            // the inlier threshold (threshold_sample_px)
  std::string source;                                   // "calibrate_bag drive.bag", "calibration_node"
  std::string lidar_frame, camera_frame;
};

// Writes the files into `dir` (made if missing) and returns their paths. Throws
// std::runtime_error naming the file that could not be written.
std::vector<std::string> writeCalibrationReport(const std::string& dir, const ReportInput& input);

}  // namespace thermal_lidar_calibration
