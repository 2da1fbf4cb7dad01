// DriftWatchWorker: the drift watch on a thread of its own, fed in order through a queue.

#include "thermal_lidar_calibration/node/drift_watch_worker.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace thermal_lidar_calibration {

struct DriftWatchWorker::State {
  explicit State(DriftMonitor m) : monitor(std::move(m)) {}
  // `monitor` is touched only under `monitor_mutex` (the thread during a test; accept() and
  // setReference() between tests); the queue and the snapshot under `mutex`.
  std::mutex monitor_mutex;
  DriftMonitor monitor;
  mutable std::mutex mutex;
  std::condition_variable wake;          // a pair was queued, or stop
  mutable std::condition_variable idle;  // the queue ran empty
  std::deque<CalibrationPair> queue;
  bool stop = false;
  Snapshot snapshot;

  void refreshSnapshot() {  // under monitor_mutex and mutex
    snapshot.reference = monitor.reference();
    snapshot.state = monitor.state();
    snapshot.last = monitor.lastRecord();
    snapshot.candidate = monitor.candidate();
    snapshot.update_ready = monitor.updateReady();
    snapshot.pairs_seen = monitor.pairsSeen();
    snapshot.association_pairs = monitor.associationPairs();
    snapshot.pairs_in_window = monitor.pairsInWindow();
    snapshot.seconds = monitor.secondsInTests();
    snapshot.candidates_refused = monitor.candidatesRefused();
    snapshot.queued = queue.size();
    snapshot.time_offset_s = monitor.timeOffset();
    snapshot.timing_state = monitor.timingState();
    snapshot.timing_change_s = monitor.timingChange();
  }

  void run() {
    for (;;) {
      CalibrationPair pair;
      {
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait(lock, [&] { return stop || !queue.empty(); });
        if (stop) return;
        pair = std::move(queue.front());
        queue.pop_front();
        snapshot.queued = queue.size();
        snapshot.testing = true;
      }
      std::lock_guard<std::mutex> monitor_lock(monitor_mutex);
      std::string error;
      bool tested = false;
      try {
        tested = monitor.add(std::move(pair)).has_value();
      } catch (const std::exception& e) {
        error = e.what();
      }
      std::lock_guard<std::mutex> lock(mutex);
      if (tested) ++snapshot.tests;
      if (!error.empty()) snapshot.error = error;
      refreshSnapshot();
      snapshot.testing = false;
      if (queue.empty()) idle.notify_all();
    }
  }
};

DriftWatchWorker::DriftWatchWorker(const CameraModel& camera, const Extrinsic& reference,
                                   const DriftConfig& drift, const CalibrationConfig& calibration,
                                   std::optional<double> time_offset_s,
                                   const std::optional<AssociationPairing>& association)
    : state_(std::make_shared<State>(DriftMonitor(camera, reference, drift, calibration, time_offset_s))) {
  if (association) state_->monitor.pairByAssociation(*association);
  {
    std::lock_guard<std::mutex> monitor_lock(state_->monitor_mutex);
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->refreshSnapshot();
  }
  std::thread([state = state_] { state->run(); }).detach();
}

DriftWatchWorker::~DriftWatchWorker() {
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stop = true;
  }
  state_->wake.notify_all();
  // The thread owns `state_` too and ends after the test in progress; not joined, so a
  // shutdown never waits for a fit.
}

void DriftWatchWorker::submit(CalibrationPair pair) {
  pair.image.release();
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    if (state_->queue.size() >= kMaxQueued) {
      state_->queue.pop_front();
      ++state_->snapshot.dropped;
    }
    state_->queue.push_back(std::move(pair));
    state_->snapshot.queued = state_->queue.size();
  }
  state_->wake.notify_one();
}

DriftWatchWorker::Snapshot DriftWatchWorker::snapshot() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->snapshot;
}

bool DriftWatchWorker::drain(double timeout_s) const {
  std::unique_lock<std::mutex> lock(state_->mutex);
  return state_->idle.wait_for(lock, std::chrono::duration<double>(timeout_s),
                               [&] { return state_->queue.empty() && !state_->snapshot.testing; });
}

std::optional<DriftUpdate> DriftWatchWorker::accept() {
  std::lock_guard<std::mutex> monitor_lock(state_->monitor_mutex);
  std::optional<DriftUpdate> update = state_->monitor.acceptCandidate();
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->refreshSnapshot();
  // The latest test measured the old reference: none has measured the new one yet.
  if (update) state_->snapshot.last.reset();
  return update;
}

void DriftWatchWorker::setReference(const Extrinsic& reference) {
  std::lock_guard<std::mutex> monitor_lock(state_->monitor_mutex);
  state_->monitor.setReference(reference);
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->refreshSnapshot();
}

}  // namespace thermal_lidar_calibration
