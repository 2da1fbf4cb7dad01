#pragma once
// The drift watch's verdict from one window test to the next:
//   OK    -> WARN  on a changed window (a change suspected),
//   WARN  -> ERROR after `confirm_windows` consecutive changed windows (confirmed),
//   WARN  -> OK    on an unchanged window,
//   ERROR holds until a new reference is taken (reset): a confirmed change does not go away
//   because a later window is inconclusive, it waits for someone to act on it.
// With confirm_windows = 1 the first changed window is already an ERROR.

#include <cstdint>
#include <optional>

namespace thermal_lidar_calibration {

enum class DriftState : std::uint8_t { kOk = 0, kWarn = 1, kError = 2 };
const char* toString(DriftState state);  // "OK", "WARN", "ERROR"

class DriftStateMachine {
 public:
  explicit DriftStateMachine(int confirm_windows);

  // One window test (its stamp = the newest pair in the window); returns the new state.
  DriftState onTest(bool changed, double stamp_s);
  // A new reference is in use: back to OK, a new episode (the first-stamps are cleared).
  void reset();

  DriftState state() const { return state_; }
  int consecutiveChanged() const { return consecutive_; }
  // The first test of this episode that found a change / that confirmed it.
  std::optional<double> firstWarnStamp() const { return first_warn_; }
  std::optional<double> firstErrorStamp() const { return first_error_; }

 private:
  int confirm_windows_;
  DriftState state_ = DriftState::kOk;
  int consecutive_ = 0;
  std::optional<double> first_warn_, first_error_;
};

}  // namespace thermal_lidar_calibration
