#include "thermal_lidar_calibration/core/drift_state.hpp"

#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

const char* toString(DriftState state) {
  switch (state) {
    case DriftState::kOk: return "OK";
    case DriftState::kWarn: return "WARN";
    case DriftState::kError: return "ERROR";
  }
  return "UNKNOWN";
}

DriftStateMachine::DriftStateMachine(int confirm_windows) : confirm_windows_(confirm_windows) {
  if (confirm_windows < 1) {
    throw std::invalid_argument("parameter 'monitor_confirm_windows' = " +
                                std::to_string(confirm_windows) + ": must be at least 1");
  }
}

DriftState DriftStateMachine::onTest(bool changed, double stamp_s) {
  if (!changed) {
    consecutive_ = 0;
    if (state_ == DriftState::kWarn) state_ = DriftState::kOk;
    return state_;
  }
  ++consecutive_;
  if (!first_warn_) first_warn_ = stamp_s;
  if (state_ != DriftState::kError) {
    state_ = consecutive_ >= confirm_windows_ ? DriftState::kError : DriftState::kWarn;
    if (state_ == DriftState::kError) first_error_ = stamp_s;
  }
  return state_;
}

void DriftStateMachine::reset() {
  state_ = DriftState::kOk;
  consecutive_ = 0;
  first_warn_.reset();
  first_error_.reset();
}

}  // namespace thermal_lidar_calibration
