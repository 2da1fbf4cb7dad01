#pragma once
// Runs the calibration job (calibration_job.hpp) on a background thread so the node's
// callbacks stay responsive. The thread catches its own exceptions (reported in the outcome);
// requestStop() is checked in the job's progress callback, so a run stops within one generation
// or bootstrap resample. ROS-free.

#include "thermal_lidar_calibration/app/runtime/calibration_job.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

class CalibrationWorker {
 public:
  using Outcome = CalibrationJobOutcome;

  CalibrationWorker();
  // Asks a running calibration to stop and waits for it up to `kStopWait`; a thread still
  // running after that is detached (it owns all it uses) so shutdown never hangs.
  ~CalibrationWorker();
  CalibrationWorker(const CalibrationWorker&) = delete;
  CalibrationWorker& operator=(const CalibrationWorker&) = delete;

  // Starts the job (the fit, its quality, the result file and report it asks for). Throws
  // std::logic_error if a run is still going.
  void start(CalibrationJobRequest request);
  void requestStop();
  bool busy() const;  // a run is going (or stopping)
  std::optional<Progress> progress() const;  // latest fit progress of the current or last run
  // The outcome of a finished run, once; nullopt while running or when already taken.
  std::optional<Outcome> takeOutcome();

  static constexpr double kStopWaitS = 2.0;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace thermal_lidar_calibration
