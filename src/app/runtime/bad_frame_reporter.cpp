#include "thermal_lidar_calibration/app/runtime/bad_frame_reporter.hpp"

#include <cstdio>

namespace thermal_lidar_calibration {

std::string BadFrameReporter::report(double stamp_s, const std::string& where, const std::string& error,
                                     FaultThrottle::Clock::time_point now) {
  ++total_;
  const auto held_back = throttle_.admit(where + error, now);
  if (!held_back) return "";
  char head[64];
  std::snprintf(head, sizeof(head), "bad frame at %.3f", stamp_s);
  return std::string(head) + where + ": " + error + " (" + std::to_string(total_) + " bad so far)" +
         throttle_.heldBackText(*held_back);
}

std::string BadFrameReporter::reportAtStamp(double stamp_s, const std::string& where, const std::string& error) {
  const auto at = FaultThrottle::Clock::time_point(
      std::chrono::duration_cast<FaultThrottle::Clock::duration>(std::chrono::duration<double>(stamp_s)));
  return report(stamp_s, where, error, at);
}

}  // namespace thermal_lidar_calibration
