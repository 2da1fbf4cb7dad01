#pragma once
// Runs calibrate() on a background thread so the node's callbacks stay responsive. The thread
// catches its own exceptions (reported in the outcome); requestStop() is checked in the
// progress callback, so a run stops within one generation. ROS-free apart from its location.

#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

class CalibrationWorker {
 public:
  struct Outcome {
    std::optional<CalibrationResult> result;  // set on success (result->stopped if stopped)
    std::optional<QualityAssessment> quality;  // with a quality request, after a finished fit
    std::string error;                        // set on failure
  };

  CalibrationWorker();
  // Asks a running calibration to stop and waits for it up to `kStopWait`; a thread still
  // running after that is detached (it owns all it uses) so shutdown never hangs.
  ~CalibrationWorker();
  CalibrationWorker(const CalibrationWorker&) = delete;
  CalibrationWorker& operator=(const CalibrationWorker&) = delete;

  // Starts a run on copies of the inputs. Throws std::logic_error if a run is still going.
  // With `quality`, the fit is followed on the same thread by assessQuality() (bootstrap
  // intervals, coverage, verdict, the reference's standing); a failure there leaves the result.
  struct QualityRequest {
    QualityConfig config;
    std::optional<Extrinsic> reference;
  };
  void start(const CameraModel& camera, std::vector<CalibrationPair> pairs,
             const CalibrationConfig& config,
             std::optional<QualityRequest> quality = std::nullopt);
  void requestStop();
  bool busy() const;  // a run is going (or stopping)
  std::optional<Progress> progress() const;  // latest progress of the current or last run
  // The outcome of a finished run, once; nullopt while running or when already taken.
  std::optional<Outcome> takeOutcome();

  static constexpr double kStopWaitS = 2.0;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace thermal_lidar_calibration
