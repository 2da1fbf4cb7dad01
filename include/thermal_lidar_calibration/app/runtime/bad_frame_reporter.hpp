#pragma once
// One account and one wording of bad frames for calibration_node and calibrate_bag (they used
// two, and calibrate_bag's was keyed on the full text, so sizes in the text made every bad frame
// a new "distinct" error). A line per kind of fault and period, counting the rest; the caller
// gives the time: the node its wall clock, calibrate_bag the bag's own time, so a bag read in a
// second still reports as the node would have while it played.

#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"

#include <cstdint>
#include <string>

namespace thermal_lidar_calibration {

class BadFrameReporter {
 public:
  explicit BadFrameReporter(double period_s = 5.0) : throttle_(period_s) {}

  // Counts one bad frame. Returns the line to say now ("bad frame at 1600000012.300 (where):
  // error (14 bad so far) (and 3 more like it in the last 5 s)"), or "" when it is held back.
  std::string report(double stamp_s, const std::string& where, const std::string& error,
                     FaultThrottle::Clock::time_point now);
  // report() with `now` taken from the frame's own stamp (offline).
  std::string reportAtStamp(double stamp_s, const std::string& where, const std::string& error);

  std::uint64_t total() const { return total_; }

 private:
  FaultThrottle throttle_;
  std::uint64_t total_ = 0;
};

}  // namespace thermal_lidar_calibration
