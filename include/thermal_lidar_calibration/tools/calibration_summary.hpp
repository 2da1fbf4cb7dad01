#pragma once
// The one-screen summary calibrate_bag prints at the end, and the tf command line.

#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <optional>
#include <string>

namespace thermal_lidar_calibration {

struct SummaryInput {
  std::string bag_path;
  std::string output_path;
  std::string lidar_frame;
  std::string camera_frame;
  std::string algorithm_text;        // "Algorithm 2, refine local, seed 1"
  std::uint64_t messages_read = 0;
  std::uint64_t frames = 0;          // synchronized candidates
  RejectionCounts counts;
  CalibrationResult result;
  std::optional<TruthComparison> truth;
  std::optional<QualityAssessment> quality;  // uncertainty, coverage, verdict, reference
  std::optional<PairingSummary> pairing;     // pairs by rule (issue 23)
  double total_seconds = 0.0;        // whole tool run
};

std::string formatCalibrationSummary(const SummaryInput& in);

}  // namespace thermal_lidar_calibration
