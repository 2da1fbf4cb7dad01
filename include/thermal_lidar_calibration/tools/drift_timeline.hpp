#pragma once
// calibrate_bag --monitor's work, ROS-free: the kept pairs of a drive, in time order, through a
// DriftMonitor against a reference extrinsic, and the timeline written as the INTERFACE says
// (OUT.yaml with the latest fit and a `drift:` block, OUT.drift.csv, OUT.drift.png).

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include <opencv2/core.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct DriftTimeline {
  Extrinsic reference;
  std::vector<DriftRecord> records;         // one per window test, in time order
  std::optional<DriftCandidate> candidate;  // the new extrinsic after a confirmed change
  DriftState state = DriftState::kOk;       // at the end
  std::optional<double> first_warn_stamp_s, first_error_stamp_s;
  std::uint64_t pairs = 0;
  // Issue 23: of `pairs`, those made by association, and the candidate frames offered for it.
  std::uint64_t association_pairs = 0;
  std::uint64_t candidates = 0;
  double seconds = 0.0;                     // in the monitor's tests and fits
  // Issue 21: the reference's camera time offset, and a change of it the tests found.
  std::optional<double> time_offset_s;
  DriftState timing_state = DriftState::kOk;
  std::optional<double> timing_change_s;    // the latest, while the timing state is not OK
};

// `stream`: kept pairs and candidate frames in time order (inOfferOrder, dataset_builder.hpp);
// the candidates pair by `association` when given, else they are passed over.
// `progress(done, total)` after each; return false to stop early.
// `time_offset_s`: the reference's camera time offset, when its calibration applied one.
DriftTimeline watchDrift(const CameraModel& camera, const std::vector<CalibrationPair>& stream,
                         const Extrinsic& reference, const DriftConfig& drift,
                         const CalibrationConfig& calibration,
                         const std::function<bool(std::size_t, std::size_t)>& progress = {},
                         std::optional<double> time_offset_s = std::nullopt,
                         const std::optional<AssociationPairing>& association = std::nullopt);

// One row per test: stamp, pairs_in_window, state, rotation_change_deg, translation_change_cm,
// loss_reference, loss_fit (the change's angle and length against the reference). Throws
// std::runtime_error naming the file when it cannot be written.
void writeDriftCsv(const std::string& path, const DriftTimeline& timeline);

// The result keys of the latest fit (the candidate when a change was confirmed, else the last
// window's fit) and the `drift:` block. Throws std::runtime_error naming the file.
void writeDriftResult(const std::string& path, const DriftTimeline& timeline,
                      const std::string& lidar_frame, const std::string& camera_frame,
                      const std::string& reference_file);

// The change per axis over time (rotation about the camera's x, y, z in deg above, translation
// along them in cm below), WARN tests in orange and ERROR in red; width x height BGR.
cv::Mat drawDriftPlot(const DriftTimeline& timeline, int width = 1000, int height = 600);

}  // namespace thermal_lidar_calibration
