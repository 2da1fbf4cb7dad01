#pragma once
// Throttling of per-message fault warnings by fault text: each distinct fault is logged at most
// once per period (ROS_WARN_THROTTLE throttles per call site, which would hide a second kind of
// fault behind the first).

#include <chrono>
#include <string>
#include <unordered_map>

namespace thermal_lidar_calibration {

class FaultThrottle {
 public:
  explicit FaultThrottle(double period_s) : period_(period_s) {}
  double periodS() const { return period_.count(); }
  // True if `fault` was not reported within the period (and records it as reported now).
  bool shouldReport(const std::string& fault) {
    const auto now = std::chrono::steady_clock::now();
    if (last_.size() > 256) last_.clear();  // bounded: faults with changing text
    auto it = last_.find(fault);
    if (it != last_.end() && now - it->second < period_) return false;
    last_[fault] = now;
    return true;
  }

 private:
  std::chrono::duration<double> period_;
  std::unordered_map<std::string, std::chrono::steady_clock::time_point> last_;
};

}  // namespace thermal_lidar_calibration
