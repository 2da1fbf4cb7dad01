// Background calibration thread with a cooperative stop.

#include "thermal_lidar_calibration/node/calibration_worker.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace thermal_lidar_calibration {

struct CalibrationWorker::State {
  mutable std::mutex mutex;
  std::condition_variable finished_cv;
  std::atomic<bool> stop{false};
  bool running = false;
  std::optional<Progress> progress;
  std::optional<Outcome> outcome;
  std::thread thread;
};

CalibrationWorker::CalibrationWorker() : state_(std::make_shared<State>()) {}

CalibrationWorker::~CalibrationWorker() {
  state_->stop = true;
  std::unique_lock<std::mutex> lock(state_->mutex);
  const bool done = state_->finished_cv.wait_for(
      lock, std::chrono::duration<double>(kStopWaitS), [this] { return !state_->running; });
  lock.unlock();
  if (!state_->thread.joinable()) return;
  if (done) {
    state_->thread.join();
  } else {
    state_->thread.detach();  // the thread holds its own shared_ptr to the state
  }
}

void CalibrationWorker::start(CalibrationJobRequest request) {
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (state_->running) throw std::logic_error("a calibration is already running");
  if (state_->thread.joinable()) state_->thread.join();  // finished: reap it
  state_->stop = false;
  state_->running = true;
  state_->progress.reset();
  state_->outcome.reset();
  std::shared_ptr<State> state = state_;
  state_->thread = std::thread([state, request = std::move(request)]() {
    Outcome outcome;
    try {
      outcome = runCalibrationJob(request, [&state](const JobProgress& p) {
        if (p.stage == JobProgress::Stage::kFit) {
          std::lock_guard<std::mutex> lock(state->mutex);
          state->progress = p.fit;
        }
        return !state->stop.load();
      });
    } catch (const std::exception& e) {
      outcome.error = e.what();
    } catch (...) {
      outcome.error = "unknown exception in the calibration thread";
    }
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      state->outcome = std::move(outcome);
      state->running = false;
    }
    state->finished_cv.notify_all();
  });
}

void CalibrationWorker::requestStop() { state_->stop = true; }

bool CalibrationWorker::busy() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->running;
}

std::optional<Progress> CalibrationWorker::progress() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->progress;
}

std::optional<CalibrationWorker::Outcome> CalibrationWorker::takeOutcome() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (state_->running || !state_->outcome) return std::nullopt;
  std::optional<Outcome> out = std::move(state_->outcome);
  state_->outcome.reset();
  return out;
}

}  // namespace thermal_lidar_calibration
