#pragma once
// The node's drift watch (~mode: monitor): kept pairs are queued by the callbacks and go through
// a DriftMonitor on a background thread, in the order they were kept (so the verdicts are those
// calibrate_bag --monitor gives on the same pairs); the callbacks and the status timer read a
// snapshot. ROS-free.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace thermal_lidar_calibration {

class DriftWatchWorker {
 public:
  struct Snapshot {
    Extrinsic reference;
    DriftState state = DriftState::kOk;
    std::optional<DriftRecord> last;           // the latest window test
    std::optional<DriftCandidate> candidate;   // after a confirmed change
    bool update_ready = false;                 // DriftMonitor::updateReady()
    std::uint64_t pairs_seen = 0;
    std::uint64_t association_pairs = 0;       // of pairs_seen, made by association (issue 23)
    std::size_t pairs_in_window = 0;
    std::uint64_t tests = 0;
    std::uint64_t candidates_refused = 0;      // new fits too far to offer (max_update_*)
    std::size_t queued = 0;                    // pairs waiting for the thread
    bool testing = false;                      // the thread is testing a pair (not in `queued`)
    std::uint64_t dropped = 0;                 // pairs dropped: the queue was full
    double seconds = 0.0;                      // in tests and fits so far (CPU of the watch)
    std::string error;                         // a test that threw (the watch goes on)
    // Issue 21: the camera's time offset the reference goes with, and a change of it found by
    // the tests (a timing change, not a drift of the extrinsic).
    std::optional<double> time_offset_s;
    DriftState timing_state = DriftState::kOk;
    std::optional<double> timing_change_s;
  };

  // Throws std::invalid_argument on a bad config or camera. With `association`, candidate frames
  // submitted are paired by association at the reference in use (DriftMonitor::pairByAssociation).
  DriftWatchWorker(const CameraModel& camera, const Extrinsic& reference, const DriftConfig& drift,
                   const CalibrationConfig& calibration, std::optional<double> time_offset_s = std::nullopt,
                   const std::optional<AssociationPairing>& association = std::nullopt);
  // Stops the thread after the test in progress (at most one window fit).
  ~DriftWatchWorker();
  DriftWatchWorker(const DriftWatchWorker&) = delete;
  DriftWatchWorker& operator=(const DriftWatchWorker&) = delete;

  // Queues a kept pair or a candidate frame, in time order (its image is dropped). At most kMaxQueued wait; beyond that the oldest
  // waiting pair is dropped and counted (a machine too slow for the watch must not grow without
  // bound).
  void submit(CalibrationPair pair);
  Snapshot snapshot() const;
  // Waits until every queued pair has been through the monitor (tests, shutdown); false after
  // `timeout_s`.
  bool drain(double timeout_s) const;
  // Makes the candidate the reference (DriftMonitor::acceptCandidate), between two tests.
  std::optional<DriftUpdate> accept();
  // A new reference from elsewhere (a new calibration, ~reference_file).
  void setReference(const Extrinsic& reference);

  static constexpr std::size_t kMaxQueued = 1000;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace thermal_lidar_calibration
